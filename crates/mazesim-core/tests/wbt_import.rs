//! Acceptance of the `.wbt` importer on real Webots worlds (`tests/data/webots-worlds/`, copied
//! from public Webots repositories): the obstacles and robot pose of its README, to 1 mm and
//! 0.01 rad, and the same world from the R2021c (NUE) and R2023b (ENU) files.

use std::f64::consts::{FRAC_PI_2, PI};
use std::path::PathBuf;

use mazesim_core::wbt::{Obstacle, WbtImport};
use mazesim_core::world::spec::BodySpec;
use mazesim_core::world::values::xy;

const LENGTH_TOLERANCE: f64 = 1e-3;
const ANGLE_TOLERANCE: f64 = 0.01;

fn corpus_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../tests/data/webots-worlds")
}

/// Imports a corpus file; a missing corpus fails the test loudly.
fn import(name: &str) -> WbtImport {
    let path = corpus_dir().join(name);
    assert!(
        path.is_file(),
        "the Webots test corpus is missing: expected {} (copied from ../shared/webots-worlds)",
        path.display()
    );
    WbtImport::load(&path).unwrap_or_else(|e| panic!("{name} does not import: {e}"))
}

/// Angle difference folded into [0, period / 2].
fn angle_gap(a: f64, b: f64, period: f64) -> f64 {
    let d = (a - b).rem_euclid(period);
    d.min(period - d)
}

/// Whether two boxes cover the same rectangle (a box turned by pi, or by pi/2 with its sizes
/// swapped, is the same box).
fn same_box(a: (&[f64; 2], &[f64; 2], f64), b: (&[f64; 2], &[f64; 2], f64)) -> bool {
    let near = |p: &[f64; 2], q: &[f64; 2]| {
        (p[0] - q[0]).abs() <= LENGTH_TOLERANCE && (p[1] - q[1]).abs() <= LENGTH_TOLERANCE
    };
    if !near(a.0, b.0) {
        return false;
    }
    let straight = near(a.1, b.1) && angle_gap(a.2, b.2, PI) <= ANGLE_TOLERANCE;
    let turned =
        near(a.1, &[b.1[1], b.1[0]]) && angle_gap(a.2, b.2 + PI / 2.0, PI) <= ANGLE_TOLERANCE;
    straight || turned
}

fn boxes(import: &WbtImport) -> Vec<([f64; 2], [f64; 2], f64)> {
    import
        .obstacles
        .iter()
        .filter_map(|o| match *o {
            Obstacle::Box { center, size, yaw } => Some((center, size, yaw)),
            Obstacle::Circle { .. } => None,
        })
        .collect()
}

/// Every expected box is found once among the imported boxes, and no other box is there.
fn assert_boxes(import: &WbtImport, expected: &[([f64; 2], [f64; 2], f64)]) {
    let found = boxes(import);
    assert_eq!(found.len(), expected.len(), "{found:?}");
    for e in expected {
        let matches = found
            .iter()
            .filter(|f| same_box((&f.0, &f.1, f.2), (&e.0, &e.1, e.2)))
            .count();
        assert_eq!(matches, 1, "expected box {e:?} once among {found:?}");
    }
}

fn assert_robot(import: &WbtImport, x: f64, y: f64, yaw: f64) {
    let [rx, ry, ryaw] = import.robot.expect("an e-puck start pose");
    assert!((rx - x).abs() <= LENGTH_TOLERANCE, "x {rx} != {x}");
    assert!((ry - y).abs() <= LENGTH_TOLERANCE, "y {ry} != {y}");
    assert!(
        angle_gap(ryaw, yaw, 2.0 * PI) <= ANGLE_TOLERANCE,
        "yaw {ryaw} != {yaw}"
    );
}

fn warned(import: &WbtImport, words: &str) -> bool {
    import.warnings.iter().any(|w| w.contains(words))
}

/// The e-puck.wbt world: RectangleArena 2 x 2 and five WoodenBoxes of 0.1 m.
fn epuck_world_boxes() -> Vec<([f64; 2], [f64; 2], f64)> {
    vec![
        ([1.005, 0.0], [0.01, 2.0], 0.0),
        ([-1.005, 0.0], [0.01, 2.0], 0.0),
        ([0.0, 1.005], [2.02, 0.01], 0.0),
        ([0.0, -1.005], [2.02, 0.01], 0.0),
        ([-0.683174, 0.2], [0.1, 0.1], 0.5),
        ([0.35, 0.75], [0.1, 0.1], 4.96782),
        ([-0.35471, -0.5], [0.1, 0.1], 5.36782),
        ([0.36, 0.3], [0.1, 0.1], 5.36782),
        ([-0.66, 0.65], [0.1, 0.1], 5.36782),
    ]
}

