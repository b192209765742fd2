//! Walls that are seen and not touched (`sensed_only = true`, a Webots Solid without a
//! `boundingObject`): infra-red rays meet them, range rays, contacts and the physics do not.

mod common;

use std::sync::Arc;

use common::world;
use mazesim_core::wbt::{Obstacle, WbtImport};
use mazesim_core::world::Motion;
use mazesim_core::{RobotProfile, SimConfig, Simulator, World};

/// A robot with two forward sensors at (0.03, 0) on the same linear table (1000 at 0 m, 0 at
/// 0.1 m): `ir` of an infra-red model, `sonar` of a range model.
fn two_kinds() -> Arc<RobotProfile> {
    let text = "name = \"two-kinds\"\nbody_radius = 0.035\nwheel_radius = 0.02\n\
        axle_length = 0.053\nmax_wheel_speed = 6.28\n\
        [models.ir]\nkind = \"infrared\"\nunit = \"raw\"\ntable = [[0, 1000, 0], [0.1, 0, 0]]\n\
        [models.sonar]\nkind = \"range\"\nunit = \"raw\"\ntable = [[0, 1000, 0], [0.1, 0, 0]]\n\
        [[distance_sensors]]\nname = \"ir\"\nposition = [0.03, 0]\nmodel = \"ir\"\n\
        [[distance_sensors]]\nname = \"sonar\"\nposition = [0.03, 0]\nmodel = \"sonar\"\n";
    Arc::new(RobotProfile::from_toml(text, "two-kinds.toml").unwrap())
}

/// A 1 cm thick wall across the robot's way, its near face 0.055 m ahead of the origin.
fn wall_ahead(sensed_only: bool) -> Arc<World> {
    let key = if sensed_only {
        "sensed_only = true\n"
    } else {
        ""
    };
    world(
        32.0,
        &format!(
            "[[walls]]\ncenter = [0.06, 0.0]\nsize = [0.01, 0.2]\ncolour = [1.0, 0.0, 0.0]\n{key}"
        ),
    )
}

fn simulator(world: Arc<World>) -> Simulator {
    let config = SimConfig {
        seed: 3,
        noise: false,
        control_step: None,
    };
    Simulator::new(world, two_kinds(), config).unwrap()
}

#[test]
fn an_infrared_ray_meets_a_sensed_only_wall_and_a_range_ray_passes_it() {
    // 0.025 m from the sensors to the wall: 750 on the table.
    let solid = simulator(wall_ahead(false));
    assert_eq!(solid.distance_sensors(), &[750.0, 750.0]);
    let sensed = simulator(wall_ahead(true));
    assert_eq!(sensed.distance_sensors()[0], 750.0);
    assert_eq!(
        sensed.distance_sensors()[1],
        0.0,
        "the range ray meets nothing"
    );
}

#[test]
fn a_robot_drives_through_a_sensed_only_wall_untouched() {
    let mut s = simulator(wall_ahead(true));
    for _ in 0..60 {
        s.step(6.0, 6.0).unwrap();
    }
    assert!(
        s.pose()[0] > 0.2,
        "the robot passed the wall: {:?}",
        s.pose()
    );
    assert_eq!(s.collisions(), 0);
    // Behind the wall now, its infra-red ray ahead meets nothing.
    assert_eq!(s.distance_sensors()[0], 0.0);
    // A solid wall stops it.
    let mut blocked = simulator(wall_ahead(false));
    for _ in 0..60 {
        blocked.step(6.0, 6.0).unwrap();
    }
    assert!(blocked.pose()[0] < 0.03, "{:?}", blocked.pose());
    assert!(blocked.collisions() > 0);
}

#[test]
fn a_robot_may_start_inside_a_sensed_only_wall() {
    let w = world(
        32.0,
        "[[walls]]\ncenter = [0.0, 0.0]\nsize = [0.2, 0.2]\nsensed_only = true\n",
    );
    assert!(simulator(w).check_start(0.0, 0.0, 0.0).is_ok());
}

