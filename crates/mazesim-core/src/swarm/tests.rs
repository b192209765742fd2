use super::*;
use crate::world::World;

/// A corridor 0.2 m wide between two walls 1 m long, without robots (a world's text).
const CORRIDOR: &str = r#"format = "mazesim-world"
version = 1
name = "corridor"

[[walls]]
center = [0.0, 0.105]
size = [1.0, 0.01]

[[walls]]
center = [0.0, -0.105]
size = [1.0, 0.01]
"#;

fn corridor(gap: f64) -> Arc<World> {
    // Two e-pucks facing each other in a corridor 0.2 m wide, centres 2 * 0.037 + gap apart.
    let half = 0.037 + gap / 2.0;
    let text = format!(
        r#"{CORRIDOR}
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

#[test]
fn a_robot_placed_onto_another_is_pushed_apart_by_the_contacts() {
    let mut swarm = Swarm::new(corridor(0.05), epuck(), SimConfig::default()).unwrap();
    // set_pose keeps robots apart; place puts "east" 2 cm into "west", as a supervisor may.
    let err = swarm.set_pose(1, -0.042, 0.0, 0.0).err().unwrap();
    assert!(err.to_string().contains("overlapping robot 0"), "{err}");
    swarm.place(1, -0.008, 0.0, 0.0).unwrap();
    let gap = |s: &Swarm| {
        let [a, b] = [0, 1].map(|i| s.robots()[i].pose());
        f64::from(b[0] - a[0]) - 0.074
    };
    assert!((gap(&swarm) + 0.02).abs() < 1e-6, "{}", gap(&swarm));
    assert!(swarm.robots().iter().all(|r| r.touching_robot()));
    for _ in 0..5 {
        swarm.step(&[[0.0, 0.0], [0.0, 0.0]]).unwrap();
    }
    assert!(gap(&swarm).abs() < 1e-3, "gap {}", gap(&swarm));
    // Each was pushed by half the overlap.
    let west = swarm.robots()[0].pose()[0] as f64;
    assert!((west - (-0.062 - 0.01)).abs() < 1e-3, "west at {west}");
}

/// A corridor 0.2 m wide: robot "pusher" at x = -0.3 behind a box at x = -0.2, robot "crosser"
/// at `crosser` facing +y, the box's way along the corridor running through its path.
fn box_world(crosser: [f64; 2]) -> Arc<World> {
    let [cx, cy] = crosser;
    let text = format!(
        r#"format = "mazesim-world"
version = 1
name = "box-in-the-way"

[[walls]]
center = [0.0, 0.105]
size = [1.2, 0.01]

[[walls]]
center = [0.0, -0.105]
size = [1.2, 0.01]

[[bodies]]
shape = "box"
center = [-0.2, 0.0]
size = [0.04, 0.04]
mass = 0.05

[[robots]]
name = "pusher"
x = -0.3
y = 0.0

[[robots]]
name = "crosser"
x = {cx}
y = {cy}
yaw = 1.5707963267948966
"#
    );
    Arc::new(World::from_toml(&text, "box-in-the-way").unwrap())
}

#[test]
fn a_robot_pushes_a_box_into_another_robots_path() {
    let config = SimConfig {
        noise: false,
        ..SimConfig::default()
    };
    let mut swarm = Swarm::new(box_world([0.1, -0.06]), epuck(), config).unwrap();
    let start = swarm.robots()[0].body_poses()[0];
    // The crosser waits while the pusher drives the box along the corridor.
    let mut crosser_saw = 0.0f32;
    for _ in 0..120 {
        swarm.step(&[[5.0, 5.0], [0.0, 0.0]]).unwrap();
        let ps = swarm.robots()[1].distance_sensors();
        crosser_saw = crosser_saw.max(ps[0].max(ps[7]).max(ps[1]).max(ps[6]));
    }
    let pushed = swarm.robots()[0].body_poses()[0];
    assert!(
        pushed[0] - start[0] > 0.15,
        "the box was pushed: {pushed:?}"
    );
    // The box went past the crosser's front, which saw it.
    assert!(
        crosser_saw > 200.0,
        "the crosser saw the box: {crosser_saw}"
    );
    // Now the crosser drives across: the box, held by the pusher, or the pusher stops it.
    let before = swarm.robots()[1].pose();
    for _ in 0..60 {
        swarm.step(&[[0.0, 0.0], [5.0, 5.0]]).unwrap();
    }
    let after = swarm.robots()[1].pose();
    let box_now = swarm.robots()[0].body_poses()[0];
    // Nothing went through anything: the crosser's disc does not overlap the box's square
    // (its centre, in the box's frame, at least its radius from the square).
    let (s, c) = box_now[2].sin_cos();
    let [dx, dy] = [after[0] - box_now[0], after[1] - box_now[1]];
    let local = [c * dx + s * dy, c * dy - s * dx];
    let outside = local.map(|v| (v.abs() - 0.02).max(0.0));
    let inside = outside[0].hypot(outside[1]) < 0.037 - 1e-3;
    assert!(!inside, "crosser {after:?} inside the box at {box_now:?}");
    assert!(
        after[1] > before[1],
        "the crosser moved: {before:?} -> {after:?}"
    );
    for robot in swarm.robots() {
        assert!(robot.wall_clearance() > -1e-3, "{}", robot.wall_clearance());
    }
}

#[test]
fn robots_in_contact_with_each_other_and_a_box_run_the_same_in_any_batch() {
    use crate::batch::{Batch, StepOutputs};
    let world = box_world([-0.2, -0.06]);
    let run = |envs: usize, threads: usize| -> Vec<f32> {
        let seeds: Vec<u64> = (0..envs as u64).map(|k| 7 + k % 3).collect();
        let mut batch = Batch::with_swarms(
            vec![world.clone(); envs],
            epuck(),
            &seeds,
            true,
            None,
            threads,
        )
        .unwrap();
        let width = batch.observation_width();
        let mut obs = vec![0.0; envs * 2 * width];
        let mut poses = vec![0.0; envs * 2 * 3];
        let mut colliding = vec![false; envs * 2];
        let mut crossings = vec![0; envs * 2];
        let mut seen = Vec::new();
        let (mut robots_touching, start) = (0, batch.envs()[0].body_poses()[0]);
        for k in 0..80 {
            let actions: Vec<f32> = (0..envs * 4).map(|i| 3.0 + ((i + k) % 4) as f32).collect();
            let out = StepOutputs {
                observations: &mut obs,
                poses: &mut poses,
                colliding: &mut colliding,
                crossings: &mut crossings,
            };
            batch.step(&actions, out).unwrap();
            seen.extend_from_slice(&obs[..2 * width]);
            seen.extend_from_slice(&poses[..6]);
            seen.extend(batch.envs()[0].body_poses().iter().flatten());
            robots_touching += usize::from(batch.envs()[0].touching_robot());
        }
        let moved = batch.envs()[0].body_poses()[0];
        assert!(
            robots_touching > 10,
            "robots in contact {robots_touching} steps"
        );
        assert!(
            (moved[0] - start[0]).abs() + (moved[1] - start[1]).abs() > 0.02,
            "{moved:?}"
        );
        seen
    };
    let reference = run(1, 1);
    for (envs, threads) in [(1, 2), (9, 1), (9, 2)] {
        assert_eq!(
            reference,
            run(envs, threads),
            "{envs} envs, {threads} threads"
        );
    }
}

/// The e-puck with every distance sensor read through Webots' default `DistanceSensor` table
/// (0 at 0 m rising to 1000 at 0.1 m): a profile of the e-puck's name that is not the built-in.
fn webots_default_table_epuck() -> Arc<RobotProfile> {
    let mut profile = RobotProfile::builtin("e-puck").unwrap();
    let model = crate::robot::SensorModel {
        table: crate::lut::LookupTable::new(&[[0.0, 0.0, 0.0], [0.1, 1000.0, 0.0]]).unwrap(),
        ..(*profile.distance_sensors[0].model).clone()
    };
    let model = Arc::new(model);
    for sensor in &mut profile.distance_sensors {
        sensor.model = model.clone();
    }
    Arc::new(profile)
}

#[test]
fn a_robot_given_its_own_profile_reads_through_it_and_the_others_as_before() {
    let config = SimConfig {
        noise: false,
        ..SimConfig::default()
    };
    let world = corridor(0.02);
    let mut before = Swarm::new(world.clone(), epuck(), config).unwrap();
    let own = webots_default_table_epuck();
    let mut swarm =
        Swarm::with_profiles(world.clone(), epuck(), &[None, Some(own.clone())], config).unwrap();
    assert_eq!(swarm.profile_overrides().len(), 2);
    assert!(before.profile_overrides().is_empty());
    assert_eq!(**swarm.robots()[1].robot(), *own);
    for _ in 0..5 {
        before.step(&[[1.0, 1.0], [1.0, 1.0]]).unwrap();
        swarm.step(&[[1.0, 1.0], [1.0, 1.0]]).unwrap();
        // Robot 0 reads as it did; robot 1's front sees robot 0 (2.7 cm away, reflectance 0.38:
        // 0.071 m on the table) on the rising table.
        assert_eq!(
            swarm.robots()[0].distance_sensors(),
            before.robots()[0].distance_sensors()
        );
        let front = swarm.robots()[1].distance_sensors()[0];
        assert!(front > 0.0 && front < 1000.0, "{front}");
        assert_ne!(front, before.robots()[1].distance_sensors()[0]);
        // Its rear ray meets nothing within 0.1 m: the table's last row.
        assert_eq!(swarm.robots()[1].distance_sensors()[3], 1000.0);
    }
    let copy = swarm.duplicate().unwrap();
    assert_eq!(copy.profile_overrides(), swarm.profile_overrides());
}

#[test]
fn a_given_profile_is_not_lent_to_a_placement_naming_its_built_in() {
    let text = corridor(0.05)
        .to_toml()
        .unwrap()
        .replace("name = \"east\"", "name = \"east\"\nprofile = \"e-puck\"");
    let world = Arc::new(World::from_toml(&text, "corridor").unwrap());
    let own = webots_default_table_epuck();
    let swarm =
        Swarm::with_profiles(world, epuck(), &[Some(own), None], SimConfig::default()).unwrap();
    assert_eq!(**swarm.robots()[1].robot(), *epuck());
}

#[test]
fn profiles_for_some_of_the_robots_only_are_refused() {
    let own = Some(webots_default_table_epuck());
    let err = Swarm::with_profiles(corridor(0.05), epuck(), &[own], SimConfig::default())
        .err()
        .unwrap();
    let message = err.to_string();
    assert!(
        message.contains("one per robot of world \"corridor\" (2), found 1"),
        "{message}"
    );
}

/// An e-puck at the origin facing +x, a gate wall (`[[walls]]` entry 0) `gate` m ahead of its
/// centre, and with `with_box` a movable box off to the side.
fn gate_world(gate: f64, with_box: bool) -> Arc<World> {
    let body = if with_box {
        "[[bodies]]\nshape = \"box\"\ncenter = [0.0, 0.3]\nsize = [0.04, 0.04]\nmass = 0.05\n"
    } else {
        ""
    };
    let text = format!(
        r#"format = "mazesim-world"
version = 1
name = "gate"

[start]
x = 0.0
y = 0.0

[[walls]]
center = [{gate}, 0.0]
size = [0.02, 0.2]

[[walls]]
center = [0.8, 0.0]
size = [0.02, 1.0]

{body}"#
    );
    Arc::new(World::from_toml(&text, "gate").unwrap())
}

/// The e-puck of `world` with noiseless sensors.
fn quiet(world: Arc<World>) -> Swarm {
    let config = SimConfig {
        noise: false,
        ..SimConfig::default()
    };
    Swarm::new(world, epuck(), config).unwrap()
}

/// The e-puck's front sensors' sum after one step at rest.
fn front_reading(swarm: &mut Swarm) -> f32 {
    swarm.step(&[[0.0, 0.0]]).unwrap();
    let readings = swarm.robots()[0].distance_sensors();
    readings[0] + readings[7]
}

#[test]
fn a_moved_wall_is_seen_and_met_where_it_is_now() {
    let mut swarm = quiet(gate_world(0.5, false));
    let far = front_reading(&mut swarm);
    let motion = Motion {
        from: [0.5, 0.0, 0.0],
        to: [0.06, 0.0, 0.0],
    };
    swarm.move_solid(&[0], &[], &[], motion).unwrap();
    let near = front_reading(&mut swarm);
    assert!(near > far + 500.0, "front sensors {far} -> {near}");
    for _ in 0..40 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    let x = swarm.robots()[0].pose()[0];
    assert!(
        x < 0.06 - 0.01 - 0.037 + 1e-3,
        "went through the moved wall to x {x}"
    );
    assert!(swarm.robots()[0].collisions() >= 1);
}

/// A world of one robot at (0, 0) and a dark mark 10 cm square at (0.5, 0).
fn marked_world() -> Arc<World> {
    let text = r#"format = "mazesim-world"
version = 1
[start]
x = 0.0
y = 0.0
[[paint]]
shape = "rect"
center = [0.5, 0.0]
size = [0.1, 0.1]
reflectance = 0.1
"#;
    Arc::new(World::from_toml(text, "marked").unwrap())
}

fn ground_sum(swarm: &mut Swarm) -> f32 {
    swarm.step(&[[0.0, 0.0]]).unwrap();
    swarm.robots()[0].ground_sensors().iter().sum()
}

#[test]
fn a_moved_floor_mark_is_read_where_it_is_now() {
    let mut swarm = quiet(marked_world());
    let bare = ground_sum(&mut swarm);
    let bare_again = ground_sum(&mut swarm); // the readers now hold the bare floor around
    assert_eq!(bare, bare_again);
    let under = Motion {
        from: [0.5, 0.0, 0.0],
        to: [0.0, 0.0, 0.0],
    };
    swarm.move_solid(&[], &[], &[0], under).unwrap();
    let dark = ground_sum(&mut swarm);
    assert!(dark < bare * 0.5, "ground sensors {bare} -> {dark}");
    let away = Motion {
        from: under.to,
        to: [0.0, 0.3, 0.0],
    };
    swarm.move_solid(&[], &[], &[0], away).unwrap();
    assert_eq!(ground_sum(&mut swarm), bare);
    // A reset puts the mark back where the world has it.
    swarm.reset_scene();
    assert_eq!(
        swarm.robots()[0].world().floor().reflectance_at([0.5, 0.0]),
        0.1
    );
    let error = swarm.move_solid(&[], &[], &[1], under).unwrap_err();
    assert!(error.to_string().contains("found 1"), "{error}");
}

#[test]
fn moving_a_wall_away_clears_the_way() {
    let mut swarm = Swarm::new(gate_world(0.06, true), epuck(), SimConfig::default()).unwrap();
    for _ in 0..20 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    let blocked = swarm.robots()[0].pose()[0];
    assert!(blocked < 0.02, "x {blocked}");
    // The gate turns a quarter turn about its far end: the corridor ahead is open.
    let motion = Motion {
        from: [0.06, 0.1, 0.0],
        to: [0.06, 0.1, std::f64::consts::FRAC_PI_2],
    };
    swarm.move_solid(&[0], &[], &[], motion).unwrap();
    for _ in 0..40 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    let x = swarm.robots()[0].pose()[0];
    assert!(x > 0.15, "still blocked at x {x}");
}

#[test]
fn a_moved_box_is_seen_and_pushed_from_where_it_was_put() {
    let mut swarm = quiet(gate_world(0.5, true));
    let clear = front_reading(&mut swarm);
    let motion = Motion {
        from: [0.0, 0.3, 0.0],
        to: [0.07, 0.0, 0.3],
    };
    swarm.move_solid(&[], &[0], &[], motion).unwrap();
    let [x, y, yaw] = swarm.robots()[0].body_poses()[0];
    assert!((x - 0.07).abs() < 1e-6 && y.abs() < 1e-6 && (yaw - 0.3).abs() < 1e-6);
    let seen = front_reading(&mut swarm);
    assert!(seen > clear + 150.0, "front sensors {clear} -> {seen}");
    for _ in 0..30 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    assert!(
        swarm.robots()[0].body_poses()[0][0] > 0.1,
        "the box was not pushed"
    );
    let error = swarm
        .move_solid(&[], &[1], &[], motion)
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("below the world's 1 bodies, found 1"),
        "{error}"
    );
}

#[test]
fn the_same_moves_give_the_same_run() {
    let run = || {
        let mut swarm = Swarm::new(gate_world(0.3, true), epuck(), SimConfig::default()).unwrap();
        let mut poses = Vec::new();
        for step in 0..60 {
            if step == 10 {
                let motion = Motion {
                    from: [0.3, 0.0, 0.0],
                    to: [0.12, 0.02, 0.4],
                };
                swarm.move_solid(&[0], &[], &[], motion).unwrap();
                let to_box = Motion {
                    from: [0.0, 0.3, 0.0],
                    to: [0.09, -0.01, 0.2],
                };
                swarm.move_solid(&[], &[0], &[], to_box).unwrap();
            }
            swarm.step(&[[5.0, 6.0]]).unwrap();
            let robot = &swarm.robots()[0];
            poses.push((
                robot.pose(),
                robot.body_poses(),
                robot.distance_sensors().to_vec(),
            ));
        }
        poses
    };
    assert_eq!(run(), run());
}

#[test]
fn moving_the_robot_leaves_a_pushed_box_where_it_is() {
    let mut swarm = quiet(gate_world(0.5, true));
    let motion = Motion {
        from: [0.0, 0.3, 0.0],
        to: [0.07, 0.0, 0.0],
    };
    swarm.move_solid(&[], &[0], &[], motion).unwrap();
    for _ in 0..30 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    let pushed = swarm.robots()[0].body_poses()[0];
    assert!(pushed[0] > 0.1, "the box was not pushed: {pushed:?}");
    swarm.set_pose(0, -0.2, -0.2, 1.0).unwrap();
    assert_eq!(swarm.robots()[0].body_poses()[0], pushed);
    assert_eq!(swarm.robots()[0].pose()[0], -0.2);
}

#[test]
fn resetting_the_scene_puts_robots_walls_and_bodies_back_and_time_goes_on() {
    let made = quiet(gate_world(0.5, true));
    let mut swarm = quiet(gate_world(0.5, true));
    let wall = Motion {
        from: [0.5, 0.0, 0.0],
        to: [0.3, 0.1, 0.5],
    };
    swarm.move_solid(&[0], &[], &[], wall).unwrap();
    let to_box = Motion {
        from: [0.0, 0.3, 0.0],
        to: [0.07, 0.0, 0.0],
    };
    swarm.move_solid(&[], &[0], &[], to_box).unwrap();
    for _ in 0..30 {
        swarm.step(&[[6.0, 5.0]]).unwrap();
    }
    swarm.reset_scene();
    let robot = &swarm.robots()[0];
    assert_eq!(robot.world().walls(), made.robots()[0].world().walls());
    assert_eq!(robot.body_poses(), made.robots()[0].body_poses());
    assert_eq!(robot.body_velocities(), vec![[0.0; 3]]);
    assert_eq!(robot.pose(), made.robots()[0].pose());
    assert_eq!(robot.steps(), 30);
    // From there it runs as the world as made does.
    let mut fresh = quiet(gate_world(0.5, true));
    let (mut a, mut b) = (Vec::new(), Vec::new());
    for _ in 0..20 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
        fresh.step(&[[6.0, 6.0]]).unwrap();
        a.push(swarm.robots()[0].pose());
        b.push(fresh.robots()[0].pose());
    }
    assert_eq!(a, b);
}

