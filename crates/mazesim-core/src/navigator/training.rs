//! A round of the lower level's Q-learning in the core (`mazesim.learn.lower`): every robot of a
//! batch practises its sub-task, acting epsilon-greedily from the stacked tables, and the tables
//! learn from every finished decision and its mirror image, for a whole round in one call.
//!
//! The round follows the numpy reference round of `tests/lower_oracle.py` operation for operation
//! in f64 (the same products and sums in the same order, the sub-tasks' odometry of
//! [`crate::navigator::door`], the Table 4.1 state of [`crate::navigator::Discretiser`], the batch
//! updates of [`crate::navigator::qlearning`]), so that both give the same tables bit for bit. Its random numbers come from the caller, drawn
//! before the round: each robot's queue of episode starts and each step's exploration draws. The
//! robots step in parallel; everything between two steps runs in robot order on the calling
//! thread, so the result does not depend on the thread count.
//!
//! A round may drive several batches at once, one [`Crew`] each: a fleet of robots of different
//! sensor sets (a batch holds robots of one set), each crew with its wheel speeds and, for robots
//! other than the seed robot, the map of its readings into the seed robot's volts
//! ([`SeedVolts`]). Its robots are numbered across the crews, and the tables learn from them in
//! that order, as from one batch.

use std::sync::Arc;

use crate::batch::{Row, CHUNK_ENVS};
use crate::error::{Error, Result};
use crate::navigator::door::{self, Phases, SubTaskEnd, SubTaskState};
use crate::navigator::heading_hold::BlindRule;
use crate::navigator::qlearning::{best_action, LearningRate, QTable, Transition};
use crate::navigator::seed_volts::SeedVolts;
use crate::navigator::symmetry::Symmetry;
use crate::navigator::Discretiser;
use crate::navigator::{NUM_ACTIONS, NUM_SENSORS};
use crate::rollout::chunks_of;
use crate::{Batch, Simulator, StepOutputs as Outputs, World};

/// Values of each door-path row: start (2), door centre (2), heading in (2), heading out (2), and
/// the length of the first leg.
pub const PATH_WIDTH: usize = 9;

/// The rewards of the lower level (`mazesim.learn.subtasks`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rewards {
    /// Per metre of progress (along the door path, or forward in a corridor).
    pub progress: f64,
    /// Per step in contact with a wall.
    pub collision: f64,
    /// Per step of Corridors and Corners.
    pub corridor_step: f64,
    /// Per step of a door sub-task.
    pub door_step: f64,
    /// Per radian by which "Going forward on a door" brings its heading back.
    pub heading: f64,
    /// At the end of a door sub-task that entered its opening.
    pub door_success: f64,
    /// At the end of one that did not.
    pub door_failure: f64,
}

impl Rewards {
    /// The navigator's rewards, as `mazesim.learn.subtasks` sets them (the binding takes them
    /// from the caller; this copy serves the core's own tests and benches).
    pub const NAVIGATOR: Rewards = Rewards {
        progress: 10.0,
        collision: -2.0,
        corridor_step: -0.02,
        door_step: -0.03,
        heading: 2.0,
        door_success: 5.0,
        door_failure: -5.0,
    };
}

/// How a round learns.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RoundSettings {
    /// Discount per control step.
    pub gamma: f64,
    /// Exploration rate of the round.
    pub epsilon: f64,
    /// Longest decision, in control steps.
    pub decision_steps: u64,
    /// Length of a Corridors-and-Corners episode.
    pub corridor_episode_steps: u64,
    /// The learning rate of the updates.
    pub rate: LearningRate,
    /// The rewards.
    pub rewards: Rewards,
    /// How far into the opening a door path runs (metres).
    pub door_path_exit: f64,
    /// A door sub-task entered its opening when it ended this far past the door's centre...
    pub success_past_centre: f64,
    /// ...and at most this far off the opening's centre line (metres).
    pub success_across: f64,
    /// What the door sub-tasks' phases count; the tables have `phases.rows()` rows each.
    pub phases: Phases,
    /// What Corridors and Corners does where no sensor sees a wall, exploring or not.
    pub blind: BlindRule,
}