#[test]
fn sensed_only_walls_round_trip_and_stay_apart_from_the_solid_ones() {
    let w = world(
        32.0,
        "[[walls]]\ncenter = [0.5, 0.0]\nsize = [0.01, 0.2]\n\
         [[walls]]\ncenter = [0.06, 0.0]\nsize = [0.01, 0.2]\ncolour = [1.0, 0.0, 0.0]\nsensed_only = true\n\
         [[walls]]\ncenter = [-0.5, 0.0]\nsize = [0.01, 0.2]\ncolour = [0.0, 0.0, 1.0]\n",
    );
    assert_eq!(w.walls().len(), 2);
    assert_eq!(w.solid_walls().len(), 2);
    assert_eq!(w.wall_colours(), vec![None, Some([0.0, 0.0, 1.0])]);
    let sensed = w.sensed_walls().expect("one sensed-only wall");
    assert_eq!(sensed.walls().len(), 1);
    assert_eq!(sensed.walls()[0].center, [0.06, 0.0]);
    assert_eq!(sensed.colours(), &[Some([1.0, 0.0, 0.0])]);
    let text = w.to_toml().unwrap();
    assert_eq!(text.matches("sensed_only = true").count(), 1, "{text}");
    let again = World::from_toml(&text, "again.toml").unwrap();
    assert_eq!(again, *w);
    assert_eq!(again.sensed_walls().unwrap().walls(), sensed.walls());
    // A world without any writes no key and holds none.
    let plain = wall_ahead(false);
    assert!(plain.sensed_walls().is_none());
    assert!(!plain.to_toml().unwrap().contains("sensed_only"));
}

#[test]
fn a_supervisor_moves_a_sensed_only_wall_with_its_index() {
    let w = world(
        32.0,
        "[[walls]]\ncenter = [0.5, 0.0]\nsize = [0.01, 0.2]\n\
         [[walls]]\ncenter = [0.06, 0.0]\nsize = [0.01, 0.2]\nsensed_only = true\n\
         [[walls]]\ncenter = [-0.5, 0.0]\nsize = [0.01, 0.2]\n",
    );
    let motion = Motion {
        from: [0.0, 0.0, 0.0],
        to: [0.0, 1.0, 0.0],
    };
    let moved = w.with_walls_moved(&[1, 2], motion).unwrap();
    assert_eq!(moved.sensed_walls().unwrap().walls()[0].center, [0.06, 1.0]);
    assert_eq!(moved.walls()[0].center, [0.5, 0.0]);
    assert_eq!(moved.walls()[1].center, [-0.5, 1.0]);
    let ray = moved
        .sensed_walls()
        .unwrap()
        .cast_ray([0.0, 1.0], [1.0, 0.0], 0.1);
    assert!((ray.unwrap().distance - 0.055).abs() < 1e-6);
}

/// A Webots world with an e-puck at the origin facing +x, a red 5 cm tall box whose near face is
/// 5 cm ahead of its centre (a Solid, with a `boundingObject` when `bounded`), a flat red goal
/// disc on the floor ahead of the box, and a post 20 cm up (over the rays).
fn goal_world(bounded: bool) -> String {
    let bounding = if bounded {
        "boundingObject Box { size 0.1 0.1 0.05 }"
    } else {
        ""
    };
    format!(
        "#VRML_SIM R2023b utf8\nWorldInfo {{ basicTimeStep 32 }}\n\
         E-puck {{ translation 0 0 0 controller \"void\" }}\n\
         Solid {{ translation 0.1 0 0.025 children [ Shape {{ appearance PBRAppearance {{ \
         baseColor 1 0 0 }} geometry Box {{ size 0.1 0.1 0.05 }} }} ] name \"goal\" {bounding} }}\n\
         Solid {{ translation 0.3 0 0.0005 children [ Shape {{ appearance PBRAppearance {{ \
         baseColor 1 0 0 }} geometry Cylinder {{ radius 0.05 height 0.001 }} }} ] name \"disc\" }}\n\
         Solid {{ translation -0.3 0 0.2 children [ Shape {{ geometry Box {{ size 0.05 0.05 0.05 }} \
         }} ] name \"lamp\" }}\n"
    )
}

