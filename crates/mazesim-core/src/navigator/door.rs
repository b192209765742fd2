//! The door sub-tasks of the navigator's lower level (`mazesim.learn.subtasks`): the phase a
//! robot is in, from the heading change its odometry saw since the sub-task began, and the end
//! of the sub-task, from that heading change and the displacement, in f64 (the wrap is numpy's
//! floor remainder, as the navigator was trained with; `tests/navigator_oracle.py` keeps a numpy
//! reference that the tests check it against bit for bit).

use std::f64::consts::PI;

use super::discretiser::NUM_STATES;
use crate::error::{Error, Result};

/// Corridors and Corners: one phase, never ends by itself.
pub const CORRIDOR: usize = 0;
/// Right turn on a door.
pub const RIGHT: usize = 1;
/// Left turn on a door.
pub const LEFT: usize = 2;
/// Going forward on a door.
pub const FORWARD: usize = 3;
/// The sub-tasks.
pub const NUM_SUBTASKS: usize = 4;
/// Phases of each sub-task.
pub const NUM_PHASES: [usize; NUM_SUBTASKS] = [1, 3, 3, 3];
/// The most phases of any sub-task: the tables of a navigator's lower level are stacked as
/// `NUM_SUBTASKS x MAX_PHASES` tables of the distance state, table `subtask * MAX_PHASES + phase`.
pub const MAX_PHASES: usize = 3;
/// The stacked tables of the four sub-tasks' phases.
pub const NUM_TABLES: usize = NUM_SUBTASKS * MAX_PHASES;
/// The heading change each sub-task aims at (radians, counter-clockwise positive).
pub const TARGET_TURN: [f64; NUM_SUBTASKS] = [0.0, -PI / 2.0, PI / 2.0, 0.0];
/// Control steps after which a door sub-task gives up.
pub const MAX_DOOR_STEPS: u64 = 200;
/// Metres driven towards the new heading after entering phase 2, to end a turn.
pub const TURN_EXIT_DISTANCE: f64 = 0.08;
/// Metres ahead of its start at which "Going forward on a door" ends.
pub const FORWARD_DISTANCE: f64 = 0.40;
/// Edges (metres ahead of the sub-task's start, along the heading it began with) of the door
/// sub-tasks' distance bins, when their phases count the distance ([`Phases::HeadingAndDistance`]).
pub const DISTANCE_EDGES: [f64; 5] = [0.12, 0.18, 0.22, 0.26, 0.30];

/// What a door sub-task's phase counts (`mazesim.learn.subtasks.phase_counts`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Phases {
    /// The heading change alone: [`MAX_PHASES`] phases.
    #[default]
    Heading,
    /// The heading phase plus [`MAX_PHASES`] times the distance bin ([`DISTANCE_EDGES`]) of how
    /// far the odometry has carried the robot ahead of the sub-task's start: 18 phases
    /// (`mazesim train --door-distance`).
    HeadingAndDistance,
}

impl Phases {
    /// The most phases of a sub-task.
    pub const fn count(self) -> usize {
        match self {
            Self::Heading => MAX_PHASES,
            Self::HeadingAndDistance => MAX_PHASES * (DISTANCE_EDGES.len() + 1),
        }
    }

    /// Rows of each sub-task's table: the distance state of each phase.
    pub const fn rows(self) -> usize {
        self.count() * NUM_STATES
    }

    /// The phase of `task` at `pose` (the pose its last update saw).
    pub fn phase(self, task: &SubTaskState, pose: [f32; 3]) -> usize {
        self.phase_at(task, pose.map(f64::from))
    }

    /// [`Phases::phase`] at a pose of f64 odometry.
    pub fn phase_at(self, task: &SubTaskState, pose: [f64; 3]) -> usize {
        match self {
            Self::Heading => task.phase,
            Self::HeadingAndDistance if task.subtask == CORRIDOR => 0,
            Self::HeadingAndDistance => {
                let [x, y, _] = pose;
                let [x0, y0, yaw0] = task.start;
                let driven = (x - x0) * yaw0.cos() + (y - y0) * yaw0.sin();
                let bin = DISTANCE_EDGES
                    .iter()
                    .filter(|&&edge| edge <= driven)
                    .count();
                task.phase + MAX_PHASES * bin
            }
        }
    }

    /// The row of its sub-task's table a robot running `task` acts from at `pose`:
    /// `distance_state + 4096 * phase`.
    pub fn table_row(self, task: &SubTaskState, pose: [f32; 3], distance_state: usize) -> usize {
        distance_state + NUM_STATES * self.phase(task, pose)
    }
}

