//! Acceptance of the sensors against Webots' tables (docs/robots.md).

mod common;

use std::sync::Arc;

use common::{sim, world};
use mazesim_core::World;

/// e-puck ps0 / ps7 poses in the robot frame.
const PS0: ([f64; 2], f64) = ([0.03, -0.01], -0.3008);
const PS7: ([f64; 2], f64) = ([0.03, 0.01], 0.2992);

const IR_TABLE: [(f64, f64); 10] = [
    (0.0, 4095.0),
    (0.005, 2133.33),
    (0.01, 1465.73),
    (0.015, 601.46),
    (0.02, 383.84),
    (0.03, 234.93),
    (0.04, 158.03),
    (0.05, 120.0),
    (0.06, 104.09),
    (0.07, 67.19),
];

fn lut(x: f64) -> f64 {
    if x >= 0.07 {
        return 67.19;
    }
    let i = IR_TABLE.iter().position(|r| r.0 > x).unwrap();
    let (a, b) = (IR_TABLE[i - 1], IR_TABLE[i]);
    a.1 + (x - a.0) / (b.0 - a.0) * (b.1 - a.1)
}

/// A world with one wall square to the sensor's ray, `d` metres from the sensor; robot at origin.
fn wall_in_front(sensor: ([f64; 2], f64), d: f64, reflectance: f64) -> Arc<World> {
    let ([px, py], h) = sensor;
    let t = 0.01;
    let cx = px + h.cos() * (d + t / 2.0);
    let cy = py + h.sin() * (d + t / 2.0);
    world(
        32.0,
        &format!(
            "[[walls]]\ncenter = [{cx}, {cy}]\nsize = [{t}, 0.2]\nyaw = {h}\nreflectance = {reflectance}\n"
        ),
    )
}

#[test]
fn walls_in_front_of_ps0_and_ps7_read_the_lookup_table() {
    for (sensor, index) in [(PS0, 0usize), (PS7, 7usize)] {
        for d in [0.01, 0.02, 0.03, 0.05] {
            let s = sim(wall_in_front(sensor, d, 1.0), "e-puck", 1, false);
            let v = s.distance_sensors()[index] as f64;
            let expected = lut(d);
            assert!(
                (v - expected).abs() <= 0.005 * expected,
                "ps{index} at {d}: {v} vs {expected}"
            );
        }
    }
}

#[test]
fn free_space_reads_the_last_row() {
    let s = sim(world(32.0, ""), "e-puck", 1, false);
    assert!(s.distance_sensors().iter().all(|&v| v == 67.19));
}

#[test]
fn a_wall_of_reflectance_f_reads_lut_of_d_over_f() {
    for (d, f) in [(0.01, 0.5), (0.02, 0.5), (0.015, 0.3), (0.03, 0.8)] {
        let s = sim(wall_in_front(PS0, d, f), "e-puck", 1, false);
        let v = s.distance_sensors()[0] as f64;
        let expected = lut(d / f);
        assert!(
            (v - expected).abs() <= 0.005 * expected,
            "d {d} f {f}: {v} vs {expected}"
        );
    }
}

#[test]
fn noise_has_the_tables_relative_sigma() {
    // At 2 cm the table's sigma is 0.01472; at 4 cm 0.0287.
    for (d, sigma) in [(0.02, 0.01472), (0.04, 0.0287)] {
        let mut s = sim(wall_in_front(PS0, d, 1.0), "e-puck", 11, true);
        let expected = lut(d);
        let n = 10_000;
        let mut xs = Vec::with_capacity(n);
        for _ in 0..n {
            s.set_pose(0.0, 0.0, 0.0).unwrap();
            xs.push(s.distance_sensors()[0] as f64);
        }
        let mean = xs.iter().sum::<f64>() / n as f64;
        let sd = (xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64).sqrt();
        let rel = sd / expected;
        assert!(
            (rel - sigma).abs() < 0.1 * sigma,
            "d {d}: relative sd {rel} vs {sigma}"
        );
        assert!((mean - expected).abs() < 0.01 * expected);
    }
}

#[test]
fn ground_sensors_read_white_black_and_in_between_over_an_edge() {
    // Black paint for x >= 0.1; gs sensors sit 3 cm ahead of the centre.
    let w = world(
        32.0,
        "[[paint]]\nshape = \"rect\"\ncenter = [0.6, 0.0]\nsize = [1.0, 1.0]\nreflectance = 0.2\n",
    );
    let mut s = sim(w, "e-puck", 1, false);
    let white = s.ground_sensors().to_vec();
    assert!(white.iter().all(|&v| (v - 856.0).abs() < 1.0), "{white:?}");
    s.set_pose(0.2, 0.0, 0.0).unwrap();
    assert!(s.ground_sensors().iter().all(|&v| (v - 300.0).abs() < 0.5));
    s.set_pose(0.07, 0.0, 0.0).unwrap(); // sensors at x = 0.1, right on the edge
    let edge = s.ground_sensors().to_vec();
    assert!(edge.iter().all(|&v| v > 320.0 && v < 840.0), "{edge:?}");
}

