//! Steps a batch of distinct 5 x 5 mazes under one workload and prints env-steps per second, the
//! share of steps in contact and the deepest penetration (for callgrind and quick comparisons).
//! `contact` drives ahead into walls with a slight curve, `free` steers clear by the Braitenberg
//! rule, `random` draws uniform wheel speeds held for 25 steps (so that robots cross corridors
//! and meet walls); `random 4096 8000 2` is the long penetration check (32.8M env-steps).
//!
//! `cargo run --release --example workload -- <contact|free|random> <envs> <steps> <threads>`
use mazesim_core::rng::Rng;
use mazesim_core::{Batch, OutputBuffers, RobotProfile};
use std::sync::Arc;
#[path = "../../../benches/common/mod.rs"]
mod common;

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let workload = args.get(1).map_or("contact", String::as_str).to_string();
    let arg = |i: usize, d: usize| args.get(i).and_then(|s| s.parse().ok()).unwrap_or(d);
    let (n, steps, threads) = (arg(2, 1024), arg(3, 300), arg(4, 1));
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let seeds: Vec<u64> = (0..n as u64).collect();
    let mut b = Batch::new(
        common::distinct_mazes(n),
        robot,
        &seeds,
        true,
        None,
        threads,
    )
    .unwrap();
    let w = b.observation_width();
    let mut out = OutputBuffers::new(n, w);
    let mut actions = vec![0f32; 2 * n];
    let mut rng = Rng::new(1);
    let max = b.envs()[0].robot().max_wheel_speed;
    let (mut contact, mut deepest) = (0u64, 0f32);
    let started = std::time::Instant::now();
    for k in 0..steps {
        for i in 0..n {
            let (l, r) = match workload.as_str() {
                "contact" => common::pushing(k, i),
                "free" => common::braitenberg(&out.observations[i * w..i * w + 8]),
                _ if k % 25 == 0 => (rng.uniform_range(-max, max), rng.uniform_range(-max, max)),
                _ => (actions[2 * i] as f64, actions[2 * i + 1] as f64),
            };
            actions[2 * i] = l as f32;
            actions[2 * i + 1] = r as f32;
        }
        b.step(&actions, out.outputs()).unwrap();
        contact += out.colliding.iter().filter(|&&c| c).count() as u64;
        for env in b.envs() {
            deepest = deepest.min(env.wall_clearance());
        }
    }
    let secs = started.elapsed().as_secs_f64();
    println!(
        "{workload}: {n} envs x {steps} steps: {:.0} env-steps/s, {:.1} % in contact, deepest {:.4} mm",
        (n * steps) as f64 / secs,
        100.0 * contact as f64 / (n * steps) as f64,
        -deepest * 1000.0
    );
}
