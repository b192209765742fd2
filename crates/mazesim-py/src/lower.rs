//! `train_lower_round` and `q_batch_update` for Python: the arrays of a round of the lower
//! level's Q-learning borrowed and checked, its crews (batches of robots, each with its buffers,
//! wheel speeds and readings map) and settings read from dicts, its counts returned as a dict.

use std::sync::Arc;

use mazesim_core::limits::MAX_ENVS;
use mazesim_core::navigator::door::{Phases, NUM_SUBTASKS};
use mazesim_core::navigator::heading_hold::BlindRule;
use mazesim_core::navigator::qlearning::{LearningRate, QTable, Transition};
use mazesim_core::navigator::seed_volts::{Interpolation, SeedVolts, SensorDistance};
use mazesim_core::navigator::symmetry::Symmetry;
use mazesim_core::navigator::training::{
    self, Crew, LowerRound, Rewards, RoundCounts, RoundSettings, StartQueues, PATH_WIDTH,
};
use mazesim_core::navigator::{NUM_ACTIONS, NUM_SENSORS};
use mazesim_core::World;
use numpy::{PyReadonlyArrayDyn, PyReadwriteArrayDyn};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{bounded_items, dict_argument, type_name, typed_argument, unknown_key};
use crate::args::{Keywords, Real};
use crate::batch::{Borrowed, PyBatch};
use crate::buffers::{copied, readable, shape_refusal, writable};
use crate::errors::{invalid, wrong_type, IntoPy};
use crate::guard::{enter, enter_detached};
use crate::lower_settings::round_keywords;
use crate::world::world_argument;

/// The keywords of `train_lower_round` after its crews: the round's arrays, then its settings.
const KEYWORDS: &str = "worlds role starts explore random_action q visits allowed \
    settings";

/// The keys of each crew of `train_lower_round` (`readings` may be left out: the seed robot's
/// own volts).
const CREW: &str = "simulator observations poses colliding crossings world_of_env wheel_speeds \
    members readings";

