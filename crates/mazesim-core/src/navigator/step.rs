//! The navigator's step for N robots (the report's Alg. 5 below the higher level): each robot's
//! six distances become levels and a state, its running sub-task's odometry follows its pose, a
//! door sub-task that ended hands over to Corridors and Corners, a sub-task the higher level
//! chose (handed in as data, per robot) begins there, and the running sub-task's table gives the
//! action, greedy among the actions the sub-task may take, under the rules of Corridors and
//! Corners ([`CorridorRules`]: a turn on the spot kept rather than reversed and, with
//! [`BlindRule::HoldHeading`], the heading held on the grid in the blind state), as the
//! multi-step call's tabular controller follows them. The poses are any odometry (a batch's, or
//! one dead-reckoned from the actions), in f64.

use super::discretiser::{level_of_cm, state_of_levels, NUM_SENSORS, NUM_STATES};
use super::door::{self, Phases, SubTaskEnd, SubTaskState, NUM_SUBTASKS};
use super::heading_hold::{spin_of, BlindRule, CorridorRules};
use super::qlearning::best_action;
use super::tabular::{finite_q_values, NUM_ACTIONS};
use crate::error::{Error, Result};

/// Backward (`99`), which Corridors and Corners may not take.
const BACKWARD: usize = 11;

/// What one robot's step saw and did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct StepRecord {
    /// Table 4.1 level of each distance.
    pub levels: [u8; NUM_SENSORS],
    /// The distance state.
    pub state: usize,
    /// The running sub-task after the step's hand-overs.
    pub subtask: usize,
    /// Its phase (with the distance bin when the tables count it).
    pub phase: usize,
    /// The action.
    pub action: usize,
    /// A door sub-task ended (done or gave up) in this step.
    pub ended: bool,
}

/// One robot's running sub-task and the action of its last step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RobotState {
    /// The running sub-task.
    pub task: SubTaskState,
    /// The action of the last step, `None` after a reset.
    pub previous: Option<usize>,
}

/// The lower level of N robots: their stacked tables and each one's running sub-task.
#[derive(Debug, Clone, PartialEq)]
pub struct Navigator {
    /// `(NUM_SUBTASKS, rows, NUM_ACTIONS)` values.
    values: Vec<f64>,
    phases: Phases,
    /// Corridors and Corners keeps its turns on the spot, and follows the blind rule given.
    rules: CorridorRules,
    robots: Vec<RobotState>,
}

impl Navigator {
    /// A navigator of `robots` robots acting from the stacked tables `values` (`4 x rows x 12`,
    /// `rows` of [`Phases::Heading`] or [`Phases::HeadingAndDistance`], which the phases follow),
    /// Corridors and Corners following `blind` in the blind state; every robot starts in
    /// Corridors and Corners at the origin.
    pub fn new(values: Vec<f64>, robots: usize, blind: BlindRule) -> Result<Self> {
        let per_subtask = |p: Phases| p.rows() * NUM_ACTIONS;
        let phases = [Phases::Heading, Phases::HeadingAndDistance]
            .into_iter()
            .find(|&p| values.len() == NUM_SUBTASKS * per_subtask(p))
            .ok_or_else(|| {
                Error::InvalidArgument(format!(
                    "expected lower-level tables of shape ({NUM_SUBTASKS}, {}, {NUM_ACTIONS}) or \
                     ({NUM_SUBTASKS}, {}, {NUM_ACTIONS}), found {} values",
                    Phases::Heading.rows(),
                    Phases::HeadingAndDistance.rows(),
                    values.len()
                ))
            })?;
        finite_q_values(&values, phases.rows())?;
        if blind == BlindRule::Forward {
            return Err(Error::InvalidArgument(
                "expected the blind rule \"table\" or \"hold_heading\" (a navigator trained to \
                 drive forward there has tables that say so), found \"forward\""
                    .into(),
            ));
        }
        let start = RobotState {
            task: SubTaskState::begin_at(door::CORRIDOR, [0.0; 3]),
            previous: None,
        };
        Ok(Self {
            values,
            phases,
            rules: CorridorRules {
                keep_turns: true,
                blind,
            },
            robots: vec![start; robots],
        })
    }

    /// The robots' states.
    pub fn robots(&self) -> &[RobotState] {
        &self.robots
    }

    /// The robots' states, to set from outside (a multi-step call that followed their sub-tasks).
    pub fn robots_mut(&mut self) -> &mut [RobotState] {
        &mut self.robots
    }

    /// What the door sub-tasks' phases count.
    pub fn phases(&self) -> Phases {
        self.phases
    }

    /// Starts robot `robot` afresh at `pose`: Corridors and Corners, no last action.
    pub fn reset(&mut self, robot: usize, pose: [f64; 3]) {
        self.robots[robot] = RobotState {
            task: SubTaskState::begin_at(door::CORRIDOR, pose),
            previous: None,
        };
    }

    /// Begins sub-task `subtask` for robot `robot` at `pose`, its last action kept.
    pub fn begin(&mut self, robot: usize, subtask: usize, pose: [f64; 3]) -> Result<()> {
        if subtask >= NUM_SUBTASKS {
            return Err(Error::InvalidArgument(format!(
                "expected sub-task numbers in 0..{NUM_SUBTASKS}, found {subtask} for robot {robot}"
            )));
        }
        self.robots[robot].task = SubTaskState::begin_at(subtask, pose);
        Ok(())
    }

