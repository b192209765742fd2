//! The multi-step call: many control steps of every environment of a batch in one call, each
//! environment's wheel speeds chosen by a built-in [`Controller`] in the core, with episodes
//! ending on a step limit or at the goal and, optionally, reset as they end.
//!
//! Environments are independent, so each runs a block of steps on its own (its state stays in
//! cache) before the next takes its place; the threads take chunks of environments from one queue
//! as a single step does. A run of `k` steps gives, bit for bit, what `k` calls of
//! [`Batch::step`] give with the same controller computed outside, whatever the thread count or
//! the batch size: each environment draws only from its own stream (seeded per environment) and
//! its simulator's. Per-step outputs are written only where the caller asks for them.

use std::ops::Range;
use std::sync::Arc;
use std::time::Instant;

use crate::batch::{CHUNK_ENVS, INTERRUPT_POLL};
use crate::control::Controller;
use crate::error::{Error, Result};
use crate::navigator::door::{self, SubTaskEnd, SubTaskState};
use crate::rng::{next_seed, Rng};
use crate::{Batch, Simulator, StepOutputs};

/// Steps each environment takes before the next takes its place: long enough to keep an
/// environment in cache, short enough that Ctrl-C (asked between environments) is answered soon.
const BLOCK_STEPS: usize = 64;

/// How a multi-step call runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct RunOptions {
    /// Control steps of every environment.
    pub steps: usize,
    /// An episode ends after this many control steps since its reset (0: no limit).
    pub max_episode_steps: u64,
    /// An episode also ends on the step the robot's centre enters its goal disc (the world's, or
    /// the one `set_goal` gave).
    pub end_at_goal: bool,
    /// An episode also ends on a step that crosses a barcode. Without `autoreset`, an environment
    /// stopped by a crossing stands still for the rest of the call only: the next call moves it
    /// on (after, say, a higher level chose what it does next).
    pub end_at_crossing: bool,
    /// An environment whose episode ends is reset at once (its next seed is
    /// [`crate::rng::next_seed`] of its last one) and goes on; otherwise it stands still for the
    /// rest of the call and later calls (until it is reset).
    pub autoreset: bool,
}

