//! A round of the lower level's Q-learning in the core: the same tables and counts whatever the
//! thread count, learning from every decision and its mirror image, and refusing bad arrays
//! before anything moves.

use std::sync::Arc;

use mazesim_core::generator::{generate, MazeParams};
use mazesim_core::navigator::door::{Phases, NUM_SUBTASKS};
use mazesim_core::navigator::heading_hold::BlindRule;
use mazesim_core::navigator::qlearning::LearningRate;
use mazesim_core::navigator::symmetry::Symmetry;
use mazesim_core::navigator::training::{
    train_lower_round, Crew, LowerRound, Rewards, RoundCounts, RoundSettings, StartQueues,
    PATH_WIDTH,
};
use mazesim_core::navigator::{NUM_ACTIONS, NUM_STATES};
use mazesim_core::rng::Rng;
use mazesim_core::{Batch, Error, RobotProfile, StepOutputs, World};

const ENVS: usize = 20;
const PER_ENV: usize = 6;
const STEPS: usize = 260;
const ROWS: usize = Phases::Heading.rows();
const TABLE: usize = NUM_SUBTASKS * ROWS * NUM_ACTIONS;

struct Setup {
    worlds: Vec<Arc<World>>,
    role: Vec<i64>,
    start_world: Vec<i64>,
    start_pose: Vec<f64>,
    start_seed: Vec<u64>,
    start_path: Vec<f64>,
    explore: Vec<f64>,
    random_action: Vec<i64>,
    mirrored_states: Vec<u16>,
}

fn setup() -> Setup {
    let worlds: Vec<Arc<World>> = (0..3)
        .map(|s| Arc::new(generate(&MazeParams::default(), 70 + s).unwrap()))
        .collect();
    let mut rng = Rng::new(5);
    let role: Vec<i64> = (0..ENVS as i64).map(|i| i % NUM_SUBTASKS as i64).collect();
    let (mut start_world, mut start_pose, mut start_seed, mut start_path) =
        (vec![], vec![], vec![], vec![]);
    for _ in 0..ENVS * PER_ENV {
        let w = (rng.uniform() * 3.0) as usize;
        // The centre of a random cell of the 5 x 5 maze of 0.25 m cells, facing any way.
        let (cx, cy) = ((rng.uniform() * 5.0).floor(), (rng.uniform() * 5.0).floor());
        let (x, y) = (0.125 + 0.25 * cx, 0.125 + 0.25 * cy);
        let yaw = rng.uniform_range(-3.1, 3.1);
        start_world.push(w as i64);
        start_pose.extend([x, y, yaw]);
        start_seed.push(rng.next_u64());
        let (c, s) = (yaw.cos(), yaw.sin());
        start_path.extend([x, y, x + 0.25 * c, y + 0.25 * s, c, s, s, -c, 0.25]);
    }
    let explore = (0..STEPS * ENVS).map(|_| rng.uniform()).collect();
    let random_action = (0..STEPS * ENVS)
        .map(|i| (rng.uniform() * if i % 4 == 0 { 11.0 } else { 12.0 }) as i64)
        .collect();
    let mirrored_states = (0..NUM_STATES as u16).collect();
    Setup {
        worlds,
        role,
        start_world,
        start_pose,
        start_seed,
        start_path,
        explore,
        random_action,
        mirrored_states,
    }
}

fn settings(epsilon: f64) -> RoundSettings {
    RoundSettings {
        gamma: 0.99,
        epsilon,
        decision_steps: 10,
        corridor_episode_steps: 60,
        rate: LearningRate::new(0.5, 0.02, 0.5).unwrap(),
        rewards: Rewards::NAVIGATOR,
        door_path_exit: 0.25,
        success_past_centre: 0.04,
        success_across: 0.08,
        phases: Phases::Heading,
        blind: BlindRule::Table,
    }
}

struct Outcome {
    q: Vec<f64>,
    visits: Vec<i64>,
    counts: Result<RoundCounts, Error>,
    poses: Vec<f32>,
}