#[test]
fn sharp_sensors_read_volts_and_convert_back_to_cm() {
    // The seed robot's front Sharp sensor at (0.037, 0) heading 0: a wall 10 cm ahead reads 1.25 V.
    let w = world(
        32.0,
        "[[walls]]\ncenter = [0.142, 0.0]\nsize = [0.01, 0.5]\n",
    );
    let s = sim(w, "seed", 1, false);
    let v = s.distance_sensors()[0] as f64;
    assert!((v - 1.25).abs() < 0.005, "{v}");
    let cm = mazesim_core::sharp_volts_to_cm(v).unwrap();
    assert!((cm - 10.0).abs() < 0.1, "{cm}");
    assert!((mazesim_core::sharp_volts_to_cm(2.01).unwrap() - 6.0).abs() < 1e-6);
    assert!(mazesim_core::sharp_volts_to_cm(f64::NAN).is_err());
    // Below 0 V no Sharp sensor reads (issue 35): refused, not clamped to 40 cm.
    assert!(mazesim_core::sharp_volts_to_cm(-1.0).is_err());
    assert!((mazesim_core::sharp_volts_to_cm(0.0).unwrap() - 40.0).abs() < 1e-9);
}

/// A simulator of the e-puck whose infra-red rays rise `elevation` radians.
fn tilted(world: Arc<World>, elevation: f64) -> mazesim_core::Simulator {
    use mazesim_core::{RobotProfile, SimConfig, Simulator};
    let profile = RobotProfile::builtin("e-puck")
        .unwrap()
        .with_infrared_elevation(elevation)
        .unwrap();
    let config = SimConfig {
        seed: 1,
        noise: false,
        control_step: None,
    };
    Simulator::new(world, Arc::new(profile), config).unwrap()
}

#[test]
fn a_tilted_ray_reads_a_wall_as_far_as_its_slant_to_it() {
    // Webots' E-puck PROTO tilts its rays 0.16 rad: a wall 0.03 m away across the floor is met
    // 0.03 / cos(0.16) = 0.030386 m along the ray.
    let e = 0.16f64;
    for (sensor, index) in [(PS0, 0usize), (PS7, 7usize)] {
        for d in [0.01, 0.03, 0.05] {
            let level = sim(wall_in_front(sensor, d, 1.0), "e-puck", 1, false);
            let tilt = tilted(wall_in_front(sensor, d, 1.0), e);
            let (flat, up) = (
                level.distance_sensors()[index] as f64,
                tilt.distance_sensors()[index] as f64,
            );
            let expected = lut(d / e.cos());
            assert!(
                (up - expected).abs() <= 0.005 * expected,
                "{up} vs {expected}"
            );
            assert!(
                up < flat,
                "ps{index} at {d}: the slant reads farther ({up} vs {flat})"
            );
        }
    }
}

#[test]
fn a_tilted_ray_reaches_less_far_across_the_floor() {
    // The 0.07 m ray tilted 0.5 rad reaches 0.0614 m across the floor: a wall 0.065 m away is
    // out of its reach (the last row), where the level ray still meets it.
    let world = wall_in_front(PS0, 0.065, 1.0);
    let level = sim(world.clone(), "e-puck", 1, false).distance_sensors()[0];
    let tilt = tilted(world, 0.5).distance_sensors()[0];
    assert!(level > 67.19 + 1.0, "{level}");
    assert_eq!(tilt, 67.19f32);
}

#[test]
fn a_level_profile_is_unchanged_by_a_zero_elevation() {
    use mazesim_core::RobotProfile;
    let plain = RobotProfile::builtin("e-puck").unwrap();
    let zero = plain.with_infrared_elevation(0.0).unwrap();
    assert_eq!(format!("{zero:?}"), format!("{plain:?}"));
    assert!(!format!("{plain:?}").contains("elevation"));
    let world = wall_in_front(PS7, 0.02, 1.0);
    let a = sim(world.clone(), "e-puck", 1, false)
        .distance_sensors()
        .to_vec();
    let b = tilted(world, 0.0).distance_sensors().to_vec();
    assert_eq!(a, b);
}

#[test]
fn elevations_round_trip_through_toml_and_bad_ones_are_refused() {
    use mazesim_core::RobotProfile;
    let tilt = RobotProfile::builtin("e-puck")
        .unwrap()
        .with_infrared_elevation(0.16)
        .unwrap();
    let text = tilt.to_toml().unwrap();
    assert!(text.contains("elevation = 0.16"), "{text}");
    assert_eq!(RobotProfile::from_toml(&text, "t.toml").unwrap(), tilt);
    for bad in [-0.1, 1.2, f64::NAN] {
        let err = RobotProfile::builtin("e-puck")
            .unwrap()
            .with_infrared_elevation(bad)
            .unwrap_err()
            .to_string();
        assert!(err.contains("infra-red elevation"), "{err}");
    }
    let steep = text.replacen("elevation = 0.16", "elevation = 1.5", 1);
    let err = RobotProfile::from_toml(&steep, "t.toml")
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("distance_sensors[0].elevation") && err.contains("1.5"),
        "{err}"
    );
}
