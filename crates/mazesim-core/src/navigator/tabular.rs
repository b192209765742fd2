//! A tabular policy over the report's lower-level state: the six Sharp distances discretised by
//! Table 4.1 (as `mazesim.learn.discretise` does) and the twelve primitive actions (as
//! `mazesim.actions` lists them), acting greedily, optionally within a mask of allowed actions and
//! with epsilon-greedy exploration from each environment's own stream.

use super::discretiser::{Discretiser, NUM_STATES};
use super::door::{self, Phases, SubTaskState};
use super::heading_hold::{keep_turn, BlindRule, CorridorRules, SPIN_LEFT, SPIN_RIGHT};
use super::qlearning::best_action;
use crate::error::{Error, Result};
use crate::rng::Rng;

/// The primitive actions.
pub const NUM_ACTIONS: usize = 12;

/// (left, right) wheel speeds of the primitive actions as fractions of the motor limit, in the
/// order of `mazesim.actions.ACTION_CODES`: `00`, `11`-`44`, `55`-`88`, `aa`, `bb`, `99`.
pub const WHEEL_SPEED_FRACTIONS: [[f64; 2]; NUM_ACTIONS] = [
    [0.5, 0.5],
    [0.5, 0.375],
    [0.5, 0.25],
    [0.5, 0.125],
    [0.5, 0.0],
    [0.375, 0.5],
    [0.25, 0.5],
    [0.125, 0.5],
    [0.0, 0.5],
    [0.25, -0.25],
    [-0.25, 0.25],
    [-0.25, -0.25],
];

/// Greedy (or epsilon-greedy) actions from one or several Q-tables of shape
/// `(NUM_STATES, NUM_ACTIONS)`.
#[derive(Debug, Clone, PartialEq)]
pub struct TabularPolicy {
    /// `(tables, NUM_STATES, NUM_ACTIONS)` values, all finite.
    values: Vec<f64>,
    tables: usize,
    /// Per table, the actions it may take, listed in increasing order.
    allowed: Vec<Vec<u8>>,
    /// Per environment, the table it acts from; all use table 0 when `None`.
    table_of_env: Option<Vec<u32>>,
    epsilon: f64,
    /// Keep turning on the spot the way the last step turned rather than turn back (everywhere
    /// without sub-tasks, in Corridors and Corners with them), and, in sub-tasks, what Corridors
    /// and Corners does where no sensor sees a wall.
    rules: CorridorRules,
    /// The motor limit whose fractions every robot drives at (each robot's own when `None`).
    speed_limit: Option<f64>,
    discretiser: Discretiser,
}

impl TabularPolicy {
    /// A policy from `values` (`tables` Q-tables of `NUM_STATES x NUM_ACTIONS` values, row-major),
    /// each acting among its `allowed` actions (`tables x NUM_ACTIONS` flags; all when `None`),
    /// environment i from table `table_of_env[i]` (table 0 for all when `None`), exploring with
    /// probability `epsilon`.
    pub fn new(
        values: Vec<f64>,
        tables: usize,
        allowed: Option<&[bool]>,
        table_of_env: Option<Vec<u32>>,
        epsilon: f64,
    ) -> Result<Self> {
        let per_table = NUM_STATES * NUM_ACTIONS;
        if tables == 0 || values.len() != tables * per_table {
            return Err(Error::InvalidArgument(format!(
                "expected a Q-table of shape ({NUM_STATES}, {NUM_ACTIONS}) or (tables, \
                 {NUM_STATES}, {NUM_ACTIONS}), found {} values for {tables} tables",
                values.len()
            )));
        }
        finite_q_values(&values, NUM_STATES)?;
        if !(0.0..=1.0).contains(&epsilon) {
            return Err(Error::InvalidArgument(format!(
                "expected epsilon in [0, 1], found {epsilon}"
            )));
        }
        let allowed: Vec<Vec<u8>> = match allowed {
            None => vec![(0..NUM_ACTIONS as u8).collect(); tables],
            Some(flags) => {
                if flags.len() != tables * NUM_ACTIONS {
                    return Err(Error::InvalidArgument(format!(
                        "expected allowed actions of shape ({NUM_ACTIONS},) or ({tables}, \
                         {NUM_ACTIONS}), found {} flags",
                        flags.len()
                    )));
                }
                flags
                    .chunks_exact(NUM_ACTIONS)
                    .map(|row| {
                        (0..NUM_ACTIONS as u8)
                            .filter(|&a| row[a as usize])
                            .collect()
                    })
                    .collect()
            }
        };
        if let Some(t) = allowed.iter().position(|a| a.is_empty()) {
            return Err(Error::InvalidArgument(format!(
                "expected at least one allowed action per table, found none for table {t}"
            )));
        }
        if let Some(map) = &table_of_env {
            if let Some(i) = map.iter().position(|&t| t as usize >= tables) {
                return Err(Error::InvalidArgument(format!(
                    "expected table indices below {tables}, found {} for environment {i}",
                    map[i]
                )));
            }
        }
        Ok(Self {
            values,
            tables,
            allowed,
            table_of_env,
            epsilon,
            rules: CorridorRules::default(),
            speed_limit: None,
            discretiser: Discretiser::new()?,
        })
    }

