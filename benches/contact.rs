//! Criterion benches of contact: 1,024 envs of distinct 5 x 5 mazes driven into walls (the
//! contact workload, about nine steps in ten in contact once warmed up) and the same envs
//! steered clear of them by the Braitenberg rule (almost no contact), in env-steps per second.
//! Each starts from 300 warm-up steps, so that the pushing robots have reached their walls.

mod common;

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use mazesim_core::{Batch, OutputBuffers, RobotProfile};

const ENVS: usize = 1024;

struct Workload {
    batch: Batch,
    out: OutputBuffers,
    actions: Vec<f32>,
    step: usize,
}

impl Workload {
    fn new() -> Self {
        let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
        let seeds: Vec<u64> = (0..ENVS as u64).collect();
        let batch = Batch::new(common::distinct_mazes(ENVS), robot, &seeds, true, None, 0).unwrap();
        Workload {
            out: OutputBuffers::of(&batch),
            batch,
            actions: vec![0.0; 2 * ENVS],
            step: 0,
        }
    }

    fn step(&mut self, pushing: bool) {
        let width = self.batch.observation_width();
        for i in 0..ENVS {
            let (l, r) = if pushing {
                common::pushing(self.step, i)
            } else {
                common::braitenberg(&self.out.observations[i * width..i * width + 8])
            };
            self.actions[2 * i] = l as f32;
            self.actions[2 * i + 1] = r as f32;
        }
        self.batch.step(&self.actions, self.out.outputs()).unwrap();
        self.step += 1;
    }
}

fn contact(c: &mut Criterion) {
    let mut g = c.benchmark_group("contact_1024_envs");
    g.throughput(Throughput::Elements(ENVS as u64));
    for (name, pushing) in [("into_walls", true), ("steering_clear", false)] {
        let mut w = Workload::new();
        for _ in 0..300 {
            w.step(pushing);
        }
        g.bench_function(name, |b| b.iter(|| w.step(pushing)));
    }
    g.finish();
}

criterion_group!(benches, contact);
criterion_main!(benches);
