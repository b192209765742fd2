//! Tests of the batch: rows set apart, panics and interrupts, profiles of several kinds.

use super::*;
use crate::limits::{MAX_ENVS, MAX_THREADS};

fn batch(n: usize, threads: usize, control_step: Option<f64>) -> Batch {
    let world = Arc::new(World::builtin("arena").unwrap());
    let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let seeds: Vec<u64> = (0..n as u64).collect();
    Batch::new(vec![world; n], robot, &seeds, true, control_step, threads).unwrap()
}

#[test]
fn set_starts_at_moves_the_listed_envs_only() {
    let mut b = batch(3, 1, None);
    let mut out = OutputBuffers::of(&b);
    b.reset(None, None, out.outputs()).unwrap();
    let before = out.poses.clone();
    b.set_starts_at(&[2], &[0.1, -0.1, 1.0]).unwrap();
    b.reset(None, None, out.outputs()).unwrap();
    assert_eq!(&out.poses[..6], &before[..6]);
    assert!((out.poses[6] - 0.1).abs() < 1e-6 && (out.poses[7] + 0.1).abs() < 1e-6);
    let bad = b.set_starts_at(&[0, 3], &[0.0; 6]).unwrap_err().to_string();
    assert!(bad.contains("below 3, found 3"), "{bad}");
    let short = b.set_starts_at(&[0, 1], &[0.0; 3]).unwrap_err().to_string();
    assert!(short.contains("shape (2, 3)"), "{short}");
}

#[test]
fn set_goals_at_sets_the_listed_envs_goals_checked_first() {
    let mut b = batch(3, 1, None);
    let world_goal = b.envs()[0].goal();
    b.set_goals_at(&[1], &[0.3, 0.2, 0.05]).unwrap();
    assert_eq!(b.envs()[0].goal(), world_goal);
    let own = b.envs()[1].goal().unwrap();
    assert_eq!((own.center, own.radius), ([0.3, 0.2], 0.05));
    let rows = [0.1, 0.1, 0.05, 0.1, 0.1, -1.0];
    let bad = b.set_goals_at(&[0, 2], &rows).unwrap_err().to_string();
    assert!(
        bad.contains("environment 2") && bad.contains("radius"),
        "{bad}"
    );
    assert_eq!(b.envs()[0].goal(), world_goal, "nothing applied");
    let far = b.set_goals_at(&[0], &[f64::NAN, 0.0, 0.1]).unwrap_err();
    assert!(far.to_string().contains("goal's x"), "{far}");
    let index = b.set_goals_at(&[3], &[0.1, 0.1, 0.1]).unwrap_err();
    assert!(index.to_string().contains("below 3, found 3"), "{index}");
    // A snapshot carries the environment's own goal.
    let snapshot = b.envs()[1].snapshot();
    b.env_mut(0).unwrap().restore(&snapshot).unwrap();
    assert_eq!(b.envs()[0].goal(), Some(own));
}

#[test]
fn a_panic_while_stepping_reaches_the_caller_and_the_batch_goes_on() {
    let mut b = batch(96, 3, None);
    let mut out = OutputBuffers::of(&b);
    let caught = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        b.run(out.outputs(), |i, _, _| assert!(i != 70, "env {i} broke"))
    }));
    let payload = caught.expect_err("the panic comes back");
    assert!(payload.downcast_ref::<String>().unwrap().contains("env 70"));
    b.step(&vec![1.0; 192], out.outputs()).unwrap();
}

#[test]
fn an_interrupt_stops_a_long_step() {
    // 64 environments of 10,000 physics steps each: minutes without the interrupt.
    let mut b = batch(64, 2, Some(320.0));
    b.set_interrupt(Box::new(|| true));
    let mut out = OutputBuffers::of(&b);
    let started = Instant::now();
    let result = b.step(&vec![6.0; 128], out.outputs());
    assert!(matches!(result, Err(Error::Interrupted)));
    assert!(started.elapsed() < Duration::from_secs(30));
}