    /// The policy keeping a turn on the spot (as [`super::step::Navigator`] does): an
    /// environment whose last step turned one way on the spot (its wheel speeds, see
    /// [`TabularPolicy::action_after`]) and whose action now turns the other way keeps turning
    /// as before.
    pub fn with_held_spins(mut self, hold: bool) -> Self {
        self.rules.keep_turns = hold;
        self
    }

    /// [`TabularPolicy::action`] after a step with wheel speeds `last` (`[0, 0]` after a reset),
    /// a turn on the spot kept when the policy holds spins.
    pub fn action_after(
        &self,
        env: usize,
        volts: &[f32],
        last: [f32; 2],
        stream: &mut Rng,
    ) -> usize {
        let action = self.action(env, volts, stream);
        if self.rules.keep_turns {
            keep_turn(action, last_spin(last))
        } else {
            action
        }
    }

    /// The policy with Corridors and Corners following `rule` in the blind state, in
    /// sub-tasks ([`TabularPolicy::action_in_task`]).
    pub fn with_blind_rule(mut self, rule: BlindRule) -> Self {
        self.rules.blind = rule;
        self
    }

    /// The policy driving every robot at the fractions of the motor limit `limit` (rad/s;
    /// clamped to each robot's own by its step), as a loop that turns actions into wheel speeds
    /// for a whole batch does; each robot's own limit when `None`.
    pub fn with_speed_limit(mut self, limit: Option<f64>) -> Result<Self> {
        if let Some(limit) = limit.filter(|l| !(l.is_finite() && *l > 0.0)) {
            return Err(Error::InvalidArgument(format!(
                "expected a wheel speed limit above 0 rad/s, found {limit}"
            )));
        }
        self.speed_limit = limit;
        Ok(self)
    }

    /// The motor limit whose fractions a robot of limit `own` drives at.
    pub fn speed_limit(&self, own: f64) -> f64 {
        self.speed_limit.unwrap_or(own)
    }

    /// What the door sub-tasks' phases count, from the number of stacked tables: `NUM_SUBTASKS`
    /// times the phases of [`Phases::Heading`] or of [`Phases::HeadingAndDistance`].
    pub fn phases(&self) -> Option<Phases> {
        [Phases::Heading, Phases::HeadingAndDistance]
            .into_iter()
            .find(|p| self.tables == door::NUM_SUBTASKS * p.count())
    }

    /// The phase whose table a robot running `task` at `pose` acts from: its heading phase, plus
    /// the distance bin times 3 when the door sub-tasks count the distance.
    pub fn task_phase(&self, task: &SubTaskState, pose: [f32; 3]) -> usize {
        self.phases().unwrap_or_default().phase(task, pose)
    }

    /// The action of a robot running door sub-task state `task` at `pose` (see [`super::door`]):
    /// from the table of its sub-task's phase (table `subtask * phases + phase` of the stacked
    /// tables, [`TabularPolicy::phases`]), then the rules of Corridors and Corners
    /// ([`CorridorRules::action`]: a turn on the spot kept when the policy holds spins, the
    /// blind rule), as the navigator's step follows them.
    pub fn action_in_task(
        &self,
        task: &SubTaskState,
        pose: [f32; 3],
        volts: &[f32],
        last: [f32; 2],
        stream: &mut Rng,
    ) -> usize {
        let phases = self.phases().unwrap_or_default();
        let table = task.subtask * phases.count() + self.task_phase(task, pose);
        let action = self.action_from(table, volts, stream);
        let yaw = f64::from(pose[2]);
        let state = || self.discretiser.state(volts);
        self.rules
            .action(task.subtask, action, last_spin(last), yaw, state)
    }

    /// Checks that the policy can drive `envs` environments.
    pub fn check_envs(&self, envs: usize) -> Result<()> {
        match &self.table_of_env {
            Some(map) if map.len() != envs => Err(Error::InvalidArgument(format!(
                "expected one table index per environment ({envs}), found {}",
                map.len()
            ))),
            _ => Ok(()),
        }
    }