/// Each robot's queue of episode starts for the round, `(n, per_env)` rows; robot i's k-th
/// episode takes row `k % per_env` of its queue.
pub struct StartQueues<'a> {
    /// Starts per robot.
    pub per_env: usize,
    /// The world of each start (an index into the round's worlds).
    pub world: &'a [i64],
    /// x, y, yaw of each start.
    pub pose: &'a [f64],
    /// The sensor-noise seed of each start.
    pub seed: &'a [u64],
    /// The door path of each start (`PATH_WIDTH` values; unused by Corridors and Corners).
    pub path: &'a [f64],
}

/// Everything a round reads and writes.
pub struct LowerRound<'a> {
    /// How it learns.
    pub settings: RoundSettings,
    /// The worlds the starts name.
    pub worlds: &'a [Arc<World>],
    /// Each robot's sub-task.
    pub role: &'a [i64],
    /// The episode starts.
    pub starts: StartQueues<'a>,
    /// `(steps, n)` uniform draws in [0, 1): a deciding robot explores when its draw is below
    /// epsilon. The round runs `steps` control steps.
    pub explore: &'a [f64],
    /// `(steps, n)` the action a deciding robot takes when it explores.
    pub random_action: &'a [i64],
    /// `(4, rows, NUM_ACTIONS)` values (`rows` of [`RoundSettings::phases`]), updated in place.
    pub q: &'a mut [f64],
    /// Update counts of the same shape, updated in place.
    pub visits: &'a mut [i64],
    /// The actions each sub-task may take.
    pub allowed: [[bool; NUM_ACTIONS]; door::NUM_SUBTASKS],
    /// The mirror image ([`Symmetry::new`] of the round's phases, or another for tests).
    pub symmetry: &'a Symmetry,
}

/// The robots of one batch in a round, and what is particular to them.
pub struct Crew<'a> {
    /// The robots.
    pub batch: &'a mut Batch,
    /// The batch's buffers, left holding the last step.
    pub out: Outputs<'a>,
    /// The round's number of each of the batch's robots, in increasing order.
    pub members: Vec<usize>,
    /// The world each of the batch's robots is in (updated as robots move to other worlds).
    pub world_of_env: &'a mut [i64],
    /// Left and right wheel speeds (rad/s) of each action.
    pub wheel_speeds: [[f32; 2]; NUM_ACTIONS],
    /// How their distance readings become the seed robot's six volts; `None`: the first six
    /// readings are those volts.
    pub volts: Option<&'a SeedVolts>,
}

impl Crew<'_> {
    fn check(&self) -> Result<()> {
        let batch = &*self.batch;
        batch.check_outputs(&self.out)?;
        if self.members.len() != batch.len() || self.world_of_env.len() != batch.len() {
            return Err(Error::InvalidArgument(format!(
                "expected a round number and a world for each of a crew's {} robots, found {} \
                 and {}",
                batch.len(),
                self.members.len(),
                self.world_of_env.len()
            )));
        }
        if self.members.windows(2).any(|pair| pair[0] >= pair[1]) {
            return Err(Error::InvalidArgument(
                "expected a crew's round numbers in increasing order".into(),
            ));
        }
        let width = batch.envs()[0].distance_sensors().len();
        match self.volts {
            None if width < NUM_SENSORS => Err(Error::InvalidArgument(format!(
                "the lower level reads {NUM_SENSORS} distance sensors, the robots have {width}"
            ))),
            Some(map) if map.sensor_count() != width => Err(Error::InvalidArgument(format!(
                "expected a map of the readings of {width} distance sensors into seed volts, \
                 found one of {}",
                map.sensor_count()
            ))),
            _ => Ok(()),
        }
    }
}

/// The Table 4.1 state of a robot's distance `readings`, through `volts` when it reads otherwise
/// than the seed robot.
fn distance_state(discretiser: &Discretiser, volts: Option<&SeedVolts>, readings: &[f32]) -> usize {
    match volts {
        Some(map) => discretiser.state(&map.volts(readings)),
        None => discretiser.state(readings),
    }
}

