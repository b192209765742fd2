//! `TaskFeatures` for Python: the navigation features of the gymnasium tasks
//! (`mazesim_core::tasks`), read from and written to numpy arrays.

use mazesim_core::tasks::{
    check_ordered, FeatureKinds, Features, GoalMode, GoalTable, Grid, Place, MAX_FEATURE_CELLS,
    SIDES, TARGETS,
};
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyBytes;

use crate::args::{type_name, Bytes, Flag, IntArg, Real, Text};
use crate::buffers::copied;
use crate::errors::{invalid, wrong_type, IntoPy};
use crate::guard::enter;
use crate::lock::Exclusive;

/// What busy features are called in `SimulatorBusyError`.
const FEATURES: &str = "these TaskFeatures";
/// The values of `place`: goal x, y, extent, corner x, y, cell size, origin x, y.
const PLACE_VALUES: usize = 8;

/// The rows of an (n, 2) or (n, 4) float64 array whose row count is not known in advance.
fn rows_of<const W: usize>(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<Vec<[f64; W]>> {
    let rows = crate::args::shape_of(obj)
        .filter(|shape| shape.len() == 2 && shape[1] == W)
        .map(|shape| shape[0])
        .unwrap_or(0);
    let flat = copied::<f64>(obj, name, "float64", &[rows, W])?;
    Ok(flat
        .chunks_exact(W)
        .map(|c| std::array::from_fn(|i| c[i]))
        .collect())
}

/// The navigation features (goal, explored map, waypoint, pose, previous action) of N
/// environments, computed per step in the core.
#[pyclass(name = "TaskFeatures", module = "mazesim._core", frozen)]
pub struct PyTaskFeatures {
    inner: Exclusive<Features>,
    /// Values of one observation.
    #[pyo3(get)]
    width: usize,
    sensors: usize,
    num_envs: usize,
}

#[pymethods]
impl PyTaskFeatures {
    #[new]
    #[pyo3(signature = (num_envs, observation, include_pose, sensor_scale, feature_low, feature_high))]
    fn new(
        num_envs: IntArg,
        observation: Text,
        include_pose: Flag,
        sensor_scale: &Bound<'_, PyAny>,
        feature_low: &Bound<'_, PyAny>,
        feature_high: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        enter(|| {
            let num_envs = num_envs.count("num_envs", MAX_FEATURE_CELLS)?;
            let observation = observation.value("observation", "a str")?;
            let pose = include_pose.value("include_pose", "a bool")?;
            let (guided, plan, explore) = match observation.as_str() {
                "goal" => (false, false, false),
                "explore" => (false, false, true),
                "guided" => (true, false, false),
                "plan" => (false, true, true),
                other => {
                    return Err(invalid(format!(
                        "expected observation to be one of goal, explore, guided, plan; found \
                         {:?}",
                        other.chars().take(80).collect::<String>()
                    )))
                }
            };
            let kinds = FeatureKinds {
                guided,
                plan,
                explore,
                pose,
            };
            let sensors = crate::args::shape_of(sensor_scale)
                .filter(|s| s.len() == 1)
                .map(|s| s[0])
                .unwrap_or(0);
            let scale = copied::<f64>(sensor_scale, "sensor_scale", "float64", &[sensors])?;
            let width = Features::width_of(kinds, sensors);
            let low = copied::<f32>(feature_low, "feature_low", "float32", &[width])?;
            let high = copied::<f32>(feature_high, "feature_high", "float32", &[width])?;
            let features = Features::new(num_envs, kinds, scale, low, high).py()?;
            Ok(Self {
                width: features.width(),
                sensors,
                num_envs,
                inner: Exclusive::new(features, FEATURES),
            })
        })
    }

    /// Puts environment `env` into a world: `place` (float64: goal x, y, the world's larger
    /// side, its south-west corner x, y, the cell size, the grid's south-west corner x, y), its
    /// grid of `rows` x `cols` cells, the next `waypoints` of its cells ((n, 2) float64), the
    /// true `open_sides` of its cells ((rows * cols, 4) float64, 1.0 open) or None, and the
    /// `goal_cell` (row-major) to plan towards or None. Restarts the episode's map.
    #[pyo3(signature = (env, place, rows, cols, waypoints, open_sides, goal_cell))]
    fn set_env(
        &self,
        env: IntArg,
        place: &Bound<'_, PyAny>,
        rows: IntArg,
        cols: IntArg,
        waypoints: &Bound<'_, PyAny>,
        open_sides: Option<&Bound<'_, PyAny>>,
        goal_cell: Option<IntArg>,
    ) -> PyResult<()> {
        enter(|| {
            let env = env.count("env", usize::MAX)?;
            let p = copied::<f64>(place, "place", "float64", &[PLACE_VALUES])?;
            let rows = rows.count("rows", MAX_FEATURE_CELLS)?;
            let cols = cols.count("cols", MAX_FEATURE_CELLS)?;
            let waypoints = rows_of::<2>(waypoints, "waypoints")?;
            let sides = open_sides
                .map(|sides| rows_of::<SIDES>(sides, "open_sides"))
                .transpose()?;
            let goal_cell = goal_cell
                .map(|c| c.count("goal_cell", usize::MAX))
                .transpose()?;
            let place = Place {
                goal: [p[0], p[1]],
                extent: p[2],
                corner: [p[3], p[4]],
                cell_size: p[5],
                origin: [p[6], p[7]],
                grid: Grid { rows, cols },
            };
            self.inner.with(|f| {
                f.set_env(env, place, &waypoints, sides.as_deref(), goal_cell)
                    .py()
            })?
        })
    }

    /// The state of every environment as bytes, for `restore` (pickling, copies).
    fn state<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyBytes>> {
        let state = enter(|| self.inner.with(|f| f.state()))?;
        Ok(PyBytes::new(py, &state))
    }

    /// Puts every environment in the `state` of TaskFeatures of the same kind and number of
    /// environments.
    fn restore(&self, state: Bytes) -> PyResult<()> {
        enter(|| {
            let state = state.value("state", "bytes")?;
            self.inner.with(|f| f.restore(&state.0).py())?
        })
    }

    /// Sets the distance table of environment `env`'s goal: `mode` (`"maze"`, `"straight"` or
    /// `"none"`), the `goal` disc (float64 x, y, radius), the grid's `cell_size`, south-west
    /// `origin` (float64 x, y), its `shape` (rows, cols), and the (rows * cols, 5) float64
    /// `targets` of its cells (east, north, west, south, goal; NaN where none).
    #[pyo3(signature = (env, mode, goal, cell_size, origin, shape, targets))]
    fn set_goal(
        &self,
        env: IntArg,
        mode: Text,
        goal: &Bound<'_, PyAny>,
        cell_size: Real,
        origin: &Bound<'_, PyAny>,
        shape: &Bound<'_, PyAny>,
        targets: &Bound<'_, PyAny>,
    ) -> PyResult<()> {
        let (rows, cols) = shape.extract::<(IntArg, IntArg)>().map_err(|_| {
            wrong_type(format!(
                "expected shape to be a (rows, cols) pair of ints, found {}",
                type_name(shape)
            ))
        })?;
        enter(|| {
            let env = env.count("env", usize::MAX)?;
            let mode = match mode.value("mode", "a str")?.as_str() {
                "maze" => GoalMode::Maze,
                "straight" => GoalMode::Straight,
                "none" => GoalMode::Nowhere,
                other => {
                    return Err(invalid(format!(
                        "expected mode to be one of maze, straight, none; found {:?}",
                        other.chars().take(80).collect::<String>()
                    )))
                }
            };
            let g = copied::<f64>(goal, "goal", "float64", &[3])?;
            let o = copied::<f64>(origin, "origin", "float64", &[2])?;
            let rows = rows.count("rows", MAX_FEATURE_CELLS)?;
            let cols = cols.count("cols", MAX_FEATURE_CELLS)?;
            let targets = rows_of::<TARGETS>(targets, "targets")?;
            let size = cell_size.value("cell_size")?;
            let table = GoalTable::new(
                mode,
                [g[0], g[1], g[2]],
                size,
                [o[0], o[1]],
                rows,
                cols,
                &targets,
            )
            .py()?;
            self.inner.with(|f| f.set_goal(env, table).py())?
        })
    }

    /// Forgets the explored map's visits of environment `env` (a new episode).
    fn restart(&self, env: IntArg) -> PyResult<()> {
        enter(|| {
            let env = env.count("env", usize::MAX)?;
            self.inner.with(|f| f.restart(env).py())?
        })
    }

    /// The (N, width) float32 observations of every environment from their (N, sensors)
    /// float32 raw `readings`, (N, 3) float32 `poses` and (N, 2) float32 `previous` actions
    /// (wheel speed fractions).
    fn observe<'py>(
        &self,
        py: Python<'py>,
        readings: &Bound<'py, PyAny>,
        poses: &Bound<'py, PyAny>,
        previous: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyArray2<f32>>> {
        enter(|| {
            let n = self.num_envs;
            let readings = copied::<f32>(readings, "readings", "float32", &[n, self.sensors])?;
            let poses = copied::<f32>(poses, "poses", "float32", &[n, 3])?;
            let previous = copied::<f32>(previous, "previous", "float32", &[n, 2])?;
            let width = self.width;
            let mut out = vec![0.0f32; n * width];
            self.inner.with(|f| {
                for env in 0..n {
                    let pose = [poses[3 * env], poses[3 * env + 1], poses[3 * env + 2]];
                    let sensors = &readings[env * self.sensors..(env + 1) * self.sensors];
                    let last = [previous[2 * env], previous[2 * env + 1]];
                    let slot = &mut out[env * width..(env + 1) * width];
                    f.observe(env, sensors, pose, last, slot).py()?;
                }
                Ok::<_, PyErr>(())
            })??;
            PyArray1::from_vec(py, out).reshape([n, width])
        })
    }

    /// The (width,) float32 observation of environment `env` from its float32 raw `readings`
    /// and `pose`, the previous action being the wheel speeds `left` and `right` (rad/s, float32
    /// values) over `max_speed` in float32; then the distance in metres from the pose to the
    /// goal (`set_goal`) and whether the pose is in the goal disc.
    fn observe_env<'py>(
        &self,
        py: Python<'py>,
        env: IntArg,
        readings: &Bound<'py, PyAny>,
        pose: &Bound<'py, PyAny>,
        left: Real,
        right: Real,
        max_speed: Real,
    ) -> PyResult<(Bound<'py, PyArray1<f32>>, f64, bool)> {
        enter(|| {
            let env = env.count("env", usize::MAX)?;
            let readings = copied::<f32>(readings, "readings", "float32", &[self.sensors])?;
            let pose = copied::<f32>(pose, "pose", "float32", &[3])?;
            let previous = previous_action(&left, &right, &max_speed)?;
            let (out, distance, reached) =
                self.observe_one(env, &readings, [pose[0], pose[1], pose[2]], previous)?;
            Ok((PyArray1::from_vec(py, out), distance, reached))
        })
    }
}

