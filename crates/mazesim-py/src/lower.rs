//! `BatchSimulator.train_lower_round` and `q_batch_update` for Python: the arrays of a round of
//! the lower level's Q-learning borrowed and checked, its settings read from a dict, its counts
//! returned as a dict.

use std::sync::Arc;

use mazesim_core::control::door::{Phases, NUM_SUBTASKS};
use mazesim_core::control::heading_hold::BlindRule;
use mazesim_core::control::tabular::NUM_ACTIONS;
use mazesim_core::limits::MAX_ENVS;
use mazesim_core::lower_training::{
    LowerRound, Rewards, RoundCounts, RoundSettings, StartQueues, Symmetry, PATH_WIDTH,
};
use mazesim_core::qlearning::{LearningRate, QTable, Transition};
use mazesim_core::World;
use numpy::{PyReadonlyArrayDyn, PyReadwriteArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{bounded_items, dict_argument, type_name, unknown_key, Keywords, Real};
use crate::buffers::{copied, readable, writable};
use crate::errors::{invalid, IntoPy};
use crate::world::world_argument;

/// The keywords of `train_lower_round` after its four buffers: the round's arrays, then its
/// settings.
pub const KEYWORDS: &str = "worlds world_of_env role starts explore random_action q visits \
    symmetry allowed wheel_speeds settings";

/// The keys of a round's `settings` dict (`phases` and `blind` may be left out: heading phases,
/// the table in the blind state).
const SETTINGS: &str = "gamma epsilon decision_steps corridor_episode_steps rate_initial \
    rate_floor rate_power progress_reward collision_penalty corridor_step_reward door_step_reward \
    heading_reward door_success_reward door_failure_reward door_path_exit success_past_centre \
    success_across phases blind";

/// The names a round's `settings["phases"]` and `settings["blind"]` may take.
const PHASES: [(&str, Phases); 2] = [
    ("heading", Phases::Heading),
    ("heading_and_distance", Phases::HeadingAndDistance),
];
const BLIND_RULES: [(&str, BlindRule); 3] = [
    ("table", BlindRule::Table),
    ("forward", BlindRule::Forward),
    ("hold_heading", BlindRule::HoldHeading),
];

/// `settings[key]`, one of `names` (`default` when absent).
fn named<T: Copy>(
    dict: &Bound<'_, PyDict>,
    key: &str,
    names: &[(&str, T)],
    default: T,
) -> PyResult<T> {
    let Some(value) = dict.get_item(key)? else {
        return Ok(default);
    };
    let known: Vec<&str> = names.iter().map(|(name, _)| *name).collect();
    let name = value.extract::<String>().map_err(|_| {
        invalid(format!(
            "expected settings[{key:?}] to be one of {known:?}, found a {}",
            type_name(&value)
        ))
    })?;
    names
        .iter()
        .find(|(known, _)| *known == name)
        .map(|&(_, item)| item)
        .ok_or_else(|| {
            invalid(format!(
                "expected settings[{key:?}] to be one of {known:?}, found {name:?}"
            ))
        })
}

fn entry<'py>(dict: &Bound<'py, PyDict>, name: &str, key: &str) -> PyResult<Bound<'py, PyAny>> {
    dict.get_item(key)?.ok_or_else(|| {
        invalid(format!(
            "expected {name} to hold {key:?}, found no such key"
        ))
    })
}

fn number(dict: &Bound<'_, PyDict>, key: &str) -> PyResult<f64> {
    let value = entry(dict, "settings", key)?;
    let number = value.extract::<f64>().map_err(|_| {
        invalid(format!(
            "expected settings[{key:?}] to be a number, found a {}",
            type_name(&value)
        ))
    })?;
    if !number.is_finite() {
        return Err(invalid(format!(
            "expected settings[{key:?}] to be finite, found {number}"
        )));
    }
    Ok(number)
}

fn steps_setting(dict: &Bound<'_, PyDict>, key: &str) -> PyResult<u64> {
    let value = number(dict, key)?;
    if value < 1.0 || value.fract() != 0.0 || value > 1e12 {
        return Err(invalid(format!(
            "expected settings[{key:?}] to be a whole number of steps from 1, found {value}"
        )));
    }
    Ok(value as u64)
}

