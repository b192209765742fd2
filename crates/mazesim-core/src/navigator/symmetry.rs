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

/// The sensor each sensor's reading comes from in the mirror image, in the report's order
/// (front, back, left, right, left-front, right-front).
const SWAPPED_SENSOR: [usize; NUM_SENSORS] = [0, 1, 3, 2, 5, 4];
/// The mirror image of each sub-task: the turns swap.
const MIRRORED_SUBTASK: [usize; NUM_SUBTASKS] =
    [door::CORRIDOR, door::LEFT, door::RIGHT, door::FORWARD];

/// The mirror image of every row of every sub-task's table, of every action and of every
/// sub-task.
#[derive(Debug, Clone, PartialEq)]
pub struct Symmetry {
    /// `(NUM_SUBTASKS, rows)`: the mirror image of each row of each sub-task's table.
    pub states: Vec<usize>,
    /// The mirror image of each action: its wheel speeds swapped.
    pub actions: [usize; NUM_ACTIONS],
    /// The mirror image of each sub-task.
    pub subtasks: [usize; NUM_SUBTASKS],
}

impl Symmetry {
    /// The mirror image of tables whose door sub-tasks count `phases`.
    pub fn new(phases: Phases) -> Self {
        let rows = phases.rows();
        let states = (0..NUM_SUBTASKS)
            .flat_map(|subtask| (0..rows).map(move |row| mirrored_row(subtask, row)))
            .collect();
        Self {
            states,
            actions: std::array::from_fn(mirrored_action),
            subtasks: MIRRORED_SUBTASK,
        }
    }
}

/// The distance state with the left and right sensors swapped.
pub fn mirrored_distance_state(state: usize) -> usize {
    let level = |sensor: usize| state / NUM_LEVELS.pow(sensor as u32) % NUM_LEVELS;
    (0..NUM_SENSORS).rev().fold(0, |mirrored, i| {
        mirrored * NUM_LEVELS + level(SWAPPED_SENSOR[i])
    })
}

/// The mirror image of row `row` (`distance_state + 4096 * phase`) of `subtask`'s table. A
/// turn's phase counts its progress towards its own side, so it stays; the heading phase of
/// "Going forward on a door" tells right of straight (0) from left of it (2), so those two swap;
/// a distance bin (`heading_phase + 3 * bin`) stays.
pub fn mirrored_row(subtask: usize, row: usize) -> usize {
    let mut phase = row / NUM_STATES;
    if subtask == door::FORWARD {
        let (heading, bin) = (phase % MAX_PHASES, phase / MAX_PHASES);
        phase = 2 - heading + MAX_PHASES * bin;
    }
    mirrored_distance_state(row % NUM_STATES) + NUM_STATES * phase
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
            for subtask in 0..NUM_SUBTASKS {
                for row in (0..rows).step_by(37) {
                    let once = symmetry.states[subtask * rows + row];
                    assert!(once < rows);
                    assert_eq!(symmetry.states[subtask * rows + once], row);
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
