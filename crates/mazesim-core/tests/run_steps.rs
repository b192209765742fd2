//! The multi-step call: `run_steps(k)` equals `k` calls of `step` with the controller computed
//! outside, bit for bit, whatever the thread count or the batch size.

mod common;

use std::sync::Arc;

use mazesim_core::control::avoid_collision::EPUCK_MAX_SPEED;
use mazesim_core::control::{braitenberg, AvoidCollision};
use mazesim_core::generator::{generate, MazeParams};
use mazesim_core::navigator::TabularPolicy;
use mazesim_core::rng::{next_seed, Rng};
use mazesim_core::{
    Batch, Controller, OutputBuffers, RobotProfile, RunCounters, RunOptions, RunTrace, World,
};

fn mazes(n: usize) -> Vec<Arc<World>> {
    let p = MazeParams {
        loops: 0.1,
        ..Default::default()
    };
    (0..n as u64)
        .map(|s| Arc::new(generate(&p, 100 + s).unwrap()))
        .collect()
}

fn batch(worlds: Vec<Arc<World>>, robot: &str, seeds: &[u64], threads: usize) -> Batch {
    let profile = Arc::new(RobotProfile::builtin(robot).unwrap());
    Batch::new(worlds, profile, seeds, true, None, threads).unwrap()
}

/// The per-step outputs of a run.
struct Traced {
    obs: Vec<f32>,
    poses: Vec<f32>,
    colliding: Vec<bool>,
    wheels: Vec<f32>,
    actions: Vec<i32>,
    ends: Vec<bool>,
    final_state: OutputBuffers,
    counters: RunCounters,
}

fn run(b: &mut Batch, controller: &Controller, seeds: &[u64], options: RunOptions) -> Traced {
    let (n, w, k) = (b.len(), b.observation_width(), options.steps);
    let mut t = Traced {
        obs: vec![0.0; k * n * w],
        poses: vec![0.0; k * n * 3],
        colliding: vec![false; k * n],
        wheels: vec![0.0; k * n * 2],
        actions: vec![0; k * n],
        ends: vec![false; k * n],
        final_state: OutputBuffers::of(b),
        counters: RunCounters::default(),
    };
    let trace = RunTrace {
        observations: Some(&mut t.obs),
        poses: Some(&mut t.poses),
        colliding: Some(&mut t.colliding),
        wheel_speeds: Some(&mut t.wheels),
        actions: Some(&mut t.actions),
        episode_ends: Some(&mut t.ends),
        ..Default::default()
    };
    let out = t.final_state.outputs();
    let counters = b
        .run_steps(controller, seeds, &options, out, trace)
        .unwrap();
    t.counters = counters;
    t
}

const LIMIT: u64 = 45;

fn options(steps: usize) -> RunOptions {
    RunOptions {
        steps,
        max_episode_steps: LIMIT,
        end_at_goal: true,
        end_at_crossing: false,
        autoreset: true,
    }
}

fn random_table(seed: u64, tables: usize) -> Vec<f64> {
    let mut rng = Rng::new(seed);
    // Few distinct values, so that ties (first maximum wins) are common.
    (0..tables * 4096 * 12)
        .map(|_| (rng.uniform() * 4.0).floor())
        .collect()
}

/// Steps `b` from outside for `steps` steps: wheel speeds from `choose(env, step, observation)`,
/// episodes ended and reset as the multi-step call does; returns the observations of each step.
fn step_outside(
    b: &mut Batch,
    steps: usize,
    choose: impl Fn(usize, usize, &[f32]) -> [f32; 2],
) -> Vec<f32> {
    let (n, w) = (b.len(), b.observation_width());
    let mut state = OutputBuffers::of(b);
    b.observe(state.outputs()).unwrap();
    let mut trace = vec![];
    for step in 0..steps {
        let actions: Vec<f32> = (0..n)
            .flat_map(|i| choose(i, step, &state.observations[i * w..(i + 1) * w]))
            .collect();
        b.step(&actions, state.outputs()).unwrap();
        trace.extend_from_slice(&state.observations);
        let ended: Vec<bool> = b
            .envs()
            .iter()
            .map(|e| {
                let goal = e.world().goal().unwrap();
                let [x, y, _] = e.pose();
                let (dx, dy) = (x as f64 - goal.center[0], y as f64 - goal.center[1]);
                e.steps() >= LIMIT || dx * dx + dy * dy <= goal.radius * goal.radius
            })
            .collect();
        let seeds: Vec<u64> = b
            .envs()
            .iter()
            .map(|e| next_seed(e.config().seed))
            .collect();
        b.reset(Some(&ended), Some(&seeds), state.outputs())
            .unwrap();
    }
    trace
}

