use super::*;
use crate::world::World;

fn corridor(gap: f64) -> Arc<World> {
    // Two e-pucks facing each other in a corridor 0.2 m wide, centres 2 * 0.037 + gap apart.
    let half = 0.037 + gap / 2.0;
    let text = format!(
        r#"format = "mazesim-world"
version = 1
name = "corridor"

[[walls]]
center = [0.0, 0.105]
size = [1.0, 0.01]

[[walls]]
center = [0.0, -0.105]
size = [1.0, 0.01]

[[robots]]
name = "west"
x = {}
y = 0.0
yaw = 0.0

[[robots]]
name = "east"
x = {half}
y = 0.0
yaw = 3.141592653589793
"#,
        -half
    );
    Arc::new(World::from_toml(&text, "corridor").unwrap())
}

fn epuck() -> Arc<RobotProfile> {
    Arc::new(RobotProfile::builtin("e-puck").unwrap())
}

#[test]
fn robots_driven_into_each_other_stop_at_contact() {
    let mut swarm = Swarm::new(corridor(0.05), epuck(), SimConfig::default()).unwrap();
    for _ in 0..60 {
        swarm.step(&[[6.0, 6.0], [6.0, 6.0]]).unwrap();
    }
    let [a, b] = [0, 1].map(|i| swarm.robots()[i].pose());
    let gap = (b[0] - a[0]) - 0.074;
    assert!(gap.abs() < 1e-3, "gap {gap}");
    assert!(swarm
        .robots()
        .iter()
        .all(|r| r.colliding() && r.touching_robot()));
    assert!(swarm.robots().iter().all(|r| r.collisions() == 1));
}

#[test]
fn a_world_of_one_robot_steps_as_a_simulator() {
    let world = Arc::new(World::builtin("arena").unwrap());
    let config = SimConfig::default();
    let mut swarm = Swarm::new(world.clone(), epuck(), config).unwrap();
    let mut sim = Simulator::new(world, epuck(), config).unwrap();
    for k in 0..300 {
        let w = [(k % 7) as f64, 6.0 - (k % 5) as f64];
        swarm.step(&[w]).unwrap();
        sim.step(w[0], w[1]).unwrap();
        assert_eq!(swarm.robots()[0].distance_sensors(), sim.distance_sensors());
        assert_eq!(swarm.robots()[0].pose(), sim.pose());
    }
}

#[test]
fn overlapping_starts_are_refused() {
    let err = Swarm::new(corridor(-0.01), epuck(), SimConfig::default())
        .err()
        .unwrap();
    assert!(err.to_string().contains("overlapping robot"), "{err}");
}