#[test]
fn resetting_the_scene_starts_the_noise_streams_again() {
    let noisy = || {
        let config = SimConfig {
            noise: true,
            seed: 7,
            ..SimConfig::default()
        };
        Swarm::new(gate_world(0.1, false), epuck(), config).unwrap()
    };
    let readings = |swarm: &mut Swarm| -> Vec<Vec<f32>> {
        (0..5)
            .map(|_| {
                swarm.step(&[[0.0, 0.0]]).unwrap();
                swarm.robots()[0].distance_sensors().to_vec()
            })
            .collect()
    };
    let mut swarm = noisy();
    let first = readings(&mut swarm);
    assert_ne!(first[0], first[1], "the readings are noisy");
    for _ in 0..10 {
        swarm.step(&[[3.0, 3.0]]).unwrap();
    }
    swarm.reset_scene();
    assert_eq!(readings(&mut swarm), first);
    assert_eq!(readings(&mut noisy()), first);
}

#[test]
fn a_body_set_moving_slides_and_slows() {
    let mut swarm = quiet(gate_world(0.5, true));
    swarm.set_body_velocity(0, [0.0, -0.2, 1.0]).unwrap();
    let [vx, vy, turn] = swarm.robots()[0].body_velocities()[0];
    assert_eq!((vx, vy, turn), (0.0, -0.2, 1.0));
    swarm.step(&[[0.0, 0.0]]).unwrap();
    let [x, y, _] = swarm.robots()[0].body_poses()[0];
    let [_, slower, turn] = swarm.robots()[0].body_velocities()[0];
    // Coulomb friction 0.5: 0.5 g off the speed per second whatever the speed, and the travel
    // of a constant deceleration.
    let (dt, slowing) = (0.032, 0.5 * 9.81);
    let travel = 0.2 * dt - 0.5 * slowing * dt * dt;
    assert!(x.abs() < 1e-6, "body at ({x}, {y})");
    assert!((y - (0.3 - travel)).abs() < 1e-4, "body at ({x}, {y})");
    assert!((slower - (slowing * dt - 0.2)).abs() < 1e-4, "vy {slower}");
    // The turn of a 4 cm box stops within 4 ms at this friction.
    assert_eq!(turn, 0.0);
    let error = swarm
        .set_body_velocity(1, [0.0; 3])
        .unwrap_err()
        .to_string();
    assert!(
        error.contains("below the world's 1 bodies, found 1"),
        "{error}"
    );
    let error = swarm
        .set_body_velocity(0, [f64::NAN, 0.0, 0.0])
        .unwrap_err();
    assert!(error.to_string().contains("vx"), "{error}");
}