/// What happened in a round.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct RoundCounts {
    /// Door episodes of each sub-task that ended in their opening.
    pub success: [u64; door::NUM_SUBTASKS],
    /// Door episodes that ended elsewhere, or gave up turned round.
    pub failure: [u64; door::NUM_SUBTASKS],
    /// Door episodes that ran out of steps.
    pub cut: [u64; door::NUM_SUBTASKS],
    /// Metres Corridors and Corners drove forward, summed step by step in robot order.
    pub corridor_metres: f64,
    /// Robot-steps in contact with a wall.
    pub contact_steps: u64,
}

/// A door path: to the door along the corridor, then into the opening.
#[derive(Debug, Clone, Copy, Default)]
struct DoorPath {
    start: [f64; 2],
    centre: [f64; 2],
    heading_in: [f64; 2],
    heading_out: [f64; 2],
    first_leg: f64,
}

fn dot(a: [f64; 2], from: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - from[0]) * b[0] + (a[1] - from[1]) * b[1]
}

impl DoorPath {
    fn of(row: &[f64]) -> Self {
        Self {
            start: [row[0], row[1]],
            centre: [row[2], row[3]],
            heading_in: [row[4], row[5]],
            heading_out: [row[6], row[7]],
            first_leg: row[8],
        }
    }

    /// Metres along the path (the first leg clipped to its length).
    fn progress(&self, p: [f64; 2], exit: f64) -> f64 {
        let first = dot(p, self.start, self.heading_in);
        let second = dot(p, self.centre, self.heading_out);
        first.min(self.first_leg) + second.clamp(0.0, exit)
    }

    /// Whether `p` is past the door's centre into the opening, near its centre line.
    fn entered(&self, p: [f64; 2], settings: &RoundSettings) -> bool {
        let along = dot(p, self.centre, self.heading_out);
        let relative = [p[0] - self.centre[0], p[1] - self.centre[1]];
        let across = (relative[0] * self.heading_out[1] - relative[1] * self.heading_out[0]).abs();
        along >= settings.success_past_centre && across <= settings.success_across
    }
}

/// One robot's episode and decision.
#[derive(Debug, Clone, Copy)]
struct Learner {
    role: usize,
    task: SubTaskState,
    path: DoorPath,
    progress: f64,
    previous_error: f64,
    /// The row of its table it is in.
    state: usize,
    action: usize,
    reward: f64,
    discount: f64,
    decided_steps: u64,
    deciding: bool,
    episode_steps: u64,
    next_start: usize,
    /// What its last step brought.
    step: StepDone,
}

/// What one robot's control step brought, for the tables and the counts.
#[derive(Debug, Clone, Copy, Default)]
struct StepDone {
    /// The decision that ended with the step, and its mirror image.
    transitions: Option<[Transition; 2]>,
    /// A door episode ended (in its opening or not, not cut short).
    ended: bool,
    /// ...in its opening.
    good: bool,
    /// A door episode ran out of steps.
    cut_short: bool,
    /// Metres driven forward by Corridors and Corners (0 in a door sub-task).
    forward: f64,
    colliding: bool,
    /// The episode is over: the robot starts its next one.
    restart: bool,
}

/// What every robot's step reads, shared by the threads.
struct Pass<'a> {
    q: &'a [f64],
    allowed: &'a [[bool; NUM_ACTIONS]; door::NUM_SUBTASKS],
    symmetry: &'a Symmetry,
    wheel_speeds: &'a [[f32; 2]; NUM_ACTIONS],
    settings: &'a RoundSettings,
    discretiser: &'a Discretiser,
    volts: Option<&'a SeedVolts>,
}

