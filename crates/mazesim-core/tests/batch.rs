//! The batch engine: env i of a batch equals a lone simulator with the same seed and actions,
//! whatever the thread count or the batch size.

mod common;

use std::sync::Arc;

use common::seed_maze_epuck;
use mazesim_core::{Batch, OutputBuffers, RobotProfile, World};

const STEPS: usize = 300;

fn action(env: usize, step: usize) -> [f32; 2] {
    let t = step as f32 * 0.05 + env as f32;
    [4.0 + 2.5 * t.sin(), 4.0 + 2.5 * (1.7 * t).cos()]
}

/// Observation and pose bits of env `watch` over the run, from a batch of `n` envs.
fn batch_trace(n: usize, threads: usize, watch: usize) -> Vec<u32> {
    let world = Arc::new(World::builtin("seed-maze").unwrap());
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let seeds: Vec<u64> = (0..n as u64).map(|i| 1000 + i).collect();
    let mut b = Batch::new(vec![world; n], robot, &seeds, true, None, threads).unwrap();
    let w = b.observation_width();
    let mut buf = OutputBuffers::new(n, w);
    b.reset(None, None, buf.outputs()).unwrap();
    let mut trace = Vec::new();
    for step in 0..STEPS {
        let actions: Vec<f32> = (0..n).flat_map(|i| action(i, step)).collect();
        b.step(&actions, buf.outputs()).unwrap();
        trace.extend(
            buf.observations[watch * w..(watch + 1) * w]
                .iter()
                .map(|v| v.to_bits()),
        );
        trace.extend(
            buf.poses[watch * 3..watch * 3 + 3]
                .iter()
                .map(|v| v.to_bits()),
        );
    }
    trace
}

fn lone_trace(env: usize) -> Vec<u32> {
    let mut s = seed_maze_epuck(1000 + env as u64);
    let mut trace = Vec::new();
    for step in 0..STEPS {
        let [l, r] = action(env, step);
        s.step(l as f64, r as f64).unwrap();
        trace.extend(
            s.distance_sensors()
                .iter()
                .chain(s.ground_sensors())
                .map(|v| v.to_bits()),
        );
        trace.extend(s.pose().iter().map(|v| v.to_bits()));
    }
    trace
}

#[test]
fn env_i_equals_a_lone_simulator_for_any_threads_and_batch_size() {
    let lone0 = lone_trace(0);
    for (n, threads) in [(1, 1), (7, 1), (7, 2), (64, 2), (64, 0)] {
        assert_eq!(
            batch_trace(n, threads, 0),
            lone0,
            "batch {n}, threads {threads}"
        );
    }
    let lone6 = lone_trace(6);
    assert_eq!(batch_trace(7, 1, 6), lone6);
    assert_eq!(batch_trace(64, 2, 6), lone6);
    assert_ne!(lone0, lone6);
    // Past the first chunks of work the threads take: env 40 of 64.
    let lone40 = lone_trace(40);
    assert_eq!(batch_trace(64, 2, 40), lone40);
    assert_eq!(batch_trace(64, 0, 40), lone40);
}

#[test]
fn bad_actions_and_masks_are_refused_before_anything_moves() {
    let world = Arc::new(World::builtin("arena").unwrap());
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let mut b = Batch::new(vec![world; 3], robot, &[1, 2, 3], false, None, 1).unwrap();
    let mut buf = OutputBuffers::new(3, b.observation_width());
    let err = b
        .step(&[1.0, 1.0, f32::NAN, 1.0, 1.0, 1.0], buf.outputs())
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("environment 1") && err.contains("left"),
        "{err}"
    );
    assert!(b.envs().iter().all(|e| e.steps() == 0));
    assert!(b.step(&[1.0; 4], buf.outputs()).is_err());
    assert!(b.reset(Some(&[true, false]), None, buf.outputs()).is_err());
    assert!(b.reset(None, Some(&[1, 2]), buf.outputs()).is_err());
    let mut short = OutputBuffers::new(2, b.observation_width());
    assert!(b.step(&[1.0; 6], short.outputs()).is_err());
}

#[test]
fn masked_reset_touches_only_the_masked_envs() {
    let world = Arc::new(World::builtin("arena").unwrap());
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let mut b = Batch::new(vec![world; 3], robot, &[1, 2, 3], true, None, 0).unwrap();
    let mut buf = OutputBuffers::new(3, b.observation_width());
    for _ in 0..10 {
        b.step(&[5.0; 6], buf.outputs()).unwrap();
    }
    b.reset(Some(&[false, true, false]), Some(&[9, 9, 9]), buf.outputs())
        .unwrap();
    let steps: Vec<u64> = b.envs().iter().map(|e| e.steps()).collect();
    assert_eq!(steps, vec![10, 0, 10]);
    assert_eq!(buf.poses[3..6], b.envs()[1].pose());
}

/// A corridor with `robots` e-pucks along it, `gap` metres apart, the first at `x`.
fn corridor_of(robots: usize, x: f64, gap: f64) -> Arc<World> {
    let mut text = String::from(
        "format = \"mazesim-world\"\nversion = 1\n\n[[walls]]\ncenter = [0.0, 0.105]\n\
         size = [2.0, 0.01]\n\n[[walls]]\ncenter = [0.0, -0.105]\nsize = [2.0, 0.01]\n",
    );
    for i in 0..robots {
        let yaw = if i % 2 == 0 { 0.0 } else { 3.0 };
        text += &format!(
            "\n[[robots]]\nname = \"r{i}\"\nx = {}\ny = 0.0\nyaw = {yaw}\n",
            x + gap * i as f64
        );
    }
    Arc::new(World::from_toml(&text, "corridor").unwrap())
}

/// Observation bits of env `watch` of a swarm batch over 40 steps of the same actions.
fn swarm_trace(b: &mut Batch, watch: usize) -> Vec<u32> {
    let (n, r, w) = (b.num_envs(), b.robots_per_env(), b.observation_width());
    let mut buf = OutputBuffers::new(n * r, w);
    b.observe(buf.outputs()).unwrap();
    let mut trace = Vec::new();
    for step in 0..40 {
        let actions: Vec<f32> = (0..n * r).flat_map(|i| action(i % r, step)).collect();
        b.step_swarms(&actions, buf.outputs()).unwrap();
        let rows = watch * r * w..(watch + 1) * r * w;
        trace.extend(buf.observations[rows].iter().map(|v| v.to_bits()));
    }
    trace
}

#[test]
fn set_world_puts_an_env_of_several_robots_into_another_world() {
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let (first, second) = (corridor_of(2, -0.1, 0.2), corridor_of(2, -0.3, 0.15));
    let worlds = vec![first.clone(), first];
    let mut b = Batch::with_swarms(worlds, robot.clone(), &[1, 2], true, None, 1).unwrap();
    b.set_world(1, second.clone(), 5).unwrap();
    let fresh_worlds = vec![second.clone(), second];
    let mut fresh = Batch::with_swarms(fresh_worlds, robot, &[5, 5], true, None, 1).unwrap();
    assert_eq!(swarm_trace(&mut b, 1), swarm_trace(&mut fresh, 0));
    let three = corridor_of(3, -0.3, 0.15);
    let refused = b.set_world(0, three, 5).unwrap_err().to_string();
    assert!(
        refused.contains("expected a world placing 2 robots"),
        "{refused}"
    );
    assert!(b.set_world(2, corridor_of(2, 0.0, 0.2), 5).is_err());
}