/// The previous action of an observation: the wheel speeds `left` and `right` (rad/s) over
/// `max_speed`, each in float32.
pub(crate) fn previous_action(left: &Real, right: &Real, max_speed: &Real) -> PyResult<[f32; 2]> {
    let most = max_speed.value("max_speed")?;
    Ok(scaled(left.value("left")?, right.value("right")?, most))
}

/// The wheel speeds `left` and `right` over `max_speed`, each in float32.
fn scaled(left: f64, right: f64, max_speed: f64) -> [f32; 2] {
    let most = max_speed as f32;
    [left as f32 / most, right as f32 / most]
}

/// What a single env's task step (`Simulator.step_task`) keeps for the whole episode: the
/// bounds its readings are clamped to and the motor limit its previous action is scaled by.
#[pyclass(name = "StepBounds", module = "mazesim._core", frozen)]
pub struct PyStepBounds {
    low: Vec<f32>,
    high: Vec<f32>,
    /// The motor limit (rad/s) the previous action's wheel speeds are divided by.
    #[pyo3(get)]
    max_speed: f64,
}

#[pymethods]
impl PyStepBounds {
    #[new]
    #[pyo3(signature = (low, high, max_speed))]
    fn new(low: &Bound<'_, PyAny>, high: &Bound<'_, PyAny>, max_speed: Real) -> PyResult<Self> {
        enter(|| {
            let width = crate::args::shape_of(low)
                .filter(|s| s.len() == 1)
                .map_or(0, |s| s[0]);
            let low = copied::<f32>(low, "low", "float32", &[width])?;
            let high = copied::<f32>(high, "high", "float32", &[width])?;
            check_ordered(&low, &high, "reading bounds").py()?;
            let max_speed = max_speed.value("max_speed")?;
            if !(max_speed.is_finite() && max_speed > 0.0) {
                return Err(invalid(format!(
                    "expected max_speed to be a wheel speed above 0 rad/s, found {max_speed}"
                )));
            }
            Ok(Self {
                low,
                high,
                max_speed,
            })
        })
    }

