use mazesim_core::generator::{generate, MazeParams};
use mazesim_core::{Batch, RobotProfile, StepOutputs};
use std::sync::Arc;
#[path = "../../../benches/common/mod.rs"]
mod common;
fn main() {
    let n: usize = std::env::args().nth(1).unwrap().parse().unwrap();
    let threads: usize = std::env::args().nth(2).unwrap().parse().unwrap();
    let p = MazeParams {
        loops: 0.1,
        ..Default::default()
    };
    let worlds: Vec<_> = (0..n)
        .map(|i| Arc::new(generate(&p, i as u64).unwrap()))
        .collect();
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let seeds: Vec<u64> = (0..n as u64).collect();
    let mut b = Batch::new(worlds, robot, &seeds, true, None, threads).unwrap();
    let mut obs = vec![0f32; n * 11];
    let mut poses = vec![0f32; n * 3];
    let mut col = vec![false; n];
    let mut cr = vec![0i32; n];
    let mut actions = vec![0f32; n * 2];
    let steps: usize = std::env::var("STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(2_000_000 / n + 20);
    let t = std::time::Instant::now();
    for _ in 0..steps {
        for i in 0..n {
            let (l, r) = common::braitenberg(&obs[i * 11..i * 11 + 8]);
            actions[2 * i] = l as f32;
            actions[2 * i + 1] = r as f32;
        }
        b.step(
            &actions,
            StepOutputs {
                observations: &mut obs,
                poses: &mut poses,
                colliding: &mut col,
                crossings: &mut cr,
            },
        )
        .unwrap();
    }
    let el = t.elapsed().as_secs_f64();
    println!(
        "n {n} threads {threads}: {:.0} env-steps/s",
        (n * steps) as f64 / el
    );
}
