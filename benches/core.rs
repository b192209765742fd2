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
criterion_main!(benches, physics_benches);

fn body_step(c: &mut Criterion) {
    let world = common::world();
    let mut body =
        mazesim_core::physics::Body::new(world.walls(), 0.037, [0.125, 1.125, 0.0], 0.032);
    let mut g = c.benchmark_group("body_step");
    g.throughput(Throughput::Elements(1));
    let mut i = 0u32;
    g.bench_function("rapier_only", |b| {
        b.iter(|| {
            i += 1;
            let w = if (i / 50) % 2 == 0 { 0.0 } else { 2.0 };
            body.step(0.1, w, 0.0);
        })
    });
    g.finish();
}
criterion_group!(physics_benches, body_step);