impl Pass<'_> {
    /// One control step of one robot: its decision when it is deciding (exploring when `draw`
    /// is below epsilon, then taking `random`), the step, its reward, and the decision it ends.
    fn step(
        &self,
        env: &mut Simulator,
        learner: &mut Learner,
        row: Row<'_>,
        draw: f64,
        random: i64,
    ) {
        let settings = self.settings;
        let rows = settings.phases.rows();
        let per_table = rows * NUM_ACTIONS;
        if learner.deciding {
            let chosen = if draw < settings.epsilon {
                random as usize
            } else {
                let table = &self.q[learner.role * per_table..][..per_table];
                let values = &table[learner.state * NUM_ACTIONS..][..NUM_ACTIONS];
                let allowed = &self.allowed[learner.role];
                best_action(values, (0..NUM_ACTIONS).filter(|&a| allowed[a]))
            };
            let yaw = f64::from(env.pose()[2]);
            learner.action =
                settings
                    .blind
                    .action(learner.role, learner.state, yaw, learner.action, chosen);
            learner.reward = 0.0;
            learner.discount = 1.0;
            learner.decided_steps = 0;
        }
        let [bx, by, byaw] = env.pose().map(f64::from);
        let [left, right] = self.wheel_speeds[learner.action];
        // The wheel speeds are finite (checked when the round began), so a step cannot fail.
        let _ = env.step(f64::from(left), f64::from(right));
        row.write(env);
        let pose = env.pose();
        let here = position(pose);
        learner.episode_steps += 1;
        let end = learner.task.update(pose);
        let is_door = learner.role != door::CORRIDOR;
        let gave_up = end == SubTaskEnd::GaveUp;
        let done = end == SubTaskEnd::Done;
        let out_of_steps = gave_up && is_door && learner.task.steps >= door::MAX_DOOR_STEPS;
        let distance = distance_state(self.discretiser, self.volts, env.distance_sensors());
        let next_state = settings.phases.table_row(&learner.task, pose, distance);

        // Metres forward along the heading before the step: Corridors and Corners' reward and
        // count (a door sub-task's reward reads its path's progress instead).
        let forward = if is_door {
            0.0
        } else {
            (here[0] - bx) * byaw.cos() + (here[1] - by) * byaw.sin()
        };
        let new_progress = learner.path.progress(here, settings.door_path_exit);
        let rewards = &settings.rewards;
        let mut reward = if is_door {
            rewards.progress * (new_progress - learner.progress) + rewards.door_step
        } else {
            rewards.progress * forward + rewards.corridor_step
        };
        let colliding = env.colliding();
        reward += rewards.collision * f64::from(u8::from(colliding));
        learner.progress = new_progress;
        let heading_error = learner.task.heading_change.abs();
        reward += if learner.role == door::FORWARD {
            rewards.heading * (learner.previous_error - heading_error)
        } else {
            0.0
        };
        learner.previous_error = heading_error;
        let ended = is_door && (done || (gave_up && !out_of_steps));
        let good = ended && done && learner.path.entered(here, settings);
        reward += if ended {
            if good {
                rewards.door_success
            } else {
                rewards.door_failure
            }
        } else {
            0.0
        };
        let cut_short = is_door && out_of_steps;
        let corridor_over = !is_door && learner.episode_steps >= settings.corridor_episode_steps;

        learner.reward += learner.discount * reward;
        learner.discount *= settings.gamma;
        learner.decided_steps += 1;
        learner.deciding = ended
            || cut_short
            || corridor_over
            || next_state != learner.state
            || learner.decided_steps >= settings.decision_steps;
        let transitions = learner.deciding.then(|| {
            let bootstrap = if ended { 0.0 } else { learner.discount };
            let mirror = |row: usize| self.symmetry.row(learner.role, row);
            [
                Transition {
                    state: learner.state,
                    action: learner.action,
                    reward: learner.reward,
                    next_state,
                    bootstrap,
                },
                Transition {
                    state: mirror(learner.state),
                    action: self.symmetry.actions[learner.action],
                    reward: learner.reward,
                    next_state: mirror(next_state),
                    bootstrap,
                },
            ]
        });
        learner.state = next_state;
        learner.step = StepDone {
            transitions,
            ended,
            good,
            cut_short,
            forward,
            colliding,
            restart: ended || cut_short || corridor_over,
        };
    }
}

/// Checks that every one of `indices` names one of `worlds` worlds.
fn world_indices(indices: &[i64], worlds: usize) -> Result<()> {
    let worlds = worlds as i64;
    match indices.iter().find(|&&w| !(0..worlds).contains(&w)) {
        Some(w) => Err(Error::InvalidArgument(format!(
            "expected world indices in [0, {worlds}), found {w}"
        ))),
        None => Ok(()),
    }
}