    /// The action of environment `env` on Sharp readings `volts`: with probability epsilon a
    /// uniformly random allowed action, otherwise the first allowed action of greatest value (as
    /// `numpy.argmax` picks it). Every decision draws two numbers from `stream`, whatever epsilon
    /// is: a uniform `u` (explore when `u < epsilon`) and 64 bits `k` (the `floor(k * count /
    /// 2^64)`-th allowed action when exploring).
    pub fn action(&self, env: usize, volts: &[f32], stream: &mut Rng) -> usize {
        let table = self.table_of_env.as_ref().map_or(0, |m| m[env] as usize);
        self.action_from(table, volts, stream)
    }

    /// [`TabularPolicy::action`] from table `table`.
    fn action_from(&self, table: usize, volts: &[f32], stream: &mut Rng) -> usize {
        let allowed = &self.allowed[table];
        let explore = stream.uniform() < self.epsilon;
        let bits = stream.next_u64();
        if explore {
            let pick = ((bits as u128 * allowed.len() as u128) >> 64) as usize;
            return allowed[pick] as usize;
        }
        let state = self.discretiser.state(volts);
        let start = (table * NUM_STATES + state) * NUM_ACTIONS;
        let row = &self.values[start..start + NUM_ACTIONS];
        best_action(row, allowed.iter().map(|&a| usize::from(a)))
    }

    /// Checks that the policy can drive robots through door sub-tasks: the stacked tables of the
    /// sub-tasks' phases ([`TabularPolicy::phases`]), and no fixed table per environment.
    pub fn check_subtasks(&self) -> Result<()> {
        if self.phases().is_none() || self.table_of_env.is_some() {
            let [heading, distance] = [Phases::Heading, Phases::HeadingAndDistance]
                .map(|p| door::NUM_SUBTASKS * p.count());
            return Err(Error::InvalidArgument(format!(
                "expected, with subtasks, the {heading} stacked tables of the sub-tasks' heading \
                 phases (shape ({heading}, {NUM_STATES}, {NUM_ACTIONS})) or the {distance} of \
                 their heading and distance phases, and no table_index, found {} tables{}",
                self.tables,
                if self.table_of_env.is_some() {
                    " and a table_index"
                } else {
                    ""
                }
            )));
        }
        Ok(())
    }
}

/// The turn on the spot of a last step with wheel speeds `last`: `aa` is the only action with
/// the left wheel forward and the right one backward, `bb` the only one the other way round, and
/// the motor limit (positive) keeps the signs; after a reset both are 0 (no turn).
fn last_spin(last: [f32; 2]) -> Option<usize> {
    let [left, right] = last;
    if left > 0.0 && right < 0.0 {
        Some(SPIN_RIGHT)
    } else if left < 0.0 && right > 0.0 {
        Some(SPIN_LEFT)
    } else {
        None
    }
}