#[test]
fn braitenberg_run_equals_single_steps() {
    let seeds: Vec<u64> = (0..37).collect();
    let controller = Controller::Braitenberg;
    let ran = run(
        &mut batch(mazes(37), "e-puck", &seeds, 2),
        &controller,
        &seeds,
        options(130),
    );
    let mut outside = batch(mazes(37), "e-puck", &seeds, 1);
    let stepped = step_outside(&mut outside, 130, |_, _, obs| {
        braitenberg::wheel_speeds(&obs[..8])
    });
    assert_eq!(ran.obs, stepped);
    assert!(ran.ends.iter().any(|&e| e), "episodes end within the run");
    assert_eq!(
        ran.counters.episodes_finished.iter().sum::<u64>(),
        ran.ends.iter().filter(|&&e| e).count() as u64
    );
}

#[test]
fn avoid_collision_run_equals_single_steps() {
    let seeds: Vec<u64> = (5..25).collect();
    // A low threshold, so that sensor noise alone makes the robots turn both ways.
    let rule = AvoidCollision::new(70.0, EPUCK_MAX_SPEED).unwrap();
    let controller = Controller::AvoidCollision(rule);
    let ran = run(
        &mut batch(mazes(20), "e-puck", &seeds, 3),
        &controller,
        &seeds,
        options(100),
    );
    let mut outside = batch(mazes(20), "e-puck", &seeds, 1);
    let stepped = step_outside(&mut outside, 100, |_, _, obs| rule.wheel_speeds(&obs[..8]));
    assert_eq!(ran.obs, stepped);
    let turns = |side: usize| ran.wheels.chunks(2).filter(|w| w[side] == 0.0).count();
    assert!(turns(0) > 0 && turns(1) > 0, "the robots turned both ways");
}

#[test]
fn tabular_and_random_runs_equal_their_wheel_speeds_stepped_outside() {
    let seeds: Vec<u64> = (0..21).collect();
    let policy = TabularPolicy::new(
        random_table(1, 2),
        2,
        None,
        Some((0..21).map(|i| i % 2).collect()),
        0.3,
    )
    .unwrap();
    for (robot, controller) in [
        ("seed", Controller::Tabular(Box::new(policy))),
        ("e-puck", Controller::RandomWheels),
    ] {
        let ran = run(
            &mut batch(mazes(21), robot, &seeds, 2),
            &controller,
            &seeds,
            options(90),
        );
        let mut outside = batch(mazes(21), robot, &seeds, 1);
        let wheels = &ran.wheels;
        let stepped = step_outside(&mut outside, 90, |i, t, _| {
            let at = 2 * (t * 21 + i);
            [wheels[at], wheels[at + 1]]
        });
        assert_eq!(ran.obs, stepped, "{}", controller.name());
    }
}

#[test]
fn runs_do_not_depend_on_threads_batch_size_or_blocks() {
    let seeds: Vec<u64> = (0..40).map(|s| 1000 + s).collect();
    let policy = TabularPolicy::new(random_table(2, 1), 1, None, None, 0.2).unwrap();
    for (robot, controller) in [
        ("e-puck", Controller::RandomWheels),
        ("seed", Controller::Tabular(Box::new(policy))),
    ] {
        let reference = run(
            &mut batch(mazes(40), robot, &seeds, 1),
            &controller,
            &seeds,
            options(150),
        );
        let threaded = run(
            &mut batch(mazes(40), robot, &seeds, 3),
            &controller,
            &seeds,
            options(150),
        );
        assert_eq!(reference.obs, threaded.obs);
        assert_eq!(reference.actions, threaded.actions);
        // Env 33 alone, in a batch of one.
        let worlds = vec![mazes(40)[33].clone()];
        let alone = run(
            &mut batch(worlds, robot, &seeds[33..34], 0),
            &controller,
            &seeds[33..34],
            options(150),
        );
        let w = alone.obs.len() / 150;
        for t in 0..150 {
            assert_eq!(
                alone.obs[t * w..(t + 1) * w],
                reference.obs[(t * 40 + 33) * w..(t * 40 + 34) * w]
            );
        }
        assert_eq!(alone.poses[..3], reference.poses[33 * 3..34 * 3]);
        assert_eq!(alone.colliding[0], reference.colliding[33]);
    }
    // A deterministic controller: two calls of k steps equal one of 2k.
    let mut once = batch(mazes(40), "e-puck", &seeds, 2);
    let whole = run(&mut once, &Controller::Braitenberg, &seeds, options(140));
    let mut twice = batch(mazes(40), "e-puck", &seeds, 2);
    run(&mut twice, &Controller::Braitenberg, &seeds, options(70));
    let second = run(&mut twice, &Controller::Braitenberg, &seeds, options(70));
    assert_eq!(
        whole.final_state.observations,
        second.final_state.observations
    );
    assert_eq!(whole.obs[whole.obs.len() / 2..], second.obs[..]);
}

