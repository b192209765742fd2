//! Shared set-up of the integration tests: small worlds written as text, simulators and the
//! output buffers of a batch.
#![allow(dead_code)]

use std::sync::Arc;

use mazesim_core::{Batch, RobotProfile, SimConfig, Simulator, StepOutputs, World};

/// A world with the given extra TOML after the header.
pub fn world(time_step_ms: f64, body: &str) -> Arc<World> {
    let text = format!(
        "format = \"mazesim-world\"\nversion = 1\nname = \"test\"\nbasic_time_step_ms = {time_step_ms}\n{body}"
    );
    Arc::new(World::from_toml(&text, "test.toml").expect("test world parses"))
}

/// A simulator of `robot` in `world`.
pub fn sim(world: Arc<World>, robot: &str, seed: u64, noise: bool) -> Simulator {
    let profile = Arc::new(RobotProfile::builtin(robot).unwrap());
    Simulator::new(
        world,
        profile,
        SimConfig {
            seed,
            noise,
            control_step: None,
        },
    )
    .unwrap()
}

/// A simulator of the e-puck in the built-in seed maze, with noise.
pub fn seed_maze_epuck(seed: u64) -> Simulator {
    sim(
        Arc::new(World::builtin("seed-maze").unwrap()),
        "e-puck",
        seed,
        true,
    )
}

/// The output buffers of a batch: observations, poses, collision flags and crossings.
pub struct Buffers {
    pub obs: Vec<f32>,
    pub poses: Vec<f32>,
    pub colliding: Vec<bool>,
    pub crossings: Vec<i32>,
}

impl Buffers {
    /// Buffers of `n` rows, observations `width` wide.
    pub fn new(n: usize, width: usize) -> Self {
        Self {
            obs: vec![0.0; n * width],
            poses: vec![0.0; n * 3],
            colliding: vec![false; n],
            crossings: vec![0; n],
        }
    }

    /// Buffers of the shape of `b`'s outputs.
    pub fn of(b: &Batch) -> Self {
        Self::new(b.len(), b.observation_width())
    }

    /// The buffers as the outputs of a call.
    pub fn out(&mut self) -> StepOutputs<'_> {
        StepOutputs {
            observations: &mut self.obs,
            poses: &mut self.poses,
            colliding: &mut self.colliding,
            crossings: &mut self.crossings,
        }
    }
}
