//! What stays the same from round to round of the lower level's training in the core, as one
//! typed, frozen value checked when it is made (`LowerRoundSettings`: the learning's numbers,
//! the worlds, each robot's sub-task and the allowed actions; the tables' mirror symmetry is the
//! core's own), and the arguments of `train_lower_round` read from it and the round's own arrays. The keywords
//! `train_lower_round` took before it still work, with a `DeprecationWarning`, for one release.

use mazesim_core::limits::MAX_ENVS;
use mazesim_core::navigator::door::NUM_SUBTASKS;
use mazesim_core::navigator::NUM_ACTIONS;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{dict_argument, shape_of, typed_argument, unknown_key};
use crate::args::{warn_deprecated, Keywords};
use crate::buffers::{copied, shape_refusal};
use crate::errors::invalid;
use crate::guard::enter;
use crate::lower::round_settings;
use crate::world::world_argument;

/// The keywords `train_lower_round` took before its settings, beside its round's arrays.
const FORMER_KEYWORDS: &str = "worlds role allowed settings starts explore \
    random_action q visits";

/// The arrays of one round of `train_lower_round`, by name, in its order.
pub type RoundArguments<'a, 'py> = [(&'static str, Option<&'a Bound<'py, PyAny>>); 5];

/// The settings of rounds of the lower level's training in the core that stay the same from
/// round to round but for the exploration rate: the learning's numbers (`learning`, a dict of
/// `gamma`, `epsilon`, the learning rate, the rewards, the door sub-tasks' bounds, and perhaps
/// their `phases` and the `blind` rule), the `worlds` the robots' starts index, each robot's
/// sub-task (`role`, (N,) int64) and the `allowed` actions of
/// each sub-task ((4, 12) bool). The arrays are the caller's own, checked when made and again by
/// each round.
#[pyclass(name = "LowerRoundSettings", module = "mazesim._core", frozen)]
pub struct PyLowerRoundSettings {
    learning: Py<PyAny>,
    worlds: Py<PyAny>,
    role: Py<PyAny>,
    allowed: Py<PyAny>,
    robots: usize,
    world_count: usize,
    gamma: f64,
    epsilon: f64,
}

#[pymethods]
impl PyLowerRoundSettings {
    #[new]
    #[pyo3(signature = (learning, worlds, role, allowed),
        text_signature = "(learning, worlds, role, allowed)")]
    pub fn new(
        learning: &Bound<'_, PyAny>,
        worlds: &Bound<'_, PyAny>,
        role: &Bound<'_, PyAny>,
        allowed: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        enter(|| {
            dict_argument(learning, "learning", " of name -> number or name")?;
            let numbers = round_settings(learning)?;
            let given = crate::world::world_items(worlds, "mazesim.World", MAX_ENVS)?;
            for world in &given {
                world_argument(world, "each of worlds")?;
            }
            let robots = match shape_of(role).unwrap_or_default()[..] {
                [n] if n > 0 => n,
                _ => {
                    return Err(shape_refusal(
                        role,
                        format!(
                            "expected role to be an (N,) int64 array with N >= 1, found shape {:?}",
                            shape_of(role).unwrap_or_default()
                        ),
                    ))
                }
            };
            copied::<i64>(role, "role", "int64", &[robots])?;
            copied::<bool>(allowed, "allowed", "bool", &[NUM_SUBTASKS, NUM_ACTIONS])?;
            Ok(Self {
                learning: learning.clone().unbind(),
                worlds: worlds.clone().unbind(),
                role: role.clone().unbind(),
                allowed: allowed.clone().unbind(),
                robots,
                world_count: given.len(),
                gamma: numbers.gamma,
                epsilon: numbers.epsilon,
            })
        })
    }

    /// The learning's numbers, as given.
    #[getter]
    fn learning(&self, py: Python<'_>) -> Py<PyAny> {
        self.learning.clone_ref(py)
    }

    /// The worlds the robots' starts index.
    #[getter]
    fn worlds(&self, py: Python<'_>) -> Py<PyAny> {
        self.worlds.clone_ref(py)
    }

    /// (N,) int64, each robot's sub-task.
    #[getter]
    fn role(&self, py: Python<'_>) -> Py<PyAny> {
        self.role.clone_ref(py)
    }

    /// (4, 12) bool, the actions each sub-task may take.
    #[getter]
    fn allowed(&self, py: Python<'_>) -> Py<PyAny> {
        self.allowed.clone_ref(py)
    }

    fn __repr__(&self) -> String {
        format!(
            "LowerRoundSettings(robots={}, worlds={}, gamma={:?}, epsilon={:?})",
            self.robots, self.world_count, self.gamma, self.epsilon
        )
    }
}

/// The keywords of one `train_lower_round` call as the round reads them: from `settings` (a
/// `LowerRoundSettings`) and the round's `arrays`, or (deprecated, with a warning) from the
/// keywords it took before (`former`, the round's arrays among them).
pub fn round_keywords<'py>(
    py: Python<'py>,
    settings: Option<&Bound<'py, PyAny>>,
    arrays: RoundArguments<'_, 'py>,
    former: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let round = PyDict::new(py);
    for (key, value) in arrays {
        if let Some(value) = value {
            round.set_item(key, value)?;
        }
    }
    let first = former.map(|f| unknown_key(f, "")).transpose()?.flatten();
    if let (Some(former), Some(key)) = (former, first) {
        Keywords::new(Some(former), "train_lower_round", FORMER_KEYWORDS)?;
        if settings.is_some_and(|s| s.cast::<PyLowerRoundSettings>().is_ok()) {
            return Err(invalid(format!(
                "expected either a LowerRoundSettings or train_lower_round's former keywords, \
                 found both (and '{key}')"
            )));
        }
        warn_deprecated(
            py,
            format!(
                "train_lower_round's keyword '{key}' is deprecated and will be removed: pass \
                 train_lower_round(crews, LowerRoundSettings(...), starts, explore, \
                 random_action, q, visits)"
            ),
        )?;
        round.update(former.as_mapping())?;
        if let Some(settings) = settings {
            round.set_item("settings", settings)?;
        }
        return Ok(round);
    }
    if let Some((missing, _)) = arrays.iter().find(|(_, value)| value.is_none()) {
        return Err(invalid(format!(
            "train_lower_round() missing required argument: '{missing}'"
        )));
    }
    let settings = settings.ok_or_else(|| {
        invalid("train_lower_round() missing required argument: 'settings'".to_string())
    })?;
    let what = "a LowerRoundSettings";
    let settings = typed_argument::<PyLowerRoundSettings>(settings, "settings", what)?;
    let s = settings.get();
    round.set_item("settings", s.learning.bind(py))?;
    round.set_item("worlds", s.worlds.bind(py))?;
    round.set_item("role", s.role.bind(py))?;
    round.set_item("allowed", s.allowed.bind(py))?;
    Ok(round)
}