/// Steps `batch` (one env per robot of `robots`, all in `world`, seeded `seeds`) `steps`
/// times with wheel speeds `actions`, and each env alone in a batch of its own as many times:
/// both end at the same pose with the same readings.
fn assert_each_steps_as_alone(
    batch: &mut Batch,
    world: &Arc<World>,
    robots: &[Arc<RobotProfile>],
    seeds: &[u64],
    actions: &[f32],
    steps: usize,
) {
    let mut out = OutputBuffers::of(batch);
    for _ in 0..steps {
        batch.step(actions, out.outputs()).unwrap();
    }
    for (i, robot) in robots.iter().enumerate() {
        let mut alone = Batch::new(
            vec![world.clone()],
            robot.clone(),
            &seeds[i..=i],
            true,
            None,
            1,
        )
        .unwrap();
        let mut one = OutputBuffers::of(&alone);
        for _ in 0..steps {
            alone
                .step(&actions[2 * i..2 * i + 2], one.outputs())
                .unwrap();
        }
        assert_eq!(&out.poses[3 * i..3 * i + 3], &one.poses[..], "env {i}");
        assert_eq!(
            &out.observations[7 * i..7 * i + 7],
            &one.observations[..],
            "env {i}"
        );
    }
}

#[test]
fn profiles_parsed_apart_share_their_sensor_channels_and_step_as_each_alone() {
    // Each robot of a randomised batch is perturbed from its own parse of a profile: the
    // batch reads one copy of their equal sensor channels (models and all), each robot its
    // own rays and imperfections, and each steps as in a batch of its own.
    let world = Arc::new(World::builtin("seed-maze").unwrap());
    let robots: Vec<Arc<RobotProfile>> = (0..3)
        .map(|k| {
            let parsed = RobotProfile::builtin("seed").unwrap();
            let p = crate::Perturbation {
                ground_gain: 0.9 + 0.1 * k as f64,
                ir_angle_error: 0.02 * k as f64,
                ..Default::default()
            };
            Arc::new(parsed.perturbed(&p).unwrap())
        })
        .collect();
    let model = |robot: &RobotProfile, k: usize| robot.distance_sensors[k].model.clone();
    assert!(!Arc::ptr_eq(&model(&robots[0], 0), &model(&robots[1], 0)));
    let seeds = [7, 8, 9];
    let mut batch =
        Batch::with_robots(vec![world.clone(); 3], &robots, &seeds, true, None, 2).unwrap();
    let first = batch.envs()[0].rig().clone();
    for (i, (env, robot)) in batch.envs().iter().zip(&robots).enumerate() {
        assert!(Arc::ptr_eq(env.robot(), robot));
        assert!(env.rig().shares_channels_with(&first), "env {i}");
        assert_eq!(Arc::ptr_eq(env.rig(), &first), i == 0, "env {i}");
    }
    // A rig made alone has channel lists of its own.
    assert!(!Rig::new(robots[0].clone()).shares_channels_with(&first));
    let actions: Vec<f32> = (0..6).map(|k| 2.0 + (k % 4) as f32).collect();
    assert_each_steps_as_alone(&mut batch, &world, &robots, &seeds, &actions, 40);
}

#[test]
fn envs_of_several_profiles_step_as_each_alone() {
    let world = Arc::new(World::builtin("seed-maze").unwrap());
    let seed = Arc::new(RobotProfile::builtin("seed").unwrap());
    let faster = Arc::new(
        seed.perturbed(&crate::Perturbation {
            wheel_radius_scale: 1.05,
            noise_scale: 2.0,
            ..Default::default()
        })
        .unwrap(),
    );
    let robots = vec![seed.clone(), faster.clone(), seed.clone(), faster];
    let seeds = [3, 4, 5, 6];
    let mut mixed =
        Batch::with_robots(vec![world.clone(); 4], &robots, &seeds, true, None, 2).unwrap();
    // Equal profiles share one rig.
    assert!(Arc::ptr_eq(mixed.envs()[0].rig(), mixed.envs()[2].rig()));
    assert!(!Arc::ptr_eq(mixed.envs()[0].rig(), mixed.envs()[1].rig()));
    let actions: Vec<f32> = (0..8).map(|k| 3.0 + (k % 3) as f32).collect();
    assert_each_steps_as_alone(&mut mixed, &world, &robots, &seeds, &actions, 30);
    let epuck = Arc::new(RobotProfile::builtin("e-puck").unwrap());
    let err = Batch::with_robots(vec![world; 2], &[seed, epuck], &[0, 1], true, None, 1)
        .err()
        .unwrap()
        .to_string();
    assert!(err.contains("environment 1 with 8 and 3"), "{err}");
}

#[test]
fn thread_counts_and_batch_sizes_are_bounded() {
    assert!(Helpers::new(MAX_THREADS + 1).is_err());
    assert!(check_size(MAX_ENVS + 1, 0).is_err());
    assert!(check_size(0, 0).is_err());
    assert!(check_size(4, 40).is_ok());
}