#[test]
fn a_sliding_body_stops_after_the_coulomb_distance_whatever_its_speed() {
    // v^2 / (2 mu g): a body twice as fast slides four times as far, to a step's resolution.
    for speed in [0.05_f32, 0.1, 0.2] {
        let mut swarm = quiet(gate_world(0.5, true));
        swarm
            .set_body_velocity(0, [0.0, -f64::from(speed), 0.0])
            .unwrap();
        for _ in 0..20 {
            swarm.step(&[[0.0, 0.0]]).unwrap();
        }
        let [_, y, _] = swarm.robots()[0].body_poses()[0];
        let expected = speed * speed / (2.0 * 0.5 * 9.81);
        assert!(
            ((0.3 - y) - expected).abs() < 7e-4,
            "{speed} m/s: slid {}",
            0.3 - y
        );
        assert_eq!(swarm.robots()[0].body_velocities()[0], [0.0; 3]);
    }
}

#[test]
fn encoders_count_the_turn_since_a_reset_to_the_tick() {
    // Webots' position sensor restarts from its reset joint: the reading after a reset is the
    // turn since, quantised; never the difference of two quantised readings, a tick off.
    let resolution = 0.00628;
    let mut profile = RobotProfile::builtin("e-puck").unwrap();
    profile.encoder_resolution = resolution;
    let config = SimConfig {
        noise: false,
        ..SimConfig::default()
    };
    let mut swarm = Swarm::new(gate_world(0.5, false), Arc::new(profile), config).unwrap();
    let quantised = |a: f64| (a / resolution).round() * resolution;
    // 4.4 ticks before the reset, then 3.3 ticks a step: without dropping the 0.4 of a tick
    // at the reset, the first reading would be 4 ticks (round(7.7) - round(4.4)), not 3.
    let (before_speed, speed) = (0.8635_f64, 0.6476_f64);
    swarm.step(&[[before_speed, before_speed]]).unwrap();
    swarm.reset_scene();
    let [before, _] = swarm.robots()[0].encoders();
    for steps in 1..=4 {
        swarm.step(&[[speed, speed]]).unwrap();
        let turned = f64::from(speed as f32) * 0.032 * f64::from(steps);
        let [after, _] = swarm.robots()[0].encoders();
        assert!(
            (after - before - quantised(turned)).abs() < 1e-9,
            "after {steps} steps: {} for {}",
            after - before,
            quantised(turned)
        );
    }
}

