//! Ramps: a static box whose upper face rises from the floor at a slope the e-puck's wheels hold
//! is ground the robot drives on (a robot may even be saved standing on it), not a wall; a box
//! too steep, or whose upper face starts above the floor, stays a wall.

use mazesim_core::wbt::WbtImport;

/// A world of one e-puck at `(robot_x, 0)` standing `robot_z` above the floor and one Solid: a
/// `size` box centred at `(0, 0, z)`, turned `angle` radians about the x axis.
fn world(size: [f64; 3], z: f64, angle: f64, robot_x: f64, robot_z: f64) -> WbtImport {
    let [sx, sy, sz] = size;
    let text = format!(
        "#VRML_SIM R2023b utf8\nWorldInfo {{ }}\n\
         Solid {{ translation 0 0 {z} rotation 1 0 0 {angle} name \"ramp\" \
         boundingObject Box {{ size {sx} {sy} {sz} }} }}\n\
         E-puck {{ translation {robot_x} 0 {robot_z} controller \"c\" }}\n"
    );
    WbtImport::from_text(&text, "ramps.wbt").unwrap_or_else(|e| panic!("{e}"))
}

fn warned(import: &WbtImport, words: &str) -> bool {
    import.warnings.iter().any(|w| w.contains(words))
}

#[test]
fn a_slab_tilted_from_the_floor_that_the_robot_stands_on_is_floor() {
    // A 1 m slab 1 cm thick turned 0.05 rad: its upper face runs from the floor up to 5 cm,
    // and the robot is saved on it (Webots' e-puck_cross-compilation world).
    let w = world([1.0, 1.0, 0.01], 0.02, -0.05, 0.0, 0.029);
    assert!(w.obstacles.is_empty(), "{:?}", w.obstacles);
    assert!(warned(&w, "a ramp"), "{:?}", w.warnings);
    assert!(warned(&w, "the robot drives on it, imported as floor"));
}

#[test]
fn a_ramp_down_from_a_platform_is_floor_and_says_its_top_and_slope() {
    // Webots' novice_accelerometer ramp: 0.46 m long, 2 cm thick, 0.47 rad, from the floor to
    // the top of a 0.21 m springboard.
    let w = world([0.2, 0.46, 0.02], 0.095, 0.47, 0.5, 0.0);
    assert!(w.obstacles.is_empty(), "{:?}", w.obstacles);
    assert!(
        warned(&w, "rises from the floor to 0.208 m at 27 degrees"),
        "{:?}",
        w.warnings
    );
}

#[test]
fn a_box_steeper_than_the_wheels_hold_stays_a_wall() {
    // The same plank turned 0.9 rad (52 degrees): its face rises from the floor too steeply.
    let half = 0.23 * 0.9_f64.sin() + 0.01 * 0.9_f64.cos();
    let w = world([0.2, 0.46, 0.02], half, 0.9, 0.5, 0.0);
    assert_eq!(w.obstacles.len(), 1, "{:?}", w.warnings);
    assert!(!warned(&w, "a ramp"));
}

#[test]
fn a_tilted_box_whose_top_starts_above_the_floor_stays_a_wall() {
    // A 5 cm block turned 0.2 rad and resting on its edge: its upper face starts 3 cm up.
    let w = world([0.1, 0.1, 0.05], 0.045, 0.2, 0.5, 0.0);
    assert_eq!(w.obstacles.len(), 1, "{:?}", w.warnings);
    assert!(!warned(&w, "a ramp"));
    // Level, the block is a wall as before (no slope: not a ramp).
    let level = world([0.1, 0.1, 0.05], 0.025, 0.0, 0.5, 0.0);
    assert_eq!(level.obstacles.len(), 1);
}
