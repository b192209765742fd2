//! `Navigator` for Python: the core's step of the navigator's lower level for N robots
//! (`mazesim_core::navigator::step`), its tables copied in, each step's distances, poses and
//! the higher level's choices read from numpy arrays and what it did returned as arrays.

use mazesim_core::limits::MAX_ENVS;
use mazesim_core::navigator::door::{Phases, SubTaskState, NUM_SUBTASKS};
use mazesim_core::navigator::heading_hold::BlindRule;
use mazesim_core::navigator::step::{Navigator, RobotState};
use mazesim_core::navigator::{NUM_ACTIONS, NUM_SENSORS};
use numpy::{PyArray1, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{Flag, IntArg};
use crate::buffers::copied;
use crate::errors::{invalid, IntoPy};
use crate::guard::enter;
use crate::lock::Exclusive;
use crate::subtasks::SubTaskArrays;

/// What a busy navigator is called in `SimulatorBusyError`.
const NAVIGATOR: &str = "this Navigator";

/// The lower level of the report's navigator for N robots, stepped in the core.
#[pyclass(name = "Navigator", module = "mazesim._core", frozen)]
pub struct PyNavigator {
    inner: Exclusive<Navigator>,
    num_envs: usize,
}

/// The (N, 3) float64 odometry poses of `obj` as rows.
fn poses(obj: &Bound<'_, PyAny>, n: usize) -> PyResult<Vec<[f64; 3]>> {
    let flat = copied::<f64>(obj, "odometry", "float64", &[n, 3])?;
    Ok(flat.chunks_exact(3).map(|p| [p[0], p[1], p[2]]).collect())
}

/// `values` as a 1-D numpy array, reshaped to `shape`.
fn array<'py, T: numpy::Element>(
    py: Python<'py>,
    values: Vec<T>,
    shape: &[usize],
) -> PyResult<Bound<'py, PyAny>> {
    Ok(PyArray1::from_vec(py, values)
        .reshape(numpy::IxDyn(shape))?
        .into_any())
}

