//! The settings of `BatchSimulator.run` as typed, frozen objects, each checked when it is made:
//! how episodes end (`EpisodeLimits`), the settings of a built-in controller
//! (`AvoidCollisionSettings`, `TabularSettings`, given as `run`'s controller) and the per-env
//! inputs and outputs of one call (`RunSettings`).

use mazesim_core::control::avoid_collision::EPUCK_MAX_SPEED;
use mazesim_core::control::AvoidCollision;
use mazesim_core::limits::MAX_ENVS;
use mazesim_core::navigator::heading_hold::BlindRule;
use mazesim_core::navigator::{self, TabularPolicy};
use mazesim_core::RunOptions;
use pyo3::prelude::*;

use crate::args::{class_name, dict_argument, shape_of, typed_argument, Flag, IntArg, Real};
use crate::batch::Seeds;
use crate::buffers::{copied, readable};
use crate::errors::{invalid, IntoPy};
use crate::guard::enter;

/// How the episodes of a `run` call end, and what follows the end.
#[pyclass(name = "EpisodeLimits", module = "mazesim._core", frozen)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PyEpisodeLimits {
    /// Control steps after which an episode ends (0: no limit).
    #[pyo3(get)]
    max_steps: u64,
    /// Whether an episode ends on the step the robot's centre enters its goal disc.
    #[pyo3(get)]
    end_at_goal: bool,
    /// Whether an episode ends on a step that crosses a barcode.
    #[pyo3(get)]
    end_at_crossing: bool,
    /// Whether an ended episode is reset at once (else the env stands still until reset).
    #[pyo3(get)]
    autoreset: bool,
}

impl PyEpisodeLimits {
    /// The core's options of a call of `steps` control steps with these limits.
    pub fn options(&self, steps: usize) -> RunOptions {
        RunOptions {
            steps,
            max_episode_steps: self.max_steps,
            end_at_goal: self.end_at_goal,
            end_at_crossing: self.end_at_crossing,
            autoreset: self.autoreset,
        }
    }
}

#[pymethods]
impl PyEpisodeLimits {
    #[new]
    #[pyo3(signature = (max_steps = IntArg::ZERO, end_at_goal = Flag::Value(false), end_at_crossing = Flag::Value(false), autoreset = Flag::Value(true)),
        text_signature = "(max_steps=0, end_at_goal=False, end_at_crossing=False, autoreset=True)")]
    pub fn new(
        max_steps: IntArg,
        end_at_goal: Flag,
        end_at_crossing: Flag,
        autoreset: Flag,
    ) -> PyResult<Self> {
        enter(|| {
            Ok(Self {
                max_steps: max_steps.seed("max_steps")?,
                end_at_goal: end_at_goal.value("end_at_goal", "a bool")?,
                end_at_crossing: end_at_crossing.value("end_at_crossing", "a bool")?,
                autoreset: autoreset.value("autoreset", "a bool")?,
            })
        })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyEpisodeLimits>()
            .is_ok_and(|o| *o.get() == *self)
    }

    fn __hash__(&self) -> u64 {
        self.max_steps
            ^ (u64::from(self.end_at_goal) << 61)
            ^ (u64::from(self.end_at_crossing) << 62)
            ^ (u64::from(self.autoreset) << 63)
    }

    /// Pickles (and copies) as the constructor's arguments.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> (Bound<'py, pyo3::types::PyType>, (u64, bool, bool, bool)) {
        let l = slf.get();
        let arguments = (l.max_steps, l.end_at_goal, l.end_at_crossing, l.autoreset);
        (slf.get_type(), arguments)
    }

    fn __repr__(&self) -> String {
        let py_bool = |b: bool| if b { "True" } else { "False" };
        format!(
            "EpisodeLimits(max_steps={}, end_at_goal={}, end_at_crossing={}, autoreset={})",
            self.max_steps,
            py_bool(self.end_at_goal),
            py_bool(self.end_at_crossing),
            py_bool(self.autoreset)
        )
    }
}

/// The avoid-collision controller of the report's Algorithm 1, as `run`'s controller.
#[pyclass(name = "AvoidCollisionSettings", module = "mazesim._core", frozen)]
#[derive(Clone, Copy, Debug)]
pub struct PyAvoidCollisionSettings {
    pub(crate) rule: AvoidCollision,
}

