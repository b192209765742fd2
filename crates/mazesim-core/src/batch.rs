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

use rayon::prelude::*;
use rayon::ThreadPool;

use crate::error::{Error, Result};
use crate::limits::{check_count, MAX_ENVS, MAX_THREADS};
use crate::robot::RobotProfile;
use crate::simulator::{Rig, SharedChannels, SimConfig, Simulator};
use crate::world::World;

/// Environments per chunk of work: enough to amortise taking it from the queue, few enough that
/// the threads finish close together.
pub(crate) const CHUNK_ENVS: usize = 16;

/// How often the calling thread asks whether to stop (Ctrl-C) while a batch call runs.
pub(crate) const INTERRUPT_POLL: Duration = Duration::from_millis(50);

/// How long a helper waits awake for the next step of the batch it just helped.
const LINGER: Duration = Duration::from_micros(200);

/// The helpers of batches that use every core: one thread fewer than the machine has cores,
/// shared by all such batches of a process; `None` on a single core.
///
/// A forked child process inherits the parent's pool without its threads (`fork` copies only the
/// calling thread), so work given to it would wait forever. The pool is therefore kept with the
/// id of the process that made it, and a process that finds another's makes its own (the
/// parent's copy is left alone: its threads do not exist here). This is the fork guard.
fn shared_helpers() -> Option<&'static ThreadPool> {
    static HELPERS: Mutex<Option<(u32, Option<&'static ThreadPool>)>> = Mutex::new(None);
    let pid = std::process::id();
    let mut helpers = HELPERS.lock().unwrap_or_else(|p| p.into_inner());
    match *helpers {
        Some((owner, pool)) if owner == pid => pool,
        _ => {
            let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
            let pool = helper_pool(cores.min(MAX_THREADS))
                .ok()
                .flatten()
                .map(|p| &*Box::leak(Box::new(p)));
            *helpers = Some((pid, pool));
            pool
        }
    }
}

/// A pool of `threads - 1` helper threads (`None` for one thread: the caller works alone).
fn helper_pool(threads: usize) -> Result<Option<ThreadPool>> {
    if threads <= 1 {
        return Ok(None);
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads - 1)
        .thread_name(|i| format!("mazesim-batch-{i}"))
        .build()
        .map(Some)
        .map_err(|e| Error::InvalidArgument(format!("cannot start {threads} threads: {e}")))
}

/// Who steps a batch besides the calling thread.
pub(crate) enum Helpers {
    /// The pool shared by batches that use every core.
    Shared(Option<&'static ThreadPool>),
    /// A pool of the batch's own, for an explicit thread count.
    Own(Option<ThreadPool>, usize),
}

impl Helpers {
    /// The helpers for `threads` (0: every core), made in this process.
    pub(crate) fn new(threads: usize) -> Result<Helpers> {
        if threads > MAX_THREADS {
            return Err(Error::InvalidArgument(format!(
                "expected threads in 0..={MAX_THREADS} (0 = one per core), found {threads}"
            )));
        }
        Ok(if threads == 0 {
            Helpers::Shared(shared_helpers())
        } else {
            Helpers::Own(helper_pool(threads)?, threads)
        })
    }

    pub(crate) fn pool(&self) -> Option<&ThreadPool> {
        match self {
            Helpers::Shared(p) => *p,
            Helpers::Own(p, _) => p.as_ref(),
        }
    }

    /// `make` of every item, in order, on the helpers where there are some; the error of an
    /// item that fails.
    pub(crate) fn make_all<T: Send, U: Send>(
        &self,
        items: Vec<T>,
        make: impl Fn(T) -> Result<U> + Sync + Send,
    ) -> Result<Vec<U>> {
        match self.pool() {
            Some(p) => p.install(|| items.into_par_iter().map(make).collect()),
            None => items.into_iter().map(make).collect(),
        }
    }