#[test]
fn wheel_turns_are_the_encoders_before_their_rounding() {
    let profile = RobotProfile::builtin("e-puck").unwrap();
    let tick = profile.encoder_resolution;
    let config = SimConfig {
        noise: false,
        ..SimConfig::default()
    };
    let mut swarm = Swarm::new(gate_world(0.5, false), Arc::new(profile), config).unwrap();
    swarm.step(&[[1.0, -0.5]]).unwrap();
    let robot = &swarm.robots()[0];
    let (turns, encoders) = (robot.wheel_turns(), robot.encoders());
    for (turn, speed) in turns.iter().zip([1.0_f64, -0.5]) {
        assert!((turn - speed * 0.032).abs() < 1e-6, "{turn}");
    }
    for (turn, reading) in turns.iter().zip(encoders) {
        assert_eq!(reading, (turn / tick).round() * tick);
        assert!(
            (turn - reading).abs() > 1e-6,
            "0.032 rad is no whole number of ticks"
        );
    }
}

#[test]
fn a_reset_puts_moved_walls_back_too() {
    let made = quiet(gate_world(0.5, false));
    let mut swarm = quiet(gate_world(0.5, false));
    let wall = Motion {
        from: [0.5, 0.0, 0.0],
        to: [0.06, 0.0, 0.0],
    };
    swarm.move_solid(&[0], &[], &[], wall).unwrap();
    swarm.reset(None);
    assert_eq!(
        swarm.robots()[0].world().walls(),
        made.robots()[0].world().walls()
    );
    for _ in 0..40 {
        swarm.step(&[[6.0, 6.0]]).unwrap();
    }
    assert!(
        swarm.robots()[0].pose()[0] > 0.1,
        "held back by the moved wall"
    );
}