    /// One step of robot `robot`: its six distances in cm (front, back, left, right, left-front,
    /// right-front), its pose after the last step and, if the higher level chose one at a
    /// checkpoint, the sub-task that begins now.
    pub fn decide(
        &mut self,
        robot: usize,
        distances_cm: &[f64],
        pose: [f64; 3],
        chosen: Option<usize>,
    ) -> Result<StepRecord> {
        let mut levels = [0u8; NUM_SENSORS];
        for (level, &cm) in levels.iter_mut().zip(&distances_cm[..NUM_SENSORS]) {
            *level = level_of_cm(cm) as u8;
        }
        let state = state_of_levels(levels.iter().map(|&l| usize::from(l)));
        let ended = self.robots[robot].task.follow_at(pose) != SubTaskEnd::Running;
        if let Some(subtask) = chosen {
            self.begin(robot, subtask, pose)?;
        }
        let RobotState { task, previous } = self.robots[robot];
        let phase = self.phases.phase_at(&task, pose);
        let row = state + NUM_STATES * phase;
        let start = (task.subtask * self.phases.rows() + row) * NUM_ACTIONS;
        let values = &self.values[start..start + NUM_ACTIONS];
        let corridor = task.subtask == door::CORRIDOR;
        let allowed = (0..NUM_ACTIONS).filter(|&a| !(corridor && a == BACKWARD));
        let last_spin = previous.and_then(spin_of);
        let chosen = best_action(values, allowed);
        let action = self
            .rules
            .action(task.subtask, chosen, last_spin, pose[2], || state);
        self.robots[robot].previous = Some(action);
        Ok(StepRecord {
            levels,
            state,
            subtask: task.subtask,
            phase,
            action,
            ended,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::navigator::heading_hold::{SPIN_LEFT, SPIN_RIGHT};

    fn tables(phases: Phases, best: impl Fn(usize, usize) -> usize) -> Vec<f64> {
        let rows = phases.rows();
        let mut values = vec![0.0; NUM_SUBTASKS * rows * NUM_ACTIONS];
        for subtask in 0..NUM_SUBTASKS {
            for row in 0..rows {
                values[(subtask * rows + row) * NUM_ACTIONS + best(subtask, row)] = 1.0;
            }
        }
        values
    }

    #[test]
    fn tables_holding_a_value_that_is_not_finite_are_refused_naming_where() {
        for bad in [f64::NAN, f64::INFINITY, f64::NEG_INFINITY] {
            let mut values = tables(Phases::HeadingAndDistance, |_, _| 0);
            let rows = Phases::HeadingAndDistance.rows();
            values[(2 * rows + 7) * NUM_ACTIONS + 3] = bad;
            let err = Navigator::new(values, 1, BlindRule::Table).err().unwrap();
            let text = err.to_string();
            assert!(text.contains("expected finite Q-values"), "{text}");
            assert!(text.contains("table 2, state 7, action 3"), "{text}");
        }
    }

    #[test]
    fn a_chosen_sub_task_acts_from_its_phase_and_a_finished_one_hands_over() {
        // Each table's best action names its sub-task (0..4) plus 4 in phase 1 of the turns.
        let values = tables(Phases::Heading, |k, row| {
            k + 4 * usize::from(row / NUM_STATES == 1)
        });
        let mut nav = Navigator::new(values, 2, BlindRule::Table).unwrap();
        let near = [5.0; 6];
        let step = nav.decide(0, &near, [0.0; 3], None).unwrap();
        assert_eq!((step.subtask, step.action, step.state), (0, 0, 0));
        let step = nav.decide(0, &near, [0.0; 3], Some(door::RIGHT)).unwrap();
        assert_eq!((step.subtask, step.phase, step.action), (1, 0, 1));
        // 40 degrees to the right: phase 1 of the right turn.
        let step = nav.decide(0, &near, [0.0, 0.0, -0.7], None).unwrap();
        assert_eq!((step.subtask, step.phase, step.action), (1, 1, 5));
        // Turned round: the turn gives up and Corridors and Corners takes over.
        let step = nav.decide(0, &near, [0.0, 0.0, 3.0], None).unwrap();
        assert!(step.ended);
        assert_eq!(step.subtask, door::CORRIDOR);
        assert!(nav.begin(1, 4, [0.0; 3]).is_err());
        assert!(Navigator::new(vec![0.0; 10], 1, BlindRule::Table).is_err());
    }

    #[test]
    fn corridors_and_corners_keeps_its_turn_and_never_backs() {
        let mut nav = Navigator::new(
            tables(Phases::Heading, |_, _| BACKWARD),
            1,
            BlindRule::Table,
        )
        .unwrap();
        // Backward is best, but not allowed: the first allowed action of value 0 is forward.
        assert_eq!(nav.decide(0, &[5.0; 6], [0.0; 3], None).unwrap().action, 0);
        let spin = |right: bool| if right { SPIN_RIGHT } else { SPIN_LEFT };
        let values = tables(Phases::Heading, |_, row| spin(row % NUM_STATES == 0));
        let mut nav = Navigator::new(values, 1, BlindRule::HoldHeading).unwrap();
        assert_eq!(
            nav.decide(0, &[5.0; 6], [0.0; 3], None).unwrap().action,
            SPIN_RIGHT
        );
        // State 1 says spin left: the right turn goes on.
        let left_state = [8.0, 5.0, 5.0, 5.0, 5.0, 5.0];
        assert_eq!(
            nav.decide(0, &left_state, [0.0; 3], None).unwrap().action,
            SPIN_RIGHT
        );
        // Blind, 10 degrees left of the grid, still spinning right: the hold rule keeps it.
        let blind = [30.0; 6];
        let yawed = [0.0, 0.0, 10f64.to_radians()];
        assert_eq!(
            nav.decide(0, &blind, yawed, None).unwrap().action,
            SPIN_RIGHT
        );
        nav.reset(0, yawed);
        assert_eq!(nav.decide(0, &blind, yawed, None).unwrap().action, 1);
    }
}