/// Reads and checks a round's settings.
pub fn round_settings(settings: &Bound<'_, PyAny>) -> PyResult<RoundSettings> {
    let dict = dict_argument(settings, "settings", "")?;
    if let Some(key) = unknown_key(dict, SETTINGS)? {
        return Err(invalid(format!(
            "expected settings to hold only {SETTINGS:?}, found {key:?}"
        )));
    }
    let gamma = number(dict, "gamma")?;
    let epsilon = number(dict, "epsilon")?;
    if !(0.0..=1.0).contains(&gamma) || !(0.0..=1.0).contains(&epsilon) {
        return Err(invalid(format!(
            "expected gamma and epsilon in [0, 1], found {gamma} and {epsilon}"
        )));
    }
    Ok(RoundSettings {
        gamma,
        epsilon,
        decision_steps: steps_setting(dict, "decision_steps")?,
        corridor_episode_steps: steps_setting(dict, "corridor_episode_steps")?,
        rate: LearningRate::new(
            number(dict, "rate_initial")?,
            number(dict, "rate_floor")?,
            number(dict, "rate_power")?,
        )
        .py()?,
        rewards: Rewards {
            progress: number(dict, "progress_reward")?,
            collision: number(dict, "collision_penalty")?,
            corridor_step: number(dict, "corridor_step_reward")?,
            door_step: number(dict, "door_step_reward")?,
            heading: number(dict, "heading_reward")?,
            door_success: number(dict, "door_success_reward")?,
            door_failure: number(dict, "door_failure_reward")?,
        },
        door_path_exit: number(dict, "door_path_exit")?,
        success_past_centre: number(dict, "success_past_centre")?,
        success_across: number(dict, "success_across")?,
        phases: named(dict, "phases", &PHASES, Phases::Heading)?,
        blind: named(dict, "blind", &BLIND_RULES, BlindRule::Table)?,
    })
}

/// The arrays of a round, borrowed (the inputs that are not copied, and the outputs).
pub struct RoundArrays<'py> {
    worlds: Vec<Arc<World>>,
    world_of_env: PyReadwriteArrayDyn<'py, i64>,
    role: Vec<i64>,
    per_env: usize,
    start_world: PyReadonlyArrayDyn<'py, i64>,
    start_pose: PyReadonlyArrayDyn<'py, f64>,
    start_seed: PyReadonlyArrayDyn<'py, u64>,
    start_path: PyReadonlyArrayDyn<'py, f64>,
    explore: PyReadonlyArrayDyn<'py, f64>,
    random_action: PyReadonlyArrayDyn<'py, i64>,
    q: PyReadwriteArrayDyn<'py, f64>,
    visits: PyReadwriteArrayDyn<'py, i64>,
    allowed: [[bool; NUM_ACTIONS]; NUM_SUBTASKS],
    mirrored_states: Vec<i64>,
    mirrored_action: [usize; NUM_ACTIONS],
    mirrored_subtask: [usize; NUM_SUBTASKS],
    wheel_speeds: [[f32; 2]; NUM_ACTIONS],
}

fn shape_of(obj: &Bound<'_, PyAny>) -> Vec<usize> {
    crate::args::shape_of(obj).unwrap_or_default()
}

fn indices<const K: usize>(values: Vec<i64>, name: &str, below: usize) -> PyResult<[usize; K]> {
    let mut out = [0; K];
    for (slot, &v) in out.iter_mut().zip(&values) {
        if v < 0 || v as usize >= below {
            return Err(invalid(format!(
                "expected {name} in [0, {below}), found {v}"
            )));
        }
        *slot = v as usize;
    }
    Ok(out)
}

