//! `BatchSimulator` for Python: N environments stepped in parallel into caller-owned numpy buffers,
//! with the GIL released while they run.

use std::sync::Arc;

use mazesim_core::limits::{MAX_ENVS, MAX_THREADS};
use mazesim_core::rollout::RunEnvs;
use mazesim_core::{Batch, StepOutputs, World};
use numpy::{IxDyn, PyArray1, PyArrayDyn, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{bounded_items, dict_argument, type_name, Bytes, Flag, IntArg, Real};
use crate::buffers::{copied, writable};
use crate::errors::{invalid, wrong_type, IntoPy};
use crate::guard::{ctrl_c_pressed, enter, enter_detached};
use crate::lock::Exclusive;
use crate::profile::RobotArg;
use crate::run::{self, RunCall, Traces};
use crate::subtasks::SubTaskArrays;
use crate::world::{not_a_world, world_argument, world_items, PyWorld};

/// N independent environments stepped together.
#[pyclass(name = "BatchSimulator", module = "mazesim._core", frozen)]
pub struct PyBatch {
    pub(crate) inner: Exclusive<Batch>,
    /// Number of environments.
    #[pyo3(get, name = "num_envs")]
    n: usize,
    /// Robots per environment (1 but in a batch of worlds of several robots).
    #[pyo3(get, name = "robots_per_env")]
    robots: usize,
    #[pyo3(get)]
    distance_width: usize,
    #[pyo3(get)]
    ground_width: usize,
}

/// Most control steps one `run` call takes.
const MAX_RUN_STEPS: usize = 1 << 40;

/// The four output buffers of a batch: observations, poses, colliding, crossings.
type OutputBuffers<'py> = (
    Bound<'py, PyArrayDyn<f32>>,
    Bound<'py, PyArrayDyn<f32>>,
    Bound<'py, PyArrayDyn<bool>>,
    Bound<'py, PyArrayDyn<i32>>,
);

impl PyBatch {
    /// Runs `work` on the batch with the four output buffers (observations, poses, colliding,
    /// crossings) borrowed and checked, the GIL released.
    fn with_outputs<'py, T: Send>(
        &self,
        py: Python<'py>,
        buffers: [&Bound<'py, PyAny>; 4],
        work: impl FnOnce(&mut Batch, StepOutputs<'_>) -> mazesim_core::Result<T> + Send,
    ) -> PyResult<T> {
        let [observations, poses, colliding, crossings] = buffers;
        let mut borrowed = Borrowed::new(self, observations, poses, colliding, crossings)?;
        let out = borrowed.outputs()?;
        enter_detached(py, || self.inner.with_detached(|b| work(b, out)))
    }

    /// One value per environment (`(N,)`), or per robot of each (`(N, R)`), as a numpy array.
    fn per_env<'py, T: numpy::Element>(
        &self,
        py: Python<'py>,
        value: impl Fn(&mazesim_core::Simulator) -> T,
    ) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
        self.per_robot(py, &[], |e| [value(e)])
    }

    /// `K` values per environment (`(N, *tail)`), or per robot of each (`(N, R, *tail)`), as a
    /// numpy array; `tail` is `[]` for one value, `[K]` for several.
    fn per_robot<'py, T: numpy::Element, const K: usize>(
        &self,
        py: Python<'py>,
        tail: &[usize],
        value: impl Fn(&mazesim_core::Simulator) -> [T; K],
    ) -> PyResult<Bound<'py, PyArrayDyn<T>>> {
        enter(|| {
            let v: Vec<T> = self
                .inner
                .with(|b| b.envs().iter().flat_map(value).collect())?;
            PyArray1::from_vec(py, v).reshape(IxDyn(&self.shape(tail)))
        })
    }

    /// Environments in the batch.
    pub(crate) fn len(&self) -> usize {
        self.n
    }

    /// Distance sensors of each robot.
    pub(crate) fn distance_sensor_count(&self) -> usize {
        self.distance_width
    }

    fn width(&self) -> usize {
        self.distance_width + self.ground_width
    }

    /// The shape of a buffer of one row of `tail` per robot: `(n, *tail)` with one robot per
    /// environment, `(n, robots, *tail)` with several.
    fn shape(&self, tail: &[usize]) -> Vec<usize> {
        let mut shape = vec![self.n];
        if self.robots > 1 {
            shape.push(self.robots);
        }
        shape.extend_from_slice(tail);
        shape
    }

    /// `run` in a batch of worlds of several robots: every robot driven by `controller` on its
    /// own readings for `steps` control steps; returns a dict of "steps_in_contact", an
    /// (n, robots) uint64 array.
    fn run_robots<'py>(
        &self,
        py: Python<'py>,
        controller: &mazesim_core::Controller,
        steps: usize,
        max_speed: f64,
        buffers: [&Bound<'py, PyAny>; 4],
    ) -> PyResult<Bound<'py, PyDict>> {
        let contacts = self.with_outputs(py, buffers, |b, out| {
            b.run_swarms(controller, steps, max_speed, out)
        })?;
        let d = PyDict::new(py);
        d.set_item(
            "steps_in_contact",
            PyArray1::from_vec(py, contacts).reshape([self.n, self.robots])?,
        )?;
        Ok(d)
    }

    /// Refuses `what` in a batch of worlds of several robots, saying what to do instead.
    pub(crate) fn one_robot(&self, what: &str, instead: &str) -> PyResult<()> {
        if self.robots == 1 {
            Ok(())
        } else {
            Err(invalid(format!(
                "expected a batch of worlds of one robot for {what}, found {} robots per \
                 environment: {instead}",
                self.robots
            )))
        }
    }

    /// The (M,) int64 indices `envs` as checked env indices, and the (M, 3) float64 rows of
    /// `values` (named `what`) that go with them, (M, R, 3) with several robots per environment.
    fn listed_rows(
        &self,
        envs: &Bound<'_, PyAny>,
        values: &Bound<'_, PyAny>,
        what: &str,
    ) -> PyResult<(Vec<usize>, Vec<f64>)> {
        let m = envs.len().map_err(|_| {
            wrong_type(format!(
                "expected envs to be an (M,) int64 array of env indices, found {}",
                type_name(envs)
            ))
        })?;
        let indices = copied::<i64>(envs, "envs", "int64", &[m])?;
        let mut shape = self.shape(&[3]);
        shape[0] = m;
        let rows = copied::<f64>(values, what, "float64", &shape)?;
        Ok((env_indices(&indices, self.n)?, rows))
    }
}

