//! Many independent environments stepped in parallel, writing into buffers the caller owns. Each
//! environment has its own world, robot and random stream, so its results do not depend on the
//! thread count, the batch size or its place in the batch.
//!
//! The calling thread steps environments too: it and the helper threads (a rayon pool of one
//! thread fewer than asked for) take chunks of environments from a shared queue until none is
//! left. The caller starts at once, without waiting for a helper to wake up. After a step each
//! helper stays awake for up to `LINGER` for the caller's next step (its policy, in a Python loop,
//! takes tens of microseconds), so that it joins that step at once instead of being woken up from
//! sleep; the caller's own core is never spun on. Batches that share the all-core pool may find
//! its helpers still waiting on another batch: they join once that wait ends (at most `LINGER`),
//! the caller working alone until then.

use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use crate::error::{Error, Result};
use crate::robot::RobotProfile;
use crate::simulator::{check_goal, Rig, SimConfig, Simulator};
use crate::swarm::check_apart;
use crate::world::World;

/// Environments per chunk of work: enough to amortise taking it from the queue, few enough that
/// the threads finish close together.
pub(crate) const CHUNK_ENVS: usize = 16;

/// How often the calling thread asks whether to stop (Ctrl-C) while a batch call runs.
pub(crate) const INTERRUPT_POLL: Duration = Duration::from_millis(50);

/// How long a helper waits awake for the next step of the batch it just helped.
const LINGER: Duration = Duration::from_micros(200);

mod assembly;
mod helpers;
mod outputs;
#[cfg(test)]
mod tests;

pub(crate) use assembly::{check_seeds, rigs_of};
pub use assembly::{check_size, share_equal_worlds};
pub(crate) use helpers::Helpers;
pub(crate) use outputs::Row;
pub use outputs::{OutputBuffers, StepOutputs};

/// N environments stepped together.
pub struct Batch {
    /// The robots of every environment, environment after environment (`robots` each).
    pub(crate) envs: Vec<Simulator>,
    /// Robots per environment: 1 but in a batch of worlds of several robots (`crate::swarm`).
    pub(crate) robots: usize,
    pub(crate) distance_width: usize,
    pub(crate) ground_width: usize,
    pub(crate) helpers: Helpers,
    /// Counts the batch's parallel runs; lingering helpers stop waiting when it moves.
    pub(crate) runs: Arc<AtomicU64>,
    /// The process that made `helpers` (see `guard_fork`).
    pub(crate) pid: u32,
    /// Asked between chunks whether to stop (see `set_interrupt`).
    pub(crate) interrupt: Option<Box<dyn Fn() -> bool + Send + Sync>>,
}

impl Batch {
    /// One environment per world, all with `robot`; env i gets `seeds[i]`.
    /// `threads`: 0 = every core, otherwise that many threads (the caller's among them).
    pub fn new(
        worlds: Vec<Arc<World>>,
        robot: Arc<RobotProfile>,
        seeds: &[u64],
        noise: bool,
        control_step: Option<f64>,
        threads: usize,
    ) -> Result<Batch> {
        let robots = vec![robot; worlds.len().max(1)];
        Self::with_robots(worlds, &robots, seeds, noise, control_step, threads)
    }

    /// One environment per world, env i with robot `robots[i]` (or all with `robots[0]` when it
    /// is the only one) and seed `seeds[i]`: a batch of several profiles (domain randomisation).
    /// Every profile must have as many distance and ground sensors as the first; envs of equal
    /// profiles share one sensing rig. `threads` as for [`Batch::new`].
    pub fn with_robots(
        worlds: Vec<Arc<World>>,
        robots: &[Arc<RobotProfile>],
        seeds: &[u64],
        noise: bool,
        control_step: Option<f64>,
        threads: usize,
    ) -> Result<Batch> {
        if worlds.is_empty() {
            return Err(Error::InvalidArgument(
                "expected at least one environment, found 0".into(),
            ));
        }
        check_seeds(worlds.len(), seeds)?;
        let rigs = rigs_of(robots, worlds.len())?;
        let robot = rigs[0].robot().clone();
        let worlds = share_equal_worlds(worlds);
        let walls = |w: &Arc<World>| w.solid_walls().len() as u128;
        let mut counted = std::collections::HashSet::new();
        let distinct = worlds
            .iter()
            .filter(|w| counted.insert(Arc::as_ptr(w)))
            .map(walls)
            .collect::<Vec<_>>();
        let with_bodies = worlds.iter().filter(|w| !w.bodies().is_empty()).map(walls);
        check_size(worlds.len(), distinct.into_iter().chain(with_bodies).sum())?;
        let helpers = Helpers::new(threads)?;
        let make = |(world, seed, rig): (Arc<World>, u64, Arc<Rig>)| {
            Simulator::with_rig(
                world,
                rig,
                SimConfig {
                    seed,
                    noise,
                    control_step,
                },
            )
        };
        let rig_of = |i: usize| rigs[i.min(rigs.len() - 1)].clone();
        let pairs: Vec<(Arc<World>, u64, Arc<Rig>)> = (worlds.into_iter().zip(seeds).enumerate())
            .map(|(i, (world, &seed))| (world, seed, rig_of(i)))
            .collect();
        let envs = helpers.make_all(pairs, make)?;
        Ok(Batch::assemble(envs, 1, &robot, helpers))
    }

