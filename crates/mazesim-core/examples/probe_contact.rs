//! Instructions per physics step while the body pushes into a wall (run under callgrind).
fn main() {
    use mazesim_core::world::WallBox;
    let walls = [WallBox {
        center: [0.3, 0.0],
        half: [0.005, 0.5],
        yaw: 0.0,
        reflectance: 1.0,
    }];
    let mut body = mazesim_core::physics::Body::new(&walls, &[], 0.037, [0.25, 0.0, 0.3], 0.032);
    let n: usize = std::env::var("STEPS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(1000);
    for _ in 0..n {
        body.step(0.12, 0.0, 0.0);
    }
    println!("{:?}", body.pose());
}