fn round(threads: usize, epsilon: f64, spoil: impl FnOnce(&mut Setup)) -> Outcome {
    round_in_crews(threads, epsilon, 1, spoil)
}

/// A batch's observations, poses, contact flags and crossings.
type Buffers = (Vec<f32>, Vec<f32>, Vec<bool>, Vec<i32>);

/// The round with its robots dealt out to `crews` batches in turn (robot i to crew i % crews).
fn round_in_crews(
    threads: usize,
    epsilon: f64,
    crews: usize,
    spoil: impl FnOnce(&mut Setup),
) -> Outcome {
    let mut s = setup();
    spoil(&mut s);
    let profile = Arc::new(RobotProfile::builtin("seed").unwrap());
    let (mut q, mut visits) = (vec![0.0; TABLE], vec![0i64; TABLE]);
    let mut allowed = [[true; NUM_ACTIONS]; NUM_SUBTASKS];
    allowed[0][11] = false;
    let limit = profile.max_wheel_speed as f32;
    let fractions = mazesim_core::navigator::WHEEL_SPEED_FRACTIONS;
    let wheel_speeds = fractions.map(|[l, r]| [l as f32 * limit, r as f32 * limit]);
    let members: Vec<Vec<usize>> = (0..crews)
        .map(|c| (c..ENVS).step_by(crews).collect())
        .collect();
    let mut batches: Vec<Batch> = members
        .iter()
        .map(|envs| {
            let seeds: Vec<u64> = envs.iter().map(|&i| i as u64).collect();
            let worlds = envs.iter().map(|&i| s.worlds[i % 3].clone()).collect();
            Batch::new(worlds, profile.clone(), &seeds, true, None, threads).unwrap()
        })
        .collect();
    let mut world_of_env: Vec<Vec<i64>> = members
        .iter()
        .map(|envs| envs.iter().map(|&i| (i % 3) as i64).collect())
        .collect();
    let width = batches[0].observation_width();
    let mut buffers: Vec<Buffers> = members
        .iter()
        .map(|envs| {
            let n = envs.len();
            (
                vec![0.0; n * width],
                vec![0.0; 3 * n],
                vec![false; n],
                vec![0; n],
            )
        })
        .collect();
    let mut crews: Vec<Crew<'_>> = batches
        .iter_mut()
        .zip(&mut buffers)
        .zip(&mut world_of_env)
        .zip(&members)
        .map(
            |(((batch, (obs, poses, colliding, crossings)), world_of_env), envs)| Crew {
                batch,
                out: StepOutputs {
                    observations: obs,
                    poses,
                    colliding,
                    crossings,
                },
                members: envs.clone(),
                world_of_env,
                wheel_speeds,
                volts: None,
            },
        )
        .collect();
    let counts = train_lower_round(
        LowerRound {
            settings: settings(epsilon),
            worlds: &s.worlds,
            role: &s.role,
            starts: StartQueues {
                per_env: PER_ENV,
                world: &s.start_world,
                pose: &s.start_pose,
                seed: &s.start_seed,
                path: &s.start_path,
            },
            explore: &s.explore,
            random_action: &s.random_action,
            q: &mut q,
            visits: &mut visits,
            allowed,
            symmetry: &Symmetry {
                distance_states: s.mirrored_states.clone(),
                phases: (0..NUM_SUBTASKS)
                    .flat_map(|_| 0..Phases::Heading.count())
                    .collect(),
                actions: std::array::from_fn(|a| a),
                subtasks: [0, 2, 1, 3],
            },
        },
        &mut crews,
    );
    drop(crews);
    // Each robot's pose, in the round's order.
    let mut poses = vec![0.0; 3 * ENVS];
    for (envs, (_, crew_poses, _, _)) in members.iter().zip(&buffers) {
        for (r, &i) in envs.iter().enumerate() {
            poses[3 * i..3 * i + 3].copy_from_slice(&crew_poses[3 * r..3 * r + 3]);
        }
    }
    Outcome {
        q,
        visits,
        counts,
        poses,
    }
}