/// Declares the per-step outputs once: [`RunTrace`], the caller's buffers; `ChunkTrace`, one
/// chunk of environments' rows of each step of a block (empty when not traced); the check of
/// their sizes and the split into chunks. Each output is `name: type = width per environment`,
/// the width an expression of the observation width, named by the first word.
macro_rules! trace_outputs {
    ($width:ident; $($(#[doc = $doc:expr])* $name:ident: $t:ty = $w:expr,)*) => {
        /// Per-step outputs of a multi-step call, each `(steps, n, width)` values in step-major
        /// order, written only where given. Row `[t, i]` holds environment i's state after its
        /// step t, before any reset that step's end of episode brings; an environment that
        /// stands still repeats its observation and pose, with colliding false, crossing 0,
        /// wheel speeds 0 and action -1.
        #[derive(Default)]
        pub struct RunTrace<'a> {
            $($(#[doc = $doc])* pub $name: Option<&'a mut [$t]>,)*
        }

        /// One chunk of environments' rows of each step of a block, per traced output (empty
        /// when not traced).
        struct ChunkTrace<'a> {
            $($name: Vec<&'a mut [$t]>,)*
        }

        impl RunTrace<'_> {
            /// Checks that each traced output holds `steps x n x width` values.
            fn check(&self, steps: usize, n: usize, $width: usize) -> Result<()> {
                $(check_trace(concat!(stringify!($name), " trace"), &self.$name, [steps, n, $w])?;)*
                Ok(())
            }

            /// Per chunk of `CHUNK_ENVS` environments, its rows of steps `steps` of each traced
            /// output.
            fn chunk_rows(
                &mut self,
                steps: Range<usize>,
                n: usize,
                $width: usize,
            ) -> Vec<ChunkTrace<'_>> {
                $(let mut $name = chunk_part(&mut self.$name, &steps, n, $w);)*
                (0..n.div_ceil(CHUNK_ENVS))
                    .map(|_| ChunkTrace {
                        $($name: $name.next().unwrap_or_default(),)*
                    })
                    .collect()
            }
        }
    };
}

trace_outputs! {
    width;
    /// Observations, `(steps, n, observation_width)`.
    observations: f32 = width,
    /// Poses (x, y, yaw), `(steps, n, 3)`.
    poses: f32 = 3,
    /// Touched a wall during the step, `(steps, n)`.
    colliding: bool = 1,
    /// Signed checkpoint id of a barcode crossed in the step, 0 for none, `(steps, n)`.
    crossings: i32 = 1,
    /// The wheel speeds the controller chose (rad/s, before the motor limit), `(steps, n, 2)`.
    wheel_speeds: f32 = 2,
    /// The primitive action the controller chose, -1 for none, `(steps, n)`.
    actions: i32 = 1,
    /// The episode ended with the step, `(steps, n)`.
    episode_ends: bool = 1,
    /// With sub-tasks, the sub-task the step's action was chosen in, -1 for none, `(steps, n)`.
    subtasks: i32 = 1,
    /// With sub-tasks, the phase whose table the action came from, -1 for none, `(steps, n)`.
    phases: i32 = 1,
    /// With sub-tasks, a door sub-task ended (or gave up) before the step's action was chosen,
    /// `(steps, n)`.
    subtask_ends: bool = 1,
}

/// Which environments a multi-step call moves, and the sub-tasks its tabular controller follows.
#[derive(Default)]
pub struct RunEnvs<'a> {
    /// The environments that move (all when `None`); the others stand still for the whole call,
    /// as an environment whose episode ended does, and their random streams are not drawn from.
    pub active: Option<&'a [bool]>,
    /// Each environment's running sub-task of the navigator's lower level (`None`: the tabular
    /// controller acts from `table_of_env`). The tabular controller then acts from the table
    /// of the sub-task's phase and follows the odometry after every step, as
    /// `mazesim.learn.policy.HierarchicalPolicy.act` does: a door sub-task that ends (or gives
    /// up) hands over to Corridors and Corners, which goes on. A state is taken as the caller
    /// left it after following the last step (so the first step of a call follows nothing)
    /// and is left the same way: the odometry has followed every step of the call but the last.
    /// An environment reset by `autoreset` begins Corridors and Corners at its new pose.
    pub subtasks: Option<&'a mut [SubTaskState]>,
}

/// What a multi-step call counted, per environment.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct RunCounters {
    /// Control steps taken (fewer than asked for an environment that stood still).
    pub steps: Vec<u64>,
    /// Steps during which the robot touched a wall.
    pub steps_in_contact: Vec<u64>,
    /// Episodes that ended.
    pub episodes_finished: Vec<u64>,
    /// Episodes that ended at the goal.
    pub goals_reached: Vec<u64>,
    /// Door sub-tasks that reached their end (with `RunEnvs::subtasks`).
    pub subtasks_done: Vec<u64>,
    /// Door sub-tasks that gave up: out of steps or turned round (with `RunEnvs::subtasks`).
    pub subtasks_given_up: Vec<u64>,
}

/// One environment's counters, as the threads add to them.
#[derive(Debug, Clone, Copy, Default)]
struct Counts {
    /// Held still for the whole call (not among the call's active environments).
    held: bool,
    /// Stopped by an episode's end for the rest of the call (without autoreset).
    stopped: bool,
    steps: u64,
    in_contact: u64,
    finished: u64,
    at_goal: u64,
    /// The running sub-task, when the call follows sub-tasks.
    task: Option<SubTaskState>,
    subtasks_done: u64,
    subtasks_given_up: u64,
}

/// Per chunk of `CHUNK_ENVS` environments, its rows of each step of `block` (`(steps, n, width)`
/// values); empty lists when `block` is `None`.
fn rows_per_chunk<T>(block: Option<&mut [T]>, n: usize, width: usize) -> Vec<Vec<&mut [T]>> {
    let mut per_chunk: Vec<Vec<&mut [T]>> = (0..n.div_ceil(CHUNK_ENVS)).map(|_| vec![]).collect();
    for step in block.into_iter().flat_map(|b| b.chunks_mut(n * width)) {
        for (rows, chunk) in step.chunks_mut(CHUNK_ENVS * width).zip(&mut per_chunk) {
            chunk.push(rows);
        }
    }
    per_chunk
}

