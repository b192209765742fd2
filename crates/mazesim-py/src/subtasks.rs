//! The navigator's sub-task states for `BatchSimulator.run`: the arrays of
//! `Navigator.subtask_arrays` (a dict of name -> array) borrowed writable, read
//! into the core's states and written back after the call. A tracker whose phases count the
//! distance holds `heading phase + 3 * distance bin`; the core keeps the heading phase alone
//! (it computes the distance bin from the pose), which is what is written back.

use mazesim_core::navigator::door::{Phases, SubTaskState, MAX_PHASES};
use mazesim_core::Controller;
use numpy::PyReadwriteArrayDyn;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::dict_argument;
use crate::buffers::writable;
use crate::errors::invalid;

/// The keys of `run`'s `subtasks` dict.
const KEYS: [&str; 7] = [
    "subtask",
    "start",
    "previous_yaw",
    "heading_change",
    "steps",
    "phase",
    "turn_point",
];

/// The sub-task arrays of one call, borrowed.
pub struct SubTaskArrays<'py> {
    subtask: PyReadwriteArrayDyn<'py, i64>,
    start: PyReadwriteArrayDyn<'py, f64>,
    previous_yaw: PyReadwriteArrayDyn<'py, f64>,
    heading_change: PyReadwriteArrayDyn<'py, f64>,
    steps: PyReadwriteArrayDyn<'py, i64>,
    phase: PyReadwriteArrayDyn<'py, i64>,
    turn_point: PyReadwriteArrayDyn<'py, f64>,
}

/// The array under `key` of `dict`, writable, of `dtype` and `shape`.
fn item<'py, T: numpy::Element>(
    dict: &Bound<'py, PyDict>,
    key: &str,
    dtype: &str,
    shape: &[usize],
) -> PyResult<PyReadwriteArrayDyn<'py, T>> {
    let value = dict.get_item(key)?.ok_or_else(|| {
        invalid(format!(
            "expected subtasks to hold the arrays {KEYS:?}, found no {key:?}"
        ))
    })?;
    writable(&value, &format!("subtasks[{key:?}]"), dtype, shape)
}

/// `values` as a slice (`writable` has checked that the array is contiguous).
fn slice<'a, T: numpy::Element>(values: &'a PyReadwriteArrayDyn<'_, T>) -> &'a [T] {
    values.as_slice().unwrap_or_default()
}

impl<'py> SubTaskArrays<'py> {
    /// Borrows the arrays of `subtasks` for `n` environments, each checked against its dtype
    /// and shape; unknown keys are refused.
    pub fn new(subtasks: &Bound<'py, PyAny>, n: usize) -> PyResult<Self> {
        let dict = dict_argument(subtasks, "subtasks", " of name -> array")?;
        for key in dict.keys() {
            let known = key
                .extract::<String>()
                .is_ok_and(|k| KEYS.contains(&k.as_str()));
            if !known {
                return Err(invalid(format!(
                    "expected subtasks keys among {KEYS:?}, found {key}"
                )));
            }
        }
        Ok(Self {
            subtask: item(dict, "subtask", "int64", &[n])?,
            start: item(dict, "start", "float64", &[n, 3])?,
            previous_yaw: item(dict, "previous_yaw", "float64", &[n])?,
            heading_change: item(dict, "heading_change", "float64", &[n])?,
            steps: item(dict, "steps", "int64", &[n])?,
            phase: item(dict, "phase", "int64", &[n])?,
            turn_point: item(dict, "turn_point", "float64", &[n, 2])?,
        })
    }

    /// The core's states for `controller` (checked by the core), or an error naming the first
    /// negative count.
    pub fn states(&self, controller: &Controller) -> PyResult<Vec<SubTaskState>> {
        self.read(match controller {
            Controller::Tabular(policy) => policy.phases() == Some(Phases::HeadingAndDistance),
            _ => false,
        })
    }

    /// The states, each phase taken modulo the heading phases when they `counts_distance`.
    pub fn read(&self, counts_distance: bool) -> PyResult<Vec<SubTaskState>> {
        let (subtask, steps, phase) =
            (slice(&self.subtask), slice(&self.steps), slice(&self.phase));
        let (start, turn_point) = (slice(&self.start), slice(&self.turn_point));
        let (previous_yaw, heading_change) =
            (slice(&self.previous_yaw), slice(&self.heading_change));
        let count = |name: &str, value: i64, env: usize| {
            usize::try_from(value).map_err(|_| {
                invalid(format!(
                    "expected subtasks[{name:?}] values of at least 0, found {value} for \
                     environment {env}"
                ))
            })
        };
        (0..subtask.len())
            .map(|i| {
                Ok(SubTaskState {
                    subtask: count("subtask", subtask[i], i)?,
                    start: [start[3 * i], start[3 * i + 1], start[3 * i + 2]],
                    previous_yaw: previous_yaw[i],
                    heading_change: heading_change[i],
                    steps: count("steps", steps[i], i)? as u64,
                    phase: count("phase", phase[i], i).map(|phase| {
                        if counts_distance {
                            phase % MAX_PHASES
                        } else {
                            phase
                        }
                    })?,
                    turn_point: [turn_point[2 * i], turn_point[2 * i + 1]],
                })
            })
            .collect()
    }

    /// Writes `states` back into the arrays.
    pub fn store(&mut self, states: &[SubTaskState]) {
        fill(&mut self.subtask, states, |s| [s.subtask as i64]);
        fill(&mut self.start, states, |s| s.start);
        fill(&mut self.previous_yaw, states, |s| [s.previous_yaw]);
        fill(&mut self.heading_change, states, |s| [s.heading_change]);
        // A count past i64::MAX (only from a count handed in near it) stays at the largest.
        fill(&mut self.steps, states, |s| {
            [i64::try_from(s.steps).unwrap_or(i64::MAX)]
        });
        fill(&mut self.phase, states, |s| [s.phase as i64]);
        fill(&mut self.turn_point, states, |s| s.turn_point);
    }
}

/// Writes `field` of each state as its row of `array` (`W` values a row).
fn fill<T: numpy::Element + Copy, const W: usize>(
    array: &mut PyReadwriteArrayDyn<'_, T>,
    states: &[SubTaskState],
    field: impl Fn(&SubTaskState) -> [T; W],
) {
    let rows = array.as_slice_mut().unwrap_or_default();
    for (row, state) in rows.chunks_exact_mut(W).zip(states) {
        row.copy_from_slice(&field(state));
    }
}