fn epuck(world: World) -> Simulator {
    let profile = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let config = SimConfig {
        seed: 1,
        noise: false,
        control_step: None,
    };
    Simulator::new(Arc::new(world), profile, config).unwrap()
}

#[test]
fn a_solid_without_bounding_object_in_the_rays_is_sensed_only_and_read_as_webots_reads_it() {
    let import = WbtImport::from_text(&goal_world(false), "goal.wbt").unwrap();
    assert!(import.obstacles.is_empty(), "{:?}", import.obstacles);
    assert_eq!(import.sensed_obstacles.len(), 1, "{:?}", import.warnings);
    let Obstacle::Box { center, size, .. } = import.sensed_obstacles[0] else {
        panic!("a box")
    };
    assert_eq!((center, size), ([0.1, 0.0], [0.1, 0.1]));
    let colours: Vec<_> = import.sensed_looks.iter().map(|look| look.colour).collect();
    assert_eq!(colours, vec![Some([1.0, 0.0, 0.0])]);
    // The flat disc stays floor paint, the post over the rays a warning.
    assert_eq!(import.paint.len(), 1);
    assert!(import.warnings.iter().any(
        |w| w.starts_with("line 6: Shape") && w.contains("out of the proximity sensors' rays")
    ));
    let world = import.to_world("goal").unwrap();
    assert!(world.walls().is_empty());
    assert_eq!(world.sensed_walls().unwrap().walls().len(), 1);
    let again = World::from_toml(&world.to_toml().unwrap(), "goal.toml").unwrap();
    assert_eq!(again, world);
    // Webots' infra-red rays meet the shape itself, with or without a bounding object: the
    // front sensors read what they read of the same box as a wall.
    let seen = epuck(world);
    let walled = WbtImport::from_text(&goal_world(true), "walled.wbt").unwrap();
    assert_eq!(walled.obstacles.len(), 1);
    assert!(walled.sensed_obstacles.is_empty());
    let wall = epuck(walled.to_world("walled").unwrap());
    let free = epuck(World::from_toml(&world_text(""), "free.toml").unwrap());
    for ps in [0, 7] {
        assert_eq!(
            seen.distance_sensors()[ps],
            wall.distance_sensors()[ps],
            "ps{ps}"
        );
        assert!(
            seen.distance_sensors()[ps] > 2.0 * free.distance_sensors()[ps],
            "ps{ps}"
        );
    }
}

fn world_text(body: &str) -> String {
    format!("format = \"mazesim-world\"\nversion = 1\nname = \"t\"\n{body}")
}

#[test]
fn an_import_names_the_nodes_holding_each_sensed_only_wall_and_its_walls_after_the_solid_ones() {
    // A wall Solid, a round post (a ring of walls) and a visual-only box a supervisor may move.
    let text = "#VRML_SIM R2023b utf8\nWorldInfo { }\n\
        Solid { translation 0.5 0 0.05 children [ Shape { geometry DEF W Box { size 0.02 0.3 0.1 } } ] boundingObject USE W }\n\
        Solid { translation -0.5 0 0.05 children [ Shape { geometry DEF P Cylinder { radius 0.05 height 0.1 } } ] name \"post\" boundingObject USE P }\n\
        DEF PED Solid { translation 0 0.5 0.05 children [ Shape { geometry Box { size 0.1 0.1 0.1 } } ] name \"ped\" }\n\
        E-puck { }\n";
    let import = WbtImport::from_text(text, "ped.wbt").unwrap();
    let solid = import.obstacle_walls();
    let after = solid.last().map(|&(first, n)| first + n).unwrap();
    assert!(after > 2, "the post is a ring: {solid:?}");
    assert_eq!(import.sensed_walls(), vec![(after, 1)]);
    assert_eq!(import.sensed_owners, vec![vec![5]]);
    // Those are the indices of the world's `[[walls]]` entries the sensed-only box became.
    let spec = import.to_spec("ped");
    assert!(spec.walls[after].sensed_only && !spec.walls[after - 1].sensed_only);
    assert_eq!(spec.walls.len(), after + 1);
}