    /// A batch of the simulators `envs`, `robots` per environment, each with the sensors of
    /// `robot`, stepped on `helpers`.
    pub(crate) fn assemble(
        envs: Vec<Simulator>,
        robots: usize,
        robot: &RobotProfile,
        helpers: Helpers,
    ) -> Batch {
        Batch {
            envs,
            robots,
            distance_width: robot.distance_sensors.len(),
            ground_width: robot.ground_sensors.len(),
            helpers,
            runs: Arc::new(AtomicU64::new(0)),
            pid: std::process::id(),
            interrupt: None,
        }
    }

    /// Bytes the batch holds per environment, rounded down: each env's simulator, each distinct
    /// world once (envs of equal worlds share one), the robot's rig once (`crate::footprint`).
    pub fn bytes_per_env(&self) -> usize {
        let mut worlds = std::collections::HashSet::new();
        let mut rigs = std::collections::HashSet::new();
        let mut channels = std::collections::HashSet::new();
        let shared: usize = self
            .envs
            .iter()
            .map(|env| {
                let world = if worlds.insert(Arc::as_ptr(env.world())) {
                    env.world().heap_bytes()
                } else {
                    0
                };
                let rig = if rigs.insert(Arc::as_ptr(env.rig())) {
                    env.rig().heap_bytes() + env.rig().channel_bytes(&mut channels)
                } else {
                    0
                };
                world + rig
            })
            .sum();
        let own: usize = self.envs.iter().map(Simulator::heap_bytes).sum();
        (shared + own + std::mem::size_of_val(self)) / self.envs.len()
    }

    /// Number of environments.
    pub fn len(&self) -> usize {
        self.envs.len()
    }

    /// Never true: a batch has at least one environment.
    pub fn is_empty(&self) -> bool {
        self.envs.is_empty()
    }

    /// Floats per observation row: distance sensors then ground sensors.
    pub fn observation_width(&self) -> usize {
        self.distance_width + self.ground_width
    }

    /// The environments.
    pub fn envs(&self) -> &[Simulator] {
        &self.envs
    }

    pub(crate) fn check_outputs(&self, out: &StepOutputs<'_>) -> Result<()> {
        let n = self.envs.len();
        let check = |name: &str, len: usize, width: usize| {
            if len != n * width {
                Err(Error::InvalidArgument(format!(
                    "expected {name} to hold {n} x {width} values, found {len}"
                )))
            } else {
                Ok(())
            }
        };
        check(
            "observations",
            out.observations.len(),
            self.observation_width(),
        )?;
        check("poses", out.poses.len(), 3)?;
        check("colliding", out.colliding.len(), 1)?;
        check("crossings", out.crossings.len(), 1)
    }

    /// Sets the check for an interruption (Ctrl-C) that long calls make between environments,
    /// at most every `INTERRUPT_POLL`, on the calling thread. When it answers true
    /// the call stops taking chunks and returns `Error::Interrupted`; the environments then stand
    /// where they were, some stepped and some not: reset the batch before using it again.
    pub fn set_interrupt(&mut self, interrupt: Box<dyn Fn() -> bool + Send + Sync>) {
        self.interrupt = Some(interrupt);
    }

