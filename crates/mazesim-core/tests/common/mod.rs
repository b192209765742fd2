//! Shared set-up of the integration tests: small worlds written as text, and simulators.
#![allow(dead_code)]

use std::sync::Arc;

use mazesim_core::{RobotProfile, SimConfig, Simulator, World};

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