#[test]
fn a_round_gives_the_same_tables_whatever_the_threads() {
    let one = round(1, 0.3, |_| {});
    let two = round(2, 0.3, |_| {});
    assert_eq!(one.q, two.q);
    assert_eq!(one.visits, two.visits);
    assert_eq!(one.poses, two.poses);
    assert_eq!(one.counts.unwrap(), two.counts.unwrap());
}

#[test]
fn robots_dealt_out_to_several_batches_learn_as_in_one() {
    // A fleet's crews: the tables learn from the robots in the round's order, wherever they are.
    let one = round(2, 0.3, |_| {});
    let three = round_in_crews(2, 0.3, 3, |_| {});
    assert_eq!(one.q, three.q);
    assert_eq!(one.visits, three.visits);
    assert_eq!(one.poses, three.poses);
    assert_eq!(one.counts.unwrap(), three.counts.unwrap());
}

#[test]
fn every_decision_teaches_its_table_and_its_mirror_image() {
    let ran = round(2, 1.0, |_| {});
    let counts = ran.counts.unwrap();
    let per_table = ROWS * NUM_ACTIONS;
    let visits_of =
        |k: usize| -> i64 { ran.visits[k * per_table..(k + 1) * per_table].iter().sum() };
    // The right and left turns teach each other's table as much as their own.
    assert_eq!(visits_of(1), visits_of(2));
    assert!(visits_of(0) > 0 && visits_of(3) > 0);
    // Corridors and Corners never takes its forbidden action, even exploring all the time.
    let backward: i64 = (0..ROWS)
        .map(|row| ran.visits[row * NUM_ACTIONS + 11])
        .sum();
    assert_eq!(backward, 0);
    assert!(ran.q.iter().all(|v| v.is_finite()) && ran.q.iter().any(|&v| v != 0.0));
    // Random driving ends door episodes (by 200 steps at the latest), some in contact with walls.
    let ended: u64 = (1..4)
        .map(|k| counts.success[k] + counts.failure[k] + counts.cut[k])
        .sum();
    assert!(ended > 0, "{counts:?}");
    assert!(counts.contact_steps > 0 && counts.contact_steps < (ENVS * STEPS) as u64);
    assert!(counts.corridor_metres.is_finite());
}

/// A change that makes one array bad.
type Spoil = Box<dyn FnOnce(&mut Setup)>;

#[test]
fn bad_arrays_are_refused_before_anything_moves() {
    let cases: Vec<(Spoil, &str)> = vec![
        (Box::new(|s| s.start_world[3] = 7), "world indices"),
        (
            Box::new(|s| s.start_pose.pop().map(drop).unwrap_or(())),
            "start poses",
        ),
        (Box::new(|s| s.explore[0] = f64::NAN), "finite"),
        (Box::new(|s| s.random_action[1] = 12), "exploring actions"),
        // Robot 0 runs Corridors and Corners, which may not take action 11 (`99`).
        (
            Box::new(|s| s.random_action[2 * ENVS] = 11),
            "robot 0 (sub-task 0) at step 2",
        ),
        (Box::new(|s| s.role[0] = 4), "sub-tasks"),
        (
            Box::new(|s| s.mirrored_states[5] = NUM_STATES as u16),
            "mirrored distance states",
        ),
        (
            Box::new(|s| s.start_path.truncate(PATH_WIDTH)),
            "door paths",
        ),
    ];
    for (spoil, message) in cases {
        let ran = round(1, 0.3, spoil);
        let err = ran.counts.unwrap_err().to_string();
        assert!(err.contains(message), "{message}: {err}");
        assert!(ran.q.iter().all(|&v| v == 0.0) && ran.visits.iter().all(|&v| v == 0));
    }
}
