//! Criterion bench of the multi-step call against single steps: 1024 envs, 100 control steps per
//! iteration, the controller in the core either way (computed between `step` calls, or inside
//! `run_steps`). Throughput is in env-steps.

mod common;

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use mazesim_core::control::avoid_collision::EPUCK_MAX_SPEED;
use mazesim_core::control::braitenberg;
use mazesim_core::navigator::TabularPolicy;
use mazesim_core::rng::Rng;
use mazesim_core::{Batch, Controller, OutputBuffers, RobotProfile, RunOptions, RunTrace};

const ENVS: usize = 1024;
const STEPS: usize = 100;

fn batch(robot: &str) -> Batch {
    let profile = Arc::new(RobotProfile::builtin(robot).unwrap());
    let seeds: Vec<u64> = (0..ENVS as u64).collect();
    Batch::new(common::distinct_mazes(ENVS), profile, &seeds, true, None, 0).unwrap()
}

fn random_policy() -> TabularPolicy {
    let mut rng = Rng::new(0);
    let values = (0..4096 * 12).map(|_| rng.uniform()).collect();
    TabularPolicy::new(values, 1, None, None, 0.1).unwrap()
}

fn run_against_steps(c: &mut Criterion) {
    let mut g = c.benchmark_group("run_vs_steps_1024_envs");
    g.sample_size(10);
    g.throughput(Throughput::Elements((ENVS * STEPS) as u64));
    let options = RunOptions {
        steps: STEPS,
        max_episode_steps: 1000,
        end_at_goal: false,
        end_at_crossing: false,
        autoreset: true,
    };
    let seeds: Vec<u64> = (0..ENVS as u64).collect();
    let policy = random_policy();
    let controllers = [
        ("braitenberg", "e-puck", Controller::Braitenberg),
        (
            "tabular",
            "seed",
            Controller::Tabular(Box::new(policy.clone())),
        ),
    ];
    for (name, robot, controller) in controllers {
        let mut b = batch(robot);
        let mut state = OutputBuffers::of(&b);
        g.bench_function(BenchmarkId::new("run", name), |bench| {
            bench.iter(|| {
                let trace = RunTrace::default();
                b.run_steps(&controller, &seeds, &options, state.outputs(), trace)
                    .unwrap()
            })
        });
        let mut b = batch(robot);
        let mut state = OutputBuffers::of(&b);
        b.observe(state.outputs()).unwrap();
        let w = b.observation_width();
        let mut streams: Vec<Rng> = seeds.iter().map(|&s| Rng::new(s)).collect();
        let mut actions = vec![0f32; 2 * ENVS];
        g.bench_function(BenchmarkId::new("single_steps", name), |bench| {
            bench.iter(|| {
                for _ in 0..STEPS {
                    for i in 0..ENVS {
                        let obs = &state.observations[i * w..(i + 1) * w];
                        let [l, r] = match &controller {
                            Controller::Tabular(p) => {
                                let a = p.action(i, obs, &mut streams[i]);
                                let [l, r] = mazesim_core::navigator::WHEEL_SPEED_FRACTIONS[a];
                                [(l * EPUCK_MAX_SPEED) as f32, (r * EPUCK_MAX_SPEED) as f32]
                            }
                            _ => braitenberg::wheel_speeds(&obs[..8]),
                        };
                        actions[2 * i] = l;
                        actions[2 * i + 1] = r;
                    }
                    b.step(&actions, state.outputs()).unwrap();
                    let ended: Vec<bool> = b.envs().iter().map(|e| e.steps() >= 1000).collect();
                    if ended.iter().any(|&e| e) {
                        b.reset(Some(&ended), None, state.outputs()).unwrap();
                    }
                }
            })
        });
    }
    g.finish();
}

criterion_group!(run_benches, run_against_steps);
criterion_main!(run_benches);
