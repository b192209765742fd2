//! `Simulator` for Python: one robot in one world.

use std::sync::Mutex;

use mazesim_core::{Error, SimConfig, Simulator};
use numpy::PyArray1;
use pyo3::prelude::*;

use crate::errors::IntoPy;
use crate::world::{PyRobotProfile, PyWorld};

/// One robot in one world, stepped in control steps.
#[pyclass(name = "Simulator", module = "mazesim._core", frozen)]
pub struct PySimulator {
    inner: Mutex<Simulator>,
}

impl PySimulator {
    fn with<T>(&self, f: impl FnOnce(&mut Simulator) -> T) -> T {
        let mut guard = self
            .inner
            .lock()
            .unwrap_or_else(|poisoned| poisoned.into_inner());
        f(&mut guard)
    }
}

fn seed_of(seed: i128) -> PyResult<u64> {
    u64::try_from(seed).map_err(|_| {
        crate::errors::to_py(Error::InvalidArgument(format!(
            "expected a seed in 0..2**64, found {seed}"
        )))
    })
}

#[pymethods]
impl PySimulator {
    #[new]
    #[pyo3(signature = (world, robot = "e-puck", seed = 0, noise = true, control_step_ms = None))]
    fn new(
        world: &PyWorld,
        robot: &str,
        seed: i128,
        noise: bool,
        control_step_ms: Option<f64>,
    ) -> PyResult<Self> {
        let profile = PyRobotProfile::builtin(robot)?;
        let config = SimConfig {
            seed: seed_of(seed)?,
            noise,
            control_step: control_step_ms.map(|ms| ms / 1000.0),
        };
        let sim = Simulator::new(world.inner.clone(), profile.inner, config).py()?;
        Ok(Self {
            inner: Mutex::new(sim),
        })
    }

    /// Back to the start pose, time and counters zeroed; a new seed if given.
    #[pyo3(signature = (seed = None))]
    fn reset(&self, seed: Option<i128>) -> PyResult<()> {
        let seed = seed.map(seed_of).transpose()?;
        self.with(|s| s.reset(seed));
        Ok(())
    }

    /// Advances one control step with wheel speeds in rad/s (clamped to the motor limit).
    fn step(&self, left: f64, right: f64) -> PyResult<()> {
        self.with(|s| s.step(left, right)).py()
    }

    /// Sets the pose every later reset starts from (instead of the world's start).
    fn set_start(&self, x: f64, y: f64, yaw: f64) -> PyResult<()> {
        self.with(|s| s.set_start(x, y, yaw)).py()
    }

    /// Moves the robot to (x, y, yaw) at rest and reads the sensors there.
    fn set_pose(&self, x: f64, y: f64, yaw: f64) -> PyResult<()> {
        self.with(|s| s.set_pose(x, y, yaw)).py()
    }

    /// Distance sensor readings (float32), device order.
    fn distance_sensors<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f32>> {
        self.with(|s| PyArray1::from_slice(py, s.distance_sensors()))
    }

    /// Ground sensor readings (float32), device order.
    fn ground_sensors<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f32>> {
        self.with(|s| PyArray1::from_slice(py, s.ground_sensors()))
    }

    #[getter]
    fn pose(&self) -> (f64, f64, f64) {
        let p = self.with(|s| s.pose());
        (p[0] as f64, p[1] as f64, p[2] as f64)
    }
    #[getter]
    fn time(&self) -> f64 {
        self.with(|s| s.time())
    }
    #[getter]
    fn steps(&self) -> u64 {
        self.with(|s| s.steps())
    }
    #[getter]
    fn collisions(&self) -> u64 {
        self.with(|s| s.collisions())
    }
    #[getter]
    fn colliding(&self) -> bool {
        self.with(|s| s.colliding())
    }
    #[getter]
    fn distance_travelled(&self) -> f64 {
        self.with(|s| s.distance_travelled())
    }
    #[getter]
    fn wheel_speeds(&self) -> (f64, f64) {
        let w = self.with(|s| s.wheel_speeds());
        (w[0] as f64, w[1] as f64)
    }
    #[getter]
    fn encoders(&self) -> (f64, f64) {
        let e = self.with(|s| s.encoders());
        (e[0], e[1])
    }
    #[getter]
    fn wall_clearance(&self) -> f64 {
        self.with(|s| s.wall_clearance() as f64)
    }
    /// Barcode crossed in the last step: +id along the checkpoint's yaw (arrival), -id against it
    /// (departure), 0 for none.
    #[getter]
    fn last_crossing(&self) -> i32 {
        self.with(|s| s.last_crossing())
    }

    /// Barcode crossings since reset: dicts of checkpoint, direction ("arrival" along the
    /// checkpoint's yaw, "departure" against it), step and time.
    fn crossings<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, pyo3::types::PyDict>>> {
        let (list, dt) = self.with(|s| (s.crossings().to_vec(), s.control_step()));
        list.iter()
            .map(|c| {
                let d = pyo3::types::PyDict::new(py);
                d.set_item("checkpoint", c.checkpoint)?;
                d.set_item("direction", if c.forward { "arrival" } else { "departure" })?;
                d.set_item("step", c.step)?;
                d.set_item("time", c.step as f64 * dt)?;
                Ok(d)
            })
            .collect()
    }

    #[getter]
    fn control_step_ms(&self) -> f64 {
        self.with(|s| s.control_step() * 1000.0)
    }
    #[getter]
    fn robot(&self) -> PyRobotProfile {
        PyRobotProfile {
            inner: self.with(|s| s.robot().clone()),
        }
    }
    #[getter]
    fn world(&self) -> PyWorld {
        PyWorld {
            inner: self.with(|s| s.world().clone()),
        }
    }

    fn __repr__(&self) -> String {
        self.with(|s| {
            format!(
                "Simulator(world={:?}, robot={:?}, time={:.3})",
                s.world().name(),
                s.robot().name,
                s.time()
            )
        })
    }
}