#[test]
fn collision_avoidance_has_four_walls_and_a_movable_ball() {
    let import = import("collision_avoidance.wbt");
    assert_boxes(
        &import,
        &[
            ([0.5, 0.0], [0.02, 0.98], 0.0),
            ([-0.5, 0.0], [0.02, 0.98], 0.0),
            // The file turns these two by 1.5708.
            ([0.0, -0.5], [0.02, 0.98], FRAC_PI_2),
            ([0.0, 0.5], [0.02, 0.98], FRAC_PI_2),
        ],
    );
    assert_robot(&import, 0.0, 0.0, 0.0);
    assert_eq!(import.basic_time_step_ms, 16.0);
    // The ball has physics (a 5 cm sphere of the default density, 1000 kg/m^3: 0.52 kg): it
    // becomes a movable disc where it lands, not a static one (#16).
    assert!(import
        .obstacles
        .iter()
        .all(|o| matches!(o, Obstacle::Box { .. })));
    let [BodySpec::Circle {
        center,
        radius,
        mass,
        ..
    }] = import.bodies.as_slice()
    else {
        panic!("one movable disc: {:?}", import.bodies)
    };
    assert_eq!((xy(center), radius.get()), ([0.2, 0.0], 0.05));
    assert!((mass.get() - 1000.0 * 4.0 / 3.0 * PI * 0.05f64.powi(3)).abs() < 1e-9);
    assert!(!warned(&import, "\"ball\": an object with physics"));
}

#[test]
fn advanced_path_planning_walls_come_from_the_bounding_group() {
    let import = import("advanced_path_planning.wbt");
    assert_boxes(
        &import,
        &[
            ([-0.205, -0.405], [0.63, 0.01], 0.0),
            ([-0.205, 0.105], [0.63, 0.01], 0.0),
            ([-0.515, -0.15], [0.01, 0.52], 0.0),
            ([0.105, -0.15], [0.01, 0.52], 0.0),
        ],
    );
    assert_robot(&import, -0.04, -0.04, PI);
    // The marker discs and the wall's visual mesh are not collision shapes: no warning.
    assert!(!warned(&import, "mesh"), "{:?}", import.warnings);
}

#[test]
fn rats_life_maze_has_54_lego_pieces() {
    let import = import("rats_life_benchmark.wbt");
    let found = boxes(&import);
    assert_eq!(found.len(), 54);
    let walls = found
        .iter()
        .filter(|b| {
            same_box((&b.0, &b.1, b.2), (&b.0, &[0.016, 0.096], 0.0))
                || same_box((&b.0, &b.1, b.2), (&b.0, &[0.016, 0.096], PI / 2.0))
        })
        .count();
    let intervals = found
        .iter()
        .filter(|b| same_box((&b.0, &b.1, b.2), (&b.0, &[0.016, 0.016], 0.0)))
        .count();
    assert_eq!((walls, intervals), (27, 27));
    for (center, _, _) in &found {
        let (tx, ty) = (-0.35..=0.24, -0.34..=0.27);
        let within = |range: &std::ops::RangeInclusive<f64>, v: f64| {
            v >= range.start() - LENGTH_TOLERANCE && v <= range.end() + LENGTH_TOLERANCE
        };
        assert!(
            within(&tx, center[0]) && within(&ty, center[1]),
            "{center:?}"
        );
    }
    // The first wall of the file, turned a quarter turn: 0.096 m along x.
    assert!(found
        .iter()
        .any(|b| same_box((&b.0, &b.1, b.2), (&[-0.198, -0.34], &[0.096, 0.016], 0.0))));
    assert_robot(&import, 0.0, -0.05, PI);
    assert_eq!(import.basic_time_step_ms, 20.0);
    assert_eq!(import.robot_model.as_deref(), Some("e-puck2"));
    assert_eq!(import.robot_profile, "e-puck2");
}

#[test]
fn epuck_r2023b_is_an_arena_with_five_boxes() {
    let import = import("e-puck.R2023b.wbt");
    assert_boxes(&import, &epuck_world_boxes());
    assert_robot(&import, 0.0, 0.0, 1.57);
    assert_eq!(import.basic_time_step_ms, 32.0);
}