#[pymethods]
impl PyAvoidCollisionSettings {
    #[new]
    #[pyo3(signature = (threshold = Real::Number(80.0), max_speed = Real::Number(EPUCK_MAX_SPEED)),
        text_signature = "(threshold=80.0, max_speed=6.28)")]
    pub fn new(threshold: Real, max_speed: Real) -> PyResult<Self> {
        enter(|| {
            let threshold = threshold.value("threshold")?;
            let max_speed = max_speed.value("max_speed")?;
            Ok(Self {
                rule: AvoidCollision::new(threshold, max_speed).py()?,
            })
        })
    }

    /// The raw proximity reading above which a sensor sees an obstacle.
    #[getter]
    fn threshold(&self) -> f64 {
        self.rule.threshold
    }

    /// The wheel speed the rule scales, rad/s.
    #[getter]
    fn max_speed(&self) -> f64 {
        self.rule.max_speed
    }

    /// Pickles (and copies) as the constructor's arguments.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, pyo3::types::PyType>, (f64, f64)) {
        let rule = slf.get().rule;
        (slf.get_type(), (rule.threshold, rule.max_speed))
    }

    fn __repr__(&self) -> String {
        format!(
            "AvoidCollisionSettings(threshold={:?}, max_speed={:?})",
            self.rule.threshold, self.rule.max_speed
        )
    }
}

/// The tabular controller (greedy, or epsilon-greedy, over Q-tables) as `run`'s controller; its
/// tables are copied when the settings are made.
#[pyclass(name = "TabularSettings", module = "mazesim._core", frozen)]
pub struct PyTabularSettings {
    pub(crate) policy: TabularPolicy,
    /// How many Q-tables the controller acts from.
    #[pyo3(get)]
    tables: usize,
    /// The rate of uniformly random allowed actions, in [0, 1].
    #[pyo3(get)]
    epsilon: f64,
    /// Whether a spin on the spot goes on the way the last step turned.
    #[pyo3(get)]
    hold_spins: bool,
    /// Whether Corridors and Corners holds its heading where no sensor sees a wall.
    #[pyo3(get)]
    hold_heading: bool,
    /// The motor limit whose fractions every robot drives at (each robot's own when None).
    #[pyo3(get)]
    wheel_speed_limit: Option<f64>,
}

#[pymethods]
impl PyTabularSettings {
    #[new]
    #[pyo3(signature = (table, allowed_actions = None, table_index = None, epsilon = Real::Number(0.0), hold_spins = Flag::Value(false), hold_heading = Flag::Value(false), wheel_speed_limit = None),
        text_signature = "(table, allowed_actions=None, table_index=None, epsilon=0.0, hold_spins=False, hold_heading=False, wheel_speed_limit=None)")]
    pub fn new(
        table: &Bound<'_, PyAny>,
        allowed_actions: Option<&Bound<'_, PyAny>>,
        table_index: Option<&Bound<'_, PyAny>>,
        epsilon: Real,
        hold_spins: Flag,
        hold_heading: Flag,
        wheel_speed_limit: Option<Real>,
    ) -> PyResult<Self> {
        enter(|| {
            let (values, tables, stacked) = tables_of(table)?;
            let allowed = allowed_actions
                .filter(|a| !a.is_none())
                .map(|a| {
                    let shape: &[usize] = if stacked {
                        &[tables, navigator::NUM_ACTIONS]
                    } else {
                        &[navigator::NUM_ACTIONS]
                    };
                    copied::<bool>(a, "allowed_actions", "bool", shape)
                })
                .transpose()?;
            let table_of_env = table_index
                .filter(|t| !t.is_none())
                .map(|t| table_indices(t, tables))
                .transpose()?;
            let epsilon = epsilon.value("epsilon")?;
            let hold_spins = hold_spins.value("hold_spins", "a bool")?;
            let hold_heading = hold_heading.value("hold_heading", "a bool")?;
            let wheel_speed_limit = wheel_speed_limit
                .map(|l| l.value("wheel_speed_limit"))
                .transpose()?;
            let blind = if hold_heading {
                BlindRule::HoldHeading
            } else {
                BlindRule::Table
            };
            let policy =
                TabularPolicy::new(values, tables, allowed.as_deref(), table_of_env, epsilon)
                    .py()?
                    .with_held_spins(hold_spins)
                    .with_blind_rule(blind)
                    .with_speed_limit(wheel_speed_limit)
                    .py()?;
            Ok(Self {
                policy,
                tables,
                epsilon,
                hold_spins,
                hold_heading,
                wheel_speed_limit,
            })
        })
    }

    fn __repr__(&self) -> String {
        let py_bool = |b: bool| if b { "True" } else { "False" };
        let limit = self
            .wheel_speed_limit
            .map_or_else(|| "None".to_string(), |l| format!("{l:?}"));
        format!(
            "TabularSettings(tables={}, epsilon={:?}, hold_spins={}, hold_heading={}, \
             wheel_speed_limit={limit})",
            self.tables,
            self.epsilon,
            py_bool(self.hold_spins),
            py_bool(self.hold_heading)
        )
    }
}

/// The values of `table`, a float64 `(4096, 12)` array or `(tables, 4096, 12)` stack, how many
/// tables it holds and whether it is a stack.
fn tables_of(table: &Bound<'_, PyAny>) -> PyResult<(Vec<f64>, usize, bool)> {
    let (states, actions) = (navigator::NUM_STATES, navigator::NUM_ACTIONS);
    let shape = shape_of(table).unwrap_or_default();
    let (tables, table_shape) = if shape.len() == 3 {
        (shape[0], vec![shape[0], states, actions])
    } else {
        (1, vec![states, actions])
    };
    let values = copied::<f64>(table, "table", "float64", &table_shape)?;
    Ok((values, tables, shape.len() == 3))
}

