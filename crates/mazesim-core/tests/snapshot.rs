//! Snapshots: a restored simulator goes on exactly as the original, in contact with walls and
//! movable bodies and with noise on; snapshots of another world, robot or set-up, truncated or
//! corrupt ones are refused with `Error::Snapshot` and change nothing.

mod common;

use std::sync::Arc;

use common::{sim, world};
use mazesim_core::{Error, RobotProfile, SimConfig, Simulator, World};

/// Everything a step shows, as bits, for exact comparison.
fn trace(s: &Simulator) -> Vec<u64> {
    let mut out: Vec<u64> = s.pose().iter().map(|v| v.to_bits() as u64).collect();
    out.extend(s.distance_sensors().iter().map(|v| v.to_bits() as u64));
    out.extend(s.ground_sensors().iter().map(|v| v.to_bits() as u64));
    out.extend(s.body_poses().iter().flatten().map(|v| v.to_bits() as u64));
    out.extend([
        s.time().to_bits(),
        s.steps(),
        s.collisions(),
        s.colliding() as u64,
        s.wall_clearance().to_bits() as u64,
        s.distance_travelled().to_bits(),
        s.last_crossing() as u64,
        s.crossings().len() as u64,
    ]);
    out.extend(s.encoders().map(f64::to_bits));
    out
}

/// Wheel speeds of step `k`: mostly ahead at full speed (into walls), with turns.
fn speeds(k: u64) -> (f64, f64) {
    match (k / 37) % 4 {
        0 | 1 => (6.2, 6.2),
        2 => (6.2, -2.0),
        _ => (-1.0, 5.0),
    }
}

/// Steps `s` from step `from` for `n` steps and returns the traces.
fn run(s: &mut Simulator, from: u64, n: u64) -> Vec<Vec<u64>> {
    (from..from + n)
        .map(|k| {
            let (l, r) = speeds(k);
            s.step(l, r).unwrap();
            trace(s)
        })
        .collect()
}

/// Snapshots `original` after `before` steps, runs it `after` more, and checks that both a fresh
/// simulator and the original itself, restored, replay those steps bit for bit.
fn check_replay(mut original: Simulator, before: u64, after: u64) {
    run(&mut original, 0, before);
    let snapshot = original.snapshot();
    let expected = run(&mut original, before, after);
    let mut copy = original.duplicate().unwrap();
    copy.restore(&snapshot).unwrap();
    assert_eq!(run(&mut copy, before, after), expected);
    original.restore(&snapshot).unwrap();
    assert_eq!(run(&mut original, before, after), expected);
}

#[test]
fn a_restored_simulator_goes_on_exactly_in_a_maze_with_noise() {
    let world = Arc::new(World::builtin("seed-maze").unwrap());
    let mut s = sim(world, "e-puck", 7, true);
    run(&mut s, 0, 300);
    assert!(
        s.collisions() > 0,
        "the run reaches a wall before the snapshot"
    );
    check_replay(s, 300, 3000);
}

#[test]
fn a_restored_simulator_goes_on_exactly_against_walls_and_movable_bodies() {
    let w = world(
        16.0,
        "[start]\nx = 0\ny = 0\n\n[[bodies]]\nshape = \"box\"\ncenter = [0.12, 0]\n\
         size = [0.05, 0.05]\nmass = 0.1\nfriction = 0.5\n\n[[bodies]]\nshape = \"circle\"\n\
         center = [0.1, 0.12]\nradius = 0.03\nmass = 0.2\nfriction = 0.3\n\n\
         [[walls]]\ncenter = [0.35, 0]\nsize = [0.02, 0.6]\n\n\
         [[walls]]\ncenter = [0, 0.3]\nsize = [0.72, 0.02]\n",
    );
    let mut s = sim(w, "e-puck2", 3, true);
    // Into the box until it touches the wall, so the snapshot falls in contact.
    for _ in 0..60 {
        s.step(7.0, 7.0).unwrap();
    }
    assert!(s.body_poses()[0][0] > 0.18, "{:?}", s.body_poses());
    check_replay(s, 40, 1500);
}

#[test]
fn a_duplicate_is_independent_of_its_original() {
    let world = Arc::new(World::builtin("arena").unwrap());
    let mut a = sim(world, "e-puck", 1, true);
    run(&mut a, 0, 50);
    let mut b = a.duplicate().unwrap();
    let before = trace(&b);
    run(&mut a, 50, 20);
    assert_eq!(trace(&b), before);
    assert_eq!(run(&mut b, 50, 20).last(), Some(&trace(&a)));
}

#[test]
fn a_snapshot_carries_the_seed_and_start_for_later_resets() {
    let world = Arc::new(World::builtin("arena").unwrap());
    let mut a = sim(world.clone(), "e-puck", 1, true);
    a.set_start(0.1, 0.1, 1.0).unwrap();
    a.reset(Some(99));
    let mut b = sim(world, "e-puck", 5, true);
    b.restore(&a.snapshot()).unwrap();
    a.reset(None);
    b.reset(None);
    assert_eq!(run(&mut a, 0, 200), run(&mut b, 0, 200));
}

