//! Contacts with walls resolved without rapier (`mazesim_core::contact`): random and wall-pushing
//! workloads in distinct generated mazes never sink deeper than 0.35 mm, envs of equal worlds
//! share one copy and step as envs of their own copies do, and a batch stays deterministic across
//! thread counts in contact.

use std::sync::Arc;

use mazesim_core::generator::{generate, MazeParams};
use mazesim_core::rng::Rng;
use mazesim_core::{Batch, RobotProfile, StepOutputs, World};

/// The deepest penetration allowed (metres), as rapier's set-up gave before.
const DEEPEST: f32 = 0.35e-3;

#[path = "../../../benches/common/mod.rs"]
mod workload;

use workload::distinct_mazes as mazes;

struct Run {
    batch: Batch,
    observations: Vec<f32>,
    poses: Vec<f32>,
    colliding: Vec<bool>,
    crossings: Vec<i32>,
}

impl Run {
    fn new(worlds: Vec<Arc<World>>, robot: &str, threads: usize) -> Run {
        let n = worlds.len();
        let robot = Arc::new(RobotProfile::builtin(robot).unwrap());
        let seeds: Vec<u64> = (0..n as u64).collect();
        let batch = Batch::new(worlds, robot, &seeds, true, None, threads).unwrap();
        let width = batch.observation_width();
        Run {
            batch,
            observations: vec![0.0; n * width],
            poses: vec![0.0; n * 3],
            colliding: vec![false; n],
            crossings: vec![0; n],
        }
    }

    /// Steps once; returns the share of envs in contact and the deepest penetration (metres).
    fn step(&mut self, actions: &[f32]) -> (f64, f32) {
        let out = StepOutputs {
            observations: &mut self.observations,
            poses: &mut self.poses,
            colliding: &mut self.colliding,
            crossings: &mut self.crossings,
        };
        self.batch.step(actions, out).unwrap();
        let touching = self.colliding.iter().filter(|&&c| c).count();
        let deepest = self
            .batch
            .envs()
            .iter()
            .map(|e| -e.wall_clearance())
            .fold(0.0, f32::max);
        (touching as f64 / self.colliding.len() as f64, deepest)
    }
}

#[test]
fn random_wheel_speeds_never_sink_deeper_than_before() {
    for robot in ["e-puck", "e-puck2"] {
        let mut run = Run::new(mazes(48), robot, 1);
        let max = run.batch.envs()[0].robot().max_wheel_speed;
        let mut rng = Rng::new(5);
        let mut deepest = 0f32;
        let mut actions = vec![0f32; 96];
        for k in 0..4000 {
            // Speeds held for 25 steps, so robots cross corridors and meet walls.
            if k % 25 == 0 {
                for a in actions.iter_mut() {
                    *a = rng.uniform_range(-max, max) as f32;
                }
            }
            deepest = deepest.max(run.step(&actions).1);
        }
        assert!(deepest <= DEEPEST, "{robot}: sank {:.4} mm", deepest * 1e3);
        assert!(deepest < 1e-5, "{robot}: sank {:.6} mm", deepest * 1e3);
    }
}

#[test]
fn robots_pushing_into_walls_stay_out_of_them() {
    let mut run = Run::new(mazes(64), "e-puck2", 2);
    let mut in_contact = 0.0;
    let mut deepest = 0f32;
    for k in 0..1500 {
        let actions: Vec<f32> = (0..64)
            .flat_map(|i| {
                if (k / 150 + i) % 2 == 0 {
                    [7.5, 6.0]
                } else {
                    [6.0, 7.5]
                }
            })
            .collect();
        let (share, deep) = run.step(&actions);
        in_contact += share;
        deepest = deepest.max(deep);
    }
    assert!(
        in_contact / 1500.0 > 0.8,
        "{} in contact",
        in_contact / 1500.0
    );
    assert!(deepest <= DEEPEST, "sank {:.4} mm", deepest * 1e3);
    assert!(deepest < 1e-5, "sank {:.6} mm", deepest * 1e3);
}

fn trace(worlds: Vec<Arc<World>>, threads: usize) -> Vec<u32> {
    let n = worlds.len();
    let mut run = Run::new(worlds, "e-puck", threads);
    let mut out = Vec::new();
    for k in 0..600 {
        let actions: Vec<f32> = (0..n)
            .flat_map(|i| [6.0, 4.0 + (((k / 40) + i) % 5) as f32])
            .collect();
        run.step(&actions);
        out.extend(run.observations.iter().map(|v| v.to_bits()));
        out.extend(run.poses.iter().map(|v| v.to_bits()));
        out.extend(run.colliding.iter().map(|&c| c as u32));
    }
    out
}

#[test]
fn envs_of_equal_worlds_share_one_copy_and_step_alike() {
    let p = MazeParams::default();
    let copies: Vec<Arc<World>> = (0..40)
        .map(|_| Arc::new(generate(&p, 9).unwrap()))
        .collect();
    let shared = Run::new(copies.clone(), "e-puck", 1);
    let first = shared.batch.envs()[0].world();
    assert!(shared
        .batch
        .envs()
        .iter()
        .all(|e| Arc::ptr_eq(e.world(), first)));
    let alone = shared.batch.bytes_per_env();
    let separate = Run::new(mazes(40), "e-puck", 1).batch.bytes_per_env();
    assert!(
        alone * 4 < separate,
        "{alone} bytes per env shared, {separate} distinct"
    );
    assert_eq!(trace(copies.clone(), 1), trace(copies, 2));
}

#[test]
fn contact_heavy_batches_are_the_same_for_any_thread_count() {
    assert_eq!(trace(mazes(48), 1), trace(mazes(48), 2));
    assert_eq!(trace(mazes(48), 2), trace(mazes(48), 0));
}