#[test]
fn a_changed_world_is_met_from_the_next_step_and_the_robot_goes_on_as_it_was() {
    let mut swarm = quiet(gate_world(0.5, false));
    for _ in 0..5 {
        swarm.step(&[[2.0, 2.0]]).unwrap();
    }
    let robot = &swarm.robots()[0];
    let (pose, time, encoders) = (robot.pose(), robot.time(), robot.encoders());
    let far = front_reading(&mut swarm);
    swarm.change_world(gate_world(0.08, false)).unwrap();
    let robot = &swarm.robots()[0];
    assert!(robot.pose() == pose && robot.encoders() == encoders);
    assert!(robot.time() > time, "the clock goes on");
    let near = front_reading(&mut swarm);
    // The gate, 2.6 cm ahead now, was 45 cm ahead.
    assert!(near > far + 200.0, "front sensors {far} -> {near}");
    // A reset puts back the changed world.
    swarm.reset_scene();
    let after_reset = front_reading(&mut swarm);
    assert!(
        after_reset > far + 100.0,
        "front sensors {far} -> {after_reset}"
    );
}

#[test]
fn a_box_imported_into_a_world_without_bodies_is_pushed_and_a_kept_one_goes_on() {
    let mut swarm = quiet(gate_world(0.5, false));
    swarm.change_world(gate_world(0.5, true)).unwrap();
    assert_eq!(swarm.robots()[0].body_poses().len(), 1);
    swarm.set_body_velocity(0, [0.1, 0.0, 0.0]).unwrap();
    swarm.step(&[[0.0, 0.0]]).unwrap();
    let moving = swarm.robots()[0].body_poses()[0];
    assert!(moving[0] > 0.0);
    // The same box in the next change goes on from where it is; a world without it removes it.
    swarm.change_world(gate_world(0.5, true)).unwrap();
    assert_eq!(swarm.robots()[0].body_poses()[0], moving);
    swarm.change_world(gate_world(0.5, false)).unwrap();
    assert!(swarm.robots()[0].body_poses().is_empty());
    let error = swarm.change_world(corridor(0.05)).unwrap_err().to_string();
    assert!(
        error.contains("running world's 1 robots, found 2"),
        "{error}"
    );
}

