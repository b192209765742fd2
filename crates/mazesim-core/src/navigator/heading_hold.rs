//! What Corridors and Corners does over its table's action ([`CorridorRules`]): keep a turn on
//! the spot rather than reverse it, and, in the blind state where no sensor sees a wall, act from
//! its table, drive straight on (`mazesim train --blind-forward`), or hold its heading on the
//! maze's grid (`--hold-heading`): finish a turn on the spot it began, steer gently back onto the
//! nearest multiple of 90 degrees while more than [`hold_tolerance`] off, and drive forward
//! within it. The multi-step call's tabular controller and the navigator's step both follow
//! these rules through [`CorridorRules::action`].

use std::f64::consts::FRAC_PI_2;

use super::discretiser::NUM_STATES;

/// The distance state in which no sensor sees a wall (every level 3).
pub const BLIND_STATE: usize = NUM_STATES - 1;
/// Forward (`00`) and the gentle right and left turns (`11`, `55`), as indices into the action
/// table.
const FORWARD: usize = 0;
const GENTLE_RIGHT: usize = 1;
const GENTLE_LEFT: usize = 5;
/// The turn on the spot to the right (`aa`).
pub const SPIN_RIGHT: usize = 9;
/// The turn on the spot to the left (`bb`).
pub const SPIN_LEFT: usize = 10;
const SPINS: [usize; 2] = [SPIN_RIGHT, SPIN_LEFT];

/// Largest heading error (radians) from the grid at which the rule drives straight on.
pub fn hold_tolerance() -> f64 {
    3.0_f64.to_radians()
}

/// Radians by which `yaw` lies left (positive) of the nearest multiple of 90 degrees (half-way
/// headings round to the even multiple).
pub fn grid_error(yaw: f64) -> f64 {
    yaw - (yaw / FRAC_PI_2).round_ties_even() * FRAC_PI_2
}

/// The hold rule's action for a robot heading `yaw` (its odometry's) whose last step took
/// `previous`.
pub fn hold_action(yaw: f64, previous: usize) -> usize {
    let error = grid_error(yaw);
    let tolerance = hold_tolerance();
    if error.abs() > tolerance && SPINS.contains(&previous) {
        previous
    } else if error > tolerance {
        GENTLE_RIGHT
    } else if error < -tolerance {
        GENTLE_LEFT
    } else {
        FORWARD
    }
}

/// What Corridors and Corners does in [`BLIND_STATE`].
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BlindRule {
    /// What its table says, like in every other state.
    #[default]
    Table,
    /// Forward.
    Forward,
    /// [`hold_action`].
    HoldHeading,
}

impl BlindRule {
    /// The action the rule takes instead of `chosen` for a robot of sub-task `subtask` in row
    /// `row` of its table, heading `yaw`, whose last step took `previous`.
    pub fn action(
        self,
        subtask: usize,
        row: usize,
        yaw: f64,
        previous: usize,
        chosen: usize,
    ) -> usize {
        if subtask != super::door::CORRIDOR || row != BLIND_STATE {
            return chosen;
        }
        match self {
            Self::Table => chosen,
            Self::Forward => FORWARD,
            Self::HoldHeading => hold_action(yaw, previous),
        }
    }
}

/// `chosen`, or the turn on the spot of the last step (`last_spin`, [`SPIN_RIGHT`] or
/// [`SPIN_LEFT`]) when `chosen` would reverse it.
pub fn keep_turn(chosen: usize, last_spin: Option<usize>) -> usize {
    match (last_spin, chosen) {
        (Some(SPIN_RIGHT), SPIN_LEFT) => SPIN_RIGHT,
        (Some(SPIN_LEFT), SPIN_RIGHT) => SPIN_LEFT,
        _ => chosen,
    }
}

/// The turn on the spot an action took, if it was one.
pub fn spin_of(action: usize) -> Option<usize> {
    SPINS.contains(&action).then_some(action)
}

/// What Corridors and Corners does over the action its table chose.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub struct CorridorRules {
    /// Keep a turn on the spot the last step took rather than turn back ([`keep_turn`]).
    pub keep_turns: bool,
    /// What it does in [`BLIND_STATE`].
    pub blind: BlindRule,
}

impl CorridorRules {
    /// The action of a robot running `subtask` whose table chose `chosen`, whose last step
    /// turned on the spot `last_spin` (see [`spin_of`]; `None` after a reset or any other
    /// action), heading `yaw`, in the distance state `state` (asked only in the blind rule's
    /// case). The door sub-tasks take `chosen` as it is.
    pub fn action(
        self,
        subtask: usize,
        chosen: usize,
        last_spin: Option<usize>,
        yaw: f64,
        state: impl FnOnce() -> usize,
    ) -> usize {
        if subtask != super::door::CORRIDOR {
            return chosen;
        }
        let action = if self.keep_turns {
            keep_turn(chosen, last_spin)
        } else {
            chosen
        };
        if self.blind == BlindRule::Table {
            return action;
        }
        // The blind rule reads only whether the last step turned on the spot, and which way.
        let previous = last_spin.unwrap_or(FORWARD);
        self.blind.action(subtask, state(), yaw, previous, action)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_rule_steers_back_drives_on_and_finishes_a_spin() {
        let deg = f64::to_radians;
        assert_eq!(hold_action(deg(0.0), FORWARD), FORWARD);
        assert_eq!(hold_action(deg(10.0), FORWARD), GENTLE_RIGHT);
        assert_eq!(hold_action(deg(-10.0), FORWARD), GENTLE_LEFT);
        assert_eq!(hold_action(deg(100.0), FORWARD), GENTLE_RIGHT);
        assert_eq!(hold_action(deg(30.0), SPINS[1]), SPINS[1]);
        assert_eq!(hold_action(deg(1.0), SPINS[0]), FORWARD);
        assert!((grid_error(deg(-175.0)) - deg(5.0)).abs() < 1e-12);
    }

    #[test]
    fn only_corridors_and_corners_in_the_blind_state_follows_a_rule() {
        let yaw = 0.3;
        assert_eq!(BlindRule::Table.action(0, BLIND_STATE, yaw, 0, 7), 7);
        assert_eq!(
            BlindRule::Forward.action(0, BLIND_STATE, yaw, 0, 7),
            FORWARD
        );
        assert_eq!(
            BlindRule::HoldHeading.action(0, BLIND_STATE, yaw, 0, 7),
            GENTLE_RIGHT
        );
        assert_eq!(BlindRule::HoldHeading.action(1, BLIND_STATE, yaw, 0, 7), 7);
        assert_eq!(
            BlindRule::HoldHeading.action(0, BLIND_STATE - 1, yaw, 0, 7),
            7
        );
    }
}
