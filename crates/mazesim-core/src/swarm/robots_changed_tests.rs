//! `Swarm::change_world_with_robots`: robots a supervisor imports into the running world or
//! removes from it.

use super::*;
use crate::world::World;

/// A corridor 0.2 m wide along x with the robots `(name, x, yaw)` on its axis, and a box far
/// down it when `with_box`.
fn corridor_of(robots: &[(&str, f64, f64)], with_box: bool) -> Arc<World> {
    let mut text = String::from(
        "format = \"mazesim-world\"\nversion = 1\nname = \"corridor\"\n\n\
         [[walls]]\ncenter = [0.0, 0.105]\nsize = [2.0, 0.01]\n\n\
         [[walls]]\ncenter = [0.0, -0.105]\nsize = [2.0, 0.01]\n",
    );
    if with_box {
        text.push_str(
            "\n[[bodies]]\nshape = \"box\"\ncenter = [0.8, 0.0]\nsize = [0.04, 0.04]\nmass = 0.05\n",
        );
    }
    for (name, x, yaw) in robots {
        text.push_str(&format!(
            "\n[[robots]]\nname = \"{name}\"\nx = {x}\ny = 0.0\nyaw = {yaw}\n"
        ));
    }
    Arc::new(World::from_toml(&text, "corridor").unwrap())
}

fn swarm_of(world: Arc<World>) -> Swarm {
    let profile = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    Swarm::new(world, profile, SimConfig::default()).unwrap()
}

const PI: f64 = std::f64::consts::PI;

#[test]
fn an_imported_robot_starts_at_its_pose_on_the_running_clock_and_the_others_go_on() {
    let two = corridor_of(&[("west", -0.5, 0.0), ("east", 0.5, PI)], false);
    let three = corridor_of(
        &[("west", -0.5, 0.0), ("east", 0.5, PI), ("new", 0.0, 0.0)],
        false,
    );
    let mut swarm = swarm_of(two.clone());
    for _ in 0..10 {
        swarm.step(&[[3.0, 3.0], [1.0, 1.0]]).unwrap();
    }
    let before: Vec<_> = (swarm.robots().iter())
        .map(|r| (r.pose(), r.encoders(), r.distance_sensors().to_vec()))
        .collect();
    let time = swarm.robots()[0].time();
    swarm
        .change_world_with_robots(three.clone(), &[Some(0), Some(1), None], &[])
        .unwrap();
    assert_eq!(swarm.len(), 3);
    assert_eq!(swarm.names(), ["west", "east", "new"]);
    for (robot, (pose, encoders, _)) in swarm.robots().iter().zip(&before) {
        assert_eq!((robot.pose(), robot.encoders()), (*pose, *encoders));
    }
    let new = &swarm.robots()[2];
    assert_eq!(new.pose(), [0.0, 0.0, 0.0]);
    assert_eq!((new.encoders(), new.time()), ([0.0, 0.0], time));
    // The kept robots keep their commands; the new one has none until given one.
    swarm.set_command(2, 4.0, 4.0).unwrap();
    swarm.step_commanded().unwrap();
    assert!(swarm.robots()[2].pose()[0] > 0.0, "the new robot drives");
    assert!(swarm.robots()[0].pose()[0] > before[0].0[0], "west goes on");
    // Its noise stream is its own, and the same seed gives the same run.
    let mut again = swarm_of(two);
    for _ in 0..10 {
        again.step(&[[3.0, 3.0], [1.0, 1.0]]).unwrap();
    }
    again
        .change_world_with_robots(three, &[Some(0), Some(1), None], &[])
        .unwrap();
    again.set_command(2, 4.0, 4.0).unwrap();
    again.step_commanded().unwrap();
    for (a, b) in swarm.robots().iter().zip(again.robots()) {
        assert_eq!(a.pose(), b.pose());
        assert_eq!(a.distance_sensors(), b.distance_sensors());
    }
    assert_ne!(
        swarm.robots()[2].config().seed,
        swarm.robots()[1].config().seed
    );
}

#[test]
fn keeping_every_robot_in_order_is_change_world_bit_for_bit() {
    let world = corridor_of(&[("west", -0.5, 0.0), ("east", 0.5, PI)], false);
    let changed = corridor_of(&[("west", -0.5, 0.0), ("east", 0.5, PI)], true);
    let mut plain = swarm_of(world.clone());
    let mut kept = swarm_of(world);
    for swarm in [&mut plain, &mut kept] {
        swarm.step(&[[3.0, 3.0], [2.0, 2.0]]).unwrap();
    }
    plain.change_world(changed.clone()).unwrap();
    kept.change_world_with_robots(changed, &[Some(0), Some(1)], &[])
        .unwrap();
    for _ in 0..30 {
        plain.step(&[[3.0, 3.0], [2.0, 2.0]]).unwrap();
        kept.step(&[[3.0, 3.0], [2.0, 2.0]]).unwrap();
    }
    for (a, b) in plain.robots().iter().zip(kept.robots()) {
        assert_eq!(a.pose(), b.pose());
        assert_eq!(a.distance_sensors(), b.distance_sensors());
    }
}