/// Per chunk of `CHUNK_ENVS` environments, its rows of steps `steps` of a traced output of
/// `width` values per environment.
fn chunk_part<'t, T>(
    values: &'t mut Option<&mut [T]>,
    steps: &Range<usize>,
    n: usize,
    width: usize,
) -> std::vec::IntoIter<Vec<&'t mut [T]>> {
    let span = steps.start * n * width..steps.end * n * width;
    let block = values.as_deref_mut().map(|v| &mut v[span]);
    rows_per_chunk(block, n, width).into_iter()
}

/// Writes `value` as environment `j`'s row of step `s` in `rows`, when traced.
fn put<T: Copy>(rows: &mut [&mut [T]], s: usize, j: usize, value: &[T]) {
    if let Some(step) = rows.get_mut(s) {
        let w = value.len();
        step[j * w..(j + 1) * w].copy_from_slice(value);
    }
}

/// Checks that a traced output holds `steps x n x width` values.
fn check_trace<T>(name: &str, values: &Option<&mut [T]>, shape: [usize; 3]) -> Result<()> {
    match values {
        Some(v) if v.len() != shape.iter().product::<usize>() => {
            Err(Error::InvalidArgument(format!(
                "expected {name} to hold {} x {} x {} values, found {}",
                shape[0],
                shape[1],
                shape[2],
                v.len()
            )))
        }
        _ => Ok(()),
    }
}

/// Whether the episode of `env` is over: its step limit reached, its robot at the goal or, when
/// `after_step`, a barcode crossed in its last step; and whether it is at the goal.
fn episode_over(env: &Simulator, options: &RunOptions, after_step: bool) -> (bool, bool) {
    let at_goal = options.end_at_goal
        && env.goal().is_some_and(|goal| {
            let [x, y, _] = env.pose();
            let (dx, dy) = (x as f64 - goal.center[0], y as f64 - goal.center[1]);
            dx * dx + dy * dy <= goal.radius * goal.radius
        });
    let limit = options.max_episode_steps;
    let crossed = after_step && options.end_at_crossing && env.last_crossing() != 0;
    (
        at_goal || crossed || (limit > 0 && env.steps() >= limit),
        at_goal,
    )
}

/// `chunks` with its argument's lifetime tied to its result's (a closure alone would be inferred
/// for any lifetime).
pub(crate) fn chunks_of<'e, I, F: FnOnce(&'e mut [Simulator]) -> I>(chunks: F) -> F {
    chunks
}

impl Batch {
    /// Runs `options.steps` control steps of every environment, wheel speeds from `controller`,
    /// environment i drawing its random numbers from a stream seeded with `seeds[i]`. The final
    /// state goes into `out` (as after [`Batch::step`]), the per-step outputs into the parts of
    /// `trace` that are given; the counters are returned.
    ///
    /// Ctrl-C (see [`Batch::set_interrupt`]) stops the call between environments with
    /// `Error::Interrupted`, the environments standing where they were.
    pub fn run_steps(
        &mut self,
        controller: &Controller,
        seeds: &[u64],
        options: &RunOptions,
        out: StepOutputs<'_>,
        trace: RunTrace<'_>,
    ) -> Result<RunCounters> {
        let envs = RunEnvs::default();
        self.run_steps_of(controller, seeds, options, envs, out, trace)
    }