fn refused(s: &mut Simulator, bytes: &[u8]) -> String {
    let before = trace(s);
    match s.restore(bytes) {
        Err(Error::Snapshot(m)) => {
            assert_eq!(trace(s), before, "a refused snapshot changed the simulator");
            m
        }
        other => panic!("expected a snapshot error, found {other:?}"),
    }
}

#[test]
fn a_snapshot_of_another_world_robot_or_set_up_is_refused() {
    let maze = Arc::new(World::builtin("seed-maze").unwrap());
    let arena = Arc::new(World::builtin("arena").unwrap());
    let snapshot = sim(maze.clone(), "e-puck", 1, true).snapshot();
    let message = refused(&mut sim(arena, "e-puck", 1, true), &snapshot);
    assert!(
        message.contains("\"arena\"") && message.contains("\"seed-maze\""),
        "{message}"
    );
    let message = refused(&mut sim(maze.clone(), "e-puck2", 1, true), &snapshot);
    assert!(message.contains("robot profile \"e-puck2\""), "{message}");
    let message = refused(&mut sim(maze.clone(), "e-puck", 1, false), &snapshot);
    assert!(message.contains("noise off"), "{message}");
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let config = SimConfig {
        control_step: Some(0.064),
        ..SimConfig::default()
    };
    let mut slow = Simulator::new(maze, robot, config).unwrap();
    let message = refused(&mut slow, &snapshot);
    assert!(message.contains("64 ms control step"), "{message}");
}

#[test]
fn truncated_corrupt_or_foreign_bytes_are_refused() {
    let world = Arc::new(World::builtin("seed-maze").unwrap());
    let mut s = sim(world, "e-puck", 1, true);
    run(&mut s, 0, 100);
    let snapshot = s.snapshot();
    for cut in (0..snapshot.len()).step_by(7) {
        refused(&mut s, &snapshot[..cut]);
    }
    let message = refused(&mut s, &snapshot[..snapshot.len() - 1]);
    assert!(message.contains("truncated"), "{message}");
    for at in (0..snapshot.len()).step_by(5) {
        let mut bad = snapshot.clone();
        bad[at] ^= 0x24;
        refused(&mut s, &bad);
    }
    let mut newer = snapshot.clone();
    newer[8] = 99;
    assert!(refused(&mut s, &newer).contains("version 99"));
    assert!(refused(&mut s, b"not a snapshot").contains("expected a simulator snapshot"));
    let mut longer = snapshot.clone();
    longer.push(0);
    refused(&mut s, &longer);
    s.restore(&snapshot).unwrap();
}

/// `bytes` with every occurrence of the robot's pose (three `f32`, as postcard writes them)
/// replaced by `pose`, and the checksum recomputed as the snapshot writer does.
fn edited(bytes: &[u8], from: [f32; 3], pose: [f32; 3]) -> Vec<u8> {
    let encode = |p: [f32; 3]| p.iter().flat_map(|v| v.to_le_bytes()).collect::<Vec<u8>>();
    let (old, new) = (encode(from), encode(pose));
    let mut out = bytes.to_vec();
    let mut at = 0;
    let mut found = 0;
    while let Some(offset) = out[at..]
        .windows(old.len())
        .position(|w| w == old.as_slice())
    {
        out[at + offset..at + offset + new.len()].copy_from_slice(&new);
        at += offset + new.len();
        found += 1;
    }
    assert!(
        found >= 2,
        "the pose is in the state and in the physics body"
    );
    // The header: magic, version, world, robot, physics steps, noise, length, then the checksum.
    let fixed = 8 + 4 + 8 + 8 + 4 + 1 + 8 + 8;
    let hash = mazesim_core::fingerprint::fnv1a_extend(
        mazesim_core::fingerprint::fnv1a(&out[..fixed - 8]),
        &out[fixed..],
    );
    out[fixed - 8..fixed].copy_from_slice(&hash.to_le_bytes());
    out
}

#[test]
fn a_snapshot_edited_far_away_is_refused_like_set_start() {
    let arena = Arc::new(World::builtin("arena").unwrap());
    let mut s = sim(arena.clone(), "e-puck", 3, true);
    for k in 0..5 {
        let (left, right) = speeds(k);
        s.step(left, right).unwrap();
    }
    let pose = s.pose();
    let snapshot = s.snapshot();
    let mut fresh = sim(arena, "e-puck", 3, true);
    let control = edited(&snapshot, pose, pose);
    fresh.restore(&control).unwrap();
    for far in [[1e30, 0.0, 0.0], [0.0, 2000.0, 0.0], [0.0, 0.0, 1e9]] {
        let message = refused(&mut fresh, &edited(&snapshot, pose, far));
        assert!(
            message.contains("robot pose") && message.contains("1000"),
            "{message}"
        );
    }
    let message = refused(&mut fresh, &edited(&snapshot, pose, [f32::NAN, 0.0, 0.0]));
    assert!(message.contains("finite"), "{message}");
}
