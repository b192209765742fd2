//! Criterion bench of a round of the lower level's Q-learning in the core
//! (`mazesim_core::navigator::training`): 1,024 robots of the four sub-tasks in 16 generated mazes,
//! 100 control steps per iteration, with the default navigator's options (the seed robot, phases
//! of the heading, Corridors and Corners acting from its table where blind) and with the
//! randomised navigator's (door sub-tasks that count the distance, the heading held where blind,
//! and every robot a perturbed seed robot of its own, each perturbed from its own parse of the
//! profile as `mazesim train --randomise` draws them). Throughput is in env-steps, so the two
//! figures compare as `benches/bench_train.py`'s ratio does.
//!
//! `cargo bench --bench train -- turns [ROUNDS]` times instead the two rounds in turns in one
//! thread (the order swapped every round), in processor seconds (the tables' zeroing before each
//! round left out), and prints the median of the rounds' ratios (randomised over default speed):
//! the figure a loaded machine still resolves. `turns ROUNDS default` (or `randomised`) runs one
//! of them alone, for a profiler.

use std::sync::Arc;

use criterion::{criterion_group, Criterion, Throughput};
use mazesim_core::generator::{generate, MazeParams};
use mazesim_core::navigator::door::{Phases, NUM_SUBTASKS};
use mazesim_core::navigator::heading_hold::BlindRule;
use mazesim_core::navigator::qlearning::LearningRate;
use mazesim_core::navigator::symmetry::Symmetry;
use mazesim_core::navigator::training::{
    train_lower_round, Crew, LowerRound, Rewards, RoundSettings, StartQueues,
};
use mazesim_core::navigator::{NUM_ACTIONS, NUM_STATES, WHEEL_SPEED_FRACTIONS};
use mazesim_core::rng::Rng;
use mazesim_core::{Batch, Perturbation, RobotProfile, StepOutputs, World};

const ENVS: usize = 1024;
const STEPS: usize = 100;
const PER_ENV: usize = 8;
const MAZES: usize = 16;

/// What a round reads, drawn once.
struct Draws {
    worlds: Vec<Arc<World>>,
    role: Vec<i64>,
    world: Vec<i64>,
    pose: Vec<f64>,
    seed: Vec<u64>,
    path: Vec<f64>,
    explore: Vec<f64>,
    random_action: Vec<i64>,
}

fn draws() -> Draws {
    let worlds: Vec<Arc<World>> = (0..MAZES as u64)
        .map(|s| Arc::new(generate(&MazeParams::default(), 100 + s).unwrap()))
        .collect();
    let mut rng = Rng::new(17);
    let mut d = Draws {
        worlds,
        role: (0..ENVS as i64).map(|i| i % NUM_SUBTASKS as i64).collect(),
        world: vec![],
        pose: vec![],
        seed: vec![],
        path: vec![],
        explore: vec![],
        random_action: vec![],
    };
    for _ in 0..ENVS * PER_ENV {
        // A random cell's centre of a 5 x 5 maze of 0.25 m cells, facing along the grid.
        let (cx, cy) = ((rng.uniform() * 5.0).floor(), (rng.uniform() * 5.0).floor());
        let (x, y) = (0.125 + 0.25 * cx, 0.125 + 0.25 * cy);
        let yaw = (rng.uniform() * 4.0).floor() * std::f64::consts::FRAC_PI_2;
        d.world.push((rng.uniform() * MAZES as f64) as i64);
        d.pose.extend([x, y, yaw]);
        d.seed.push(rng.next_u64());
        let (c, s) = (yaw.cos(), yaw.sin());
        d.path
            .extend([x, y, x + 0.25 * c, y + 0.25 * s, c, s, s, -c, 0.25]);
    }
    for i in 0..STEPS * ENVS {
        d.explore.push(rng.uniform());
        // Corridors and Corners never explores `99` (the last action).
        let actions = if i % NUM_SUBTASKS == 0 { 11.0 } else { 12.0 };
        d.random_action.push((rng.uniform() * actions) as i64);
    }
    d
}