/// Turn towards its side (radians) at which a turn enters phase 1 and phase 2.
fn turn_phase_angles() -> [f64; 2] {
    [30.0_f64.to_radians(), 60.0_f64.to_radians()]
}

/// Heading change (radians) beyond which "Going forward on a door" is in phase 0 or 2.
fn forward_phase_angle() -> f64 {
    5.0_f64.to_radians()
}

/// Largest heading error (radians) at which a door sub-task may end.
fn heading_tolerance() -> f64 {
    10.0_f64.to_radians()
}

/// Heading change (radians) after which a door sub-task gives up.
fn give_up_angle() -> f64 {
    150.0_f64.to_radians()
}

/// `angle` wrapped to [-pi, pi) as `(angle + pi) % (2 pi) - pi` with numpy's floor remainder
/// (the sign of the divisor).
pub fn wrap(angle: f64) -> f64 {
    let divisor = 2.0 * PI;
    let mut rest = (angle + PI) % divisor;
    if rest != 0.0 {
        if (divisor < 0.0) != (rest < 0.0) {
            rest += divisor;
        }
    } else {
        rest = 0.0_f64.copysign(divisor);
    }
    rest - PI
}

/// The phase of `subtask` after a heading change of `change` radians
/// (`heading_phases` of `tests/navigator_oracle.py`).
pub fn heading_phase(subtask: usize, change: f64) -> usize {
    if subtask == CORRIDOR {
        return 0;
    }
    let turn = TARGET_TURN[subtask];
    if turn != 0.0 {
        let towards = change * turn.signum();
        turn_phase_angles()
            .iter()
            .filter(|&&edge| edge <= towards)
            .count()
    } else {
        let angle = forward_phase_angle();
        1 + usize::from(change > angle) - usize::from(change < -angle)
    }
}

/// How a step left a sub-task.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SubTaskEnd {
    /// It goes on.
    Running,
    /// A door sub-task reached its end.
    Done,
    /// A door sub-task gave up: it ran out of steps or turned round.
    GaveUp,
}

/// One robot's running sub-task, with the odometry its phase and end read.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SubTaskState {
    /// The sub-task's number (`CORRIDOR`, `RIGHT`, `LEFT`, `FORWARD`).
    pub subtask: usize,
    /// The pose (x, y, yaw) at which it began.
    pub start: [f64; 3],
    /// The yaw after the last step.
    pub previous_yaw: f64,
    /// The heading change since it began (radians, CCW positive).
    pub heading_change: f64,
    /// Control steps since it began.
    pub steps: u64,
    /// The phase.
    pub phase: usize,
    /// Where a turn last entered phase 2 (its start until then).
    pub turn_point: [f64; 2],
}

impl SubTaskState {
    /// Sub-task `subtask` beginning at `pose` (x, y, yaw as the batch reports them).
    pub fn begin(subtask: usize, pose: [f32; 3]) -> Self {
        Self::begin_at(subtask, pose.map(f64::from))
    }

    /// [`SubTaskState::begin`] at a pose of f64 odometry (a dead-reckoned one, say).
    pub fn begin_at(subtask: usize, pose: [f64; 3]) -> Self {
        let [x, y, yaw] = pose;
        Self {
            subtask,
            start: [x, y, yaw],
            previous_yaw: yaw,
            heading_change: 0.0,
            steps: 0,
            phase: heading_phase(subtask, 0.0),
            turn_point: [x, y],
        }
    }

    /// Checks a state given from outside (robot `env`'s): a known sub-task, a phase it has, a
    /// finite odometry.
    pub fn check(&self, env: usize) -> Result<()> {
        if self.subtask >= NUM_SUBTASKS {
            return Err(Error::InvalidArgument(format!(
                "expected sub-task numbers in 0..{NUM_SUBTASKS}, found {} for environment {env}",
                self.subtask
            )));
        }
        let phases = NUM_PHASES[self.subtask];
        if self.phase >= phases {
            return Err(Error::InvalidArgument(format!(
                "expected phases in 0..{phases} for sub-task {}, found {} for environment {env}",
                self.subtask, self.phase
            )));
        }
        let odometry = [
            ("start", self.start[0]),
            ("start", self.start[1]),
            ("start", self.start[2]),
            ("previous_yaw", self.previous_yaw),
            ("heading_change", self.heading_change),
            ("turn_point", self.turn_point[0]),
            ("turn_point", self.turn_point[1]),
        ];
        match odometry.iter().find(|(_, value)| !value.is_finite()) {
            Some((name, value)) => Err(Error::InvalidArgument(format!(
                "expected a finite sub-task {name}, found {value} for environment {env}"
            ))),
            None => Ok(()),
        }
    }

