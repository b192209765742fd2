//! Acceptance of the physics: kinematics of the differential drive and contact quality.
#![allow(clippy::approx_constant)] // 6.28 rad/s is the e-puck motor limit, not tau.

mod common;

use std::f64::consts::PI;

use common::{sim, world};

/// Wheel radius and effective wheel distance of each e-puck profile: as Webots simulates it,
/// and the datasheet's hardware.
const WHEELS: [(&str, f64, f64); 3] = [
    ("e-puck", 0.02, 0.05685),
    ("e-puck2", 0.02, 0.05685),
    ("e-puck-hardware", 0.0205, 0.052),
];

#[test]
fn straight_drive_covers_r_times_w_per_second() {
    for ((robot, r, _), w) in WHEELS.iter().flat_map(|p| [1.0, 3.0, 6.28].map(|w| (p, w))) {
        let mut s = sim(world(10.0, "[start]\nx = 0\ny = 0\n"), robot, 1, false);
        for _ in 0..100 {
            s.step(w, w).unwrap();
        }
        assert!((s.time() - 1.0).abs() < 1e-9);
        let [x, y, yaw] = s.pose();
        let expected = r * w;
        assert!(
            ((x as f64) - expected).abs() < 0.01 * expected,
            "{robot} w {w}: x {x}, expected {expected}"
        );
        assert!(y.abs() < 1e-5 && yaw.abs() < 1e-5);
        assert!((s.distance_travelled() - expected).abs() < 0.01 * expected);
    }
}

#[test]
fn spinning_in_place_turns_at_2rw_over_axle() {
    for &(robot, r, axle) in &WHEELS {
        spin_for_a_second(robot, r, axle);
    }
}

fn spin_for_a_second(robot: &str, r: f64, axle: f64) {
    let w = 2.0;
    let mut s = sim(world(10.0, ""), robot, 1, false);
    let mut turned = 0.0;
    let mut last = s.pose()[2] as f64;
    for _ in 0..100 {
        s.step(-w, w).unwrap();
        let yaw = s.pose()[2] as f64;
        let mut d = yaw - last;
        if d > PI {
            d -= 2.0 * PI;
        } else if d < -PI {
            d += 2.0 * PI;
        }
        turned += d;
        last = yaw;
    }
    let expected = 2.0 * r * w / axle;
    assert!(
        (turned - expected).abs() < 0.01 * expected,
        "{robot}: turned {turned}, expected {expected}"
    );
    let [x, y, _] = s.pose();
    assert!(x.abs() < 1e-5 && y.abs() < 1e-5);
}

#[test]
fn speeds_beyond_the_motor_limit_are_clamped_and_nan_is_refused() {
    let mut s = sim(world(32.0, ""), "e-puck", 1, false);
    s.step(100.0, -100.0).unwrap();
    assert_eq!(s.wheel_speeds(), [6.28, -6.28]);
    assert!(s.step(f64::NAN, 1.0).is_err());
    assert!(s.step(1.0, f64::INFINITY).is_err());
    assert_eq!(s.steps(), 1, "a refused action does not advance time");
}

const BOX_WALL: &str = "[[walls]]\ncenter = [0.3, 0.0]\nsize = [0.01, 1.0]\n";

#[test]
fn full_speed_into_a_wall_never_penetrates_a_millimetre_and_counts_bumps() {
    let mut s = sim(world(32.0, BOX_WALL), "e-puck", 1, false);
    let mut worst = f32::INFINITY;
    let mut colliding_steps = 0;
    for _ in 0..(10_000 / 32) {
        s.step(6.28, 6.28).unwrap();
        worst = worst.min(s.wall_clearance());
        colliding_steps += usize::from(s.colliding());
    }
    assert!(worst > -0.001, "penetration {} m", -worst);
    assert!(s.collisions() >= 1);
    assert!(colliding_steps > 200, "{colliding_steps}");
    // The body rests against the wall: its centre a radius away from the wall face.
    let x = s.pose()[0];
    assert!((x - (0.295 - 0.037)).abs() < 0.001, "x {x}");
    // Back off and hit again: a second bump.
    for _ in 0..20 {
        s.step(-6.28, -6.28).unwrap();
    }
    assert!(!s.colliding());
    for _ in 0..40 {
        s.step(6.28, 6.28).unwrap();
    }
    assert_eq!(s.collisions(), 2);
}

#[test]
fn the_e_puck2_at_its_motor_limit_stays_out_of_a_wall() {
    let mut s = sim(world(32.0, BOX_WALL), "e-puck2", 1, false);
    let mut worst = f32::INFINITY;
    for _ in 0..100 {
        s.step(7.536, 7.536).unwrap();
        worst = worst.min(s.wall_clearance());
    }
    assert_eq!(s.wheel_speeds(), [7.536, 7.536]);
    assert!(worst > -0.001, "penetration {} m", -worst);
    assert_eq!(s.collisions(), 1);
}

#[test]
fn no_tunnelling_through_a_1cm_wall_at_any_speed_or_angle() {
    for &speed in &[0.5, 2.0, 4.0, 6.28] {
        for &yaw in &[0.0, 0.3, -0.6, 1.0] {
            // A wall long enough that sliding along it never reaches its end.
            let long_wall = "[[walls]]\ncenter = [0.3, 0.0]\nsize = [0.01, 10.0]\n";
            let body = format!("{long_wall}[start]\nx = 0.2\ny = 0.0\nyaw = {yaw}\n");
            let mut s = sim(world(32.0, &body), "e-puck", 3, false);
            let mut worst = f32::INFINITY;
            for _ in 0..300 {
                s.step(speed, speed).unwrap();
                worst = worst.min(s.wall_clearance());
                assert!(s.pose()[0] < 0.295, "tunnelled at speed {speed}, yaw {yaw}");
            }
            assert!(
                worst > -0.001,
                "speed {speed} yaw {yaw}: penetration {}",
                -worst
            );
        }
    }
}

#[test]
fn encoders_count_wheel_turns_at_their_resolution() {
    let mut s = sim(world(32.0, ""), "e-puck", 1, false);
    for _ in 0..10 {
        s.step(1.0, -2.0).unwrap();
    }
    let [l, r] = s.encoders();
    assert!((l - 0.32).abs() <= 2.0 * PI / 1000.0);
    assert!((r + 0.64).abs() <= 2.0 * PI / 1000.0);
    let q = 2.0 * PI / 1000.0;
    assert!(((l / q) - (l / q).round()).abs() < 1e-9);
}