#[pymethods]
impl PyNavigator {
    #[new]
    #[pyo3(
        signature = (lower_q, num_envs, hold_heading=Flag::Value(false)),
        text_signature = "(lower_q, num_envs, hold_heading=False)"
    )]
    fn new(lower_q: &Bound<'_, PyAny>, num_envs: IntArg, hold_heading: Flag) -> PyResult<Self> {
        enter(|| {
            let num_envs = num_envs.count("num_envs", MAX_ENVS)?;
            let hold = hold_heading.value("hold_heading", "a bool")?;
            let rows = match crate::args::shape_of(lower_q).as_deref() {
                Some([_, rows, _]) if *rows == Phases::HeadingAndDistance.rows() => *rows,
                _ => Phases::Heading.rows(),
            };
            let shape = [NUM_SUBTASKS, rows, NUM_ACTIONS];
            let values = copied::<f64>(lower_q, "lower_q", "float64", &shape)?;
            let blind = if hold {
                BlindRule::HoldHeading
            } else {
                BlindRule::Table
            };
            let navigator = Navigator::new(values, num_envs, blind).py()?;
            Ok(Self {
                inner: Exclusive::new(navigator, NAVIGATOR),
                num_envs,
            })
        })
    }

    /// Number of robots.
    #[getter]
    fn num_envs(&self) -> usize {
        self.num_envs
    }

    /// Starts the robots `envs` (int64) afresh in Corridors and Corners at their rows of the
    /// (N, 3) float64 `odometry` (x, y, yaw).
    fn reset(&self, envs: &Bound<'_, PyAny>, odometry: &Bound<'_, PyAny>) -> PyResult<()> {
        enter(|| {
            let n = self.num_envs;
            let count = crate::args::shape_of(envs).map_or(0, |s| s.iter().product());
            let envs = copied::<i64>(envs, "envs", "int64", &[count])?;
            let poses = poses(odometry, n)?;
            if let Some(&bad) = envs.iter().find(|&&e| !(0..n as i64).contains(&e)) {
                return Err(invalid(format!(
                    "expected robot numbers in [0, {n}), found {bad}"
                )));
            }
            self.inner.with(|nav| {
                for &env in &envs {
                    nav.reset(env as usize, poses[env as usize]);
                }
            })
        })
    }

    /// One step of every robot: the (N, 6) float64 `distances_cm` (front, back, left, right,
    /// left-front, right-front), the (N, 3) float64 `odometry` after the last step and the (N,)
    /// int64 sub-task the higher level `chosen` for each robot (-1: none). Returns a dict of
    /// arrays: `action`, `state`, `subtask`, `phase` (int64, (N,)), `levels` (int64, (N, 6))
    /// and `ended` (bool, (N,): a door sub-task ended).
    fn decide<'py>(
        &self,
        py: Python<'py>,
        distances_cm: &Bound<'py, PyAny>,
        odometry: &Bound<'py, PyAny>,
        chosen: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let n = self.num_envs;
        let records = enter(|| {
            let distances =
                copied::<f64>(distances_cm, "distances_cm", "float64", &[n, NUM_SENSORS])?;
            let poses = poses(odometry, n)?;
            let chosen = copied::<i64>(chosen, "chosen", "int64", &[n])?;
            self.inner.with(|nav| {
                (0..n)
                    .map(|i| {
                        let pick = usize::try_from(chosen[i]).ok();
                        let row = &distances[NUM_SENSORS * i..NUM_SENSORS * (i + 1)];
                        nav.decide(i, row, poses[i], pick).py()
                    })
                    .collect::<PyResult<Vec<_>>>()
            })?
        })?;
        let dict = PyDict::new(py);
        let column = |f: &dyn Fn(&mazesim_core::navigator::step::StepRecord) -> i64| {
            records.iter().map(f).collect::<Vec<i64>>()
        };
        dict.set_item("action", array(py, column(&|r| r.action as i64), &[n])?)?;
        dict.set_item("state", array(py, column(&|r| r.state as i64), &[n])?)?;
        dict.set_item("subtask", array(py, column(&|r| r.subtask as i64), &[n])?)?;
        dict.set_item("phase", array(py, column(&|r| r.phase as i64), &[n])?)?;
        let levels = records
            .iter()
            .flat_map(|r| r.levels.map(i64::from))
            .collect();
        dict.set_item("levels", array(py, levels, &[n, NUM_SENSORS])?)?;
        let ended = records.iter().map(|r| r.ended).collect();
        dict.set_item("ended", array(py, ended, &[n])?)?;
        Ok(dict)
    }

    /// Each robot's running sub-task as the arrays `BatchSimulator.run` takes as `subtasks`
    /// (copies: hand them back with `set_subtask_arrays` after the run).
    fn subtask_arrays<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let robots = enter(|| self.inner.with(|nav| nav.robots().to_vec()))?;
        let n = robots.len();
        let dict = PyDict::new(py);
        for key in ["subtask", "steps", "phase"] {
            dict.set_item(key, array(py, vec![0i64; n], &[n])?)?;
        }
        for (key, shape) in [
            ("start", &[n, 3][..]),
            ("previous_yaw", &[n][..]),
            ("heading_change", &[n][..]),
            ("turn_point", &[n, 2][..]),
        ] {
            let size = shape.iter().product();
            dict.set_item(key, array(py, vec![0.0f64; size], shape)?)?;
        }
        let tasks: Vec<SubTaskState> = robots.iter().map(|r| r.task).collect();
        SubTaskArrays::new(dict.as_any(), n)?.store(&tasks);
        Ok(dict)
    }

    /// Sets each robot's running sub-task from arrays of `subtask_arrays`' layout (after
    /// `BatchSimulator.run` followed the sub-tasks); the robots' last actions stay.
    fn set_subtask_arrays(&self, subtasks: &Bound<'_, PyAny>) -> PyResult<()> {
        enter(|| {
            let tasks = SubTaskArrays::new(subtasks, self.num_envs)?.read(false)?;
            for (i, task) in tasks.iter().enumerate() {
                task.check(i).py()?;
            }
            self.inner.with(|nav| {
                for (robot, task) in nav.robots_mut().iter_mut().zip(tasks) {
                    *robot = RobotState { task, ..*robot };
                }
            })
        })
    }
}
