//! The canonical workload of the benchmarks (docs/performance.md): a 5 x 5 maze of 0.25 m cells and
//! 0.01 m walls, the e-puck with ps0-7 and gs0-2, a 32 ms control step of one physics step, and
//! wheel speeds from a Braitenberg rule.
#![allow(dead_code)]

use std::sync::Arc;

use mazesim_core::{RobotProfile, SimConfig, Simulator, World};

/// The 5 x 5 maze of the workload.
pub const MAZE: &str = r#"
format = "mazesim-world"
version = 1
name = "bench-5x5"
basic_time_step_ms = 32
[grid]
cell_size = 0.25
wall_thickness = 0.01
map = """
+--+--+--+--+--+
|S    |        |
+--+  +  +--+  +
|     |  |     |
+  +--+  +  +--+
|  |     |     |
+  +  +--+--+  +
|     |       G|
+  +--+  +--+  +
|        |     |
+--+--+--+--+--+
"""
"#;

/// The workload's world.
pub fn world() -> Arc<World> {
    Arc::new(World::from_toml(MAZE, "bench-5x5").unwrap())
}

/// An e-puck in the workload's world.
pub fn simulator(seed: u64) -> Simulator {
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    Simulator::new(
        world(),
        robot,
        SimConfig {
            seed,
            noise: true,
            control_step: None,
        },
    )
    .unwrap()
}

/// Braitenberg wheel speeds from the eight e-puck proximity readings (rad/s): each side's
/// activation turns the robot away from that side, and a frontal
/// obstacle turns it left so that it never stalls square to a wall.
pub fn braitenberg(ps: &[f32]) -> (f64, f64) {
    let a = |i: usize| ((ps[i] as f64 - 67.19) / 300.0).clamp(0.0, 1.0);
    let right_side = a(0) + 0.7 * a(1) + 0.4 * a(2);
    let left_side = a(7) + 0.7 * a(6) + 0.4 * a(5);
    let front = 0.5 * (a(0) + a(7));
    let base = 5.0 * (1.0 - front);
    let turn = 4.0 * (right_side - left_side) + 6.0 * front;
    (base - turn, base + turn)
}

/// Wheel speeds of the contact workload for env `i` at step `k`: ahead at nearly full speed with
/// a slight curve whose side changes every 150 steps, so that robots drive into walls and keep
/// pushing along them (nine steps in ten in contact once they have reached one).
pub fn pushing(k: usize, i: usize) -> (f64, f64) {
    if (k / 150 + i) % 2 == 0 {
        (6.0, 5.0)
    } else {
        (5.0, 6.0)
    }
}

/// `n` distinct generated 5 x 5 mazes (seeds 0..n, a tenth of the walls opened into loops).
pub fn distinct_mazes(n: usize) -> Vec<Arc<World>> {
    use mazesim_core::generator::{generate, MazeParams};
    let p = MazeParams {
        loops: 0.1,
        ..Default::default()
    };
    (0..n as u64)
        .map(|s| Arc::new(generate(&p, s).unwrap()))
        .collect()
}