    /// The same helpers made again in a forked child; the parent's pool, whose threads do not
    /// exist in the child, is forgotten rather than dropped (dropping would signal them).
    fn remade(self) -> Result<Helpers> {
        match self {
            Helpers::Shared(_) => Helpers::new(0),
            Helpers::Own(pool, threads) => {
                std::mem::forget(pool);
                Helpers::new(threads)
            }
        }
    }
}

/// Bytes an environment needs besides its walls (simulator, buffers), a generous estimate.
const ENV_BYTES: u128 = 8 * 1024;

/// Bytes each solid wall adds to a world (its index entries), or to an env of a world with
/// movable bodies (its rapier collider and broad-phase entry), a generous estimate.
const WALL_BYTES: u128 = 1024;

/// `worlds` with every world of the same content as an earlier one replaced by that one, so that
/// envs of equal worlds share one copy of its walls, paint and indexes.
pub fn share_equal_worlds(worlds: Vec<Arc<World>>) -> Vec<Arc<World>> {
    let mut seen: std::collections::HashMap<u64, Vec<Arc<World>>> =
        std::collections::HashMap::new();
    worlds
        .into_iter()
        .map(|world| {
            let same = seen.entry(world.fingerprint()).or_default();
            match same
                .iter()
                .find(|w| Arc::ptr_eq(w, &world) || ***w == *world)
            {
                Some(first) => first.clone(),
                None => {
                    same.push(world.clone());
                    world
                }
            }
        })
        .collect()
}

/// Refuses a batch of `envs` environments without one seed each.
pub(crate) fn check_seeds(envs: usize, seeds: &[u64]) -> Result<()> {
    if seeds.len() != envs {
        return Err(Error::InvalidArgument(format!(
            "expected one seed per environment ({envs}), found {}",
            seeds.len()
        )));
    }
    Ok(())
}

/// Refuses a batch of `envs` environments holding `walls` solid walls in all (summed over the
/// environments) before anything is allocated: beyond `MAX_ENVS`, or when its estimated memory
/// exceeds what the process may still allocate (the address-space limit and the memory the system
/// has available, where the system tells).
pub fn check_size(envs: usize, walls: u128) -> Result<()> {
    check_count("environments (num_envs)", envs, MAX_ENVS)?;
    if envs == 0 {
        return Err(Error::InvalidArgument(
            "expected at least one environment, found 0".into(),
        ));
    }
    let needed = ENV_BYTES * envs as u128 + WALL_BYTES * walls;
    if let Some(free) = crate::memory::allocatable_bytes() {
        if needed > free as u128 {
            return Err(Error::InvalidArgument(format!(
                "expected a batch that fits in memory: num_envs = {envs} needs about {:.2} GB, \
                 but this process can allocate about {:.2} GB more",
                needed as f64 / 1e9,
                free as f64 / 1e9
            )));
        }
    }
    Ok(())
}

/// The sensing rigs of a batch of `n` envs: one per env of `robots` (or one for all when
/// `robots` holds one profile), equal profiles sharing one rig and the rigs sharing their equal
/// channel lists (profiles perturbed from copies of one profile read one copy of their sensor
/// models, which every step of every robot then finds in cache). Every profile must have sensors
/// to observe, and as many of each kind as the first.
pub(crate) fn rigs_of(robots: &[Arc<RobotProfile>], n: usize) -> Result<Vec<Arc<Rig>>> {
    if robots.len() != 1 && robots.len() != n {
        return Err(Error::InvalidArgument(format!(
            "expected one robot profile, or one per environment ({n}), found {}",
            robots.len()
        )));
    }
    let first = &robots[0];
    if first.distance_sensors.is_empty() && first.ground_sensors.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "robot profile {:?} has no sensors to observe",
            first.name
        )));
    }
    let widths = |r: &RobotProfile| (r.distance_sensors.len(), r.ground_sensors.len());
    let mut made: Vec<Arc<Rig>> = Vec::new();
    let mut channels = SharedChannels::default();
    let mut rigs = Vec::with_capacity(robots.len());
    for (i, robot) in robots.iter().enumerate() {
        if widths(robot) != widths(first) {
            return Err(Error::InvalidArgument(format!(
                "expected every environment's robot profile to have the sensors of the first \
                 ({:?}: {} distance, {} ground), found {:?} in environment {i} with {} and {}",
                first.name,
                first.distance_sensors.len(),
                first.ground_sensors.len(),
                robot.name,
                robot.distance_sensors.len(),
                robot.ground_sensors.len()
            )));
        }
        let same = made
            .iter()
            .find(|r| Arc::ptr_eq(r.robot(), robot) || **r.robot() == **robot);
        let rig = match same {
            Some(rig) => rig.clone(),
            None => {
                let rig = Rig::sharing(robot.clone(), &mut channels);
                made.push(rig.clone());
                rig
            }
        };
        rigs.push(rig);
    }
    Ok(rigs)
}