/// Refuses a stack of Q-tables (`states x NUM_ACTIONS` values each) holding a value that is not
/// finite, naming where it is: the one check of every Q-table the core is given, so that no
/// controller ever compares NaN.
pub(crate) fn finite_q_values(values: &[f64], states: usize) -> Result<()> {
    let per_table = states * NUM_ACTIONS;
    match values.iter().position(|v| !v.is_finite()) {
        Some(at) => Err(Error::InvalidArgument(format!(
            "expected finite Q-values, found {} at table {}, state {}, action {}",
            values[at],
            at / per_table,
            at % per_table / NUM_ACTIONS,
            at % NUM_ACTIONS
        ))),
        None => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn greedy_takes_the_first_best_allowed_action() {
        let mut values = vec![0.0; NUM_STATES * NUM_ACTIONS];
        values[3] = 1.0;
        values[7] = 1.0;
        let mut stream = Rng::new(0);
        let volts = [3.5f32; 6]; // state 0
        let policy = TabularPolicy::new(values.clone(), 1, None, None, 0.0).unwrap();
        assert_eq!(policy.action(0, &volts, &mut stream), 3);
        let mut mask = [true; NUM_ACTIONS];
        mask[3] = false;
        let policy = TabularPolicy::new(values, 1, Some(&mask), None, 0.0).unwrap();
        assert_eq!(policy.action(0, &volts, &mut stream), 7);
    }

    #[test]
    fn bad_tables_and_masks_are_refused() {
        let mut values = vec![0.0; NUM_STATES * NUM_ACTIONS];
        assert!(TabularPolicy::new(values.clone(), 2, None, None, 0.0).is_err());
        assert!(TabularPolicy::new(values.clone(), 1, Some(&[false; 12]), None, 0.0).is_err());
        assert!(TabularPolicy::new(values.clone(), 1, None, Some(vec![1]), 0.0).is_err());
        assert!(TabularPolicy::new(values.clone(), 1, None, None, 1.5).is_err());
        values[NUM_ACTIONS * 5 + 2] = f64::NAN;
        let err = TabularPolicy::new(values, 1, None, None, 0.0).unwrap_err();
        assert!(err.to_string().contains("state 5, action 2"), "{err}");
    }

    #[test]
    fn sub_tasks_act_from_the_table_of_their_phase_and_distance_and_hold_when_blind() {
        let per_table = NUM_STATES * NUM_ACTIONS;
        let (near, blind) = ([3.5f32; 6], [0.2f32; 6]); // states 0 and 4095
        let mut stream = Rng::new(1);
        // Going forward, 20 cm ahead of its start (distance bin 2), heading phase 1.
        let task = SubTaskState::begin(door::FORWARD, [0.0, 0.0, 0.0]);
        let pose = [0.2, 0.0, 0.0];
        for (phases, table) in [
            (Phases::Heading, 3 * 3 + 1),
            (Phases::HeadingAndDistance, 3 * 18 + 7),
        ] {
            let tables = door::NUM_SUBTASKS * phases.count();
            let mut values = vec![0.0; tables * per_table];
            values[table * per_table + 4] = 1.0;
            let policy = TabularPolicy::new(values, tables, None, None, 0.0).unwrap();
            assert_eq!(policy.phases(), Some(phases));
            assert!(policy.check_subtasks().is_ok());
            assert_eq!(
                policy.action_in_task(&task, pose, &near, [0.0; 2], &mut stream),
                4
            );
        }
        let policy = TabularPolicy::new(vec![0.0; 5 * per_table], 5, None, None, 0.0).unwrap();
        assert!(policy.phases().is_none() && policy.check_subtasks().is_err());

        // Corridors and Corners, blind, 10 degrees left of the grid: the table says forward.
        let corridor = SubTaskState::begin(door::CORRIDOR, [0.0, 0.0, 0.0]);
        let values = vec![0.0; door::NUM_TABLES * per_table];
        let table = TabularPolicy::new(values, door::NUM_TABLES, None, None, 0.0).unwrap();
        let holding = table.clone().with_blind_rule(BlindRule::HoldHeading);
        let yawed = [0.0, 0.0, 10f32.to_radians()];
        let spun_left = [-1.0, 1.0];
        let act = |p: &TabularPolicy, volts: &[f32], last, stream: &mut Rng| {
            p.action_in_task(&corridor, yawed, volts, last, stream)
        };
        assert_eq!(act(&table, &blind, [0.0; 2], &mut stream), 0);
        assert_eq!(act(&holding, &blind, [0.0; 2], &mut stream), 1);
        assert_eq!(act(&holding, &blind, spun_left, &mut stream), SPIN_LEFT);
        assert_eq!(act(&holding, &near, spun_left, &mut stream), 0);
    }

    #[test]
    fn a_speed_limit_given_replaces_each_robots_own() {
        let policy = TabularPolicy::new(vec![0.0; NUM_STATES * NUM_ACTIONS], 1, None, None, 0.0);
        let policy = policy.unwrap();
        assert_eq!(policy.speed_limit(7.5), 7.5);
        let limited = policy.clone().with_speed_limit(Some(5.5)).unwrap();
        assert_eq!(limited.speed_limit(7.5), 5.5);
        for bad in [0.0, -1.0, f64::NAN, f64::INFINITY] {
            assert!(policy.clone().with_speed_limit(Some(bad)).is_err());
        }
    }

    #[test]
    fn wheel_speeds_tell_a_turn_on_the_spot_as_the_action_does() {
        for max_speed in [1e-3, 7.536, 50.0] {
            for (last, &[l, r]) in WHEEL_SPEED_FRACTIONS.iter().enumerate() {
                let speeds = [(l * max_speed) as f32, (r * max_speed) as f32];
                let spin = [SPIN_RIGHT, SPIN_LEFT].contains(&last).then_some(last);
                assert_eq!(last_spin(speeds), spin);
            }
        }
        assert_eq!(last_spin([0.0, 0.0]), None);
    }

    #[test]
    fn exploration_takes_only_allowed_actions_and_all_of_them() {
        let values = vec![0.0; NUM_STATES * NUM_ACTIONS];
        let mut mask = [false; NUM_ACTIONS];
        mask[2] = true;
        mask[9] = true;
        mask[11] = true;
        let policy = TabularPolicy::new(values, 1, Some(&mask), None, 1.0).unwrap();
        let mut stream = Rng::new(3);
        let mut seen = [0usize; NUM_ACTIONS];
        for _ in 0..3000 {
            seen[policy.action(0, &[1.0; 6], &mut stream)] += 1;
        }
        assert_eq!(seen.iter().sum::<usize>(), seen[2] + seen[9] + seen[11]);
        assert!(seen[2] > 800 && seen[9] > 800 && seen[11] > 800, "{seen:?}");
    }
}