    /// The lower bounds of the readings (float32, the distance sensors then the ground ones).
    #[getter]
    fn low<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f32>> {
        PyArray1::from_slice(py, &self.low)
    }

    /// The upper bounds of the readings.
    #[getter]
    fn high<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f32>> {
        PyArray1::from_slice(py, &self.high)
    }

    /// Pickles (and copies) as the constructor's arguments.
    #[allow(clippy::type_complexity)]
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> (
        Bound<'py, pyo3::types::PyType>,
        (Bound<'py, PyArray1<f32>>, Bound<'py, PyArray1<f32>>, f64),
    ) {
        let (py, this) = (slf.py(), slf.get());
        (
            slf.get_type(),
            (this.low(py), this.high(py), this.max_speed),
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "StepBounds(width={}, max_speed={:?})",
            self.low.len(),
            self.max_speed
        )
    }
}

impl PyStepBounds {
    /// The readings' bounds, low then high.
    pub(crate) fn readings(&self) -> (&[f32], &[f32]) {
        (&self.low, &self.high)
    }

    /// The previous action of wheel speeds `left` and `right` (rad/s): each over the motor
    /// limit, in float32.
    pub(crate) fn previous_action(&self, left: f64, right: f64) -> [f32; 2] {
        scaled(left, right, self.max_speed)
    }
}

