//! Ground truth of barcode crossings in the built-in seed-maze.

use std::sync::Arc;

use mazesim_core::{RobotProfile, SimConfig, Simulator, World};

fn seed_maze(robot: &str) -> Simulator {
    let world = Arc::new(World::builtin("seed-maze").unwrap());
    let robot = Arc::new(RobotProfile::builtin(robot).unwrap());
    Simulator::new(
        world,
        robot,
        SimConfig {
            seed: 1,
            noise: false,
            control_step: None,
        },
    )
    .unwrap()
}

#[test]
fn driving_east_from_the_start_crosses_checkpoint_1_forward_then_back() {
    for robot in ["e-puck", "seed"] {
        let mut s = seed_maze(robot);
        let cp = s.world().checkpoints()[0].clone();
        assert_eq!(cp.id, 1);
        let mut events = Vec::new();
        for _ in 0..100 {
            s.step(6.0, 6.0).unwrap();
            if s.last_crossing() != 0 {
                events.push((s.last_crossing(), s.steps()));
            }
        }
        assert_eq!(events.len(), 1, "{robot}: {events:?}");
        assert_eq!(events[0].0, 1);
        // The sensor left the code's far end in that step.
        let sensor_x = s.pose()[0] as f64 + 0.03;
        assert!(sensor_x > cp.center[0] + cp.length / 2.0);
        for _ in 0..100 {
            s.step(-6.0, -6.0).unwrap();
        }
        let all: Vec<i32> = s.crossings().iter().map(|c| c.signed_id()).collect();
        assert_eq!(all, vec![1, -1], "{robot}");
        s.reset(None);
        assert!(s.crossings().is_empty() && s.last_crossing() == 0);
    }
}