/// The keys of a crew's `readings`: a map of its distance readings into the seed robot's volts.
const READINGS: &str = "directions readings distances seen_up_to far table_distances table_volts";

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
        wrong_type(format!(
            "expected settings[{key:?}] to be one of {known:?}, found {}",
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
    number_of(dict, "settings", key)
}

/// `dict[key]` (`name` naming the dict), a finite number.
fn number_of(dict: &Bound<'_, PyDict>, name: &str, key: &str) -> PyResult<f64> {
    let value = entry(dict, name, key)?;
    let number = value.extract::<f64>().map_err(|_| {
        wrong_type(format!(
            "expected {name}[{key:?}] to be a number, found {}",
            type_name(&value)
        ))
    })?;
    if !number.is_finite() {
        return Err(invalid(format!(
            "expected {name}[{key:?}] to be finite, found {number}"
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

/// `obj` as a dict holding no key but those of `known` (names separated by white space); `name`
/// names the argument and `holding` says what it maps.
fn closed_dict<'a, 'py>(
    obj: &'a Bound<'py, PyAny>,
    name: &str,
    holding: &str,
    known: &str,
) -> PyResult<&'a Bound<'py, PyDict>> {
    let dict = dict_argument(obj, name, holding)?;
    match unknown_key(dict, known)? {
        Some(key) => Err(invalid(format!(
            "expected {name} to hold only {known:?}, found {key:?}"
        ))),
        None => Ok(dict),
    }
}

/// Reads and checks a round's settings.
pub fn round_settings(settings: &Bound<'_, PyAny>) -> PyResult<RoundSettings> {
    let dict = closed_dict(settings, "settings", "", SETTINGS)?;
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
    /// The mirror image of the tables' phases.
    symmetry: Symmetry,
}

fn shape_of(obj: &Bound<'_, PyAny>) -> Vec<usize> {
    crate::args::shape_of(obj).unwrap_or_default()
}

impl<'py> RoundArrays<'py> {
    /// Borrows and checks the arrays of a round of `n` robots (its tables' rows as many as `q`
    /// has: the round checks them against its phases).
    pub fn new(n: usize, round: &Keywords<'py>) -> PyResult<Self> {
        let worlds = &round.required("worlds")?;
        let role = &round.required("role")?;
        let starts = &round.required("starts")?;
        let explore = &round.required("explore")?;
        let random_action = &round.required("random_action")?;
        let q = &round.required("q")?;
        let visits = &round.required("visits")?;
        let allowed = &round.required("allowed")?;
        let worlds = crate::world::world_items(worlds, "mazesim.World", MAX_ENVS)?
            .iter()
            .map(|w| world_argument(w, "each of worlds"))
            .collect::<PyResult<Vec<_>>>()?;
        let starts = dict_argument(starts, "starts", "")?;
        let start_world = entry(starts, "starts", "world")?;
        let expected = format!("starts['world'] to be an (N={n}, K) int64 array with K >= 1");
        let per_env = free_axis(&start_world, (0, n), 1, &expected)?;
        let expected = format!("explore to be a (steps, N={n}) float64 array");
        let steps = free_axis(explore, (1, n), 0, &expected)?;
        // Tables of either phase count (the round checks them against its own); any other
        // shape is refused below as one of heading phases.
        let phases = match shape_of(q).get(1) {
            Some(&rows) if rows == Phases::HeadingAndDistance.rows() => Phases::HeadingAndDistance,
            _ => Phases::Heading,
        };
        let rows = phases.rows();
        let table_shape = [NUM_SUBTASKS, rows, NUM_ACTIONS];
        let flags = copied::<bool>(allowed, "allowed", "bool", &[NUM_SUBTASKS, NUM_ACTIONS])?;
        let mut allowed = [[false; NUM_ACTIONS]; NUM_SUBTASKS];
        for (row, chunk) in allowed.iter_mut().zip(flags.chunks_exact(NUM_ACTIONS)) {
            row.copy_from_slice(chunk);
        }
        Ok(Self {
            worlds,
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
            symmetry: Symmetry::new(phases),
        })
    }

    /// The round over the borrowed arrays.
    pub fn round(&mut self, settings: RoundSettings) -> LowerRound<'_> {
        // `readable`/`writable` checked that every array is contiguous.
        LowerRound {
            settings,
            worlds: &self.worlds,
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
            symmetry: &self.symmetry,
        }
    }
}

/// The length of the free axis of `obj`, a 2-D array whose axis `fixed.0` is `fixed.1` long, if
/// it is at least `least`; else an error saying what was `expected` and the shape found.
fn free_axis(
    obj: &Bound<'_, PyAny>,
    fixed: (usize, usize),
    least: usize,
    expected: &str,
) -> PyResult<usize> {
    let shape = shape_of(obj);
    match shape[..] {
        [a, b] if [a, b][fixed.0] == fixed.1 && [b, a][fixed.0] >= least => Ok([b, a][fixed.0]),
        _ => Err(shape_refusal(
            obj,
            format!("expected {expected}, found shape {shape:?}"),
        )),
    }
}

/// A (`rows`, `columns`) float64 array's rows, `columns` taken from the array.
fn float_rows(obj: &Bound<'_, PyAny>, name: &str, rows: usize) -> PyResult<Vec<Vec<f64>>> {
    let expected = format!("{name} to be a ({rows}, K) float64 array");
    let columns = free_axis(obj, (0, rows), 0, &expected)?;
    let values = copied::<f64>(obj, name, "float64", &[rows, columns])?;
    Ok(values.chunks(columns.max(1)).map(<[f64]>::to_vec).collect())
}

/// A crew's map of its `width` distance readings into the seed robot's volts
/// (`mazesim.transfer.readings.SeedReadings.tables`).
fn seed_volts(obj: &Bound<'_, PyAny>, width: usize) -> PyResult<SeedVolts> {
    let holding = " of the tables of a map into seed volts";
    let dict = closed_dict(obj, "readings", holding, READINGS)?;
    let item = |key: &str| entry(dict, "readings", key);
    let taken = copied::<bool>(
        &item("directions")?,
        "readings['directions']",
        "bool",
        &[NUM_SENSORS, width],
    )?;
    let mut directions: [Vec<usize>; NUM_SENSORS] = Default::default();
    for (sensors, row) in directions.iter_mut().zip(taken.chunks(width.max(1))) {
        *sensors = (0..width).filter(|&s| row[s]).collect();
    }
    let readings = float_rows(&item("readings")?, "readings['readings']", width)?;
    let distances = float_rows(&item("distances")?, "readings['distances']", width)?;
    let seen = copied::<f64>(
        &item("seen_up_to")?,
        "readings['seen_up_to']",
        "float64",
        &[width],
    )?;
    let sensors = readings
        .into_iter()
        .zip(distances)
        .zip(seen)
        .map(|((xs, ys), seen_up_to)| {
            Ok(SensorDistance {
                distance: Interpolation::new(xs, ys, "a sensor's readings and distances").py()?,
                seen_up_to,
            })
        })
        .collect::<PyResult<Vec<_>>>()?;
    let table = |key: &str| -> PyResult<Vec<f64>> {
        let value = item(key)?;
        let length = shape_of(&value).first().copied().unwrap_or(0);
        copied::<f64>(&value, &format!("readings[{key:?}]"), "float64", &[length])
    };
    let volts = Interpolation::new(
        table("table_distances")?,
        table("table_volts")?,
        "the seed volts table",
    )
    .py()?;
    SeedVolts::new(
        directions,
        sensors,
        number_of(dict, "readings", "far")?,
        volts,
    )
    .py()
}

/// One crew of `train_lower_round`, read and its buffers borrowed.
struct CrewArgs<'py> {
    simulator: Bound<'py, PyBatch>,
    buffers: Borrowed<'py>,
    world_of_env: PyReadwriteArrayDyn<'py, i64>,
    wheel_speeds: [[f32; 2]; NUM_ACTIONS],
    members: Vec<usize>,
    volts: Option<SeedVolts>,
}

impl<'py> CrewArgs<'py> {
    fn new(obj: &Bound<'py, PyAny>, round_size: usize) -> PyResult<Self> {
        let holding = " of a batch's robots and buffers";
        let dict = closed_dict(obj, "each of crews", holding, CREW)?;
        let item = |key: &str| entry(dict, "each of crews", key);
        let simulator = item("simulator")?;
        let what = "a mazesim.BatchSimulator";
        let simulator = typed_argument::<PyBatch>(&simulator, "crews' 'simulator'", what)?;
        let batch = simulator.get();
        batch.one_robot(
            "train_lower_round",
            "its crews drive one robot per environment; train on a BatchSimulator of the \
             same worlds with one robot each (a [start] instead of [[robots]])",
        )?;
        let n = batch.len();
        let buffers = Borrowed::new(
            batch,
            &item("observations")?,
            &item("poses")?,
            &item("colliding")?,
            &item("crossings")?,
        )?;
        let speeds = copied::<f32>(
            &item("wheel_speeds")?,
            "wheel_speeds",
            "float32",
            &[NUM_ACTIONS, 2],
        )?;
        if let Some(s) = speeds.iter().find(|s| !s.is_finite()) {
            return Err(invalid(format!("expected finite wheel speeds, found {s}")));
        }
        let mut wheel_speeds = [[0f32; 2]; NUM_ACTIONS];
        for (row, chunk) in wheel_speeds.iter_mut().zip(speeds.chunks_exact(2)) {
            row.copy_from_slice(chunk);
        }
        let members = copied::<i64>(&item("members")?, "members", "int64", &[n])?;
        let members = members
            .into_iter()
            .map(|m| {
                usize::try_from(m)
                    .ok()
                    .filter(|&m| m < round_size)
                    .ok_or_else(|| {
                        invalid(format!("expected members in [0, {round_size}), found {m}"))
                    })
            })
            .collect::<PyResult<Vec<_>>>()?;
        let volts = match dict.get_item("readings")?.filter(|v| !v.is_none()) {
            Some(readings) => Some(seed_volts(&readings, batch.distance_sensor_count())?),
            None => None,
        };
        Ok(Self {
            world_of_env: writable(&item("world_of_env")?, "world_of_env", "int64", &[n])?,
            simulator: simulator.clone(),
            buffers,
            wheel_speeds,
            members,
            volts,
        })
    }
}

/// Runs one round of the lower level's Q-learning in the core (see `mazesim-core`'s
/// `navigator::training`) with the robots of `crews`: each a dict of a `BatchSimulator` of one robot
/// per environment, its four buffers, its `world_of_env`, the (12, 2) float32 `wheel_speeds` of
/// its actions, the `members` (its robots' numbers in the round) and, for robots that do not read
/// the seed robot's volts, the `readings` map into them. `settings` (a `LowerRoundSettings`)
/// holds what stays the same from round to round; `explore` ((steps, N) float64) sets the
/// round's length; `q` and `visits` and each `world_of_env` are updated in place, the buffers
/// hold the last step. Returns the round's counts as a dict. The GIL is released while it runs.
#[pyfunction]
#[pyo3(signature = (crews, settings = None, starts = None, explore = None, random_action = None, q = None, visits = None, **former),
    text_signature = "(crews, settings, starts, explore, random_action, q, visits)")]
pub fn train_lower_round<'py>(
    crews: &Bound<'py, PyAny>,
    settings: Option<&Bound<'py, PyAny>>,
    starts: Option<&Bound<'py, PyAny>>,
    explore: Option<&Bound<'py, PyAny>>,
    random_action: Option<&Bound<'py, PyAny>>,
    q: Option<&Bound<'py, PyAny>>,
    visits: Option<&Bound<'py, PyAny>>,
    former: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let py = crews.py();
    enter(|| {
        let arrays = [
            ("starts", starts),
            ("explore", explore),
            ("random_action", random_action),
            ("q", q),
            ("visits", visits),
        ];
        let round = round_keywords(py, settings, arrays, former)?;
        let round = Keywords::new(Some(&round), "train_lower_round", KEYWORDS)?;
        let settings = round_settings(&round.required("settings")?)?;
        let role = round.required("role")?;
        let n = match shape_of(&role)[..] {
            [n] if n > 0 => n,
            _ => {
                return Err(shape_refusal(
                    &role,
                    format!(
                        "expected role to be an (N,) int64 array with N >= 1, found shape {:?}",
                        shape_of(&role)
                    ),
                ))
            }
        };
        let items = bounded_items(crews, "crews", "dicts of a batch's robots", MAX_ENVS)?;
        let mut parts: Vec<CrewArgs<'py>> = Vec::with_capacity(items.len());
        for (k, crew) in items.iter().enumerate() {
            // Each crew's own simulator, checked before its buffers are borrowed.
            let simulator = crew.get_item("simulator").ok();
            if let Some(simulator) = &simulator {
                if parts.iter().any(|other| other.simulator.is(simulator)) {
                    return Err(invalid(format!(
                        "expected a different BatchSimulator in each crew, found crew {k}'s \
                         twice"
                    )));
                }
            }
            parts.push(CrewArgs::new(crew, n)?);
        }
        let mut arrays = RoundArrays::new(n, &round)?;
        let round = arrays.round(settings);
        let owners: Vec<Bound<'py, PyBatch>> = parts.iter().map(|p| p.simulator.clone()).collect();
        let simulators: Vec<&PyBatch> = owners.iter().map(Bound::get).collect();
        let mut sides = Vec::with_capacity(parts.len());
        for part in &mut parts {
            let CrewArgs {
                buffers,
                world_of_env,
                wheel_speeds,
                members,
                volts,
                ..
            } = part;
            let world_of_env = world_of_env
                .as_slice_mut()
                .map_err(|_| invalid("expected world_of_env to be a contiguous array".into()))?;
            sides.push((
                buffers.outputs()?,
                world_of_env,
                *wheel_speeds,
                members.clone(),
                volts.as_ref(),
            ));
        }
        let counts = enter_detached(py, move || {
            // Locks taken in one order (by address), so two rounds never wait for each other.
            let mut order: Vec<usize> = (0..simulators.len()).collect();
            order.sort_by_key(|&k| std::ptr::from_ref(simulators[k]) as usize);
            let mut held: Vec<_> = (0..simulators.len()).map(|_| None).collect();
            for k in order {
                held[k] = Some(simulators[k].inner.wait()?);
            }
            let mut crews: Vec<Crew<'_>> = held
                .iter_mut()
                .flatten()
                .zip(sides)
                .map(
                    |(batch, (out, world_of_env, wheel_speeds, members, volts))| Crew {
                        batch,
                        out,
                        members,
                        world_of_env,
                        wheel_speeds,
                        volts,
                    },
                )
                .collect();
            training::train_lower_round(round, &mut crews)
        })?;
        counts_dict(py, &counts)
    })
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
            return Err(shape_refusal(
                q,
                format!(
                    "expected q to be a (states, actions) float64 array, found shape {shape:?}"
                ),
            ));
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