/// The buffers of one call, borrowed.
pub(crate) struct Borrowed<'py> {
    obs: numpy::PyReadwriteArrayDyn<'py, f32>,
    poses: numpy::PyReadwriteArrayDyn<'py, f32>,
    colliding: numpy::PyReadwriteArrayDyn<'py, bool>,
    crossings: numpy::PyReadwriteArrayDyn<'py, i32>,
}

impl<'py> Borrowed<'py> {
    pub(crate) fn new(
        b: &PyBatch,
        observations: &Bound<'py, PyAny>,
        poses: &Bound<'py, PyAny>,
        colliding: &Bound<'py, PyAny>,
        crossings: &Bound<'py, PyAny>,
    ) -> PyResult<Self> {
        Ok(Self {
            obs: writable(
                observations,
                "observations",
                "float32",
                &b.shape(&[b.width()]),
            )?,
            poses: writable(poses, "poses", "float32", &b.shape(&[3]))?,
            colliding: writable(colliding, "colliding", "bool", &b.shape(&[]))?,
            crossings: writable(crossings, "crossings", "int32", &b.shape(&[]))?,
        })
    }

    pub(crate) fn outputs(&mut self) -> PyResult<StepOutputs<'_>> {
        let unusable = |name: &str| invalid(format!("expected {name} to be a contiguous array"));
        Ok(StepOutputs {
            observations: self
                .obs
                .as_slice_mut()
                .map_err(|_| unusable("observations"))?,
            poses: self.poses.as_slice_mut().map_err(|_| unusable("poses"))?,
            colliding: self
                .colliding
                .as_slice_mut()
                .map_err(|_| unusable("colliding"))?,
            crossings: self
                .crossings
                .as_slice_mut()
                .map_err(|_| unusable("crossings"))?,
        })
    }
}

/// Seeds as given: one int (env `i` gets `seed + i`) or one per environment.
#[derive(Clone, Debug)]
pub(crate) enum Seeds {
    From(u64),
    Each(Vec<u64>),
}