    /// Follows one control step that ended at `pose`.
    pub fn update(&mut self, pose: [f32; 3]) -> SubTaskEnd {
        self.update_at(pose.map(f64::from))
    }

    /// Follows one control step that ended at `pose` as a running navigator does: a door sub-task
    /// that ends (done or gave up) hands over to Corridors and Corners, which begins there.
    pub fn follow(&mut self, pose: [f32; 3]) -> SubTaskEnd {
        self.follow_at(pose.map(f64::from))
    }

    /// [`SubTaskState::follow`] to a pose of f64 odometry.
    pub fn follow_at(&mut self, pose: [f64; 3]) -> SubTaskEnd {
        let end = self.update_at(pose);
        if end != SubTaskEnd::Running {
            *self = Self::begin_at(CORRIDOR, pose);
        }
        end
    }

    /// [`SubTaskState::update`] to a pose of f64 odometry.
    pub fn update_at(&mut self, pose: [f64; 3]) -> SubTaskEnd {
        let [x, y, yaw] = pose;
        self.heading_change += wrap(yaw - self.previous_yaw);
        self.previous_yaw = yaw;
        self.steps += 1;
        let turn = TARGET_TURN[self.subtask];
        let is_turn = turn != 0.0;
        let phase = heading_phase(self.subtask, self.heading_change);
        if is_turn && phase == 2 && self.phase != 2 {
            self.turn_point = [x, y];
        }
        self.phase = phase;
        if self.subtask == CORRIDOR {
            return SubTaskEnd::Running;
        }
        let target_heading = self.start[2] + turn;
        let direction = [target_heading.cos(), target_heading.sin()];
        let aligned = (self.heading_change - turn).abs() <= heading_tolerance();
        let along = |from: [f64; 2]| (x - from[0]) * direction[0] + (y - from[1]) * direction[1];
        let turn_done =
            is_turn && phase == 2 && aligned && along(self.turn_point) >= TURN_EXIT_DISTANCE;
        let forward_done = self.subtask == FORWARD
            && aligned
            && along([self.start[0], self.start[1]]) >= FORWARD_DISTANCE;
        if self.steps >= MAX_DOOR_STEPS || self.heading_change.abs() > give_up_angle() {
            SubTaskEnd::GaveUp
        } else if turn_done || forward_done {
            SubTaskEnd::Done
        } else {
            SubTaskEnd::Running
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const FRAC_PI_2_F32: f32 = std::f32::consts::FRAC_PI_2;

    #[test]
    fn wrap_takes_angles_into_minus_pi_to_pi() {
        assert_eq!(wrap(0.0), 0.0);
        assert!((wrap(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
        assert!((wrap(-3.0 * PI / 2.0) - PI / 2.0).abs() < 1e-12);
        assert_eq!(wrap(PI), -PI);
        assert!((-PI..PI).contains(&wrap(-7.0)));
    }

    #[test]
    fn phases_follow_the_heading_change() {
        let deg = f64::to_radians;
        assert_eq!(heading_phase(CORRIDOR, 1.0), 0);
        assert_eq!(heading_phase(RIGHT, 0.0), 0);
        assert_eq!(heading_phase(RIGHT, deg(-45.0)), 1);
        assert_eq!(heading_phase(RIGHT, deg(-61.0)), 2);
        assert_eq!(heading_phase(RIGHT, deg(61.0)), 0);
        assert_eq!(heading_phase(LEFT, deg(61.0)), 2);
        assert_eq!(heading_phase(FORWARD, 0.0), 1);
        assert_eq!(heading_phase(FORWARD, deg(6.0)), 2);
        assert_eq!(heading_phase(FORWARD, deg(-6.0)), 0);
    }

    #[test]
    fn going_forward_ends_40_cm_ahead_within_the_tolerance() {
        let mut task = SubTaskState::begin(FORWARD, [0.0, 0.0, 0.0]);
        assert_eq!(task.phase, 1);
        assert_eq!(task.update([0.2, 0.0, 0.0]), SubTaskEnd::Running);
        assert_eq!(task.update([0.41, 0.01, 0.05]), SubTaskEnd::Done);
        let mut skewed = SubTaskState::begin(FORWARD, [0.0, 0.0, 0.0]);
        assert_eq!(skewed.update([0.41, 0.0, 0.3]), SubTaskEnd::Running);
        assert_eq!(skewed.phase, 2);
    }

    #[test]
    fn a_right_turn_ends_8_cm_past_where_it_entered_phase_2() {
        let mut task = SubTaskState::begin(RIGHT, [0.0, 0.0, 0.0]);
        assert_eq!(task.update([0.0, 0.0, -1.2]), SubTaskEnd::Running);
        assert_eq!(task.phase, 2);
        assert_eq!(task.turn_point, [0.0, 0.0]);
        assert_eq!(task.update([0.0, -0.05, -1.5]), SubTaskEnd::Running);
        assert_eq!(task.update([0.0, -0.09, -1.55]), SubTaskEnd::Done);
        assert_eq!(task.phase, 2);
    }

    #[test]
    fn distance_phases_count_the_bins_driven_ahead_of_the_start() {
        let counting = Phases::HeadingAndDistance;
        assert_eq!(
            (Phases::Heading.rows(), counting.rows()),
            (3 * NUM_STATES, 18 * NUM_STATES)
        );
        // Facing +y: 0.2 m ahead is bin 2 (18-22 cm), sideways distance does not count.
        let mut task = SubTaskState::begin(FORWARD, [0.5, 0.5, FRAC_PI_2_F32]);
        let pose = [0.6, 0.7, FRAC_PI_2_F32];
        task.update(pose);
        assert_eq!(task.phase, 1);
        assert_eq!(counting.phase(&task, pose), 1 + 3 * 2);
        assert_eq!(Phases::Heading.phase(&task, pose), 1);
        assert_eq!(counting.table_row(&task, pose, 5), 5 + 7 * NUM_STATES);
        let far = [0.5, 0.9, FRAC_PI_2_F32];
        assert_eq!(counting.phase(&task, far), 1 + 3 * 5);
        let corridor = SubTaskState::begin(CORRIDOR, [0.5, 0.5, 0.0]);
        assert_eq!(counting.phase(&corridor, [0.9, 0.5, 0.0]), 0);
    }

    #[test]
    fn states_from_outside_are_checked() {
        let task = SubTaskState::begin(LEFT, [0.0, 0.0, 0.0]);
        assert!(task.check(0).is_ok());
        let unknown = SubTaskState { subtask: 4, ..task };
        assert!(unknown
            .check(3)
            .unwrap_err()
            .to_string()
            .contains("environment 3"));
        let corridor_phase = SubTaskState {
            subtask: CORRIDOR,
            phase: 1,
            ..task
        };
        assert!(corridor_phase.check(0).is_err());
        let lost = SubTaskState {
            heading_change: f64::NAN,
            ..task
        };
        let err = lost.check(5).unwrap_err().to_string();
        assert!(
            err.contains("heading_change") && err.contains("NaN"),
            "{err}"
        );
    }

    #[test]
    fn a_door_sub_task_gives_up_when_turned_round_or_out_of_steps() {
        // A left turn that goes on past 150 degrees (0.78, 1.78, then 2.68 rad) turned round.
        let mut round = SubTaskState::begin(LEFT, [0.0, 0.0, 3.0]);
        let ends: Vec<_> = [-2.5f32, -1.5, -0.6]
            .map(|yaw| round.update([0.0, 0.0, yaw]))
            .to_vec();
        assert_eq!(
            ends,
            [SubTaskEnd::Running, SubTaskEnd::Running, SubTaskEnd::GaveUp]
        );
        let mut slow = SubTaskState::begin(FORWARD, [0.0, 0.0, 0.0]);
        let ends: Vec<_> = (0..MAX_DOOR_STEPS)
            .map(|_| slow.update([0.0, 0.0, 0.0]))
            .collect();
        assert!(ends[..ends.len() - 1]
            .iter()
            .all(|&e| e == SubTaskEnd::Running));
        assert_eq!(ends[ends.len() - 1], SubTaskEnd::GaveUp);
        let mut corridor = SubTaskState::begin(CORRIDOR, [0.0, 0.0, 0.0]);
        for _ in 0..MAX_DOOR_STEPS + 5 {
            assert_eq!(corridor.update([0.0, 0.0, 3.0]), SubTaskEnd::Running);
        }
    }
}
