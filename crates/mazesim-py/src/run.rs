//! `BatchSimulator.run` for Python: the built-in controller named by its arguments, the optional
//! per-step output arrays (`trace`) borrowed and checked, the counters returned as numpy arrays.

use mazesim_core::control::AvoidCollision;
use mazesim_core::navigator::heading_hold::BlindRule;
use mazesim_core::navigator::{self, Discretiser, TabularPolicy};
use mazesim_core::{Controller, RunCounters, RunTrace};
use numpy::{PyArray1, PyReadwriteArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{shape_of, Flag, Real};
use crate::buffers::{copied, writable};
use crate::errors::{invalid, IntoPy};
use crate::guard::enter;

/// The names `run` accepts for its controller.
const CONTROLLERS: &str = "'braitenberg', 'avoid-collision', 'tabular' or 'random'";

/// The keywords `run` takes after its six positional arguments.
pub const KEYWORDS: &str = "seeds max_episode_steps end_at_goal end_at_crossing autoreset trace \
    table allowed_actions table_index epsilon threshold max_speed active hold_spins hold_heading \
    wheel_speed_limit subtasks";

/// The keys of `run`'s `trace` dict.
const TRACE_KEYS: [&str; 10] = [
    "observations",
    "poses",
    "colliding",
    "crossings",
    "wheel_speeds",
    "actions",
    "episode_ends",
    "subtasks",
    "phases",
    "subtask_ends",
];

/// The arguments of the tabular controller, as given.
pub struct TabularArgs<'a, 'py> {
    pub table: Option<&'a Bound<'py, PyAny>>,
    pub allowed_actions: Option<&'a Bound<'py, PyAny>>,
    pub table_index: Option<&'a Bound<'py, PyAny>>,
    pub epsilon: Real,
    pub hold_spins: Flag,
    pub hold_heading: Flag,
    pub wheel_speed_limit: Option<Real>,
}

/// The controller `name` with its arguments, for `n` environments.
pub fn controller(
    name: &str,
    n: usize,
    threshold: Real,
    max_speed: Real,
    tabular: TabularArgs<'_, '_>,
) -> PyResult<Controller> {
    Ok(match name {
        "braitenberg" => Controller::Braitenberg,
        "random" => Controller::RandomWheels,
        "avoid-collision" => Controller::AvoidCollision(
            AvoidCollision::new(threshold.value("threshold")?, max_speed.value("max_speed")?)
                .py()?,
        ),
        "tabular" => Controller::Tabular(Box::new(tabular_policy(n, tabular)?)),
        other => {
            return Err(invalid(format!(
                "expected controller to be {CONTROLLERS}, found {other:?}"
            )))
        }
    })
}

fn tabular_policy(n: usize, args: TabularArgs<'_, '_>) -> PyResult<TabularPolicy> {
    let (states, actions) = (navigator::NUM_STATES, navigator::NUM_ACTIONS);
    let table = args.table.ok_or_else(|| {
        invalid(format!(
            "the tabular controller needs table, a float64 array of shape ({states}, {actions}) \
             or (tables, {states}, {actions})"
        ))
    })?;
    let shape = shape_of(table).unwrap_or_default();
    let tables = if shape.len() == 3 { shape[0] } else { 1 };
    let table_shape: Vec<usize> = if shape.len() == 3 {
        vec![tables, states, actions]
    } else {
        vec![states, actions]
    };
    let values = copied::<f64>(table, "table", "float64", &table_shape)?;
    let allowed = args
        .allowed_actions
        .map(|a| {
            let shape: &[usize] = if table_shape.len() == 3 {
                &[tables, actions]
            } else {
                &[actions]
            };
            copied::<bool>(a, "allowed_actions", "bool", shape)
        })
        .transpose()?;
    let table_of_env = args
        .table_index
        .map(|t| {
            let index = copied::<i64>(t, "table_index", "int64", &[n])?;
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
                .collect::<PyResult<Vec<u32>>>()
        })
        .transpose()?;
    let epsilon = args.epsilon.value("epsilon")?;
    let hold_spins = args.hold_spins.value("hold_spins", "a bool")?;
    let speed_limit = args
        .wheel_speed_limit
        .map(|l| l.value("wheel_speed_limit"))
        .transpose()?;
    let blind = if args.hold_heading.value("hold_heading", "a bool")? {
        BlindRule::HoldHeading
    } else {
        BlindRule::Table
    };
    TabularPolicy::new(values, tables, allowed.as_deref(), table_of_env, epsilon)
        .py()?
        .with_held_spins(hold_spins)
        .with_blind_rule(blind)
        .with_speed_limit(speed_limit)
        .py()
}

/// The per-step output arrays of one call, borrowed.
#[derive(Default)]
pub struct Traces<'py> {
    observations: Option<PyReadwriteArrayDyn<'py, f32>>,
    poses: Option<PyReadwriteArrayDyn<'py, f32>>,
    colliding: Option<PyReadwriteArrayDyn<'py, bool>>,
    crossings: Option<PyReadwriteArrayDyn<'py, i32>>,
    wheel_speeds: Option<PyReadwriteArrayDyn<'py, f32>>,
    actions: Option<PyReadwriteArrayDyn<'py, i32>>,
    episode_ends: Option<PyReadwriteArrayDyn<'py, bool>>,
    subtasks: Option<PyReadwriteArrayDyn<'py, i32>>,
    phases: Option<PyReadwriteArrayDyn<'py, i32>>,
    subtask_ends: Option<PyReadwriteArrayDyn<'py, bool>>,
}