/// Per-step outputs of a batch, one row per environment, in buffers the caller owns.
pub struct StepOutputs<'a> {
    /// `(n, observation_width)`: distance sensors then ground sensors.
    pub observations: &'a mut [f32],
    /// `(n, 3)`: x, y, yaw.
    pub poses: &'a mut [f32],
    /// `(n,)`: touched a wall during the step.
    pub colliding: &'a mut [bool],
    /// `(n,)`: barcode crossed in the step as a signed checkpoint id, 0 for none.
    pub crossings: &'a mut [i32],
}

/// Owned buffers of a batch's per-step outputs, zeroed, for callers in Rust (Python hands in
/// numpy arrays instead).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OutputBuffers {
    /// `(rows, observation_width)`: distance sensors then ground sensors.
    pub observations: Vec<f32>,
    /// `(rows, 3)`: x, y, yaw.
    pub poses: Vec<f32>,
    /// `(rows,)`: touched a wall during the step.
    pub colliding: Vec<bool>,
    /// `(rows,)`: barcode crossed in the step as a signed checkpoint id, 0 for none.
    pub crossings: Vec<i32>,
}

impl OutputBuffers {
    /// Buffers of `rows` rows, observations `width` floats wide.
    pub fn new(rows: usize, width: usize) -> Self {
        Self {
            observations: vec![0.0; rows * width],
            poses: vec![0.0; rows * 3],
            colliding: vec![false; rows],
            crossings: vec![0; rows],
        }
    }

    /// Buffers of the shape of `batch`'s outputs: a row per simulator (per robot of every
    /// environment in a batch of several robots per environment).
    pub fn of(batch: &Batch) -> Self {
        Self::new(batch.envs.len(), batch.observation_width())
    }

    /// The buffers as the outputs of a call of the batch.
    pub fn outputs(&mut self) -> StepOutputs<'_> {
        StepOutputs {
            observations: &mut self.observations,
            poses: &mut self.poses,
            colliding: &mut self.colliding,
            crossings: &mut self.crossings,
        }
    }
}