fn pose_of(poses: &[f32], i: usize) -> [f32; 3] {
    [poses[3 * i], poses[3 * i + 1], poses[3 * i + 2]]
}

fn position(pose: [f32; 3]) -> [f64; 2] {
    [f64::from(pose[0]), f64::from(pose[1])]
}

impl LowerRound<'_> {
    fn check(&self, n: usize) -> Result<()> {
        let expect = |name: &str, found: usize, wanted: usize| {
            if found == wanted {
                Ok(())
            } else {
                Err(Error::InvalidArgument(format!(
                    "expected {name} to hold {wanted} values, found {found}"
                )))
            }
        };
        let k = self.starts.per_env;
        if k == 0 {
            return Err(Error::InvalidArgument(
                "expected at least one start per robot, found 0".into(),
            ));
        }
        expect("role", self.role.len(), n)?;
        expect("start worlds", self.starts.world.len(), n * k)?;
        expect("start poses", self.starts.pose.len(), 3 * n * k)?;
        expect("start seeds", self.starts.seed.len(), n * k)?;
        expect("door paths", self.starts.path.len(), PATH_WIDTH * n * k)?;
        let steps = self.explore.len() / n;
        expect("explore", self.explore.len(), steps * n)?;
        expect("random_action", self.random_action.len(), steps * n)?;
        let rows = self.settings.phases.rows();
        let per_table = rows * NUM_ACTIONS;
        expect("q", self.q.len(), door::NUM_SUBTASKS * per_table)?;
        expect("visits", self.visits.len(), door::NUM_SUBTASKS * per_table)?;
        if let Some(r) = self.role.iter().find(|&&r| !(0..4).contains(&r)) {
            return Err(Error::InvalidArgument(format!(
                "expected sub-tasks in 0..4, found {r}"
            )));
        }
        world_indices(self.starts.world, self.worlds.len())?;
        if let Some(a) = self.random_action.iter().find(|&&a| !(0..12).contains(&a)) {
            return Err(Error::InvalidArgument(format!(
                "expected exploring actions in [0, {NUM_ACTIONS}), found {a}"
            )));
        }
        // A sub-task never explores an action it may not take (Corridors and Corners: `99`).
        let not_allowed = self.random_action.iter().enumerate().find(|&(at, &a)| {
            let subtask = self.role[at % n] as usize;
            !self.allowed[subtask][a as usize]
        });
        if let Some((at, &a)) = not_allowed {
            let (step, env) = (at / n, at % n);
            return Err(Error::InvalidArgument(format!(
                "expected exploring actions the robot's sub-task may take, found action {a} for \
                 robot {env} (sub-task {}) at step {step}",
                self.role[env]
            )));
        }
        self.symmetry.check(self.settings.phases.count())?;
        // The tables are large (56 MB with the door sub-tasks that count the distance): each is
        // read once by a reduction without branches, and searched for what is wrong only then.
        if self.visits.iter().fold(0, |all, &v| all | v) < 0 {
            let v = self
                .visits
                .iter()
                .find(|&&v| v < 0)
                .copied()
                .unwrap_or_default();
            return Err(Error::InvalidArgument(format!(
                "expected visit counts of 0 or more, found {v}"
            )));
        }
        if self.q.iter().fold(false, |bad, v| bad | !v.is_finite()) {
            let v = self
                .q
                .iter()
                .find(|v| !v.is_finite())
                .copied()
                .unwrap_or_default();
            return Err(Error::InvalidArgument(format!(
                "expected finite Q-values, found {v}"
            )));
        }
        let finite = self.starts.pose.iter().chain(self.starts.path);
        if let Some(v) = finite.chain(self.explore).find(|v| !v.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "expected finite starts, door paths and exploration draws, found {v}"
            )));
        }
        Ok(())
    }
}