#[test]
fn bodies_kept_are_matched_in_order() {
    let world = gate_world(0.5, true);
    let one = world.bodies()[0];
    let mut other = one;
    other.mass = 0.5;
    assert_eq!(
        kept_bodies(&[one, other], &[other, one]),
        vec![Some(1), None]
    );
    assert_eq!(kept_bodies(&[one, other], &[one]), vec![Some(0)]);
    assert_eq!(kept_bodies(&[], &[one]), vec![None]);
}

#[test]
fn a_pose_a_few_millimetres_into_a_wall_is_pushed_out_clear_of_it_and_of_other_robots() {
    let mut swarm = Swarm::new(corridor(0.05), epuck(), SimConfig::default()).unwrap();
    let push =
        |s: &mut Swarm, at: [f64; 2], overlap: bool| s.set_pose_pushed_out(0, at, 0.0, overlap);
    // The north wall's face is at y = 0.1: an e-puck (radius 0.037) at y = 0.066 is 3 mm in.
    assert!(swarm.set_pose(0, -0.3, 0.066, 0.0).is_err());
    let alone = push(&mut swarm, [-0.3, 0.066], false).unwrap();
    let moved = (alone[0] + 0.3).hypot(alone[1] - 0.066);
    assert!(
        moved <= 0.003 + 1e-9 && alone[1] <= 0.064 + 1e-6,
        "{alone:?}"
    );
    assert_eq!(
        swarm.robots()[0].pose(),
        [alone[0] as f32, alone[1] as f32, 0.0]
    );
    // A clear pose is taken as it is; one beyond the limits, or on another robot, is refused
    // (one deeper in a wall than 5 cm: tests/webots/test_webots_supervisor_tree.py).
    assert_eq!(push(&mut swarm, [-0.3, 0.0], false).unwrap(), [-0.3, 0.0]);
    assert!(push(&mut swarm, [2000.0, 0.0], false).is_err());
    let east = swarm.robots()[1].pose().map(f64::from);
    let on_robot = push(&mut swarm, [east[0], east[1]], false).unwrap_err();
    assert!(
        on_robot.to_string().contains("overlapping robot 1"),
        "{on_robot}"
    );
    // Robot 1 2 mm into where robot 0 was pushed out to, from the west: the push out goes on
    // to a pose clear of it too, unless robots may overlap.
    let west = [alone[0] - 0.072, alone[1]];
    swarm.set_pose(0, -0.45, 0.0, 0.0).unwrap();
    swarm.set_pose(1, west[0], west[1], 0.0).unwrap();
    let beside = push(&mut swarm, [-0.3, 0.066], false).unwrap();
    let apart = (beside[0] - west[0]).hypot(beside[1] - west[1]);
    assert!(
        beside != alone && apart >= 0.073 - 1e-6,
        "clear of robot 1: {apart}"
    );
    assert_eq!(push(&mut swarm, [-0.3, 0.066], true).unwrap(), alone);
}

#[test]
fn a_larger_robot_is_checked_at_its_own_start_not_at_the_first_robots() {
    // The first e-puck starts 3 mm from the corridor's wall; a robot of radius 0.064 m fits at
    // its own start in the middle but not at the e-puck's: it was checked there and refused.
    let text = format!(
        r#"{CORRIDOR}
[[robots]]
name = "corner"
x = -0.3
y = 0.06
yaw = 0.0

[[robots]]
name = "big"
x = 0.2
y = 0.0
yaw = 0.0
"#
    );
    let world = Arc::new(World::from_toml(&text, "mixed").unwrap());
    let mut big = RobotProfile::builtin("e-puck").unwrap();
    big.body_radius = 0.064;
    let profiles = [None, Some(Arc::new(big))];
    let swarm = Swarm::with_profiles(world, epuck(), &profiles, SimConfig::default()).unwrap();
    let [corner, big] = [0, 1].map(|i| swarm.robots()[i].pose());
    assert_eq!([corner[0], corner[1]], [-0.3, 0.06]);
    assert_eq!([big[0], big[1]], [0.2, 0.0]);
}
