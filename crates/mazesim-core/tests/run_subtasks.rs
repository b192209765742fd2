//! The multi-step call with door sub-tasks: the tabular controller acts from the table of each
//! robot's sub-task and phase and follows its odometry after every step, as stepping the batch
//! from outside with the same sub-task states does, whatever the threads or the split in calls.

use std::sync::Arc;

use mazesim_core::generator::{generate, MazeParams};
use mazesim_core::navigator::door::{self, SubTaskEnd, SubTaskState};
use mazesim_core::navigator::TabularPolicy;
use mazesim_core::navigator::{NUM_ACTIONS, NUM_STATES, WHEEL_SPEED_FRACTIONS};
use mazesim_core::rng::Rng;
use mazesim_core::rollout::RunEnvs;
use mazesim_core::{
    Batch, Controller, RobotProfile, RunCounters, RunOptions, RunTrace, StepOutputs,
};

const ENVS: usize = 24;

fn batch(threads: usize) -> Batch {
    let worlds = (0..ENVS as u64)
        .map(|s| Arc::new(generate(&MazeParams::default(), 40 + s).unwrap()))
        .collect();
    let profile = Arc::new(RobotProfile::builtin("seed").unwrap());
    let seeds: Vec<u64> = (0..ENVS as u64).collect();
    Batch::new(worlds, profile, &seeds, true, None, threads).unwrap()
}

fn policy() -> TabularPolicy {
    let mut rng = Rng::new(8);
    let values = (0..door::NUM_TABLES * NUM_STATES * NUM_ACTIONS)
        .map(|_| (rng.uniform() * 3.0).floor())
        .collect();
    TabularPolicy::new(values, door::NUM_TABLES, None, None, 0.0)
        .unwrap()
        .with_held_spins(true)
}

/// Each robot's sub-task at the start: every kind, begun at its start pose.
fn tasks(b: &Batch) -> Vec<SubTaskState> {
    b.envs()
        .iter()
        .enumerate()
        .map(|(i, env)| SubTaskState::begin(i % door::NUM_SUBTASKS, env.pose()))
        .collect()
}

struct Ran {
    poses: Vec<f32>,
    actions: Vec<i32>,
    /// Per step and robot: the sub-task and phase acted in, and whether a door sub-task ended.
    subtasks: Vec<i32>,
    phases: Vec<i32>,
    ends: Vec<bool>,
    tasks: Vec<SubTaskState>,
    counters: RunCounters,
}

fn run(b: &mut Batch, tasks: &mut [SubTaskState], steps: usize) -> Ran {
    let n = b.len();
    let mut obs = vec![0.0; n * b.observation_width()];
    let (mut pose, mut colliding, mut crossings) = (vec![0.0; n * 3], vec![false; n], vec![0; n]);
    let (mut poses, mut actions) = (vec![0.0; steps * n * 3], vec![0; steps * n]);
    let options = RunOptions {
        steps,
        max_episode_steps: 300,
        end_at_goal: true,
        end_at_crossing: false,
        autoreset: true,
    };
    let seeds: Vec<u64> = (0..n as u64).collect();
    let out = StepOutputs {
        observations: &mut obs,
        poses: &mut pose,
        colliding: &mut colliding,
        crossings: &mut crossings,
    };
    let (mut subtasks, mut phases, mut ends) = (
        vec![0; steps * n],
        vec![0; steps * n],
        vec![false; steps * n],
    );
    let trace = RunTrace {
        poses: Some(&mut poses),
        actions: Some(&mut actions),
        subtasks: Some(&mut subtasks),
        phases: Some(&mut phases),
        subtask_ends: Some(&mut ends),
        ..Default::default()
    };
    let envs = RunEnvs {
        active: None,
        subtasks: Some(tasks),
    };
    let controller = Controller::Tabular(Box::new(policy()));
    let counters = b
        .run_steps_of(&controller, &seeds, &options, envs, out, trace)
        .unwrap();
    Ran {
        poses,
        actions,
        subtasks,
        phases,
        ends,
        tasks: tasks.to_vec(),
        counters,
    }
}

