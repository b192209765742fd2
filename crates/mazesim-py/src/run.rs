//! `BatchSimulator.run` for Python: the built-in controller from its name or settings and the
//! call's `RunSettings` (or, deprecated, from the keywords `run` took before them), the optional
//! per-step output arrays (`trace`) borrowed and checked, the counters returned as numpy arrays.

use mazesim_core::control::avoid_collision::EPUCK_MAX_SPEED;
use mazesim_core::control::AvoidCollision;
use mazesim_core::navigator::{self, Discretiser};
use mazesim_core::{Controller, RunCounters, RunTrace};
use numpy::{PyArray1, PyReadwriteArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{
    shape_of, type_name, typed_argument, unknown_key, warn_deprecated, Flag, IntArg, Keywords, Real,
};
use crate::buffers::{copied, shape_refusal, writable};
use crate::errors::{invalid, wrong_type, IntoPy};
use crate::guard::enter;
use crate::run_settings::{
    PyAvoidCollisionSettings, PyEpisodeLimits, PyRunSettings, PyTabularSettings,
};

/// What `run` accepts as its controller.
const CONTROLLERS: &str = "'braitenberg', 'avoid-collision' or 'random', an \
    AvoidCollisionSettings or a TabularSettings";

/// The keywords `run` took before its settings objects: still read, with a DeprecationWarning,
/// for one release.
const DEPRECATED_KEYWORDS: &str = "seeds max_episode_steps end_at_goal end_at_crossing autoreset \
    trace table allowed_actions table_index epsilon threshold max_speed active hold_spins \
    hold_heading wheel_speed_limit subtasks";

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

/// One `run` call's controller and settings, from its `controller` argument and keywords.
pub struct RunCall {
    pub controller: Controller,
    /// The wheel speed of avoid-collision (its default when another controller drives).
    pub max_speed: f64,
    pub settings: Py<PyRunSettings>,
}

impl RunCall {
    /// Reads `controller` (a name or a controller's settings) and `keywords` (`settings`, or
    /// the deprecated keywords of `run`, which warn).
    pub fn new(
        controller: &Bound<'_, PyAny>,
        keywords: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let py = controller.py();
        let deprecated = keywords
            .map(|k| unknown_key(k, "settings"))
            .transpose()?
            .flatten();
        if let Some(key) = deprecated {
            return Self::from_keywords(controller, keywords, &key);
        }
        let kw = Keywords::new(keywords, "run", "settings")?;
        let settings = match kw.object("settings")? {
            None => Py::new(py, PyRunSettings::new(py, None, None, None, None, None)?)?,
            Some(s) => typed_argument::<PyRunSettings>(&s, "settings", "a RunSettings or None")?
                .clone()
                .unbind(),
        };
        let (controller, max_speed) = controller_of(controller)?;
        Ok(Self {
            controller,
            max_speed,
            settings,
        })
    }

    /// The call of the keywords `run` took before its settings objects, after a
    /// DeprecationWarning that names `key`, one of them.
    fn from_keywords(
        controller: &Bound<'_, PyAny>,
        keywords: Option<&Bound<'_, PyDict>>,
        key: &str,
    ) -> PyResult<Self> {
        let py = controller.py();
        let known = format!("settings {DEPRECATED_KEYWORDS}");
        let kw = Keywords::new(keywords, "run", &known)?;
        if kw.object("settings")?.is_some() {
            return Err(invalid(format!(
                "expected either settings or run's former keywords, found settings and '{key}'"
            )));
        }
        let message = format!(
            "BatchSimulator.run's keyword '{key}' is deprecated and will be removed: pass \
             settings=RunSettings(...), with the controller's own settings (TabularSettings, \
             AvoidCollisionSettings) as the controller"
        );
        warn_deprecated(py, message)?;
        // Checked whatever the controller, so that a wrong one is never silently ignored.
        let avoid = PyAvoidCollisionSettings::new(
            kw.get("threshold", Real::Number(80.0))?,
            kw.get("max_speed", Real::Number(EPUCK_MAX_SPEED))?,
        )?;
        let name = controller.extract::<String>().ok();
        let (controller, max_speed) = match name.as_deref() {
            Some("tabular") => {
                let table = kw.object("table")?.ok_or_else(|| {
                    invalid(format!(
                        "the tabular controller needs table, a float64 array of shape ({}, {}) \
                         or (tables, {0}, {1})",
                        navigator::NUM_STATES,
                        navigator::NUM_ACTIONS
                    ))
                })?;
                let settings = PyTabularSettings::new(
                    &table,
                    kw.object("allowed_actions")?.as_ref(),
                    kw.object("table_index")?.as_ref(),
                    kw.get("epsilon", Real::Number(0.0))?,
                    kw.get("hold_spins", Flag::Value(false))?,
                    kw.get("hold_heading", Flag::Value(false))?,
                    kw.get("wheel_speed_limit", None)?,
                )?;
                let policy = Controller::Tabular(Box::new(settings.policy));
                (policy, avoid.rule.max_speed)
            }
            Some("avoid-collision") => {
                (Controller::AvoidCollision(avoid.rule), avoid.rule.max_speed)
            }
            Some(_) => (controller_of(controller)?.0, avoid.rule.max_speed),
            // A controller's settings with the former keywords for the rest of the call.
            None => controller_of(controller)?,
        };
        let flag = |key: &str, default| kw.get(key, Flag::Value(default));
        let limits = PyEpisodeLimits::new(
            kw.get("max_episode_steps", IntArg::ZERO)?,
            flag("end_at_goal", false)?,
            flag("end_at_crossing", false)?,
            flag("autoreset", true)?,
        )?;
        let limits = Py::new(py, limits)?.into_bound(py).into_any();
        let settings = PyRunSettings::new(
            py,
            Some(&limits),
            kw.object("seeds")?.as_ref(),
            kw.object("active")?.as_ref(),
            kw.object("subtasks")?.as_ref(),
            kw.object("trace")?.as_ref(),
        )?;
        Ok(Self {
            controller,
            max_speed,
            settings: Py::new(py, settings)?,
        })
    }
}

/// The controller `controller` names or sets, and the wheel speed of avoid-collision.
fn controller_of(controller: &Bound<'_, PyAny>) -> PyResult<(Controller, f64)> {
    if let Ok(tabular) = controller.cast::<PyTabularSettings>() {
        let policy = tabular.get().policy.clone();
        return Ok((Controller::Tabular(Box::new(policy)), EPUCK_MAX_SPEED));
    }
    if let Ok(avoid) = controller.cast::<PyAvoidCollisionSettings>() {
        let rule = avoid.get().rule;
        return Ok((Controller::AvoidCollision(rule), rule.max_speed));
    }
    let name = controller.extract::<String>().map_err(|_| {
        wrong_type(format!(
            "expected controller to be {CONTROLLERS}, found {}",
            type_name(controller)
        ))
    })?;
    let controller = match name.as_str() {
        "braitenberg" => Controller::Braitenberg,
        "random" => Controller::RandomWheels,
        "avoid-collision" => Controller::AvoidCollision(default_avoid_collision()?),
        "tabular" => {
            return Err(invalid(format!(
                "expected controller to be {CONTROLLERS}, found 'tabular': the tabular \
                 controller needs its tables, given as a TabularSettings"
            )))
        }
        other => {
            return Err(invalid(format!(
                "expected controller to be {CONTROLLERS}, found {:?}",
                other.chars().take(80).collect::<String>()
            )))
        }
    };
    Ok((controller, EPUCK_MAX_SPEED))
}

/// Avoid-collision with its defaults (the report's threshold 80, the e-puck's 6.28 rad/s).
fn default_avoid_collision() -> PyResult<AvoidCollision> {
    Ok(PyAvoidCollisionSettings::new(Real::Number(80.0), Real::Number(EPUCK_MAX_SPEED))?.rule)
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
                return Err(shape_refusal(
                    observations,
                    format!(
                        "expected observations of shape (N, >= {sensors}) with the Sharp volts \
                         first, found shape {shape:?}"
                    ),
                ))
            }
        };
        let values = copied::<f32>(observations, "observations", "float32", &[rows, width])?;
        let sensors_read = values
            .chunks_exact(width)
            .flat_map(|row| &row[..sensors])
            .map(|&v| f64::from(v));
        refuse_readings(sensors_read, false)?;
        let discretiser = Discretiser::new().py()?;
        let states: Vec<i64> = values
            .chunks_exact(width)
            .map(|row| discretiser.state(row) as i64)
            .collect();
        Ok(PyArray1::from_vec(py, states))
    })
}

