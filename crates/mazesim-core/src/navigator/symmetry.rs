//! The left-right mirror image of the lower level, which training learns every transition from
//! twice. The `seed` robot is symmetric about its centre line: mirroring a situation swaps the
//! left and right sensors (and left-front and right-front), the wheels of every action (`11` and
//! `55`, `aa` and `bb`; `00` and `99` stay) and the right and left turns. So every transition
//! `(s, a, r, s')` of a sub-task is also a transition `(m(s), m(a), r, m(s'))` of its mirror
//! sub-task, in the mirrored maze; it doubles the experience and keeps "Right turn on a door" and
//! "Left turn on a door" each other's mirror image.

use super::discretiser::{NUM_LEVELS, NUM_SENSORS, NUM_STATES};
use super::door::{self, Phases, MAX_PHASES, NUM_SUBTASKS};
use super::tabular::{NUM_ACTIONS, WHEEL_SPEED_FRACTIONS};
use crate::error::{Error, Result};

/// The sensor each sensor's reading comes from in the mirror image, in the report's order
/// (front, back, left, right, left-front, right-front).
const SWAPPED_SENSOR: [usize; NUM_SENSORS] = [0, 1, 3, 2, 5, 4];
/// The mirror image of each sub-task: the turns swap.
const MIRRORED_SUBTASK: [usize; NUM_SUBTASKS] =
    [door::CORRIDOR, door::LEFT, door::RIGHT, door::FORWARD];

/// The mirror image of every row of every sub-task's table, of every action and of every
/// sub-task.
///
/// A row is a distance state and a phase (`distance_state + NUM_STATES * phase`), and each part
/// has its own mirror image, so the rows' mirror images are held as those of the 4096 distance
/// states and of each sub-task's phases: a few kilobytes that stay in cache, where a list of every
/// row's would take megabytes for the door sub-tasks that count the distance.
#[derive(Debug, Clone, PartialEq)]
pub struct Symmetry {
    /// The mirror image of each of the [`NUM_STATES`] distance states.
    pub distance_states: Vec<u16>,
    /// `(NUM_SUBTASKS, phases)`: the mirror image of each phase of each sub-task's table.
    pub phases: Vec<usize>,
    /// The mirror image of each action: its wheel speeds swapped.
    pub actions: [usize; NUM_ACTIONS],
    /// The mirror image of each sub-task.
    pub subtasks: [usize; NUM_SUBTASKS],
}

impl Symmetry {
    /// The mirror image of tables whose door sub-tasks count `phases`.
    pub fn new(phases: Phases) -> Self {
        let count = phases.count();
        Self {
            distance_states: (0..NUM_STATES)
                .map(|state| mirrored_distance_state(state) as u16)
                .collect(),
            phases: (0..NUM_SUBTASKS)
                .flat_map(|subtask| (0..count).map(move |phase| mirrored_phase(subtask, phase)))
                .collect(),
            actions: std::array::from_fn(mirrored_action),
            subtasks: MIRRORED_SUBTASK,
        }
    }

    /// Phases of each sub-task's table.
    pub fn phase_count(&self) -> usize {
        self.phases.len() / NUM_SUBTASKS
    }

    /// The mirror image of row `row` of `subtask`'s table (row and sub-task in range).
    pub fn row(&self, subtask: usize, row: usize) -> usize {
        let phase = self.phases[subtask * self.phase_count() + row / NUM_STATES];
        usize::from(self.distance_states[row % NUM_STATES]) + NUM_STATES * phase
    }

    /// Checks that it mirrors rows of `phase_count` phases into them.
    pub fn check(&self, phase_count: usize) -> Result<()> {
        if self.distance_states.len() != NUM_STATES
            || self.phases.len() != NUM_SUBTASKS * phase_count
        {
            return Err(Error::InvalidArgument(format!(
                "expected the mirror images of {NUM_STATES} distance states and of \
                 {NUM_SUBTASKS} x {phase_count} phases, found {} and {}",
                self.distance_states.len(),
                self.phases.len()
            )));
        }
        let state = self.distance_states.iter().map(|&s| usize::from(s));
        if let Some(s) = state.clone().find(|&s| s >= NUM_STATES) {
            return Err(Error::InvalidArgument(format!(
                "expected mirrored distance states in [0, {NUM_STATES}), found {s}"
            )));
        }
        if let Some(p) = self.phases.iter().find(|&&p| p >= phase_count) {
            return Err(Error::InvalidArgument(format!(
                "expected mirrored phases in [0, {phase_count}), found {p}"
            )));
        }
        Ok(())
    }
}

/// The distance state with the left and right sensors swapped.
pub fn mirrored_distance_state(state: usize) -> usize {
    let level = |sensor: usize| state / NUM_LEVELS.pow(sensor as u32) % NUM_LEVELS;
    (0..NUM_SENSORS).rev().fold(0, |mirrored, i| {
        mirrored * NUM_LEVELS + level(SWAPPED_SENSOR[i])
    })
}

/// The mirror image of phase `phase` of `subtask`'s table. A turn's phase counts its progress
/// towards its own side, so it stays; the heading phase of "Going forward on a door" tells right
/// of straight (0) from left of it (2), so those two swap; a distance bin (`heading_phase + 3 *
/// bin`) stays.
fn mirrored_phase(subtask: usize, phase: usize) -> usize {
    if subtask == door::FORWARD {
        let (heading, bin) = (phase % MAX_PHASES, phase / MAX_PHASES);
        2 - heading + MAX_PHASES * bin
    } else {
        phase
    }
}

/// The action whose wheel speeds are those of `action` swapped.
fn mirrored_action(action: usize) -> usize {
    let [left, right] = WHEEL_SPEED_FRACTIONS[action];
    WHEEL_SPEED_FRACTIONS
        .iter()
        .position(|&speeds| speeds == [right, left])
        .expect("every primitive action has a mirror image among them")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The mirror image of row `row` (`distance_state + 4096 * phase`) of `subtask`'s table, by
    /// its definition (`Symmetry` keeps them worked out).
    fn mirrored_row(subtask: usize, row: usize) -> usize {
        mirrored_distance_state(row % NUM_STATES)
            + NUM_STATES * mirrored_phase(subtask, row / NUM_STATES)
    }

    #[test]
    fn mirroring_twice_is_the_identity_and_swaps_sides() {
        // Front 0, back 1, left 2, right 3, left-front 0, right-front 3.
        let state = 4 + 2 * 16 + 3 * 64 + 3 * 1024;
        assert_eq!(
            mirrored_distance_state(state),
            4 + 3 * 16 + 2 * 64 + 3 * 256
        );
        for phases in [Phases::Heading, Phases::HeadingAndDistance] {
            let symmetry = Symmetry::new(phases);
            let rows = phases.rows();
            symmetry.check(phases.count()).unwrap();
            for subtask in 0..NUM_SUBTASKS {
                for row in (0..rows).step_by(37) {
                    let once = symmetry.row(subtask, row);
                    assert_eq!(once, mirrored_row(subtask, row));
                    assert!(once < rows);
                    assert_eq!(symmetry.row(subtask, once), row);
                }
            }
            assert_eq!(symmetry.actions, [0, 5, 6, 7, 8, 1, 2, 3, 4, 10, 9, 11]);
        }
        // Going forward, left of straight, in distance bin 4: right of straight, same bin.
        assert_eq!(
            mirrored_row(door::FORWARD, NUM_STATES * (2 + 3 * 4)),
            NUM_STATES * 12
        );
        assert_eq!(mirrored_row(door::RIGHT, NUM_STATES * 2), NUM_STATES * 2);
    }
}