    /// [`Batch::run_steps`] for the environments `envs.active` (all when `None`), the tabular
    /// controller following `envs.subtasks` when given (see [`RunEnvs`]). A caller that
    /// steps some environments one step at a time (deciding in between) and others many steps
    /// at once runs both through this.
    pub fn run_steps_of(
        &mut self,
        controller: &Controller,
        seeds: &[u64],
        options: &RunOptions,
        envs: RunEnvs<'_>,
        out: StepOutputs<'_>,
        trace: RunTrace<'_>,
    ) -> Result<RunCounters> {
        let RunEnvs { active, subtasks } = envs;
        let n = self.len();
        let width = self.observation_width();
        let mut checked = std::collections::HashSet::new();
        for env in self.envs() {
            if checked.insert(Arc::as_ptr(env.rig())) {
                controller.check(env.robot(), n)?;
            }
        }
        if seeds.len() != n {
            return Err(Error::InvalidArgument(format!(
                "expected one controller seed per environment ({n}), found {}",
                seeds.len()
            )));
        }
        self.check_outputs(&out)?;
        let steps = options.steps;
        trace.check(steps, n, width)?;

        let mut streams: Vec<Rng> = seeds.iter().map(|&s| Rng::new(s)).collect();
        if let Some(flags) = active {
            if flags.len() != n {
                return Err(Error::InvalidArgument(format!(
                    "expected one active flag per environment ({n}), found {}",
                    flags.len()
                )));
            }
        }
        if let Some(tasks) = &subtasks {
            controller.check_subtasks()?;
            if tasks.len() != n {
                return Err(Error::InvalidArgument(format!(
                    "expected one sub-task state per environment ({n}), found {}",
                    tasks.len()
                )));
            }
            for (i, task) in tasks.iter().enumerate() {
                task.check(i)?;
            }
        }
        let mut counts: Vec<Counts> = (0..n)
            .map(|i| Counts {
                held: active.is_some_and(|flags| !flags[i]),
                task: subtasks.as_ref().map(|tasks| tasks[i]),
                ..Counts::default()
            })
            .collect();
        let stepped = self.run_blocks(controller, options, &mut streams, &mut counts, out, trace);
        // The sub-tasks as far as they got, even when Ctrl-C stopped the call.
        if let Some(tasks) = subtasks {
            for (task, count) in tasks.iter_mut().zip(&counts) {
                *task = count.task.unwrap_or(*task);
            }
        }
        stepped?;
        let counters = |f: fn(&Counts) -> u64| counts.iter().map(f).collect();
        Ok(RunCounters {
            steps: counters(|c| c.steps),
            steps_in_contact: counters(|c| c.in_contact),
            episodes_finished: counters(|c| c.finished),
            goals_reached: counters(|c| c.at_goal),
            subtasks_done: counters(|c| c.subtasks_done),
            subtasks_given_up: counters(|c| c.subtasks_given_up),
        })
    }

    /// The blocks of steps of a multi-step call, after its checks.
    fn run_blocks(
        &mut self,
        controller: &Controller,
        options: &RunOptions,
        streams: &mut [Rng],
        counts: &mut [Counts],
        out: StepOutputs<'_>,
        trace: RunTrace<'_>,
    ) -> Result<()> {
        let n = self.len();
        let width = self.observation_width();
        let robot = self.envs()[0].robot().clone();
        let steps = options.steps;
        let dw = robot.distance_sensors.len();
        let mut out = out;
        let mut trace = trace;
        let mut first = 0;
        let mut polled = Instant::now();
        loop {
            let block = BLOCK_STEPS.min(steps - first);
            let traced = trace.chunk_rows(first..first + block, n, width);
            let outputs = out.reborrow();
            let (streams, counts) = (&mut *streams, &mut *counts);
            let chunks = chunks_of(move |envs| {
                envs.chunks_mut(CHUNK_ENVS)
                    .zip({ streams }.chunks_mut(CHUNK_ENVS))
                    .zip({ counts }.chunks_mut(CHUNK_ENVS))
                    .zip(outputs.chunks(width))
                    .zip(traced)
                    .enumerate()
            });
            self.par_chunks(chunks, |chunk, stop| {
                let (k, ((((envs, streams), counts), outputs), mut rows)) = chunk;
                let per_env = envs
                    .iter_mut()
                    .zip(streams.iter_mut())
                    .zip(counts.iter_mut())
                    .zip(outputs.rows(width, dw))
                    .enumerate();
                for (j, (((env, stream), count), row)) in per_env {
                    if stop() {
                        return;
                    }
                    let index = k * CHUNK_ENVS + j;
                    for s in 0..block {
                        let at = (s, j);
                        step_one(
                            controller, options, index, env, stream, count, &mut rows, at,
                        );
                    }
                    row.write(env);
                }
            })?;
            first += block;
            if first >= steps {
                break;
            }
            // Blocks can be shorter than the poll interval: ask between them too.
            if polled.elapsed() >= INTERRUPT_POLL {
                polled = Instant::now();
                if self.interrupted() {
                    return Err(Error::Interrupted);
                }
            }
        }
        Ok(())
    }
}