/// `mazesim train`'s settings (`LowerSettings`' defaults, an exploration rate of its first
/// rounds) with `phases` and `blind`.
fn settings(phases: Phases, blind: BlindRule) -> RoundSettings {
    RoundSettings {
        epsilon: 0.3,
        gamma: 0.99,
        decision_steps: 10,
        corridor_episode_steps: 350,
        rate: LearningRate::new(0.5, 0.02, 0.5).unwrap(),
        rewards: Rewards::NAVIGATOR,
        door_path_exit: 0.25,
        success_past_centre: 0.04,
        success_across: 0.08,
        phases,
        blind,
    }
}

/// The seed robot, or each robot a perturbed seed robot of its own.
fn robots(randomised: bool) -> Vec<Arc<RobotProfile>> {
    if !randomised {
        return vec![Arc::new(RobotProfile::builtin("seed").unwrap())];
    }
    let mut rng = Rng::new(29);
    (0..ENVS)
        .map(|_| {
            let mut between = |lo: f64, hi: f64| rng.uniform_range(lo, hi);
            let mismatch = between(-0.1, 0.1);
            let p = Perturbation {
                wheel_radius_scale: between(0.95, 1.05),
                axle_length_scale: between(0.95, 1.05),
                motor_gains: [1.0 + mismatch.min(0.0), 1.0 - mismatch.max(0.0)],
                noise_scale: between(0.5, 4.0),
                ir_angle_error: between(-5.0, 15.0).to_radians(),
                ir_offset_error: between(-10.0, 10.0) / 1000.0,
                wall_reflectance: between(0.2, 1.0),
                ground_gain: between(0.8, 1.2),
                slip_on_contact: between(0.0, 0.5),
            };
            let parsed = RobotProfile::builtin("seed").unwrap();
            Arc::new(parsed.perturbed(&p).unwrap())
        })
        .collect()
}

/// A batch of the round's robots and its buffers.
struct Robots {
    batch: Batch,
    observations: Vec<f32>,
    poses: Vec<f32>,
    colliding: Vec<bool>,
    crossings: Vec<i32>,
    world_of_env: Vec<i64>,
}

fn batch(d: &Draws, randomised: bool, threads: usize) -> Robots {
    let worlds = vec![d.worlds[0].clone(); ENVS];
    let seeds: Vec<u64> = (0..ENVS as u64).collect();
    let robots = robots(randomised);
    let batch = Batch::with_robots(worlds, &robots, &seeds, true, None, threads).unwrap();
    let width = batch.observation_width();
    Robots {
        batch,
        observations: vec![0.0; ENVS * width],
        poses: vec![0.0; ENVS * 3],
        colliding: vec![false; ENVS],
        crossings: vec![0; ENVS],
        world_of_env: vec![0; ENVS],
    }
}

/// The tables of a round, `(4, rows, NUM_ACTIONS)` values and visit counts.
struct Tables {
    q: Vec<f64>,
    visits: Vec<i64>,
}

impl Tables {
    fn new(phases: Phases) -> Self {
        let size = NUM_SUBTASKS * phases.rows() * NUM_ACTIONS;
        Self {
            q: vec![0.0; size],
            visits: vec![0; size],
        }
    }
}

impl Tables {
    /// Back to zero, in place (no allocation).
    fn clear(&mut self) {
        self.q.fill(0.0);
        self.visits.fill(0);
    }
}

/// One round of `STEPS` control steps, the tables learning from what `tables` holds.
fn round(d: &Draws, robots: &mut Robots, tables: &mut Tables, settings: RoundSettings) {
    let phases = settings.phases.count();
    let symmetry = Symmetry {
        distance_states: (0..NUM_STATES as u16).collect(),
        phases: (0..NUM_SUBTASKS).flat_map(|_| 0..phases).collect(),
        actions: std::array::from_fn(|a| a),
        subtasks: [0, 2, 1, 3],
    };
    let mut allowed = [[true; NUM_ACTIONS]; NUM_SUBTASKS];
    allowed[0][NUM_ACTIONS - 1] = false;
    let limit = robots.batch.envs()[0].robot().max_wheel_speed;
    let wheel_speeds = WHEEL_SPEED_FRACTIONS.map(|[l, r]| [(l * limit) as f32, (r * limit) as f32]);
    let mut crews = [Crew {
        batch: &mut robots.batch,
        out: StepOutputs {
            observations: &mut robots.observations,
            poses: &mut robots.poses,
            colliding: &mut robots.colliding,
            crossings: &mut robots.crossings,
        },
        members: (0..ENVS).collect(),
        world_of_env: &mut robots.world_of_env,
        wheel_speeds,
        volts: None,
    }];
    let round = LowerRound {
        settings,
        worlds: &d.worlds,
        role: &d.role,
        starts: StartQueues {
            per_env: PER_ENV,
            world: &d.world,
            pose: &d.pose,
            seed: &d.seed,
            path: &d.path,
        },
        explore: &d.explore,
        random_action: &d.random_action,
        q: &mut tables.q,
        visits: &mut tables.visits,
        allowed,
        symmetry: &symmetry,
    };
    train_lower_round(round, &mut crews).unwrap();
}