impl PyTaskFeatures {
    /// The observation of environment `env` from its clamped `readings`, `pose` and `previous`
    /// action; then the distance in metres from the pose to the goal and whether the pose is in
    /// the goal disc.
    pub(crate) fn observe_one(
        &self,
        env: usize,
        readings: &[f32],
        pose: [f32; 3],
        previous: [f32; 2],
    ) -> PyResult<(Vec<f32>, f64, bool)> {
        if readings.len() != self.sensors {
            return Err(invalid(format!(
                "expected {} sensor readings (these TaskFeatures' robot), found {}",
                self.sensors,
                readings.len()
            )));
        }
        let mut out = vec![0.0f32; self.width];
        self.inner
            .with(|f| f.observe(env, readings, pose, previous, &mut out).py())??;
        let (distance, reached) = self.goal_of(env, pose)?;
        Ok((out, distance, reached))
    }

    /// The distance in metres from `pose` to environment `env`'s goal and whether the pose is in
    /// the goal disc.
    pub(crate) fn goal_of(&self, env: usize, pose: [f32; 3]) -> PyResult<(f64, bool)> {
        let (x, y) = (f64::from(pose[0]), f64::from(pose[1]));
        self.inner.with(|f| f.goal_distance(env, x, y).py())?
    }
}
