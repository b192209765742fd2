//! Controllers that run in the core, per environment, for the multi-step call
//! ([`crate::Batch::run_steps`]): each maps an environment's latest readings (and, for those
//! that draw random numbers, its own seeded stream) to the wheel speeds of its next step.
//! Braitenberg and avoid-collision give, bit for bit, the wheel speeds of their Python
//! counterparts (`mazesim.benchmark.workloads`, `mazesim.controllers.AvoidCollision`) on the
//! same readings, and the tabular one those of the navigator's per-step
//! [`crate::navigator::Navigator`], so that a multi-step call equals stepping the batch from
//! Python one step at a time; random wheels draw from the core's streams (the same law as the
//! Python `random` workload, other draws).

pub mod avoid_collision;
pub mod braitenberg;
pub mod random_wheels;

pub use avoid_collision::AvoidCollision;

use crate::error::{Error, Result};
use crate::navigator::door::SubTaskState;
use crate::navigator::{self, TabularPolicy};
use crate::rng::Rng;
use crate::robot::RobotProfile;

/// A built-in controller.
#[derive(Debug, Clone, PartialEq)]
pub enum Controller {
    /// The Braitenberg rule of the benchmark workload on ps0..ps7 (`mazesim.benchmark.braitenberg`).
    Braitenberg,
    /// The report's Alg. 1 on ps0..ps7 (`mazesim.controllers.AvoidCollision`).
    AvoidCollision(AvoidCollision),
    /// A tabular policy over the Table 4.1 state of the first six (Sharp) distance sensors.
    Tabular(Box<TabularPolicy>),
    /// Uniform random wheel speeds within the robot's motor limit.
    RandomWheels,
}

/// What a controller chose for one environment for one step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Decision {
    /// Left and right wheel speeds, rad/s.
    pub wheel_speeds: [f32; 2],
    /// The primitive action (index into `navigator::WHEEL_SPEED_FRACTIONS`), -1 for controllers
    /// that do not choose among primitive actions.
    pub action: i32,
}

impl Controller {
    /// The controller's name as the Python API spells it.
    pub fn name(&self) -> &'static str {
        match self {
            Controller::Braitenberg => "braitenberg",
            Controller::AvoidCollision(_) => "avoid-collision",
            Controller::Tabular(_) => "tabular",
            Controller::RandomWheels => "random",
        }
    }

    /// Checks that the controller can drive `envs` environments of `robot`: enough distance
    /// sensors for its rule, one table index per environment.
    pub fn check(&self, robot: &RobotProfile, envs: usize) -> Result<()> {
        let needed = match self {
            Controller::Braitenberg | Controller::AvoidCollision(_) => 8,
            Controller::Tabular(policy) => {
                policy.check_envs(envs)?;
                navigator::NUM_SENSORS
            }
            Controller::RandomWheels => 0,
        };
        let found = robot.distance_sensors.len();
        if found < needed {
            return Err(Error::InvalidArgument(format!(
                "the {} controller reads {needed} distance sensors, robot profile {:?} has {found}",
                self.name(),
                robot.name
            )));
        }
        Ok(())
    }

    /// Checks that the controller can drive robots through door sub-tasks (see
    /// [`TabularPolicy::check_subtasks`]): only the tabular one can.
    pub fn check_subtasks(&self) -> Result<()> {
        match self {
            Controller::Tabular(policy) => policy.check_subtasks(),
            other => Err(Error::InvalidArgument(format!(
                "expected the tabular controller with subtasks, found {:?}",
                other.name()
            ))),
        }
    }

    /// The phase whose table the tabular controller acts from for a robot running `task` at
    /// `pose` ([`TabularPolicy::task_phase`]); the heading phase for the others.
    pub fn task_phase(&self, task: &SubTaskState, pose: [f32; 3]) -> usize {
        match self {
            Controller::Tabular(policy) => policy.task_phase(task, pose),
            _ => task.phase,
        }
    }

    /// The decision for environment `env` from its distance readings, the wheel speeds of its
    /// last step (`[0, 0]` after a reset), its robot's motor limit `max_speed` (rad/s), its
    /// stream and, for the tabular controller, its running sub-task `task` with its pose if it
    /// has one. Inlined into both batch loops that call it once a robot-step (one robot's and
    /// the swarm's), which two callers had stopped.
    #[inline(always)]
    pub fn decide(
        &self,
        env: usize,
        readings: &[f32],
        last_wheel_speeds: [f32; 2],
        max_speed: f64,
        stream: &mut Rng,
        task: Option<(&SubTaskState, [f32; 3])>,
    ) -> Decision {
        let free = |wheel_speeds| Decision {
            wheel_speeds,
            action: -1,
        };
        match self {
            Controller::Braitenberg => free(braitenberg::wheel_speeds(readings)),
            Controller::AvoidCollision(rule) => free(rule.wheel_speeds(readings)),
            Controller::RandomWheels => free(random_wheels::wheel_speeds(stream, max_speed)),
            Controller::Tabular(policy) => {
                let action = match task {
                    Some((task, pose)) => {
                        policy.action_in_task(task, pose, readings, last_wheel_speeds, stream)
                    }
                    None => policy.action_after(env, readings, last_wheel_speeds, stream),
                };
                let [l, r] = navigator::WHEEL_SPEED_FRACTIONS[action];
                let max_speed = policy.speed_limit(max_speed);
                Decision {
                    wheel_speeds: [(l * max_speed) as f32, (r * max_speed) as f32],
                    action: action as i32,
                }
            }
        }
    }
}