impl<'py> Traces<'py> {
    /// Borrows the arrays of `trace` (keys of `TRACE_KEYS`), each checked against its shape for
    /// `steps` steps of `n` environments with observations `width` wide.
    pub fn new(
        trace: Option<&Bound<'py, PyDict>>,
        steps: usize,
        n: usize,
        width: usize,
    ) -> PyResult<Self> {
        let mut t = Traces::default();
        let Some(trace) = trace else {
            return Ok(t);
        };
        for (key, value) in trace.iter() {
            let key: String = key.extract().map_err(|_| {
                invalid(format!(
                    "expected trace keys among {TRACE_KEYS:?}, found {key}"
                ))
            })?;
            let name = format!("trace[{key:?}]");
            match key.as_str() {
                "observations" => {
                    t.observations = Some(writable(&value, &name, "float32", &[steps, n, width])?)
                }
                "poses" => t.poses = Some(writable(&value, &name, "float32", &[steps, n, 3])?),
                "colliding" => t.colliding = Some(writable(&value, &name, "bool", &[steps, n])?),
                "crossings" => t.crossings = Some(writable(&value, &name, "int32", &[steps, n])?),
                "wheel_speeds" => {
                    t.wheel_speeds = Some(writable(&value, &name, "float32", &[steps, n, 2])?)
                }
                "actions" => t.actions = Some(writable(&value, &name, "int32", &[steps, n])?),
                "episode_ends" => {
                    t.episode_ends = Some(writable(&value, &name, "bool", &[steps, n])?)
                }
                "subtasks" => t.subtasks = Some(writable(&value, &name, "int32", &[steps, n])?),
                "phases" => t.phases = Some(writable(&value, &name, "int32", &[steps, n])?),
                "subtask_ends" => {
                    t.subtask_ends = Some(writable(&value, &name, "bool", &[steps, n])?)
                }
                other => {
                    return Err(invalid(format!(
                        "expected trace keys among {TRACE_KEYS:?}, found {other:?}"
                    )))
                }
            }
        }
        Ok(t)
    }

    /// The borrowed arrays as the core's slices.
    pub fn slices(&mut self) -> RunTrace<'_> {
        fn slice<'a, T: numpy::Element>(
            a: &'a mut Option<PyReadwriteArrayDyn<'_, T>>,
        ) -> Option<&'a mut [T]> {
            // `writable` has checked that the array is contiguous.
            a.as_mut().and_then(|a| a.as_slice_mut().ok())
        }
        RunTrace {
            observations: slice(&mut self.observations),
            poses: slice(&mut self.poses),
            colliding: slice(&mut self.colliding),
            crossings: slice(&mut self.crossings),
            wheel_speeds: slice(&mut self.wheel_speeds),
            actions: slice(&mut self.actions),
            episode_ends: slice(&mut self.episode_ends),
            subtasks: slice(&mut self.subtasks),
            phases: slice(&mut self.phases),
            subtask_ends: slice(&mut self.subtask_ends),
        }
    }
}

/// The counters of a run as a dict of (N,) uint64 arrays.
pub fn counters_dict<'py>(py: Python<'py>, counters: RunCounters) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    for (name, values) in [
        ("steps", counters.steps),
        ("steps_in_contact", counters.steps_in_contact),
        ("episodes_finished", counters.episodes_finished),
        ("goals_reached", counters.goals_reached),
        ("subtasks_done", counters.subtasks_done),
        ("subtasks_given_up", counters.subtasks_given_up),
    ] {
        dict.set_item(name, PyArray1::from_vec(py, values))?;
    }
    Ok(dict)
}

/// The lower level's state (Table 4.1 levels of the first six distance readings, in volts) of
/// each row of `observations`, an (N, W >= 6) float32 array: what the tabular controller of
/// `BatchSimulator.run` acts on.
#[pyfunction]
pub fn lower_level_states<'py>(
    py: Python<'py>,
    observations: &Bound<'py, PyAny>,
) -> PyResult<Bound<'py, PyArray1<i64>>> {
    enter(|| {
        let shape = shape_of(observations).unwrap_or_default();
        let sensors = navigator::NUM_SENSORS;
        let (rows, width) = match shape[..] {
            [rows, width] if width >= sensors => (rows, width),
            _ => {
                return Err(invalid(format!(
                    "expected observations of shape (N, >= {sensors}) with the Sharp volts \
                     first, found shape {shape:?}"
                )))
            }
        };
        let values = copied::<f32>(observations, "observations", "float32", &[rows, width])?;
        let discretiser = Discretiser::new().py()?;
        let states: Vec<i64> = values
            .chunks_exact(width)
            .map(|row| discretiser.state(row) as i64)
            .collect();
        Ok(PyArray1::from_vec(py, states))
    })
}