/// Runs one round of the lower level's Q-learning (see the module) with the robots of `crews`,
/// numbered across them: `round.explore` sets the number of control steps; the tables, each
/// crew's `world_of_env` and robots are left as the round leaves them, and each crew's buffers
/// hold its last step.
pub fn train_lower_round(round: LowerRound<'_>, crews: &mut [Crew<'_>]) -> Result<RoundCounts> {
    let n = round.role.len();
    round.check(n)?;
    // Where each robot of the round is: its crew and its row there.
    let mut place = vec![None; n];
    for (c, crew) in crews.iter().enumerate() {
        crew.check()?;
        for (r, &i) in crew.members.iter().enumerate() {
            let slot = place.get_mut(i).ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "expected round numbers in [0, {n}) in the crews, found {i}"
                ))
            })?;
            if slot.replace((c, r)).is_some() {
                return Err(Error::InvalidArgument(format!(
                    "expected each robot of the round in one crew, found robot {i} twice"
                )));
            }
        }
        world_indices(crew.world_of_env, round.worlds.len())?;
    }
    let place: Vec<(usize, usize)> = place
        .into_iter()
        .enumerate()
        .map(|(i, at)| {
            at.ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "expected robot {i} of the round in a crew, found it in none"
                ))
            })
        })
        .collect::<Result<_>>()?;
    let LowerRound {
        settings,
        worlds,
        role,
        starts,
        explore,
        random_action,
        q,
        visits,
        allowed,
        symmetry,
    } = round;
    let starter = Starter {
        starts,
        worlds,
        door_path_exit: settings.door_path_exit,
        phases: settings.phases,
        discretiser: Discretiser::new()?,
    };
    let steps = explore.len() / n.max(1);
    let learner = |i: usize| Learner {
        role: role[i] as usize,
        task: SubTaskState::begin(role[i] as usize, [0.0; 3]),
        path: DoorPath::default(),
        progress: 0.0,
        previous_error: 0.0,
        state: 0,
        action: 0,
        reward: 0.0,
        discount: 1.0,
        decided_steps: 0,
        deciding: true,
        episode_steps: 0,
        next_start: 0,
        step: StepDone::default(),
    };
    let mut learners: Vec<Vec<Learner>> = crews
        .iter()
        .map(|crew| crew.members.iter().map(|&i| learner(i)).collect())
        .collect();
    let everyone: Vec<usize> = (0..n).collect();
    let mut counts = RoundCounts::default();
    let mut originals: Vec<Vec<Transition>> = vec![Vec::new(); door::NUM_SUBTASKS];
    let mut mirrors: Vec<Vec<Transition>> = vec![Vec::new(); door::NUM_SUBTASKS];
    let mut targets = Vec::new();
    let mut restart = Vec::new();
    let per_table = settings.phases.rows() * NUM_ACTIONS;

    starter.start(crews, &everyone, &place, &mut learners)?;
    for step in 0..steps {
        let draws = &explore[step * n..(step + 1) * n];
        let randoms = &random_action[step * n..(step + 1) * n];
        // Every robot decides (reading the tables as the last step left them), steps and
        // scores its step, in parallel; what the step taught is gathered below in order.
        for (crew, learners) in crews.iter_mut().zip(&mut learners) {
            let Crew {
                batch,
                out,
                members,
                wheel_speeds,
                volts,
                ..
            } = crew;
            let pass = Pass {
                q: &*q,
                allowed: &allowed,
                symmetry,
                wheel_speeds,
                settings: &settings,
                discretiser: &starter.discretiser,
                volts: *volts,
            };
            let width = batch.observation_width();
            let distance_width = batch.envs()[0].distance_sensors().len();
            let outputs = out.reborrow();
            let members = &*members;
            let chunks = chunks_of(move |envs| {
                envs.chunks_mut(CHUNK_ENVS)
                    .zip(learners.chunks_mut(CHUNK_ENVS))
                    .zip(outputs.chunks(width))
                    .enumerate()
            });
            batch.par_chunks(chunks, |(k, ((envs, learners), outputs)), stop| {
                let rows = outputs.rows(width, distance_width);
                for (j, ((env, learner), row)) in
                    envs.iter_mut().zip(learners).zip(rows).enumerate()
                {
                    if stop() {
                        return;
                    }
                    let i = members[k * CHUNK_ENVS + j];
                    pass.step(env, learner, row, draws[i], randoms[i]);
                }
            })?;
        }

        let mut corridor_metres = 0.0;
        for (i, &(c, r)) in place.iter().enumerate() {
            let learner = &learners[c][r];
            let done = &learner.step;
            if let Some([own, mirrored]) = done.transitions {
                originals[learner.role].push(own);
                mirrors[symmetry.subtasks[learner.role]].push(mirrored);
            }
            if learner.role != door::CORRIDOR {
                counts.success[learner.role] += u64::from(done.good);
                counts.failure[learner.role] += u64::from(done.ended && !done.good);
                counts.cut[learner.role] += u64::from(done.cut_short);
            } else {
                corridor_metres += done.forward;
            }
            counts.contact_steps += u64::from(done.colliding);
            if done.restart {
                restart.push(i);
            }
        }
        counts.corridor_metres += corridor_metres;
        // Each table learns from its robots' decisions, then from the mirror images.
        for (subtask, (own, mirrored)) in originals.iter_mut().zip(&mut mirrors).enumerate() {
            own.append(mirrored);
            if !own.is_empty() {
                let mut table = QTable {
                    values: &mut q[subtask * per_table..][..per_table],
                    visits: &mut visits[subtask * per_table..][..per_table],
                    actions: NUM_ACTIONS,
                };
                table.update(own, &allowed[subtask], &settings.rate, &mut targets);
                own.clear();
            }
        }
        if !restart.is_empty() {
            starter.start(crews, &restart, &place, &mut learners)?;
            restart.clear();
        }
    }
    Ok(counts)
}