#[test]
fn a_removed_robot_disappears_and_the_bodies_go_on() {
    let world = corridor_of(&[("west", -0.2, 0.0), ("east", 0.0, PI)], true);
    let mut swarm = swarm_of(world);
    swarm.set_body_velocity(0, [0.1, 0.0, 0.0]).unwrap();
    swarm.step(&[[0.0, 0.0], [0.0, 0.0]]).unwrap();
    let body = swarm.robots()[0].body_poses()[0];
    let west = swarm.robots()[0].pose();
    // East, in west's way, is taken out: west then drives through where it stood.
    let alone = corridor_of(&[("west", -0.2, 0.0)], true);
    swarm
        .change_world_with_robots(alone.clone(), &[Some(0)], &[])
        .unwrap();
    assert_eq!(swarm.len(), 1);
    assert_eq!(swarm.robots()[0].pose(), west);
    assert_eq!(swarm.robots()[0].body_poses()[0], body);
    for _ in 0..60 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    // East stood at 0: west would have been held at -0.074.
    assert!(
        swarm.robots()[0].pose()[0] > 0.0,
        "held back by a removed robot"
    );
    // The first robot taken out: the other one holds the bodies then.
    let mut swarm = swarm_of(corridor_of(&[("west", -0.2, 0.0), ("east", 0.0, PI)], true));
    let only_east = corridor_of(&[("east", 0.0, PI)], true);
    swarm
        .change_world_with_robots(only_east, &[Some(1)], &[])
        .unwrap();
    assert_eq!((swarm.len(), swarm.names()), (1, &["east".to_string()][..]));
    assert_eq!(swarm.robots()[0].body_poses().len(), 1);
    for _ in 0..60 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    // West stood at -0.2: east would have been held at -0.126.
    assert!(
        swarm.robots()[0].pose()[0] < -0.15,
        "held back by a removed robot"
    );
}

#[test]
fn a_robot_list_that_names_no_running_robot_rightly_is_refused() {
    let world = corridor_of(&[("west", -0.5, 0.0), ("east", 0.5, PI)], false);
    let mut swarm = swarm_of(world.clone());
    let error = swarm
        .change_world_with_robots(world.clone(), &[Some(0)], &[])
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("per robot of the new world (2), found 1"),
        "{error}"
    );
    let error = swarm
        .change_world_with_robots(world.clone(), &[Some(1), Some(1)], &[])
        .unwrap_err()
        .to_string();
    assert!(error.contains("found robot 1 twice"), "{error}");
    let error = swarm
        .change_world_with_robots(world, &[Some(0), Some(2)], &[])
        .unwrap_err()
        .to_string();
    assert!(error.contains("found robot 2 past them"), "{error}");
    assert_eq!(swarm.len(), 2);
}

#[test]
fn an_imported_robot_of_its_own_profile_senses_through_it_and_keeps_it() {
    let two = corridor_of(&[("west", -0.5, 0.0), ("east", 0.5, PI)], false);
    let three = corridor_of(
        &[("west", -0.5, 0.0), ("east", 0.5, PI), ("new", 0.0, 0.0)],
        false,
    );
    let mut own = RobotProfile::builtin("e-puck").unwrap();
    own.distance_sensors.truncate(2);
    let own = Arc::new(own);
    let mut swarm = swarm_of(two);
    swarm.step(&[[1.0, 1.0], [1.0, 1.0]]).unwrap();
    let given = [None, None, Some(own.clone())];
    swarm
        .change_world_with_robots(three.clone(), &[Some(0), Some(1), None], &given)
        .unwrap();
    swarm.step_commanded().unwrap();
    let sensors: Vec<usize> = (swarm.robots().iter())
        .map(|r| r.distance_sensors().len())
        .collect();
    assert_eq!(sensors, [8, 8, 2]);
    assert!(Arc::ptr_eq(
        swarm.profile_overrides()[2].as_ref().unwrap(),
        &own
    ));
    // A later import keeps it: the robot is kept, with its own profile.
    swarm
        .change_world_with_robots(three.clone(), &[Some(0), Some(2)], &[])
        .unwrap_err();
    let two_kept = corridor_of(&[("west", -0.5, 0.0), ("new", 0.0, 0.0)], false);
    swarm
        .change_world_with_robots(two_kept, &[Some(0), Some(2)], &[])
        .unwrap();
    assert_eq!(swarm.robots()[1].distance_sensors().len(), 2);
    // A kept robot is given no profile.
    let error = swarm
        .change_world_with_robots(three, &[Some(0), Some(1), None], &[None, Some(own), None])
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("for new robots only, found one for robot 1"),
        "{error}"
    );
    assert_eq!(swarm.len(), 2);
}