impl<'py> RoundArrays<'py> {
    /// Borrows and checks the arrays of a round of `n` robots (its tables' rows as many as `q`
    /// has: the round checks them against its phases).
    pub fn new(n: usize, round: &Keywords<'py>) -> PyResult<Self> {
        let worlds = &round.required("worlds")?;
        let world_of_env = &round.required("world_of_env")?;
        let role = &round.required("role")?;
        let starts = &round.required("starts")?;
        let explore = &round.required("explore")?;
        let random_action = &round.required("random_action")?;
        let q = &round.required("q")?;
        let visits = &round.required("visits")?;
        let symmetry = &round.required("symmetry")?;
        let allowed = &round.required("allowed")?;
        let wheel_speeds = &round.required("wheel_speeds")?;
        let worlds = bounded_items(worlds, "worlds", "mazesim.World", MAX_ENVS)?
            .iter()
            .map(|w| world_argument(w, "each of worlds"))
            .collect::<PyResult<Vec<_>>>()?;
        let starts = dict_argument(starts, "starts", "")?;
        let start_world = entry(starts, "starts", "world")?;
        let per_env = match shape_of(&start_world)[..] {
            [rows, k] if rows == n && k > 0 => k,
            _ => {
                return Err(invalid(format!(
                    "expected starts['world'] to be an (N={n}, K) int64 array with K >= 1, found \
                     shape {:?}",
                    shape_of(&start_world)
                )))
            }
        };
        let steps = match shape_of(explore)[..] {
            [steps, rows] if rows == n => steps,
            _ => {
                return Err(invalid(format!(
                    "expected explore to be a (steps, N={n}) float64 array, found shape {:?}",
                    shape_of(explore)
                )))
            }
        };
        // Tables of either phase count (the round checks them against its own); any other
        // shape is refused below as one of heading phases.
        let rows = match shape_of(q).get(1) {
            Some(&rows) if rows == Phases::HeadingAndDistance.rows() => rows,
            _ => Phases::Heading.rows(),
        };
        let table_shape = [NUM_SUBTASKS, rows, NUM_ACTIONS];
        let symmetry = dict_argument(symmetry, "symmetry", "")?;
        let flags = copied::<bool>(allowed, "allowed", "bool", &[NUM_SUBTASKS, NUM_ACTIONS])?;
        let mut allowed = [[false; NUM_ACTIONS]; NUM_SUBTASKS];
        for (row, chunk) in allowed.iter_mut().zip(flags.chunks_exact(NUM_ACTIONS)) {
            row.copy_from_slice(chunk);
        }
        let speeds = copied::<f32>(wheel_speeds, "wheel_speeds", "float32", &[NUM_ACTIONS, 2])?;
        let mut wheel_speeds = [[0f32; 2]; NUM_ACTIONS];
        for (row, chunk) in wheel_speeds.iter_mut().zip(speeds.chunks_exact(2)) {
            row.copy_from_slice(chunk);
        }
        if let Some(s) = speeds.iter().find(|s| !s.is_finite()) {
            return Err(invalid(format!("expected finite wheel speeds, found {s}")));
        }
        let item = |key: &str| entry(symmetry, "symmetry", key);
        Ok(Self {
            worlds,
            world_of_env: writable(world_of_env, "world_of_env", "int64", &[n])?,
            role: copied::<i64>(role, "role", "int64", &[n])?,
            per_env,
            start_world: readable(&start_world, "starts['world']", "int64", &[n, per_env])?,
            start_pose: readable(
                &entry(starts, "starts", "pose")?,
                "starts['pose']",
                "float64",
                &[n, per_env, 3],
            )?,
            start_seed: readable(
                &entry(starts, "starts", "seed")?,
                "starts['seed']",
                "uint64",
                &[n, per_env],
            )?,
            start_path: readable(
                &entry(starts, "starts", "path")?,
                "starts['path']",
                "float64",
                &[n, per_env, PATH_WIDTH],
            )?,
            explore: readable(explore, "explore", "float64", &[steps, n])?,
            random_action: readable(random_action, "random_action", "int64", &[steps, n])?,
            q: writable(q, "q", "float64", &table_shape)?,
            visits: writable(visits, "visits", "int64", &table_shape)?,
            allowed,
            mirrored_states: copied::<i64>(
                &item("states")?,
                "symmetry['states']",
                "int64",
                &[NUM_SUBTASKS, rows],
            )?,
            mirrored_action: indices(
                copied::<i64>(
                    &item("actions")?,
                    "symmetry['actions']",
                    "int64",
                    &[NUM_ACTIONS],
                )?,
                "mirrored actions",
                NUM_ACTIONS,
            )?,
            mirrored_subtask: indices(
                copied::<i64>(
                    &item("subtasks")?,
                    "symmetry['subtasks']",
                    "int64",
                    &[NUM_SUBTASKS],
                )?,
                "mirrored sub-tasks",
                NUM_SUBTASKS,
            )?,
            wheel_speeds,
        })
    }

    /// The round over the borrowed arrays.
    pub fn round(&mut self, settings: RoundSettings) -> LowerRound<'_> {
        // `readable`/`writable` checked that every array is contiguous.
        LowerRound {
            settings,
            worlds: &self.worlds,
            world_of_env: self.world_of_env.as_slice_mut().unwrap_or_default(),
            role: &self.role,
            starts: StartQueues {
                per_env: self.per_env,
                world: self.start_world.as_slice().unwrap_or_default(),
                pose: self.start_pose.as_slice().unwrap_or_default(),
                seed: self.start_seed.as_slice().unwrap_or_default(),
                path: self.start_path.as_slice().unwrap_or_default(),
            },
            explore: self.explore.as_slice().unwrap_or_default(),
            random_action: self.random_action.as_slice().unwrap_or_default(),
            q: self.q.as_slice_mut().unwrap_or_default(),
            visits: self.visits.as_slice_mut().unwrap_or_default(),
            allowed: self.allowed,
            symmetry: Symmetry {
                states: &self.mirrored_states,
                actions: self.mirrored_action,
                subtasks: self.mirrored_subtask,
            },
            wheel_speeds: self.wheel_speeds,
        }
    }
}