/// The distances in cm and the levels `sharp_distances` returns.
type DistancesAndLevels<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<i64>>);

/// The distances in cm and the Table 4.1 levels of `readings`, a 1-D float64 array of Sharp
/// readings in volts (or, with `in_cm`, of distances in cm), by the core's discretiser: the one
/// home of `mazesim.learn.discretise.volts_to_cm` and `distance_levels`.
#[pyfunction]
#[pyo3(
    signature = (readings, in_cm=Flag::Value(false)),
    text_signature = "(readings, in_cm=False)"
)]
pub fn sharp_distances<'py>(
    py: Python<'py>,
    readings: &Bound<'py, PyAny>,
    in_cm: Flag,
) -> PyResult<DistancesAndLevels<'py>> {
    enter(|| {
        let in_cm = in_cm.value("in_cm", "a bool")?;
        let n = match shape_of(readings).unwrap_or_default()[..] {
            [n] => n,
            ref shape => {
                return Err(shape_refusal(
                    readings,
                    format!("expected readings of shape (N,), found shape {shape:?}"),
                ))
            }
        };
        let values = copied::<f64>(readings, "readings", "float64", &[n])?;
        refuse_readings(values.iter().copied(), in_cm)?;
        let cm: Vec<f64> = if in_cm {
            values
        } else {
            let discretiser = Discretiser::new().py()?;
            values.iter().map(|&v| discretiser.cm(v)).collect()
        };
        let levels = cm
            .iter()
            .map(|&d| navigator::discretiser::level_of_cm(d) as i64)
            .collect();
        Ok((PyArray1::from_vec(py, cm), PyArray1::from_vec(py, levels)))
    })
}