#[test]
fn epuck_r2021c_nue_converts_to_the_r2023b_world() {
    let old = import("e-puck.R2021c_NUE.wbt");
    let new = import("e-puck.R2023b.wbt");
    assert_boxes(&old, &epuck_world_boxes());
    assert_robot(&old, 0.0, 0.0, 1.57);
    assert_eq!(old.obstacles.len(), new.obstacles.len());
    for (a, b) in boxes(&old).iter().zip(boxes(&new).iter()) {
        assert!(
            same_box((&a.0, &a.1, a.2), (&b.0, &b.1, b.2)),
            "{a:?} != {b:?}"
        );
    }
    let (po, pn) = (old.robot.unwrap(), new.robot.unwrap());
    assert!(
        (0..3).all(|i| (po[i] - pn[i]).abs() < 1e-6),
        "{po:?} != {pn:?}"
    );
    assert_eq!(old.basic_time_step_ms, new.basic_time_step_ms);
    // The same mazesim world once built (walls compared to 1 mm, as boxes).
    let (wo, wn) = (
        old.to_world("e-puck").unwrap(),
        new.to_world("e-puck").unwrap(),
    );
    assert_eq!(wo.walls().len(), wn.walls().len());
    assert_eq!(
        wo.start().map(|v| (v * 1e6).round()),
        wn.start().map(|v| (v * 1e6).round())
    );
}

#[test]
fn webots_ros2_epuck_world_is_a_smaller_arena() {
    let import = import("webots_ros2_epuck_world.wbt");
    assert_boxes(
        &import,
        &[
            ([0.755, 0.0], [0.01, 1.5], 0.0),
            ([-0.755, 0.0], [0.01, 1.5], 0.0),
            ([0.0, 0.755], [1.52, 0.01], 0.0),
            ([0.0, -0.755], [1.52, 0.01], 0.0),
            ([-0.265062, 0.13], [0.1, 0.1], 0.0),
            ([-0.115895, -0.36], [0.1, 0.1], 0.0),
            ([0.44, 0.12], [0.1, 0.1], 0.0),
            ([0.29726, -0.29], [0.1, 0.1], 0.0),
            ([-0.158467, 0.26], [0.1, 0.1], 0.0),
        ],
    );
    // The file writes the heading as 3.1415.
    assert_robot(&import, 0.0530459, 0.00806403, PI);
}

#[test]
fn every_corpus_world_builds_a_mazesim_world() {
    let mut files: Vec<PathBuf> = std::fs::read_dir(corpus_dir())
        .expect("the Webots test corpus folder exists")
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "wbt"))
        .collect();
    files.sort();
    assert_eq!(files.len(), 6, "{files:?}");
    for path in files {
        let import = WbtImport::load(&path).unwrap();
        let world = import.to_world("imported").unwrap();
        // A box is one wall, a circle a ring of them.
        let walls: usize = import
            .obstacles
            .iter()
            .map(|o| match *o {
                Obstacle::Box { .. } => 1,
                Obstacle::Circle { radius, .. } => mazesim_core::wbt::polygon_sides(radius),
            })
            .sum();
        assert_eq!(world.walls().len(), walls, "{}", path.display());
        let [x, y, yaw] = import.robot.unwrap();
        assert_eq!(world.start(), [x, y, yaw]);
        assert_eq!(world.basic_time_step() * 1000.0, import.basic_time_step_ms);
    }
}

#[test]
fn a_light_wooden_box_becomes_a_movable_body_and_a_heavy_or_large_one_stays_static() {
    let text = "#VRML_SIM R2023b utf8\n\
        WoodenBox { translation 0.3 0 0.05 size 0.1 0.1 0.1 mass 0.1 }\n\
        WoodenBox { translation -0.3 0 0.05 size 0.1 0.1 0.1 mass 2 }\n\
        WoodenBox { translation 0 0.5 0.3 size 0.6 0.6 0.6 mass 0.1 }\n\
        Solid { translation 0 -0.3 0.02 physics Physics { mass 0.05 } boundingObject Box { size 0.04 0.04 0.04 } }\n";
    let import = WbtImport::from_text(text, "boxes.wbt").unwrap();
    let centers: Vec<[f64; 2]> = import
        .bodies
        .iter()
        .map(|b| match b {
            BodySpec::Box { center, mass, .. } => {
                assert!(mass.get() == 0.1 || mass.get() == 0.05);
                xy(center)
            }
            BodySpec::Circle { .. } => panic!("a box"),
        })
        .collect();
    assert_eq!(centers, [[0.3, 0.0], [0.0, -0.3]]);
    // The 2 kg box and the 0.6 m box stay static, with the warning.
    assert_eq!(import.obstacles.len(), 2);
    let statics = import
        .warnings
        .iter()
        .filter(|w| w.contains("imported as a static obstacle"))
        .count();
    assert_eq!(statics, 2, "{:#?}", import.warnings);
    let world = import.to_world("boxes").unwrap();
    assert_eq!(world.bodies().len(), 2);
}
