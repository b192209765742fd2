//! `Simulator` for Python: one robot in one world.

use mazesim_core::{SimConfig, Simulator};
use numpy::PyArray1;
use pyo3::prelude::*;
use pyo3::types::{PyBytes, PyDict, PyTuple};

use crate::args::{Bytes, Flag, IntArg, Real};
use crate::buffers::readable;
use crate::errors::{invalid, IntoPy};
use crate::guard::{enter, enter_detached};
use crate::lock::Exclusive;
use crate::profile::{PyRobotProfile, RobotArg};
use crate::world::{world_argument, PyWorld};

/// What a busy simulator is called in `SimulatorBusyError`.
const SIMULATOR: &str = "this Simulator";

/// One robot in one world, stepped in control steps.
#[pyclass(name = "Simulator", module = "mazesim._core", frozen)]
pub struct PySimulator {
    inner: Exclusive<Simulator>,
}

impl PySimulator {
    /// `with` for a Python entry point: a panic becomes `InternalError`.
    fn read<T>(&self, f: impl FnOnce(&mut Simulator) -> T) -> PyResult<T> {
        enter(|| self.inner.with(f))
    }
}

#[pymethods]
impl PySimulator {
    #[new]
    #[pyo3(signature = (world, robot = RobotArg::default_robot(), seed = IntArg::ZERO, noise = Flag::Value(true), control_step_ms = None),
        text_signature = "(world, robot='e-puck', seed=0, noise=True, control_step_ms=None)")]
    fn new(
        world: &Bound<'_, PyAny>,
        robot: RobotArg,
        seed: IntArg,
        noise: Flag,
        control_step_ms: Option<Real>,
    ) -> PyResult<Self> {
        enter(|| {
            let world = world_argument(world, "world")?;
            let profile = robot.profile("robot")?;
            let noise = noise.value("noise", "a bool")?;
            let control_step_ms = control_step_ms
                .map(|ms| ms.value("control_step_ms"))
                .transpose()?;
            let config = SimConfig {
                seed: seed.seed("seed")?,
                noise,
                control_step: control_step_ms.map(|ms| ms / 1000.0),
            };
            let sim = Simulator::new(world, profile, config).py()?;
            Ok(Self {
                inner: Exclusive::new(sim, SIMULATOR),
            })
        })
    }

    /// Back to the start pose, time and counters zeroed; a new seed if given.
    #[pyo3(signature = (seed = None))]
    fn reset(&self, seed: Option<IntArg>) -> PyResult<()> {
        enter(|| {
            let seed = seed.map(|s| s.seed("seed")).transpose()?;
            self.inner.with(|s| s.reset(seed))
        })
    }

    /// Advances one control step with wheel speeds in rad/s (clamped to the motor limit).
    fn step(&self, py: Python<'_>, left: Real, right: Real) -> PyResult<()> {
        let (left, right) = (left.value("left")?, right.value("right")?);
        enter_detached(py, || self.inner.with_detached(|s| s.step(left, right)))
    }

    /// `step`, then what a gym step returns, in one call: the readings (float32, the distance
    /// sensors then the ground sensors) clamped to [`low`, `high`] (float32 arrays of that
    /// width), the pose (float32 x, y, yaw), whether the body touches a wall and the signed
    /// checkpoint crossed in this step (0: none).
    #[allow(clippy::type_complexity)]
    fn step_observe<'py>(
        &self,
        py: Python<'py>,
        left: Real,
        right: Real,
        low: &Bound<'py, PyAny>,
        high: &Bound<'py, PyAny>,
    ) -> PyResult<(
        Bound<'py, PyArray1<f32>>,
        Bound<'py, PyArray1<f32>>,
        bool,
        i32,
    )> {
        let (left, right) = (left.value("left")?, right.value("right")?);
        enter(|| {
            // The bounds are read before the simulator is taken: reading them may run Python
            // code (a property of the argument) that uses this simulator.
            let width = self
                .inner
                .with(|s| s.distance_sensors().len() + s.ground_sensors().len())?;
            let low = readable::<f32>(low, "low", "float32", &[width])?;
            let high = readable::<f32>(high, "high", "float32", &[width])?;
            let contiguous = |name: &str| invalid(format!("expected {name} to be contiguous"));
            let low = low.as_slice().map_err(|_| contiguous("low"))?;
            let high = high.as_slice().map_err(|_| contiguous("high"))?;
            self.inner.with(|s| {
                s.step(left, right).py()?;
                let readings: Vec<f32> = (s.distance_sensors().iter())
                    .chain(s.ground_sensors())
                    .zip(low.iter().zip(high))
                    .map(|(value, (least, most))| value.max(*least).min(*most))
                    .collect();
                let p = s.pose();
                Ok((
                    PyArray1::from_vec(py, readings),
                    PyArray1::from_slice(py, &p),
                    s.colliding(),
                    s.last_crossing(),
                ))
            })?
        })
    }

    /// Sets the pose every later reset starts from (instead of the world's start).
    fn set_start(&self, x: Real, y: Real, yaw: Real) -> PyResult<()> {
        let (x, y, yaw) = (x.value("x")?, y.value("y")?, yaw.value("yaw")?);
        enter(|| self.inner.with(|s| s.set_start(x, y, yaw))?.py())
    }

    /// Sets the goal disc, centre (x, y) and radius in metres, instead of the world's.
    fn set_goal(&self, x: Real, y: Real, radius: Real) -> PyResult<()> {
        let (x, y, radius) = (x.value("x")?, y.value("y")?, radius.value("radius")?);
        enter(|| self.inner.with(|s| s.set_goal(x, y, radius))?.py())
    }

    /// The goal disc (x, y, radius) the episodes end at (`set_goal`'s, else the world's), or None.
    #[getter]
    fn goal(&self) -> PyResult<Option<(f64, f64, f64)>> {
        enter(|| {
            self.inner
                .with(|s| s.goal().map(|g| (g.center[0], g.center[1], g.radius)))
        })
    }

    /// Moves the robot to (x, y, yaw) at rest and reads the sensors there.
    fn set_pose(&self, x: Real, y: Real, yaw: Real) -> PyResult<()> {
        let (x, y, yaw) = (x.value("x")?, y.value("y")?, yaw.value("yaw")?);
        enter(|| self.inner.with(|s| s.set_pose(x, y, yaw))?.py())
    }

    /// Distance sensor readings (float32), device order.
    fn distance_sensors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f32>>> {
        self.read(|s| PyArray1::from_slice(py, s.distance_sensors()))
    }

    /// Ground sensor readings (float32), device order.
    fn ground_sensors<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f32>>> {
        self.read(|s| PyArray1::from_slice(py, s.ground_sensors()))
    }

    #[getter]
    fn pose(&self) -> PyResult<(f64, f64, f64)> {
        let p = self.read(|s| s.pose())?;
        Ok((p[0] as f64, p[1] as f64, p[2] as f64))
    }
    /// Current poses (x, y, yaw) of the world's movable bodies, in world order.
    fn body_poses(&self) -> PyResult<Vec<(f64, f64, f64)>> {
        let poses = self.read(|s| s.body_poses())?;
        Ok(poses
            .iter()
            .map(|p| (p[0] as f64, p[1] as f64, p[2] as f64))
            .collect())
    }
    #[getter]
    fn time(&self) -> PyResult<f64> {
        self.read(|s| s.time())
    }
    #[getter]
    fn steps(&self) -> PyResult<u64> {
        self.read(|s| s.steps())
    }
    #[getter]
    fn collisions(&self) -> PyResult<u64> {
        self.read(|s| s.collisions())
    }
    #[getter]
    fn colliding(&self) -> PyResult<bool> {
        self.read(|s| s.colliding())
    }
    #[getter]
    fn distance_travelled(&self) -> PyResult<f64> {
        self.read(|s| s.distance_travelled())
    }
    #[getter]
    fn wheel_speeds(&self) -> PyResult<(f64, f64)> {
        let w = self.read(|s| s.wheel_speeds())?;
        Ok((w[0] as f64, w[1] as f64))
    }
    #[getter]
    fn encoders(&self) -> PyResult<(f64, f64)> {
        let e = self.read(|s| s.encoders())?;
        Ok((e[0], e[1]))
    }
    #[getter]
    fn wall_clearance(&self) -> PyResult<f64> {
        self.read(|s| s.wall_clearance() as f64)
    }
    /// Barcode crossed in the last step: +id along the checkpoint's yaw (arrival), -id against it
    /// (departure), 0 for none.
    #[getter]
    fn last_crossing(&self) -> PyResult<i32> {
        self.read(|s| s.last_crossing())
    }

    /// Barcode crossings since reset: dicts of checkpoint, direction ("arrival" along the
    /// checkpoint's yaw, "departure" against it), step and time.
    fn crossings<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        let (list, dt) = self.read(|s| (s.crossings().to_vec(), s.control_step()))?;
        list.iter()
            .map(|c| {
                let d = PyDict::new(py);
                d.set_item("checkpoint", c.checkpoint)?;
                d.set_item("direction", if c.forward { "arrival" } else { "departure" })?;
                d.set_item("step", c.step)?;
                d.set_item("time", c.step as f64 * dt)?;
                Ok(d)
            })
            .collect()
    }

    #[getter]
    fn control_step_ms(&self) -> PyResult<f64> {
        self.read(|s| s.control_step() * 1000.0)
    }
    #[getter]
    fn robot(&self) -> PyResult<PyRobotProfile> {
        Ok(PyRobotProfile {
            inner: self.read(|s| s.robot().clone())?,
        })
    }
    #[getter]
    fn world(&self) -> PyResult<PyWorld> {
        Ok(PyWorld {
            inner: self.read(|s| s.world().clone())?,
        })
    }

    /// The whole state as bytes, for `restore` (pose, velocities, rapier's contact state, noise
    /// stream, time, counters, barcode tracker, readings).
    fn snapshot<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let bytes = self.read(|s| s.snapshot())?;
        Ok(PyBytes::new(py, &bytes))
    }

    /// Puts the simulator in the state of a `snapshot` of a simulator of the same world, robot
    /// profile, control step and noise setting; it then goes on exactly as that one would.
    fn restore(&self, py: Python<'_>, snapshot: Bytes) -> PyResult<()> {
        let snapshot = enter(|| snapshot.value("snapshot", "bytes"))?.0;
        enter_detached(py, || self.inner.with_detached(|s| s.restore(&snapshot)))
    }

    /// An independent simulator in the same state, sharing the (immutable) world.
    fn __copy__(&self) -> PyResult<Self> {
        enter(|| {
            let copy = self.inner.with(|s| s.duplicate())?.py()?;
            Ok(Self {
                inner: Exclusive::new(copy, SIMULATOR),
            })
        })
    }

    fn __deepcopy__(&self, _memo: &Bound<'_, PyDict>) -> PyResult<Self> {
        self.__copy__()
    }

    /// Pickles as the constructor's arguments and a snapshot.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let this = slf.get();
        let (world, robot, config, snapshot) = this.read(|s| {
            (
                s.world().clone(),
                s.robot().clone(),
                s.config(),
                s.snapshot(),
            )
        })?;
        let control_step_ms = config.control_step.map(|c| c * 1000.0);
        let args = (
            PyWorld { inner: world },
            PyRobotProfile { inner: robot },
            config.seed,
            config.noise,
            control_step_ms,
        );
        (slf.get_type(), args, PyBytes::new(py, &snapshot)).into_pyobject(py)
    }

    fn __setstate__(&self, py: Python<'_>, state: Bytes) -> PyResult<()> {
        self.restore(py, state)
    }

    fn __repr__(&self) -> PyResult<String> {
        self.read(|s| {
            format!(
                "Simulator(world={:?}, robot={:?}, time={:.3})",
                s.world().name(),
                s.robot().name,
                s.time()
            )
        })
    }
}