/// The two rounds: name, robots of their own, and the options.
const OPTIONS: [(&str, bool, Phases, BlindRule); 2] = [
    ("default", false, Phases::Heading, BlindRule::Table),
    (
        "randomised",
        true,
        Phases::HeadingAndDistance,
        BlindRule::HoldHeading,
    ),
];

fn lower_round(c: &mut Criterion) {
    let d = draws();
    let mut g = c.benchmark_group("lower_round");
    g.throughput(Throughput::Elements((ENVS * STEPS) as u64));
    g.sample_size(10);
    for (name, randomised, phases, blind) in OPTIONS {
        let mut robots = batch(&d, randomised, 0);
        let mut tables = Tables::new(phases);
        g.bench_function(name, |b| {
            b.iter(|| {
                // The tables learn from zero every iteration.
                tables.clear();
                round(&d, &mut robots, &mut tables, settings(phases, blind))
            })
        });
    }
    g.finish();
}

/// This process's processor time, seconds.
fn processor_seconds() -> f64 {
    let mut t = libc::timespec {
        tv_sec: 0,
        tv_nsec: 0,
    };
    // SAFETY: `t` is a valid timespec for the call to write.
    unsafe { libc::clock_gettime(libc::CLOCK_PROCESS_CPUTIME_ID, &mut t) };
    t.tv_sec as f64 + t.tv_nsec as f64 * 1e-9
}

/// `rounds` rounds of each option in turns, one thread, timed in processor seconds.
fn turns(rounds: usize, only: Option<&str>) {
    let d = draws();
    let mut setups: Vec<_> = (OPTIONS.iter())
        .map(|&(_, randomised, phases, _)| (batch(&d, randomised, 1), Tables::new(phases)))
        .collect();
    let mut seconds = vec![vec![]; OPTIONS.len()];
    for k in 0..rounds + 1 {
        let order: Vec<usize> = if k % 2 == 0 { vec![0, 1] } else { vec![1, 0] };
        for i in order {
            let (name, _, phases, blind) = OPTIONS[i];
            if only.is_some_and(|o| o != name) {
                continue;
            }
            let (robots, tables) = &mut setups[i];
            // Zeroing the tables is the bench's own work (`mazesim train` keeps them from round
            // to round), and the door distance's tables are larger: it is left out.
            tables.clear();
            let start = processor_seconds();
            round(&d, robots, tables, settings(phases, blind));
            // The first round of each warms the caches and is not counted.
            if k > 0 {
                seconds[i].push(processor_seconds() - start);
            }
        }
    }
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    if only.is_some() {
        return;
    }
    let ratios = seconds[0].iter().zip(&seconds[1]).map(|(a, b)| a / b);
    for (i, (name, ..)) in OPTIONS.iter().enumerate() {
        println!("{name:>11}: {:.4} s a round", median(seconds[i].clone()));
    }
    println!(
        "randomised/default: {:.3}x the speed (median of {rounds} rounds' ratios, one thread)",
        median(ratios.collect())
    );
}

criterion_group!(benches, lower_round);

fn main() {
    let args: Vec<String> = std::env::args().collect();
    if let Some(at) = args.iter().position(|a| a == "turns") {
        let rounds = args.get(at + 1).and_then(|n| n.parse().ok()).unwrap_or(9);
        turns(rounds, args.get(at + 2).map(String::as_str));
        return;
    }
    benches();
    Criterion::default().configure_from_args().final_summary();
}