    /// Asks the check for an interruption (see `set_interrupt`) now: true when the call should stop.
    pub(crate) fn interrupted(&self) -> bool {
        self.interrupt
            .as_deref()
            .is_some_and(|interrupted| interrupted())
    }

    /// Makes the helper threads again when this process is a fork of the one that made them.
    fn guard_fork(&mut self) -> Result<()> {
        let pid = std::process::id();
        if self.pid != pid {
            let inherited = std::mem::replace(&mut self.helpers, Helpers::Shared(None));
            self.helpers = inherited.remade()?;
            self.runs = Arc::new(AtomicU64::new(0));
            self.pid = pid;
        }
        Ok(())
    }

    fn run<'a, F: Fn(usize, &mut Simulator, Row<'_>) + Sync + Send>(
        &'a mut self,
        out: StepOutputs<'a>,
        f: F,
    ) -> Result<()> {
        let width = self.observation_width();
        let dw = self.distance_width;
        let chunks = move |envs: &'a mut [Simulator]| {
            envs.chunks_mut(CHUNK_ENVS)
                .zip(out.chunks(width))
                .enumerate()
        };
        self.par_chunks(chunks, |(k, (envs, out)), stop| {
            for env in envs.iter() {
                env.warm();
            }
            for (j, (env, row)) in envs.iter_mut().zip(out.rows(width, dw)).enumerate() {
                if stop() {
                    return;
                }
                f(k * CHUNK_ENVS + j, env, row);
            }
        })
    }

    /// Runs `work` on every chunk that `chunks_of` makes of the environments (chunks of
    /// `CHUNK_ENVS` environments with their slices of the outputs), on the calling thread and the
    /// helpers, each chunk taken from a shared queue. `work` gets a chunk and `stop`, to ask
    /// before each environment: once `stop()` is true (Ctrl-C) it should return at once, and the
    /// call returns `Error::Interrupted`.
    pub(crate) fn par_chunks<'e, I, C, W>(
        &'e mut self,
        chunks_of: impl FnOnce(&'e mut [Simulator]) -> I,
        work: W,
    ) -> Result<()>
    where
        I: Iterator<Item = C> + Send,
        C: Send,
        W: Fn(C, &mut dyn FnMut() -> bool) + Sync,
    {
        self.guard_fork()?;
        let interrupt = self.interrupt.as_deref();
        let stopped = AtomicBool::new(false);
        let mut polled = Instant::now();
        let alone = self.envs.len() <= CHUNK_ENVS;
        let queue = Mutex::new(chunks_of(&mut self.envs));
        // Whether to stop: the calling thread (which has `poll`) asks `interrupt` now and then,
        // every thread sees its answer before each environment.
        let stop_now = |poll: &mut Option<&mut Instant>| {
            if let (Some(last), Some(interrupted)) = (poll.as_deref_mut(), interrupt) {
                if last.elapsed() >= INTERRUPT_POLL {
                    *last = Instant::now();
                    if interrupted() {
                        stopped.store(true, Ordering::Release);
                    }
                }
            }
            stopped.load(Ordering::Acquire)
        };
        let work_through = |mut poll: Option<&mut Instant>| loop {
            if stop_now(&mut poll) {
                return;
            }
            let next = queue.lock().unwrap_or_else(|p| p.into_inner()).next();
            let Some(chunk) = next else {
                return;
            };
            work(chunk, &mut || stop_now(&mut poll));
        };
        match self.helpers.pool() {
            Some(pool) if !alone => {
                let run = self.runs.fetch_add(1, Ordering::AcqRel) + 1;
                pool.in_place_scope(|scope| {
                    for _ in 0..pool.current_num_threads() {
                        scope.spawn(|_| work_through(None));
                    }
                    work_through(Some(&mut polled));
                });
                for _ in 0..pool.current_num_threads() {
                    let runs = Arc::clone(&self.runs);
                    pool.spawn(move || {
                        let since = Instant::now();
                        while runs.load(Ordering::Acquire) == run && since.elapsed() < LINGER {
                            std::hint::spin_loop();
                        }
                    });
                }
            }
            _ => work_through(Some(&mut polled)),
        }
        if stopped.load(Ordering::Acquire) {
            return Err(Error::Interrupted);
        }
        Ok(())
    }

    /// Steps every environment with `actions` (`(n, 2)` wheel speeds in rad/s, left then right)
    /// and writes the results into `out`. NaN or infinite speeds are refused before any
    /// environment moves; the error names the first bad environment. A batch of worlds of
    /// several robots is stepped as [`Batch::step_swarms`] steps it.
    pub fn step(&mut self, actions: &[f32], out: StepOutputs<'_>) -> Result<()> {
        if self.robots > 1 {
            // Robots of one world move together (`crate::swarm`), never one alone.
            return self.step_swarms(actions, out);
        }
        check_actions(actions, self.envs.len(), 1)?;
        self.check_outputs(&out)?;
        // Actions are checked above, so a step cannot fail.
        self.run(out, |i, env, row| {
            let _ = env.step(actions[2 * i] as f64, actions[2 * i + 1] as f64);
            row.write(env);
        })
    }

    /// Resets the environments where `mask` is true (all without a mask), each with its new seed
    /// from `seeds` when given, and writes their rows of `out` (other rows are left as they are).
    pub fn reset(
        &mut self,
        mask: Option<&[bool]>,
        seeds: Option<&[u64]>,
        out: StepOutputs<'_>,
    ) -> Result<()> {
        let n = self.envs.len();
        if let Some(m) = mask {
            if m.len() != n {
                return Err(Error::InvalidArgument(format!(
                    "expected a reset mask of {n} values, found {}",
                    m.len()
                )));
            }
        }
        if let Some(s) = seeds {
            if s.len() != n {
                return Err(Error::InvalidArgument(format!(
                    "expected {n} reset seeds, found {}",
                    s.len()
                )));
            }
        }
        self.check_outputs(&out)?;
        self.run(out, |i, env, row| {
            if mask.is_none_or(|m| m[i]) {
                env.reset(seeds.map(|s| s[i]));
                row.write(env);
            }
        })
    }

    /// Mutable access to one environment (to set its start pose, for example).
    pub fn env_mut(&mut self, index: usize) -> Result<&mut Simulator> {
        let n = self.envs.len();
        self.envs.get_mut(index).ok_or_else(|| {
            Error::InvalidArgument(format!(
                "expected an environment index below {n}, found {index}"
            ))
        })
    }

    /// Sets the start of every robot of environments `envs` for their later resets, from
    /// `starts`: for each listed environment, one row of x, y, yaw per robot (`(M, 3)` with one
    /// robot per environment, `(M, robots, 3)` with several); the others keep theirs. Every
    /// start must be clear of the walls and of the environment's other new starts; all are
    /// checked before any is applied, and the error names the environment (and robot).
    pub fn set_starts_at(&mut self, envs: &[usize], starts: &[f64]) -> Result<()> {
        self.set_rows_at(
            envs,
            starts,
            "starts",
            |group, k, rows| {
                let at = |j: usize| [rows[3 * j], rows[3 * j + 1], rows[3 * j + 2]];
                let [x, y, yaw] = at(k);
                group[k].check_start(x, y, yaw)?;
                check_apart(group, k, at(k), at, "start")
            },
            |robot, [x, y, yaw]| robot.set_start(x, y, yaw),
        )
    }

    /// Sets the goal disc of every robot of environments `envs`, from `goals`: for each listed
    /// environment, one row of x, y, radius (metres) per robot, shaped as for
    /// [`Batch::set_starts_at`], instead of their world's (the others keep theirs; `set_world`
    /// goes back to the world's); checked before any is applied, as [`Batch::set_starts_at`].
    pub fn set_goals_at(&mut self, envs: &[usize], goals: &[f64]) -> Result<()> {
        self.set_rows_at(
            envs,
            goals,
            "goals",
            |_, k, rows| check_goal(rows[3 * k], rows[3 * k + 1], rows[3 * k + 2]),
            |robot, [x, y, radius]| robot.set_goal(x, y, radius),
        )
    }

    /// Applies one row of three values per robot of each listed environment with `apply`, once
    /// `check` (given the environment's robots, a robot and the environment's rows) has accepted
    /// every index and row (`what` names the rows in errors).
    fn set_rows_at(
        &mut self,
        envs: &[usize],
        rows: &[f64],
        what: &str,
        check: impl Fn(&[Simulator], usize, &[f64]) -> Result<()>,
        apply: impl Fn(&mut Simulator, [f64; 3]) -> Result<()>,
    ) -> Result<()> {
        let (m, r) = (envs.len(), self.robots);
        if rows.len() != 3 * r * m {
            let shape = match r {
                1 => format!("({m}, 3), one row per listed environment"),
                _ => format!("({m}, {r}, 3), a row per robot of each listed environment"),
            };
            return Err(Error::InvalidArgument(format!(
                "expected {what} of shape {shape}, found {} values",
                rows.len()
            )));
        }
        for (&e, env_rows) in envs.iter().zip(rows.chunks_exact(3 * r)) {
            let group = self.group(e)?;
            for k in 0..r {
                check(&self.envs[group.clone()], k, env_rows).map_err(|error| match error {
                    Error::InvalidArgument(m) if r == 1 => {
                        Error::InvalidArgument(format!("environment {e}: {m}"))
                    }
                    Error::InvalidArgument(m) => {
                        Error::InvalidArgument(format!("environment {e}, robot {k}: {m}"))
                    }
                    other => other,
                })?;
            }
        }
        for (&e, env_rows) in envs.iter().zip(rows.chunks_exact(3 * r)) {
            for (k, row) in env_rows.chunks_exact(3).enumerate() {
                apply(&mut self.envs[e * r + k], [row[0], row[1], row[2]])?;
            }
        }
        Ok(())
    }

    /// Puts environment `index` into another world, reset to its start with `seed`. Its rows of the
    /// outputs change at the next `observe`, `step` or `reset`. In a batch of worlds of several
    /// robots the new world must place as many robots; robot `i` keeps its profile.
    pub fn set_world(&mut self, index: usize, world: Arc<World>, seed: u64) -> Result<()> {
        let (n, r) = (self.num_envs(), self.robots);
        if index >= n {
            return Err(Error::InvalidArgument(format!(
                "expected an environment index below {n}, found {index}"
            )));
        }
        let placed = world.robots().len();
        if placed != r {
            return Err(Error::InvalidArgument(format!(
                "expected a world placing {r} robots (as every world of the batch), found \
                 {placed} in world {:?}",
                world.name()
            )));
        }
        let group = index * r..(index + 1) * r;
        let config = SimConfig {
            seed,
            ..self.envs[index * r].config()
        };
        // An env of an equal world lends its copy.
        let world = self
            .envs
            .iter()
            .map(Simulator::world)
            .find(|w| w.fingerprint() == world.fingerprint() && ***w == *world)
            .cloned()
            .unwrap_or(world);
        if r == 1 {
            let rig = self.envs[index].rig().clone();
            self.envs[index] = Simulator::with_rig(world, rig, config)?;
            return Ok(());
        }
        let rigs: Vec<Arc<Rig>> = self.envs[group.clone()]
            .iter()
            .map(|robot| robot.rig().clone())
            .collect();
        let robots = crate::swarm::make_robots(&world, &rigs, config)?;
        self.envs.splice(group, robots);
        Ok(())
    }

    /// Writes the current state of every environment into `out` without stepping.
    pub fn observe(&mut self, out: StepOutputs<'_>) -> Result<()> {
        self.check_outputs(&out)?;
        self.run(out, |_, env, row| row.write(env))
    }
}

/// Checks the wheel speeds of one batch step: `(envs, 2)` values, or `(envs, robots, 2)` with
/// several robots per environment, all finite; the error names the first bad environment (and
/// robot, or wheel).
pub(crate) fn check_actions(actions: &[f32], envs: usize, robots: usize) -> Result<()> {
    if actions.len() != 2 * envs * robots {
        let shape = if robots == 1 {
            format!("({envs}, 2)")
        } else {
            format!("({envs}, {robots}, 2)")
        };
        return Err(Error::InvalidArgument(format!(
            "expected actions of shape {shape}, found {} values",
            actions.len()
        )));
    }
    if let Some(i) = actions.iter().position(|a| !a.is_finite()) {
        let (env, robot) = (i / (2 * robots), (i / 2) % robots);
        let which = if robots == 1 {
            format!("({} wheel)", if i % 2 == 0 { "left" } else { "right" })
        } else {
            format!(", robot {robot}")
        };
        let space = if robots == 1 { " " } else { "" };
        return Err(Error::InvalidAction(format!(
            "expected finite wheel speeds, found {} in environment {env}{space}{which}",
            actions[i]
        )));
    }
    Ok(())
}