#[test]
fn door_sub_tasks_run_as_stepped_from_outside() {
    let steps = 200;
    let mut b = batch(2);
    let start = tasks(&b);
    let ran = run(&mut b, &mut start.clone(), steps);

    // From outside: follow the odometry, act from the sub-task's table, step (no episode ends
    // within 200 steps of a 300-step limit unless at the goal, which these mazes keep far).
    let mut outside = batch(1);
    let mut tasks = tasks(&outside);
    let tabular = policy();
    let mut streams: Vec<Rng> = (0..ENVS as u64).map(Rng::new).collect();
    let n = outside.len();
    let mut obs = vec![0.0; n * outside.observation_width()];
    let (mut pose, mut colliding, mut crossings) = (vec![0.0; n * 3], vec![false; n], vec![0; n]);
    let (mut done, mut gave_up) = (0, 0);
    for step in 0..steps {
        let mut speeds = vec![];
        for (i, env) in outside.envs().iter().enumerate() {
            let task = &mut tasks[i];
            let mut ended = false;
            if step > 0 {
                match task.update(env.pose()) {
                    SubTaskEnd::Running => {}
                    end => {
                        done += u64::from(end == SubTaskEnd::Done);
                        gave_up += u64::from(end == SubTaskEnd::GaveUp);
                        *task = SubTaskState::begin(door::CORRIDOR, env.pose());
                        ended = true;
                    }
                }
            }
            let at = step * n + i;
            let acted_in = (ran.subtasks[at], ran.phases[at], ran.ends[at]);
            let expected = (task.subtask as i32, task.phase as i32, ended);
            assert_eq!(acted_in, expected, "step {step}, env {i}");
            let volts = env.distance_sensors();
            let action = tabular.action_in_task(
                task,
                env.pose(),
                volts,
                env.wheel_speeds(),
                &mut streams[i],
            );
            assert_eq!(
                ran.actions[step * n + i],
                action as i32,
                "step {step}, env {i}"
            );
            let max_speed = env.robot().max_wheel_speed;
            speeds.extend(WHEEL_SPEED_FRACTIONS[action].map(|f| (f * max_speed) as f32));
        }
        let out = StepOutputs {
            observations: &mut obs,
            poses: &mut pose,
            colliding: &mut colliding,
            crossings: &mut crossings,
        };
        outside.step(&speeds, out).unwrap();
        assert_eq!(
            ran.poses[step * n * 3..(step + 1) * n * 3],
            pose,
            "step {step}"
        );
    }
    assert_eq!(ran.tasks, tasks, "the states as the call leaves them");
    assert!(ran.counters.episodes_finished.iter().all(|&e| e == 0));
    assert_eq!(ran.counters.subtasks_done.iter().sum::<u64>(), done);
    assert_eq!(ran.counters.subtasks_given_up.iter().sum::<u64>(), gave_up);
    assert!(done > 0, "door sub-tasks reached their end");
    let in_doors = |t: &[SubTaskState]| t.iter().filter(|t| t.subtask != door::CORRIDOR).count();
    assert!(in_doors(&ran.tasks) < in_doors(&start));
}

#[test]
fn door_sub_tasks_do_not_depend_on_threads_or_the_split_in_calls() {
    let mut whole_batch = batch(1);
    let mut whole_tasks = tasks(&whole_batch);
    let whole = run(&mut whole_batch, &mut whole_tasks, 160);
    let mut split_batch = batch(3);
    let mut split_tasks = tasks(&split_batch);
    let first = run(&mut split_batch, &mut split_tasks, 70);
    // The caller follows the last step of a call before the next (as the navigator's act does).
    for (task, env) in split_tasks.iter_mut().zip(split_batch.envs()) {
        if task.update(env.pose()) != SubTaskEnd::Running {
            *task = SubTaskState::begin(door::CORRIDOR, env.pose());
        }
    }
    let second = run(&mut split_batch, &mut split_tasks, 90);
    assert_eq!(whole.poses[..70 * ENVS * 3], first.poses[..]);
    assert_eq!(whole.poses[70 * ENVS * 3..], second.poses[..]);
    assert_eq!(whole.actions[70 * ENVS..], second.actions[..]);
    assert_eq!(whole.tasks, second.tasks);
}