/// Where the robots' episodes start: their queues, the worlds they name, and what a start sets.
struct Starter<'a> {
    starts: StartQueues<'a>,
    worlds: &'a [Arc<World>],
    door_path_exit: f64,
    phases: Phases,
    discretiser: Discretiser,
}

impl Starter<'_> {
    /// Starts the next episode of each robot of `envs` (round numbers, in increasing order) from
    /// its queue: into its world (when it is elsewhere), at its pose with its noise seed, its
    /// sub-task begun there and its decision open.
    fn start(
        &self,
        crews: &mut [Crew<'_>],
        envs: &[usize],
        place: &[(usize, usize)],
        learners: &mut [Vec<Learner>],
    ) -> Result<()> {
        for &i in envs {
            let (c, r) = place[i];
            let crew = &mut crews[c];
            let learner = &mut learners[c][r];
            let starts = &self.starts;
            let row = i * starts.per_env + learner.next_start % starts.per_env;
            learner.next_start += 1;
            let world = starts.world[row];
            let batch = &mut *crew.batch;
            if crew.world_of_env[r] != world {
                batch.set_world(r, self.worlds[world as usize].clone(), 0)?;
                crew.world_of_env[r] = world;
            }
            batch.set_starts_at(&[r], &starts.pose[3 * row..3 * row + 3])?;
            let width = batch.observation_width();
            let distance_width = batch.envs()[0].distance_sensors().len();
            let out = &mut crew.out;
            let env = batch.env_mut(r)?;
            env.reset(Some(starts.seed[row]));
            Row {
                observation: &mut out.observations[r * width..(r + 1) * width],
                distance_width,
                pose: &mut out.poses[3 * r..3 * r + 3],
                colliding: &mut out.colliding[r],
                crossing: &mut out.crossings[r],
            }
            .write(env);
            let pose = pose_of(out.poses, r);
            learner.path = DoorPath::of(&starts.path[PATH_WIDTH * row..PATH_WIDTH * (row + 1)]);
            learner.task = SubTaskState::begin(learner.role, pose);
            learner.progress = learner.path.progress(position(pose), self.door_path_exit);
            learner.previous_error = 0.0;
            let distance = distance_state(&self.discretiser, crew.volts, env.distance_sensors());
            learner.state = self.phases.table_row(&learner.task, pose, distance);
            learner.episode_steps = 0;
        }
        Ok(())
    }
}
