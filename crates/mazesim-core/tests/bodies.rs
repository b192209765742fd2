//! Movable bodies: the robot pushes them, walls stop them, sensors see them, resets put them back,
//! and a batch with bodies is deterministic.

mod common;

use std::sync::Arc;

use common::{sim, world};
use mazesim_core::{Batch, RobotProfile, World};

/// The robot at the origin facing +x, a 5 cm box of `mass` kg and floor `friction` ahead of it at
/// `box_x`, and `extra` TOML (walls).
fn box_world(box_x: f64, mass: f64, friction: f64, extra: &str) -> Arc<World> {
    world(
        32.0,
        &format!(
            "[start]\nx = 0\ny = 0\n\n[[bodies]]\nshape = \"box\"\ncenter = [{box_x}, 0]\n\
             size = [0.05, 0.05]\nmass = {mass}\nfriction = {friction}\n{extra}"
        ),
    )
}

#[test]
fn the_robot_pushes_a_light_box_forward() {
    let mut s = sim(box_world(0.15, 0.1, 0.5, ""), "e-puck", 1, false);
    assert_eq!(s.body_poses(), vec![[0.15, 0.0, 0.0]]);
    for _ in 0..100 {
        s.step(6.0, 6.0).unwrap();
    }
    let robot = s.pose();
    let [bx, by, _] = s.body_poses()[0];
    // 3.2 s at 0.12 m/s: the robot drives 0.38 m, the box ahead of it.
    assert!(robot[0] > 0.3, "robot {robot:?}");
    assert!(
        bx > robot[0] + 0.037 + 0.02,
        "box {bx} ahead of robot {robot:?}"
    );
    assert!(bx > 0.35 && by.abs() < 0.02, "box at {bx}, {by}");
}

#[test]
fn a_box_pushed_into_a_wall_stops_at_the_wall() {
    let wall = "[[walls]]\ncenter = [0.45, 0]\nsize = [0.1, 1.0]\n";
    let mut s = sim(box_world(0.15, 0.1, 0.5, wall), "e-puck", 1, false);
    for _ in 0..200 {
        s.step(6.0, 6.0).unwrap();
    }
    let [bx, _, _] = s.body_poses()[0];
    // The wall's face is at x = 0.4; the box's half side is 0.025.
    assert!(bx <= 0.375 + 2e-3, "box sank into the wall: {bx}");
    assert!(bx > 0.36, "box stopped short of the wall: {bx}");
    assert!(s.pose()[0] < 0.35 - 0.037 + 2e-3, "robot {:?}", s.pose());
}

#[test]
fn a_distance_sensor_sees_a_box_slide_away() {
    // Low floor friction: the box coasts on after the robot stops.
    let mut s = sim(box_world(0.1, 0.05, 0.05, ""), "e-puck", 1, false);
    let far = sim(world(32.0, "[start]\nx = 0\ny = 0\n"), "e-puck", 1, false);
    assert_ne!(
        s.distance_sensors(),
        far.distance_sensors(),
        "the box is seen"
    );
    for _ in 0..20 {
        s.step(6.2, 6.2).unwrap();
    }
    s.step(0.0, 0.0).unwrap();
    let near = s.distance_sensors().to_vec();
    let box_then = s.body_poses()[0][0];
    let robot_then = s.pose();
    for _ in 0..20 {
        s.step(0.0, 0.0).unwrap();
    }
    assert_eq!(s.pose(), robot_then, "the robot stood still");
    assert!(s.body_poses()[0][0] > box_then + 0.005, "the box slid on");
    // ps0 and ps7 look ahead: they read less as the box slides away.
    let later = s.distance_sensors();
    assert!(
        later[0] < near[0] && later[7] < near[7],
        "{near:?} then {later:?}"
    );
}

#[test]
fn bodies_go_back_to_their_start_on_reset() {
    let mut s = sim(box_world(0.15, 0.1, 0.5, ""), "e-puck", 1, false);
    let start = s.distance_sensors().to_vec();
    for _ in 0..60 {
        s.step(6.0, 6.0).unwrap();
    }
    assert_ne!(s.body_poses(), vec![[0.15, 0.0, 0.0]]);
    s.reset(None);
    assert_eq!(s.body_poses(), vec![[0.15, 0.0, 0.0]]);
    assert_eq!(s.distance_sensors(), start.as_slice());
}

#[test]
fn a_heavy_box_is_pushed_slowly() {
    let mut light = sim(box_world(0.15, 0.1, 0.5, ""), "e-puck", 1, false);
    let mut heavy = sim(box_world(0.15, 1.5, 0.5, ""), "e-puck", 1, false);
    for _ in 0..100 {
        light.step(6.0, 6.0).unwrap();
        heavy.step(6.0, 6.0).unwrap();
    }
    assert!(heavy.body_poses()[0][0] < light.body_poses()[0][0]);
}

