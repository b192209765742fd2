//! Criterion benches of the core: one ray cast, one env step with all sensors read.

mod common;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

fn ray_cast(c: &mut Criterion) {
    let world = common::world();
    let walls = world.wall_index();
    let mut g = c.benchmark_group("ray_cast");
    g.throughput(Throughput::Elements(1));
    g.bench_function("epuck_ps_7cm", |b| {
        let mut a = 0.0f32;
        b.iter(|| {
            a += 0.1;
            let dir = [a.cos(), a.sin()];
            std::hint::black_box(walls.cast_ray([0.125, 1.125], dir, 0.07))
        })
    });
    g.finish();
}

fn env_step(c: &mut Criterion) {
    let mut sim = common::simulator(1);
    let mut g = c.benchmark_group("env_step");
    g.throughput(Throughput::Elements(1));
    g.bench_function("epuck_5x5_braitenberg", |b| {
        b.iter(|| {
            let (l, r) = common::braitenberg(sim.distance_sensors());
            sim.step(l, r).unwrap();
            if sim.steps() > 2000 {
                sim.reset(None);
            }
        })
    });
    g.finish();
}

criterion_group!(benches, ray_cast, env_step);
criterion_main!(benches, physics_benches, batch_benches);

fn body_step(c: &mut Criterion) {
    let world = common::world();
    let mut body =
        mazesim_core::physics::Body::new(world.walls(), &[], 0.037, [0.125, 1.125, 0.0], 0.032);
    let mut g = c.benchmark_group("body_step");
    g.throughput(Throughput::Elements(1));
    let mut i = 0u32;
    g.bench_function("disc_against_walls", |b| {
        b.iter(|| {
            i += 1;
            let w = if (i / 50) % 2 == 0 { 0.0 } else { 2.0 };
            body.step(0.1, w, 0.0, world.wall_index());
        })
    });
    g.finish();
}
criterion_group!(physics_benches, body_step);

fn batch_step(c: &mut Criterion) {
    use mazesim_core::{Batch, OutputBuffers, RobotProfile};
    use std::sync::Arc;
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let mut g = c.benchmark_group("batch_step");
    for n in [1usize, 64, 1024, 4096] {
        let worlds = common::distinct_mazes(n);
        let seeds: Vec<u64> = (0..n as u64).collect();
        let mut b = Batch::new(worlds, robot.clone(), &seeds, true, None, 0).unwrap();
        let w = b.observation_width();
        let mut out = OutputBuffers::new(n, w);
        let mut actions = vec![0f32; 2 * n];
        g.throughput(Throughput::Elements(n as u64));
        g.bench_function(format!("{n}_envs"), |bench| {
            bench.iter(|| {
                for i in 0..n {
                    let (l, r) = common::braitenberg(&out.observations[i * w..i * w + 8]);
                    actions[2 * i] = l as f32;
                    actions[2 * i + 1] = r as f32;
                }
                b.step(&actions, out.outputs()).unwrap();
            })
        });
    }
    g.finish();
}
criterion_group!(batch_benches, batch_step);
