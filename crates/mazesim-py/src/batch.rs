//! `BatchSimulator` for Python: N environments stepped in parallel into caller-owned numpy buffers,
//! with the GIL released while they run.

use std::sync::{Arc, Mutex};

use mazesim_core::{Batch, Error, RobotProfile, StepOutputs, World};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;

use crate::buffers::{readable, writable};
use crate::errors::{to_py, IntoPy};
use crate::world::PyWorld;

/// N independent environments stepped together.
#[pyclass(name = "BatchSimulator", module = "mazesim._core", frozen)]
pub struct PyBatch {
    inner: Mutex<Batch>,
    n: usize,
    distance_width: usize,
    ground_width: usize,
}

fn bad(msg: String) -> PyErr {
    to_py(Error::InvalidArgument(msg))
}

impl PyBatch {
    fn with<T>(&self, f: impl FnOnce(&mut Batch) -> T) -> T {
        let mut guard = self.inner.lock().unwrap_or_else(|p| p.into_inner());
        f(&mut guard)
    }

    /// One value per environment as a numpy array.
    fn per_env<'py, T: numpy::Element>(
        &self,
        py: Python<'py>,
        value: impl Fn(&mazesim_core::Simulator) -> T,
    ) -> Bound<'py, PyArray1<T>> {
        let v: Vec<T> = self.with(|b| b.envs().iter().map(value).collect());
        PyArray1::from_vec(py, v)
    }

    fn width(&self) -> usize {
        self.distance_width + self.ground_width
    }
}

/// The buffers of one call, borrowed.
struct Borrowed<'py> {
    obs: numpy::PyReadwriteArrayDyn<'py, f32>,
    poses: numpy::PyReadwriteArrayDyn<'py, f32>,
    colliding: numpy::PyReadwriteArrayDyn<'py, bool>,
    crossings: numpy::PyReadwriteArrayDyn<'py, i32>,
}

impl<'py> Borrowed<'py> {
    fn new(
        b: &PyBatch,
        observations: &Bound<'py, PyAny>,
        poses: &Bound<'py, PyAny>,
        colliding: &Bound<'py, PyAny>,
        crossings: &Bound<'py, PyAny>,
    ) -> PyResult<Self> {
        let n = b.n;
        Ok(Self {
            obs: writable(observations, "observations", "float32", &[n, b.width()])?,
            poses: writable(poses, "poses", "float32", &[n, 3])?,
            colliding: writable(colliding, "colliding", "bool", &[n])?,
            crossings: writable(crossings, "crossings", "int32", &[n])?,
        })
    }

    fn outputs(&mut self) -> StepOutputs<'_> {
        StepOutputs {
            observations: self.obs.as_slice_mut().expect("checked contiguous"),
            poses: self.poses.as_slice_mut().expect("checked contiguous"),
            colliding: self.colliding.as_slice_mut().expect("checked contiguous"),
            crossings: self.crossings.as_slice_mut().expect("checked contiguous"),
        }
    }
}