/// A round's counts as a dict of plain values.
pub fn counts_dict<'py>(py: Python<'py>, counts: &RoundCounts) -> PyResult<Bound<'py, PyDict>> {
    let dict = PyDict::new(py);
    dict.set_item("success", counts.success.to_vec())?;
    dict.set_item("failure", counts.failure.to_vec())?;
    dict.set_item("cut", counts.cut.to_vec())?;
    dict.set_item("corridor_metres", counts.corridor_metres)?;
    dict.set_item("contact_steps", counts.contact_steps)?;
    Ok(dict)
}

/// The learning rate `(initial, floor, power)` of `q_batch_update`.
fn learning_rate(rate: &Bound<'_, PyAny>) -> PyResult<LearningRate> {
    let items = bounded_items(rate, "rate", "real numbers (initial, floor, power)", 3)?;
    let [initial, floor, power] = &items[..] else {
        return Err(invalid(format!(
            "expected rate to be (initial, floor, power), found {} items",
            items.len()
        )));
    };
    let value = |item: &Bound<'_, PyAny>, name: &str| item.extract::<Real>()?.value(name);
    LearningRate::new(
        value(initial, "rate's initial")?,
        value(floor, "rate's floor")?,
        value(power, "rate's power")?,
    )
    .py()
}

/// Applies N Q-learning updates to one table in place (`mazesim.learn.qlearning.batch_update`):
/// the targets read the table as it was before the call, then the updates apply one after the
/// other in the given order, each at its pair's learning rate
/// `max(floor, initial * (visits + 1) ** -power)`. `transitions` holds the N `states`,
/// `actions`, `rewards`, `next_states` and `bootstrap` factors; `rate` is
/// `(initial, floor, power)`.
#[pyfunction]
#[pyo3(signature = (q, visits, transitions, allowed, rate))]
pub fn q_batch_update(
    q: &Bound<'_, PyAny>,
    visits: &Bound<'_, PyAny>,
    transitions: &Bound<'_, PyAny>,
    allowed: &Bound<'_, PyAny>,
    rate: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let py = q.py();
    crate::guard::enter(|| {
        let shape = shape_of(q);
        let [rows, columns] = shape[..] else {
            return Err(invalid(format!(
                "expected q to be a (states, actions) float64 array, found shape {shape:?}"
            )));
        };
        let rate = learning_rate(rate)?;
        let transitions = dict_argument(transitions, "transitions", "")?;
        let item = |key: &str| entry(transitions, "transitions", key);
        let (states, actions, rewards) = (&item("states")?, &item("actions")?, &item("rewards")?);
        let (next_states, bootstrap) = (&item("next_states")?, &item("bootstrap")?);
        let m = shape_of(states).first().copied().unwrap_or(0);
        let states = copied::<i64>(states, "states", "int64", &[m])?;
        let actions = copied::<i64>(actions, "actions", "int64", &[m])?;
        let rewards = copied::<f64>(rewards, "rewards", "float64", &[m])?;
        let next_states = copied::<i64>(next_states, "next_states", "int64", &[m])?;
        let bootstrap = copied::<f64>(bootstrap, "bootstrap", "float64", &[m])?;
        let allowed = copied::<bool>(allowed, "allowed", "bool", &[columns])?;
        // A next state is read only where its bootstrap is not 0.
        let read = |name: &str, i: usize| name != "next_states" || bootstrap[i] != 0.0;
        for (name, values) in [
            ("states", &states),
            ("actions", &actions),
            ("next_states", &next_states),
        ] {
            if let Some(at) = (0..m).find(|&i| values[i] < 0 && read(name, i)) {
                return Err(invalid(format!(
                    "expected {name} of 0 or more, found {} at transition {at}",
                    values[at]
                )));
            }
        }
        let index = |v: i64| v.max(0) as usize;
        let batch: Vec<Transition> = (0..m)
            .map(|i| Transition {
                state: index(states[i]),
                action: index(actions[i]),
                reward: rewards[i],
                next_state: index(next_states[i]),
                bootstrap: bootstrap[i],
            })
            .collect();
        let mut values = writable::<f64>(q, "q", "float64", &[rows, columns])?;
        let mut counts = writable::<i64>(visits, "visits", "int64", &[rows, columns])?;
        let mut table = QTable {
            values: values.as_slice_mut().unwrap_or_default(),
            visits: counts.as_slice_mut().unwrap_or_default(),
            actions: columns,
        };
        table.check(&batch, &allowed).py()?;
        py.detach(|| table.update(&batch, &allowed, &rate, &mut Vec::new()));
        Ok(())
    })
}