impl Seeds {
    /// The seeds of `seeds`, an int or at most `most` ints, each in `0..2**64`.
    pub(crate) fn given(seeds: &Bound<'_, PyAny>, most: usize) -> PyResult<Self> {
        // One int: Python's, or an integer scalar of numpy's (np.int64(2), as `seed` takes it),
        // no sequence.
        let scalar = seeds.is_instance_of::<pyo3::types::PyInt>()
            || (seeds.hasattr("__index__")? && !seeds.hasattr("__len__")?);
        if scalar {
            return Ok(Seeds::From(seeds.extract::<IntArg>()?.seed("seeds")?));
        }
        let expected = "ints in 0..2**64 (one per environment), or one int (env i gets seed + i)";
        let items = bounded_items(seeds, "seeds", expected, most)?;
        let list = items
            .iter()
            .map(|s| s.extract::<IntArg>())
            .collect::<PyResult<Vec<_>>>()?;
        let each = list
            .iter()
            .enumerate()
            .map(|(i, s)| s.seed(&format!("seeds[{i}]")))
            .collect::<PyResult<Vec<u64>>>()?;
        Ok(Seeds::Each(each))
    }

    /// The seed of each of `n` environments.
    pub(crate) fn of(&self, n: usize) -> PyResult<Vec<u64>> {
        match self {
            Seeds::From(base) => Ok((0..n as u64).map(|i| base.wrapping_add(i)).collect()),
            Seeds::Each(list) if list.len() == n => Ok(list.clone()),
            Seeds::Each(list) => Err(invalid(format!("expected {n} seeds, found {}", list.len()))),
        }
    }
}