fn seeds_from(seeds: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<u64>> {
    if let Ok(base) = seeds.extract::<u64>() {
        return Ok((0..n as u64).map(|i| base.wrapping_add(i)).collect());
    }
    let list: Vec<u64> = seeds.extract().map_err(|_| {
        bad(format!(
            "expected seeds as one int (env i gets seed + i) or {n} ints in 0..2**64"
        ))
    })?;
    if list.len() != n {
        return Err(bad(format!("expected {n} seeds, found {}", list.len())));
    }
    Ok(list)
}

#[pymethods]
impl PyBatch {
    #[new]
    #[pyo3(signature = (worlds, num_envs = None, robot = "e-puck", seeds = None, noise = true, control_step_ms = None, threads = 0))]
    fn new(
        py: Python<'_>,
        worlds: &Bound<'_, PyAny>,
        num_envs: Option<usize>,
        robot: &str,
        seeds: Option<&Bound<'_, PyAny>>,
        noise: bool,
        control_step_ms: Option<f64>,
        threads: usize,
    ) -> PyResult<Self> {
        let worlds: Vec<Arc<World>> = if let Ok(w) = worlds.cast::<PyWorld>() {
            let n = num_envs.ok_or_else(|| bad("expected num_envs with a single world".into()))?;
            vec![w.get().inner.clone(); n]
        } else {
            let list: Vec<Bound<'_, PyWorld>> = worlds
                .extract()
                .map_err(|_| bad("expected worlds to be a World or a sequence of World".into()))?;
            if let Some(n) = num_envs {
                if n != list.len() {
                    return Err(bad(format!(
                        "expected num_envs to equal len(worlds) = {}, found {n}",
                        list.len()
                    )));
                }
            }
            list.iter().map(|w| w.get().inner.clone()).collect()
        };
        let n = worlds.len();
        let seeds = match seeds {
            Some(s) => seeds_from(s, n)?,
            None => (0..n as u64).collect(),
        };
        let profile = Arc::new(RobotProfile::builtin(robot).py()?);
        let (dw, gw) = (profile.distance_sensors.len(), profile.ground_sensors.len());
        let control = control_step_ms.map(|ms| ms / 1000.0);
        let batch = py
            .detach(move || Batch::new(worlds, profile, &seeds, noise, control, threads))
            .py()?;
        Ok(Self {
            inner: Mutex::new(batch),
            n,
            distance_width: dw,
            ground_width: gw,
        })
    }

    /// Number of environments.
    #[getter]
    fn num_envs(&self) -> usize {
        self.n
    }
    /// Floats per observation row (distance sensors then ground sensors).
    #[getter]
    fn observation_width(&self) -> usize {
        self.width()
    }
    #[getter]
    fn distance_width(&self) -> usize {
        self.distance_width
    }
    #[getter]
    fn ground_width(&self) -> usize {
        self.ground_width
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
        let actions = readable::<f32>(actions, "actions", "float32", &[self.n, 2])?;
        let mut buffers = Borrowed::new(self, observations, poses, colliding, crossings)?;
        let acts = actions.as_slice().expect("checked contiguous");
        let out = buffers.outputs();
        py.detach(|| self.with(|b| b.step(acts, out))).py()
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
        let mask = mask
            .map(|m| readable::<bool>(m, "mask", "bool", &[self.n]))
            .transpose()?;
        let seeds = seeds
            .map(|s| readable::<u64>(s, "seeds", "uint64", &[self.n]))
            .transpose()?;
        let mut buffers = Borrowed::new(self, observations, poses, colliding, crossings)?;
        let m = mask
            .as_ref()
            .map(|m| m.as_slice().expect("checked contiguous"));
        let s = seeds
            .as_ref()
            .map(|s| s.as_slice().expect("checked contiguous"));
        let out = buffers.outputs();
        py.detach(|| self.with(|b| b.reset(m, s, out))).py()
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
        let mut buffers = Borrowed::new(self, observations, poses, colliding, crossings)?;
        let out = buffers.outputs();
        py.detach(|| self.with(|b| b.observe(out))).py()
    }

    /// Puts environment `index` into `world`, reset to its start with `seed`; its rows of the
    /// buffers change at the next observe, step or reset.
    fn set_world(&self, py: Python<'_>, index: usize, world: &PyWorld, seed: u64) -> PyResult<()> {
        let w = world.inner.clone();
        py.detach(|| self.with(|b| b.set_world(index, w, seed)))
            .py()
    }

    /// Sets the start pose of each environment for its later resets: an (N, 3) float64 array of
    /// x, y, yaw (every value finite).
    fn set_starts(&self, starts: &Bound<'_, PyAny>) -> PyResult<()> {
        let starts = readable::<f64>(starts, "starts", "float64", &[self.n, 3])?;
        let rows = starts.as_slice().expect("checked contiguous");
        self.with(|b| {
            for i in 0..rows.len() / 3 {
                b.env_mut(i)?
                    .set_start(rows[3 * i], rows[3 * i + 1], rows[3 * i + 2])?;
            }
            Ok(())
        })
        .py()
    }

    /// Wheel position sensors of each environment, (N, 2) float64 radians (left, right),
    /// quantised to the profile's encoder resolution.
    fn encoders<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, numpy::PyArray2<f64>>> {
        let v: Vec<f64> = self.with(|b| b.envs().iter().flat_map(|e| e.encoders()).collect());
        PyArray1::from_vec(py, v).reshape([self.n, 2])
    }

    /// Simulated seconds of each environment since its reset.
    fn times<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        self.per_env(py, |e| e.time())
    }

    /// Control steps of each environment since its reset.
    fn steps<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u64>> {
        self.per_env(py, |e| e.steps())
    }

    /// Bumps of each environment since its reset.
    fn collisions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<u64>> {
        self.per_env(py, |e| e.collisions())
    }

    /// Path length of each environment since its reset, metres.
    fn distances_travelled<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
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