const BODIES_WORLD: &str = "[start]\nx = 0\ny = 0\n\n\
    [[walls]]\ncenter = [0, 0.4]\nsize = [1.0, 0.05]\n\n\
    [[walls]]\ncenter = [0, -0.4]\nsize = [1.0, 0.05]\n\n\
    [[walls]]\ncenter = [0.5, 0]\nsize = [0.05, 0.8]\n\n\
    [[walls]]\ncenter = [-0.5, 0]\nsize = [0.05, 0.8]\n\n\
    [[bodies]]\nshape = \"box\"\ncenter = [0.12, 0.02]\nsize = [0.04, 0.06]\nyaw = 0.3\nmass = 0.1\n\n\
    [[bodies]]\nshape = \"circle\"\ncenter = [0.2, -0.1]\nradius = 0.02\nmass = 0.05\n";

const STEPS: usize = 150;

fn action(env: usize, step: usize) -> [f32; 2] {
    let t = step as f32 * 0.05 + env as f32;
    [4.0 + 2.5 * t.sin(), 4.0 + 2.5 * (1.7 * t).cos()]
}

/// Observations, robot pose and body poses of env `watch` of a batch of `n` over the run.
fn batch_trace(n: usize, threads: usize, watch: usize) -> Vec<u32> {
    let world = world(32.0, BODIES_WORLD);
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let seeds: Vec<u64> = (0..n as u64).map(|i| 50 + i).collect();
    let mut b = Batch::new(vec![world; n], robot, &seeds, true, None, threads).unwrap();
    let w = b.observation_width();
    let mut obs = vec![0.0; n * w];
    let mut poses = vec![0.0; n * 3];
    let mut colliding = vec![false; n];
    let mut crossings = vec![0; n];
    macro_rules! out {
        () => {
            mazesim_core::StepOutputs {
                observations: &mut obs,
                poses: &mut poses,
                colliding: &mut colliding,
                crossings: &mut crossings,
            }
        };
    }
    b.reset(None, None, out!()).unwrap();
    let mut trace = Vec::new();
    for step in 0..STEPS {
        let actions: Vec<f32> = (0..n).flat_map(|i| action(i, step)).collect();
        b.step(&actions, out!()).unwrap();
        trace.extend(obs[watch * w..(watch + 1) * w].iter().map(|v| v.to_bits()));
        trace.extend(poses[watch * 3..watch * 3 + 3].iter().map(|v| v.to_bits()));
        let bodies = b.envs()[watch].body_poses();
        trace.extend(bodies.iter().flatten().map(|v| v.to_bits()));
    }
    trace
}

#[test]
fn a_batch_with_bodies_is_the_same_for_any_threads_and_batch_size() {
    let one = batch_trace(1, 1, 0);
    assert_eq!(batch_trace(5, 1, 0), one);
    assert_eq!(batch_trace(5, 2, 0), one);
    let third = batch_trace(5, 2, 2);
    assert_eq!(batch_trace(3, 1, 2), third);
    assert_ne!(one, third);
    let mut lone = sim(world(32.0, BODIES_WORLD), "e-puck", 50, true);
    let start = lone.body_poses();
    for step in 0..STEPS {
        let [l, r] = action(0, step);
        lone.step(l as f64, r as f64).unwrap();
    }
    assert_ne!(lone.body_poses(), start, "the robot met a body");
}

#[test]
fn bodies_round_trip_through_the_world_file() {
    let w = world(32.0, BODIES_WORLD);
    assert_eq!(w.bodies().len(), 2);
    assert_eq!(w.bodies()[1].friction, 0.5, "the default floor friction");
    let text = w.to_toml().unwrap();
    let again = World::from_toml(&text, "again.toml").unwrap();
    assert_eq!(again, *w);
    assert_eq!(again.bodies(), w.bodies());
}

#[test]
fn bad_bodies_are_refused_naming_the_field() {
    let head = "format = \"mazesim-world\"\nversion = 1\n";
    for (body, expected) in [
        (
            "shape = \"box\"\ncenter = [0, 0]\nsize = [0.1, 0.1]\nmass = -1\n",
            "above zero",
        ),
        (
            "shape = \"circle\"\ncenter = [0, 0]\nradius = 0.1\nmass = 1\nfriction = -0.5\n",
            "at or above zero",
        ),
        (
            "shape = \"circle\"\ncenter = [2000, 0]\nradius = 0.1\nmass = 1\n",
            "bodies[0]",
        ),
        (
            "shape = \"box\"\ncenter = [0, 0]\nsize = [0.1, 0.1]\nyaw = 1e9\nmass = 1\n",
            "bodies[0].yaw",
        ),
        (
            "shape = \"triangle\"\ncenter = [0, 0]\nmass = 1\n",
            "triangle",
        ),
    ] {
        let text = format!("{head}\n[[bodies]]\n{body}");
        let err = World::from_toml(&text, "bad.toml").unwrap_err().to_string();
        assert!(err.contains(expected) && err.contains("bad.toml"), "{err}");
    }
}
