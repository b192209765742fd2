#[path = "../../../benches/common/mod.rs"]
mod common;
fn main() {
    let mut sim = common::simulator(1);
    let mut near = 0;
    let n = 20000;
    let t = std::time::Instant::now();
    for _ in 0..n {
        let (l, r) = common::braitenberg(sim.distance_sensors());
        sim.step(l, r).unwrap();
        if sim.wall_clearance() < 0.015 {
            near += 1;
        }
    }
    println!(
        "{:?} per step, near {}/{} collisions {} pose {:?}",
        t.elapsed() / n,
        near,
        n,
        sim.collisions(),
        sim.pose()
    );
}