#[test]
fn without_autoreset_an_ended_episode_stands_still() {
    let seeds: Vec<u64> = (0..5).collect();
    let mut b = batch(mazes(5), "e-puck", &seeds, 1);
    let opts = RunOptions {
        autoreset: false,
        ..options(80)
    };
    let ran = run(&mut b, &Controller::Braitenberg, &seeds, opts);
    assert!(ran.counters.steps.iter().all(|&s| s <= LIMIT));
    assert_eq!(ran.counters.episodes_finished, vec![1; 5]);
    let w = b.observation_width();
    let last = &ran.obs[79 * 5 * w..];
    assert_eq!(last, &ran.final_state.observations[..]);
    assert_eq!(
        &ran.obs[(LIMIT as usize - 1) * 5 * w..LIMIT as usize * 5 * w],
        last
    );
    assert!(b.envs().iter().all(|e| e.steps() == LIMIT));
    assert!(ran.wheels[LIMIT as usize * 10..].iter().all(|&v| v == 0.0));
}

#[test]
fn bad_arguments_are_refused_before_anything_moves() {
    let seeds: Vec<u64> = (0..3).collect();
    let mut b = batch(mazes(3), "e-puck", &seeds, 1);
    let mut state = OutputBuffers::of(&b);
    let policy = TabularPolicy::new(random_table(0, 1), 1, None, None, 0.0).unwrap();
    let tabular = Controller::Tabular(Box::new(policy.clone()));
    let opts = options(5);
    assert!(b
        .run_steps(
            &Controller::Braitenberg,
            &seeds[..2],
            &opts,
            state.outputs(),
            RunTrace::default()
        )
        .is_err());
    let mut short = vec![0.0f32; 4];
    let trace = RunTrace {
        poses: Some(&mut short),
        ..Default::default()
    };
    let err = b
        .run_steps(
            &Controller::Braitenberg,
            &seeds,
            &opts,
            state.outputs(),
            trace,
        )
        .unwrap_err();
    assert!(err.to_string().contains("poses trace"), "{err}");
    assert!(b.envs().iter().all(|e| e.steps() == 0));
    // A per-env table map of the wrong length.
    let mapped = TabularPolicy::new(random_table(0, 1), 1, None, Some(vec![0; 4]), 0.0).unwrap();
    let mut seed_batch = batch(mazes(3), "seed", &seeds, 1);
    let mut seed_state = OutputBuffers::of(&seed_batch);
    let mapped = Controller::Tabular(Box::new(mapped));
    assert!(seed_batch
        .run_steps(
            &mapped,
            &seeds,
            &opts,
            seed_state.outputs(),
            RunTrace::default()
        )
        .is_err());
    assert!(seed_batch
        .run_steps(
            &tabular,
            &seeds,
            &opts,
            seed_state.outputs(),
            RunTrace::default()
        )
        .is_ok());
    // The e-puck has 8 distance sensors; the seed robot 6 (too few for Braitenberg).
    let err = seed_batch
        .run_steps(
            &Controller::Braitenberg,
            &seeds,
            &opts,
            seed_state.outputs(),
            RunTrace::default(),
        )
        .unwrap_err();
    assert!(
        err.to_string().contains("reads 8 distance sensors"),
        "{err}"
    );
}

#[test]
fn an_interrupt_stops_a_long_run() {
    let seeds: Vec<u64> = (0..64).collect();
    let mut b = batch(mazes(64), "e-puck", &seeds, 2);
    b.set_interrupt(Box::new(|| true));
    let mut state = OutputBuffers::of(&b);
    let started = std::time::Instant::now();
    let result = b.run_steps(
        &Controller::Braitenberg,
        &seeds,
        &options(10_000_000),
        state.outputs(),
        RunTrace::default(),
    );
    assert!(matches!(result, Err(mazesim_core::Error::Interrupted)));
    assert!(started.elapsed() < std::time::Duration::from_secs(30));
}

#[test]
fn an_episode_ends_at_its_environments_own_goal() {
    let worlds = mazes(2);
    let mut b = batch(worlds.clone(), "e-puck", &[0, 1], 1);
    let [x, y, _] = worlds[1].start();
    // A disc round env 1's start: its episodes end at every step; env 0 keeps its world's goal.
    b.set_goals_at(&[1], &[x, y, 0.2]).unwrap();
    let traced = run(&mut b, &Controller::Braitenberg, &[0, 1], options(20));
    assert_eq!(traced.counters.goals_reached[1], 20);
    assert_eq!(traced.counters.goals_reached[0], 0);
    // Going back to a world drops the environment's own goal.
    b.set_world(1, worlds[1].clone(), 1).unwrap();
    let traced = run(&mut b, &Controller::Braitenberg, &[0, 1], options(20));
    assert_eq!(traced.counters.goals_reached[1], 0);
}