/// One control step of environment `index` at `(s, j)`: step `s` of the block, row `j` of its
/// chunk.
#[inline]
fn step_one(
    controller: &Controller,
    options: &RunOptions,
    index: usize,
    env: &mut Simulator,
    stream: &mut Rng,
    count: &mut Counts,
    rows: &mut ChunkTrace<'_>,
    (s, j): (usize, usize),
) {
    let standing = count.held
        || (!options.autoreset && (count.stopped || episode_over(env, options, false).0));
    let mut decision = crate::control::Decision {
        wheel_speeds: [0.0; 2],
        action: -1,
    };
    let mut ended = false;
    let mut task_ended = false;
    if !standing {
        if count.steps > 0 {
            task_ended = follow_subtask(count, env.pose());
        }
        let max_speed = env.max_wheel_speed();
        let last = env.wheel_speeds();
        let task = count.task.as_ref().map(|task| (task, env.pose()));
        decision = controller.decide(index, env.distance_sensors(), last, max_speed, stream, task);
        if let Some((task, pose)) = task {
            let phase = controller.task_phase(task, pose);
            put(&mut rows.subtasks, s, j, &[task.subtask as i32]);
            put(&mut rows.phases, s, j, &[phase as i32]);
        }
        let [left, right] = decision.wheel_speeds;
        // The controllers give finite speeds, so a step cannot fail.
        let _ = env.step(left as f64, right as f64);
        count.steps += 1;
        count.in_contact += env.colliding() as u64;
        let (over, at_goal) = episode_over(env, options, true);
        ended = over;
        count.stopped = over && !options.autoreset;
        count.finished += over as u64;
        count.at_goal += at_goal as u64;
    }
    if let Some(step) = rows.observations.get_mut(s) {
        let (distance, ground) = (env.distance_sensors(), env.ground_sensors());
        let w = distance.len() + ground.len();
        let (d, g) = step[j * w..(j + 1) * w].split_at_mut(distance.len());
        d.copy_from_slice(distance);
        g.copy_from_slice(ground);
    }
    put(&mut rows.poses, s, j, &env.pose());
    put(&mut rows.colliding, s, j, &[env.colliding() && !standing]);
    put(
        &mut rows.crossings,
        s,
        j,
        &[if standing { 0 } else { env.last_crossing() }],
    );
    put(&mut rows.wheel_speeds, s, j, &decision.wheel_speeds);
    put(&mut rows.actions, s, j, &[decision.action]);
    put(&mut rows.episode_ends, s, j, &[ended]);
    put(&mut rows.subtask_ends, s, j, &[task_ended]);
    if standing || count.task.is_none() {
        put(&mut rows.subtasks, s, j, &[-1]);
        put(&mut rows.phases, s, j, &[-1]);
    }
    if ended && options.autoreset {
        let seed = next_seed(env.config().seed);
        env.reset(Some(seed));
        if let Some(task) = &mut count.task {
            *task = SubTaskState::begin(door::CORRIDOR, env.pose());
        }
    }
}

/// Follows the step that ended at `pose` in the running sub-task, if any; a door sub-task that
/// ends hands over to Corridors and Corners there (and the answer is true).
fn follow_subtask(count: &mut Counts, pose: [f32; 3]) -> bool {
    let Some(task) = &mut count.task else {
        return false;
    };
    match task.follow(pose) {
        SubTaskEnd::Running => return false,
        SubTaskEnd::Done => count.subtasks_done += 1,
        SubTaskEnd::GaveUp => count.subtasks_given_up += 1,
    }
    true
}