/// Refuses Sharp readings in volts below 0 V, infinite or not a number (the ranger reads none of
/// them), or distances in cm below 0 cm or not a number, quoting the one a refusal names: not a
/// number if one is, else the lowest.
fn refuse_readings(values: impl Iterator<Item = f64>, in_cm: bool) -> PyResult<()> {
    let refused = values
        .filter(|&v| !(v >= 0.0 && (in_cm || v < f64::INFINITY)))
        .fold(None, |quoted: Option<f64>, v| match quoted {
            Some(q) if q.is_nan() || q <= v => Some(q),
            _ => Some(v),
        });
    let Some(reading) = refused else {
        return Ok(());
    };
    let found = shown_volts(reading);
    Err(invalid(if in_cm {
        format!("expected distances of 0 cm or more (an infinite one is level 3), found {found} cm")
    } else {
        format!(
            "expected Sharp GP2Y0A41SK0F readings of 0 V or more, finite (its output never goes \
             below 0 V, as mazesim.sharp_volts_to_cm says), found {found} V"
        )
    }))
}

/// A refused reading as Python prints the float (`nan`, `inf`, `-0.5`), so that the core's
/// refusal quotes it as `learn.volts_to_cm`'s does.
fn shown_volts(value: f64) -> String {
    if value.is_nan() {
        "nan".to_owned()
    } else if value.is_infinite() {
        if value > 0.0 { "inf" } else { "-inf" }.to_owned()
    } else {
        format!("{value:?}")
    }
}