#[pymethods]
impl PyBatch {
    #[new]
    #[pyo3(signature = (worlds, num_envs = None, robot = RobotArg::default_robot(), seeds = None, noise = Flag::Value(true), control_step_ms = None, threads = IntArg::ZERO),
        text_signature = "(worlds, num_envs=None, robot='e-puck', seeds=None, noise=True, control_step_ms=None, threads=0)")]
    fn new(
        py: Python<'_>,
        worlds: &Bound<'_, PyAny>,
        num_envs: Option<IntArg>,
        robot: RobotArg,
        seeds: Option<&Bound<'_, PyAny>>,
        noise: Flag,
        control_step_ms: Option<Real>,
        threads: IntArg,
    ) -> PyResult<Self> {
        enter(|| {
            let control_step_ms = control_step_ms
                .map(|ms| ms.value("control_step_ms"))
                .transpose()?;
            let num_envs = num_envs
                .map(|n| n.count("num_envs", MAX_ENVS))
                .transpose()?;
            let threads = threads.count("threads", MAX_THREADS)?;
            let noise = noise.value("noise", "a bool")?;
            let worlds: Vec<Arc<World>> = if let Ok(w) = worlds.cast::<PyWorld>() {
                let n = num_envs
                    .ok_or_else(|| invalid("expected num_envs with a single world".into()))?;
                let world = &w.get().inner;
                let walls = world.solid_walls().len() as u128 * n as u128;
                mazesim_core::batch::check_size(n, walls).py()?;
                vec![world.clone(); n]
            } else {
                let list: Vec<Bound<'_, PyWorld>> =
                    world_items(worlds, "mazesim.World (or one World)", MAX_ENVS)?
                        .into_iter()
                        .map(|w| match w.cast::<PyWorld>() {
                            Ok(world) => Ok(world.clone()),
                            Err(_) => Err(not_a_world(&w, "each of worlds", "a mazesim.World")),
                        })
                        .collect::<PyResult<_>>()?;
                if let Some(n) = num_envs {
                    if n != list.len() {
                        return Err(invalid(format!(
                            "expected num_envs to equal len(worlds) = {}, found {n}",
                            list.len()
                        )));
                    }
                }
                list.iter().map(|w| w.get().inner.clone()).collect()
            };
            let n = worlds.len();
            let seeds = match seeds {
                Some(s) => Seeds::given(s, n)?,
                None => Seeds::From(0),
            };
            let seeds = seeds.of(n)?;
            let profiles = robot.profiles(n)?;
            let (dw, gw) = (
                profiles[0].distance_sensors.len(),
                profiles[0].ground_sensors.len(),
            );
            let control = control_step_ms.map(|ms| ms / 1000.0);
            let robots = worlds[0].robots().len();
            let mut batch = enter_detached(py, move || {
                if robots > 1 {
                    let robot = profiles[0].clone();
                    Batch::with_swarms(worlds, robot, &seeds, noise, control, threads)
                } else {
                    Batch::with_robots(worlds, &profiles, &seeds, noise, control, threads)
                }
            })?;
            batch.set_interrupt(Box::new(ctrl_c_pressed));
            Ok(Self {
                robots: batch.robots_per_env(),
                inner: Exclusive::new(batch, "this BatchSimulator"),
                n,
                distance_width: dw,
                ground_width: gw,
            })
        })
    }

    /// Floats per observation row (distance sensors then ground sensors).
    #[getter]
    fn observation_width(&self) -> usize {
        self.width()
    }

    /// Bytes the batch holds per environment: each env's own state, plus each distinct world
    /// (envs of equal worlds share one copy) and each distinct robot profile's sensing set-up
    /// counted once.
    fn bytes_per_env(&self) -> PyResult<usize> {
        enter(|| self.inner.with(|b| b.bytes_per_env()))
    }

    /// New zeroed output buffers of the shapes and dtypes every call checks, for the caller to
    /// hold: observations (N, observation_width) float32, poses (N, 3) float32, colliding (N,)
    /// bool and crossings (N,) int32; with several robots per environment, (N, R, ...) each.
    fn output_buffers<'py>(&self, py: Python<'py>) -> OutputBuffers<'py> {
        let shape = |tail: &[usize]| IxDyn(&self.shape(tail));
        (
            PyArrayDyn::zeros(py, shape(&[self.width()]), false),
            PyArrayDyn::zeros(py, shape(&[3]), false),
            PyArrayDyn::zeros(py, shape(&[]), false),
            PyArrayDyn::zeros(py, shape(&[]), false),
        )
    }

    /// Steps every environment with `actions` ((N, 2) float32 wheel speeds, rad/s).
    fn step<'py>(
        &self,
        py: Python<'py>,
        actions: &Bound<'py, PyAny>,
        observations: &Bound<'py, PyAny>,
        poses: &Bound<'py, PyAny>,
        colliding: &Bound<'py, PyAny>,
        crossings: &Bound<'py, PyAny>,
    ) -> PyResult<()> {
        enter(|| {
            let actions = copied::<f32>(actions, "actions", "float32", &self.shape(&[2]))?;
            let buffers = [observations, poses, colliding, crossings];
            self.with_outputs(py, buffers, |b, out| b.step(&actions, out))
        })
    }

    /// Runs `steps` control steps of every environment in one call, the GIL released, each
    /// environment's wheel speeds from the built-in `controller` ('braitenberg',
    /// 'avoid-collision' or 'random', or the settings of avoid-collision or the tabular
    /// controller), with `settings` (a `RunSettings`); see `docs/performance.md` and the stub.
    #[pyo3(signature = (steps, controller, observations, poses, colliding, crossings, **settings),
        text_signature = "($self, steps, controller, observations, poses, colliding, crossings, *, settings=None)")]
    fn run<'py>(
        &self,
        steps: IntArg,
        controller: &Bound<'py, PyAny>,
        observations: &Bound<'py, PyAny>,
        poses: &Bound<'py, PyAny>,
        colliding: &Bound<'py, PyAny>,
        crossings: &Bound<'py, PyAny>,
        settings: Option<&Bound<'py, PyDict>>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let py = observations.py();
        enter(|| {
            let steps = steps.count("steps", MAX_RUN_STEPS)?;
            let call = RunCall::new(controller, settings)?;
            let (controller, settings) = (call.controller, call.settings.get());
            let n = self.n;
            if self.robots > 1 {
                return self.run_robots(
                    py,
                    &controller,
                    steps,
                    call.max_speed,
                    [observations, poses, colliding, crossings],
                );
            }
            let options = settings.limits.get().options(steps);
            let given = |value: &Option<Py<PyAny>>| value.as_ref().map(|v| v.bind(py).clone());
            let seeds = match &settings.seeds {
                Some(s) => s.of(n)?,
                None => (0..n as u64).collect(),
            };
            let active = given(&settings.active)
                .map(|a| copied::<bool>(&a, "active", "bool", &[n]))
                .transpose()?;
            let trace = given(&settings.trace);
            let trace = trace
                .as_ref()
                .map(|t| dict_argument(t, "trace", " of name -> array"))
                .transpose()?;
            let mut traces = Traces::new(trace, options.steps, n, self.width())?;
            let mut subtask_arrays = given(&settings.subtasks)
                .map(|s| SubTaskArrays::new(&s, n))
                .transpose()?;
            let mut states = subtask_arrays
                .as_ref()
                .map(|a| a.states(&controller))
                .transpose()?;
            let trace = traces.slices();
            let envs = RunEnvs {
                active: active.as_deref(),
                subtasks: states.as_deref_mut(),
            };
            let buffers = [observations, poses, colliding, crossings];
            let ran = self.with_outputs(py, buffers, |b, out| {
                b.run_steps_of(&controller, &seeds, &options, envs, out, trace)
            });
            // The states as far as the call got, even when it stopped with an error.
            if let (Some(arrays), Some(states)) = (&mut subtask_arrays, &states) {
                arrays.store(states);
            }
            run::counters_dict(py, ran?)
        })
    }

    /// Resets the environments where `mask` is true (all without one), with new `seeds` if given.
    #[pyo3(signature = (observations, poses, colliding, crossings, mask = None, seeds = None))]
    fn reset<'py>(
        &self,
        py: Python<'py>,
        observations: &Bound<'py, PyAny>,
        poses: &Bound<'py, PyAny>,
        colliding: &Bound<'py, PyAny>,
        crossings: &Bound<'py, PyAny>,
        mask: Option<&Bound<'py, PyAny>>,
        seeds: Option<&Bound<'py, PyAny>>,
    ) -> PyResult<()> {
        enter(|| {
            let mask = mask
                .map(|m| copied::<bool>(m, "mask", "bool", &[self.n]))
                .transpose()?;
            let seeds = seeds
                .map(|s| copied::<u64>(s, "seeds", "uint64", &[self.n]))
                .transpose()?;
            let (m, s) = (mask.as_deref(), seeds.as_deref());
            let buffers = [observations, poses, colliding, crossings];
            if self.robots > 1 {
                return self.with_outputs(py, buffers, |b, out| b.reset_swarms(m, s, out));
            }
            self.with_outputs(py, buffers, |b, out| b.reset(m, s, out))
        })
    }

    /// Writes the current state without stepping.
    fn observe<'py>(
        &self,
        py: Python<'py>,
        observations: &Bound<'py, PyAny>,
        poses: &Bound<'py, PyAny>,
        colliding: &Bound<'py, PyAny>,
        crossings: &Bound<'py, PyAny>,
    ) -> PyResult<()> {
        enter(|| {
            let buffers = [observations, poses, colliding, crossings];
            self.with_outputs(py, buffers, |b, out| b.observe(out))
        })
    }

    /// Puts environment `index` into `world`, reset to its start with `seed`; its rows of the
    /// buffers change at the next observe, step or reset. In a batch of worlds of several robots
    /// the world must place as many robots; each robot keeps its profile.
    fn set_world(
        &self,
        py: Python<'_>,
        index: IntArg,
        world: &Bound<'_, PyAny>,
        seed: IntArg,
    ) -> PyResult<()> {
        enter(|| {
            let index = index.count("index", self.n.saturating_sub(1))?;
            let seed = seed.seed("seed")?;
            let w = world_argument(world, "world")?;
            enter_detached(py, || {
                self.inner.with_detached(|b| b.set_world(index, w, seed))
            })
        })
    }

    /// Sets the start pose of each environment for its later resets: an (N, 3) float64 array of
    /// x, y, yaw; with several robots per environment, each robot's, (N, R, 3), every start
    /// clear of the walls and of the environment's other robots. Every row is checked before
    /// any is applied.
    fn set_starts(&self, starts: &Bound<'_, PyAny>) -> PyResult<()> {
        enter(|| {
            let rows = copied::<f64>(starts, "starts", "float64", &self.shape(&[3]))?;
            let everyone: Vec<usize> = (0..self.n).collect();
            self.inner.with(|b| b.set_starts_at(&everyone, &rows))?.py()
        })
    }

    /// The whole state of environment `index` as bytes (as `Simulator.snapshot`), for
    /// `restore_env`: what pickling a vector env keeps of each environment.
    fn snapshot_env<'py>(
        &self,
        py: Python<'py>,
        index: IntArg,
    ) -> PyResult<Bound<'py, pyo3::types::PyBytes>> {
        enter(|| {
            let index = index.count("index", self.n.saturating_sub(1))?;
            let bytes = if self.robots > 1 {
                self.inner.with(|b| b.snapshot_swarm(index))?.py()?
            } else {
                self.inner.with(|b| b.envs()[index].snapshot())?
            };
            Ok(pyo3::types::PyBytes::new(py, &bytes))
        })
    }

    /// Puts environment `index` in the state of a `snapshot_env` (or `Simulator.snapshot`) of an
    /// environment of the same world, robot profile, control step and noise setting. With
    /// several robots per environment, a simulator's kept wheel commands are left: the batch
    /// takes every robot's at each step.
    fn restore_env(&self, index: IntArg, snapshot: Bytes) -> PyResult<()> {
        enter(|| {
            let index = index.count("index", self.n.saturating_sub(1))?;
            let snapshot = snapshot.value("snapshot", "bytes")?.0;
            if self.robots > 1 {
                return self.inner.with(|b| b.restore_swarm(index, &snapshot))?.py();
            }
            self.inner
                .with(|b| b.env_mut(index).and_then(|env| env.restore(&snapshot)))?
                .py()
        })
    }

    /// Sets the start pose of the environments `envs` ((M,) int64 indices) for their later
    /// resets: an (M, 3) float64 array of x, y, yaw, or (M, R, 3) with several robots per
    /// environment; the other environments keep theirs.
    fn set_starts_at(&self, envs: &Bound<'_, PyAny>, starts: &Bound<'_, PyAny>) -> PyResult<()> {
        enter(|| {
            let (indices, rows) = self.listed_rows(envs, starts, "starts")?;
            self.inner.with(|b| b.set_starts_at(&indices, &rows))?.py()
        })
    }

    /// Sets the goal disc of the environments `envs` ((M,) int64 indices): an (M, 3) float64
    /// array of x, y, radius in metres (or (M, R, 3), each robot's, with several robots per
    /// environment), instead of their worlds' goals; the other environments keep theirs, and
    /// `set_world` goes back to the world's.
    fn set_goals_at(&self, envs: &Bound<'_, PyAny>, goals: &Bound<'_, PyAny>) -> PyResult<()> {
        enter(|| {
            let (indices, rows) = self.listed_rows(envs, goals, "goals")?;
            self.inner.with(|b| b.set_goals_at(&indices, &rows))?.py()
        })
    }

    /// The goal disc of each environment, (N, 3) float64 x, y, radius; NaN rows for none; with
    /// several robots per environment, each robot's, (N, R, 3).
    fn goals<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        self.per_robot(py, &[3], |e| match e.goal() {
            Some(g) => [g.center[0], g.center[1], g.radius],
            None => [f64::NAN; 3],
        })
    }

    /// Wheel position sensors of each environment, (N, 2) float64 radians (left, right),
    /// quantised to the profile's encoder resolution; with several robots per environment,
    /// (N, R, 2).
    fn encoders<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        self.per_robot(py, &[2], |e| e.encoders())
    }

    /// Simulated seconds of each environment since its reset ((N,), or (N, R) with several
    /// robots per environment, as the other per-environment read-outs).
    fn times<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        self.per_env(py, |e| e.time())
    }

    /// Control steps of each environment since its reset.
    fn steps<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<u64>>> {
        self.per_env(py, |e| e.steps())
    }

    /// Bumps of each environment since its reset.
    fn collisions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<u64>>> {
        self.per_env(py, |e| e.collisions())
    }

    /// Path length of each environment since its reset, metres.
    fn distances_travelled<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArrayDyn<f64>>> {
        self.per_env(py, |e| e.distance_travelled())
    }

    fn __len__(&self) -> usize {
        self.n
    }

    fn __repr__(&self) -> String {
        format!(
            "BatchSimulator(num_envs={}, observation_width={})",
            self.n,
            self.width()
        )
    }
}

/// Environment indices from int64 values, each checked to be below `n`.
fn env_indices(values: &[i64], n: usize) -> PyResult<Vec<usize>> {
    values
        .iter()
        .map(|&i| {
            usize::try_from(i).ok().filter(|&i| i < n).ok_or_else(|| {
                invalid(format!(
                    "expected environment indices from 0 to {}, found {i}",
                    n.saturating_sub(1)
                ))
            })
        })
        .collect()
}