/// The table of each env from `table_index`, an (N,) int64 array of values in `0..tables`.
fn table_indices(table_index: &Bound<'_, PyAny>, tables: usize) -> PyResult<Vec<u32>> {
    let n = shape_of(table_index)
        .filter(|s| s.len() == 1)
        .map_or(0, |s| s[0]);
    let index = copied::<i64>(table_index, "table_index", "int64", &[n])?;
    index
        .iter()
        .enumerate()
        .map(|(i, &t)| {
            u32::try_from(t).map_err(|_| {
                invalid(format!(
                    "expected table_index values in 0..{tables}, found {t} for environment {i}"
                ))
            })
        })
        .collect()
}

/// The per-env inputs and outputs of one `run` call beside its controller: how its episodes
/// end, the envs' controller streams, which envs step, the navigator's running sub-tasks and
/// the per-step outputs to fill. The arrays are the caller's own (read, and written, by the
/// call), checked against the batch when it runs.
#[pyclass(name = "RunSettings", module = "mazesim._core", frozen)]
pub struct PyRunSettings {
    /// How the episodes of the call end.
    #[pyo3(get)]
    pub(crate) limits: Py<PyEpisodeLimits>,
    pub(crate) seeds: Option<Seeds>,
    /// The seeds of the envs' controller streams (an int ``s`` gives env ``i`` ``s + i``).
    #[pyo3(get, name = "seeds")]
    seeds_given: Option<Py<PyAny>>,
    /// (N,) bool, the envs that step (all when None).
    #[pyo3(get)]
    pub(crate) active: Option<Py<PyAny>>,
    /// The navigator's running sub-task of each env, arrays by key, read and written in place.
    #[pyo3(get)]
    pub(crate) subtasks: Option<Py<PyAny>>,
    /// The per-step outputs to fill, arrays by key.
    #[pyo3(get)]
    pub(crate) trace: Option<Py<PyAny>>,
}

#[pymethods]
impl PyRunSettings {
    #[new]
    #[pyo3(signature = (limits = None, seeds = None, active = None, subtasks = None, trace = None),
        text_signature = "(limits=None, seeds=None, active=None, subtasks=None, trace=None)")]
    pub fn new(
        py: Python<'_>,
        limits: Option<&Bound<'_, PyAny>>,
        seeds: Option<&Bound<'_, PyAny>>,
        active: Option<&Bound<'_, PyAny>>,
        subtasks: Option<&Bound<'_, PyAny>>,
        trace: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        enter(|| {
            let given = |value: Option<&Bound<'_, PyAny>>| {
                value.filter(|v| !v.is_none()).map(|v| v.clone().unbind())
            };
            let limits = match given(limits) {
                None => Py::new(py, PyEpisodeLimits::new_default())?,
                Some(l) => {
                    let what = "an EpisodeLimits or None";
                    typed_argument::<PyEpisodeLimits>(l.bind(py), "limits", what)?
                        .clone()
                        .unbind()
                }
            };
            let seeds_given = given(seeds);
            let seeds = seeds_given
                .as_ref()
                .map(|s| Seeds::given(s.bind(py), MAX_ENVS))
                .transpose()?;
            if let Some(a) = given(active) {
                let a = a.bind(py);
                let n = shape_of(a).filter(|s| s.len() == 1).map_or(0, |s| s[0]);
                readable::<bool>(a, "active", "bool", &[n])?;
            }
            if let Some(t) = given(trace) {
                dict_argument(t.bind(py), "trace", " of name -> array")?;
            }
            if let Some(s) = given(subtasks) {
                dict_argument(s.bind(py), "subtasks", " of name -> array")?;
            }
            Ok(Self {
                limits,
                seeds,
                seeds_given,
                active: given(active),
                subtasks: given(subtasks),
                trace: given(trace),
            })
        })
    }

    fn __repr__(&self, py: Python<'_>) -> String {
        let shown = |value: &Option<Py<PyAny>>| match value {
            None => "None".to_string(),
            Some(v) => format!("<{}>", class_name(v.bind(py))),
        };
        format!(
            "RunSettings(limits={}, seeds={}, active={}, subtasks={}, trace={})",
            self.limits.get().__repr__(),
            shown(&self.seeds_given),
            shown(&self.active),
            shown(&self.subtasks),
            shown(&self.trace)
        )
    }
}

impl PyEpisodeLimits {
    /// The limits of `EpisodeLimits()`: no step limit, no end at the goal or a crossing,
    /// autoreset.
    pub fn new_default() -> Self {
        Self {
            max_steps: 0,
            end_at_goal: false,
            end_at_crossing: false,
            autoreset: true,
        }
    }
}