impl<'a> StepOutputs<'a> {
    /// The same buffers, borrowed again for a shorter time.
    pub(crate) fn reborrow(&mut self) -> StepOutputs<'_> {
        StepOutputs {
            observations: self.observations,
            poses: self.poses,
            colliding: self.colliding,
            crossings: self.crossings,
        }
    }

    /// The buffers cut into the rows of successive chunks of `CHUNK_ENVS` environments
    /// (observations `width` wide).
    pub(crate) fn chunks(self, width: usize) -> impl Iterator<Item = StepOutputs<'a>> + Send {
        self.observations
            .chunks_mut(CHUNK_ENVS * width)
            .zip(self.poses.chunks_mut(CHUNK_ENVS * 3))
            .zip(self.colliding.chunks_mut(CHUNK_ENVS))
            .zip(self.crossings.chunks_mut(CHUNK_ENVS))
            .map(
                |(((observations, poses), colliding), crossings)| StepOutputs {
                    observations,
                    poses,
                    colliding,
                    crossings,
                },
            )
    }

    /// Each environment's row (observations `width` wide, the first `distance_width` of them
    /// distance readings).
    pub(crate) fn rows(self, width: usize, distance_width: usize) -> impl Iterator<Item = Row<'a>> {
        self.observations
            .chunks_mut(width)
            .zip(self.poses.chunks_mut(3))
            .zip(self.colliding.iter_mut())
            .zip(self.crossings.iter_mut())
            .map(move |(((observation, pose), colliding), crossing)| Row {
                observation,
                distance_width,
                pose,
                colliding,
                crossing,
            })
    }
}

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

    /// Sets the start pose of environments `envs` for their later resets from `starts`, one row
    /// of x, y, yaw per listed environment (the others keep theirs). Every index and row is
    /// checked before any is applied: a bad one changes nothing, and the error names its
    /// environment.
    pub fn set_starts_at(&mut self, envs: &[usize], starts: &[f64]) -> Result<()> {
        self.set_rows_at(
            envs,
            starts,
            "starts",
            |env, [x, y, yaw]| env.check_start(x, y, yaw),
            |env, [x, y, yaw]| env.set_start(x, y, yaw),
        )
    }

    /// Sets the goal disc of environments `envs`, one row of x, y, radius (metres) per listed
    /// environment, instead of their worlds' (the others keep theirs; `set_world` goes back to the
    /// world's). Every index and row is checked before any is applied: a bad one changes nothing,
    /// and the error names its environment.
    pub fn set_goals_at(&mut self, envs: &[usize], goals: &[f64]) -> Result<()> {
        self.set_rows_at(
            envs,
            goals,
            "goals",
            |_, [x, y, radius]| crate::simulator::check_goal(x, y, radius),
            |env, [x, y, radius]| env.set_goal(x, y, radius),
        )
    }

    /// Applies one row of three values to each listed environment with `apply`, once `check` has
    /// accepted every index and row (`what` names the rows in errors).
    fn set_rows_at(
        &mut self,
        envs: &[usize],
        rows: &[f64],
        what: &str,
        check: impl Fn(&Simulator, [f64; 3]) -> Result<()>,
        apply: impl Fn(&mut Simulator, [f64; 3]) -> Result<()>,
    ) -> Result<()> {
        let n = self.envs.len();
        if rows.len() != 3 * envs.len() {
            return Err(Error::InvalidArgument(format!(
                "expected {what} of shape ({}, 3), one row per listed environment, found {} values",
                envs.len(),
                rows.len()
            )));
        }
        let row_of = |row: &[f64]| [row[0], row[1], row[2]];
        for (&i, row) in envs.iter().zip(rows.chunks_exact(3)) {
            let env = self.envs.get(i).ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "expected an environment index below {n}, found {i}"
                ))
            })?;
            check(env, row_of(row)).map_err(|e| match e {
                Error::InvalidArgument(m) => {
                    Error::InvalidArgument(format!("environment {i}: {m}"))
                }
                other => other,
            })?;
        }
        for (&i, row) in envs.iter().zip(rows.chunks_exact(3)) {
            apply(&mut self.envs[i], row_of(row))?;
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

/// One environment's rows of the outputs.
pub(crate) struct Row<'a> {
    pub(crate) observation: &'a mut [f32],
    pub(crate) distance_width: usize,
    pub(crate) pose: &'a mut [f32],
    pub(crate) colliding: &'a mut bool,
    pub(crate) crossing: &'a mut i32,
}

impl Row<'_> {
    pub(crate) fn write(self, env: &Simulator) {
        let (d, g) = self.observation.split_at_mut(self.distance_width);
        d.copy_from_slice(env.distance_sensors());
        g.copy_from_slice(env.ground_sensors());
        self.pose.copy_from_slice(&env.pose());
        *self.colliding = env.colliding();
        *self.crossing = env.last_crossing();
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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
}
