//! A batch of worlds of several robots: `Batch` with a robot axis. Its simulators are the robots
//! of every environment, environment after environment, and its buffers hold one row per robot,
//! `(envs, robots, ...)` in memory order; every environment's robots are stepped together on one
//! thread (`step_robots`), so results do not depend on the thread count or the batch size.

use std::sync::atomic::AtomicU64;
use std::sync::Arc;

use super::snapshot::{restored_robots, snapshot_robots};
use super::{make_robots, reset_robots, step_robots};
use crate::batch::{
    check_actions, check_seeds, check_size, rigs_of, Batch, Helpers, StepOutputs, CHUNK_ENVS,
};
use crate::control::Controller;
use crate::error::{Error, Result};
use crate::limits::MAX_ROBOTS;
use crate::rng::Rng;
use crate::robot::RobotProfile;
use crate::simulator::{Rig, SimConfig, Simulator};
use crate::world::World;

impl Batch {
    /// One environment per world, each with every robot its world places (`World::robots`):
    /// robot `i` of an environment with the profile its placement names, else `robot`, and its
    /// noise stream of the environment's seed (`crate::swarm::robot_seed`). Every world must
    /// place as many robots, every profile have the sensors of `robot`. A batch of worlds of one
    /// robot is [`Batch::new`]'s. `threads` as for [`Batch::new`].
    pub fn with_swarms(
        worlds: Vec<Arc<World>>,
        robot: Arc<RobotProfile>,
        seeds: &[u64],
        noise: bool,
        control_step: Option<f64>,
        threads: usize,
    ) -> Result<Batch> {
        let Some(first) = worlds.first() else {
            return Err(Error::InvalidArgument(
                "expected at least one environment, found 0".into(),
            ));
        };
        let robots = first.robots().len();
        if let Some((i, w)) = (worlds.iter().enumerate()).find(|(_, w)| w.robots().len() != robots)
        {
            return Err(Error::InvalidArgument(format!(
                "expected every world of the batch to place {robots} robots (as the first), found \
                 {} in world {i} ({:?})",
                w.robots().len(),
                w.name()
            )));
        }
        if robots == 1 {
            return Batch::new(worlds, robot, seeds, noise, control_step, threads);
        }
        check_seeds(worlds.len(), seeds)?;
        let n = worlds.len();
        // An environment of a world with movable bodies holds a rapier scene of all its walls.
        let scene_walls: u128 = (worlds.iter())
            .filter(|w| !w.bodies().is_empty())
            .map(|w| w.solid_walls().len() as u128)
            .sum();
        check_size(n.saturating_mul(robots), scene_walls)?;
        let worlds = crate::batch::share_equal_worlds(worlds);
        // The profiles named anywhere, each made once, then one rig per distinct profile.
        let mut profiles: Vec<Arc<RobotProfile>> = vec![robot.clone()];
        for placement in worlds.iter().flat_map(|w| w.robots()) {
            if let Some(name) = &placement.profile {
                if !profiles.iter().any(|p| &p.name == name) {
                    profiles.push(Arc::new(RobotProfile::builtin(name)?));
                }
            }
        }
        let rigs = rigs_of(&profiles, profiles.len())?;
        let rig_of = |name: &Option<String>| -> Arc<Rig> {
            let i = name
                .as_ref()
                .and_then(|n| profiles.iter().position(|p| &p.name == n))
                .unwrap_or(0);
            rigs[i].clone()
        };
        let helpers = Helpers::new(threads)?;
        let make = |(world, seed): (Arc<World>, u64)| -> Result<Vec<Simulator>> {
            let env_rigs: Vec<Arc<Rig>> =
                world.robots().iter().map(|p| rig_of(&p.profile)).collect();
            let config = SimConfig {
                seed,
                noise,
                control_step,
            };
            make_robots(&world, &env_rigs, config)
        };
        let pairs: Vec<(Arc<World>, u64)> = worlds.into_iter().zip(seeds.iter().copied()).collect();
        let groups = helpers.make_all(pairs, make)?;
        let envs: Vec<Simulator> = groups.into_iter().flatten().collect();
        Ok(Batch::assemble(envs, robots, &robot, helpers))
    }

    /// Robots per environment (1 in a batch of worlds of one robot).
    pub fn robots_per_env(&self) -> usize {
        self.robots
    }

    /// Number of environments (each of `robots_per_env` robots).
    pub fn num_envs(&self) -> usize {
        self.envs.len() / self.robots
    }

    /// Runs `work` on every environment's robots with their rows of `out`, environments in chunks
    /// on the calling thread and the helpers (as `Batch::run` does for single robots).
    fn run_groups<'a, F>(&'a mut self, out: StepOutputs<'a>, work: F) -> Result<()>
    where
        F: Fn(usize, &mut [Simulator], &mut dyn FnMut(&Simulator, usize)) + Sync + Send,
    {
        let r = self.robots;
        let width = self.observation_width();
        let dw = self.distance_width;
        let per_chunk = CHUNK_ENVS * r;
        let chunks = move |envs: &'a mut [Simulator]| {
            let StepOutputs {
                observations,
                poses,
                colliding,
                crossings,
            } = out;
            envs.chunks_mut(per_chunk)
                .zip(observations.chunks_mut(per_chunk * width))
                .zip(poses.chunks_mut(per_chunk * 3))
                .zip(colliding.chunks_mut(per_chunk))
                .zip(crossings.chunks_mut(per_chunk))
                .map(|((((e, o), p), c), x)| {
                    (
                        e,
                        StepOutputs {
                            observations: o,
                            poses: p,
                            colliding: c,
                            crossings: x,
                        },
                    )
                })
                .enumerate()
        };
        self.par_chunks(chunks, |(k, (envs, out)), stop| {
            let mut rows: Vec<_> = out.rows(width, dw).map(Some).collect();
            for (j, group) in envs.chunks_mut(r).enumerate() {
                if stop() {
                    return;
                }
                let mut write = |robot: &Simulator, i: usize| {
                    if let Some(row) = rows[j * r + i].take() {
                        row.write(robot);
                    }
                };
                work(k * CHUNK_ENVS + j, group, &mut write);
            }
        })
    }

    /// Steps every environment's robots together with `actions` (`(envs, robots, 2)` wheel speeds
    /// in rad/s) and writes every robot's row of `out`. Non-finite speeds are refused before any
    /// robot moves.
    pub fn step_swarms(&mut self, actions: &[f32], out: StepOutputs<'_>) -> Result<()> {
        let r = self.robots;
        check_actions(actions, self.num_envs(), r)?;
        self.check_outputs(&out)?;
        self.run_groups(out, |e, group, write| {
            let base = 2 * r * e;
            let _ = step_robots(group, |i| {
                let a = base + 2 * i;
                [actions[a] as f64, actions[a + 1] as f64]
            });
            for (i, robot) in group.iter().enumerate() {
                write(robot, i);
            }
        })
    }

    /// Resets the environments where `mask` is true (all without one, `(envs,)`), each with its
    /// new seed from `seeds` (`(envs,)`) when given, and writes their robots' rows of `out`.
    pub fn reset_swarms(
        &mut self,
        mask: Option<&[bool]>,
        seeds: Option<&[u64]>,
        out: StepOutputs<'_>,
    ) -> Result<()> {
        let n = self.num_envs();
        for (what, len) in [
            ("reset mask", mask.map(<[bool]>::len)),
            ("reset seeds", seeds.map(<[u64]>::len)),
        ] {
            if let Some(len) = len.filter(|&len| len != n) {
                return Err(Error::InvalidArgument(format!(
                    "expected {what} of {n} values (one per environment), found {len}"
                )));
            }
        }
        self.check_outputs(&out)?;
        self.run_groups(out, |e, group, write| {
            if mask.is_none_or(|m| m[e]) {
                let names: Vec<String> = group[0]
                    .world()
                    .robots()
                    .iter()
                    .map(|p| p.name.clone())
                    .collect();
                reset_robots(group, &names, seeds.map(|s| s[e]));
                for (i, robot) in group.iter().enumerate() {
                    write(robot, i);
                }
            }
        })
    }

    /// The robots of environment `index` (a range of `envs`), or an error naming the valid
    /// indices.
    pub(crate) fn group(&self, index: usize) -> Result<std::ops::Range<usize>> {
        let (n, r) = (self.num_envs(), self.robots);
        if index >= n {
            return Err(Error::InvalidArgument(format!(
                "expected an environment index below {n}, found {index}"
            )));
        }
        Ok(index * r..(index + 1) * r)
    }

    /// Environment `index` of a batch of worlds of several robots as bytes, laid out as a
    /// simulator of its world saves them (`crate::swarm::snapshot`), every robot's wheel command
    /// zero: a batch keeps no command from step to step.
    pub fn snapshot_swarm(&self, index: usize) -> Result<Vec<u8>> {
        let group = self.group(index)?;
        Ok(snapshot_robots(
            &self.envs[group],
            &vec![[0.0; 2]; self.robots],
        ))
    }

    /// Puts environment `index` of a batch of worlds of several robots in the state of a
    /// [`Batch::snapshot_swarm`] (or a simulator's snapshot) of the same world, profiles, control
    /// step and noise setting; the wheel commands it holds are checked, then left (a batch
    /// takes every robot's at each step). A refused snapshot changes nothing.
    pub fn restore_swarm(&mut self, index: usize, snapshot: &[u8]) -> Result<()> {
        let group = self.group(index)?;
        let names: Vec<String> = (self.envs[group.start].world().robots().iter())
            .map(|p| p.name.clone())
            .collect();
        let (robots, _) = restored_robots(&self.envs[group.clone()], &names, snapshot)?;
        self.envs.splice(group, robots);
        Ok(())
    }

    /// Runs `steps` control steps of every environment, each robot's wheel speeds from
    /// `controller` on its own readings (Braitenberg or avoid-collision), and writes every
    /// robot's row of `out` after the last; returns the control steps each robot spent touching
    /// a wall or another robot, `(envs, robots)`.
    pub fn run_swarms(
        &mut self,
        controller: &Controller,
        steps: usize,
        max_speed: f64,
        out: StepOutputs<'_>,
    ) -> Result<Vec<u64>> {
        if !matches!(
            controller,
            Controller::Braitenberg | Controller::AvoidCollision(_)
        ) {
            return Err(Error::InvalidArgument(format!(
                "expected the braitenberg or avoid-collision controller in a world of several \
                 robots, found {:?}",
                controller.name()
            )));
        }
        for env in self.envs.iter() {
            controller.check(env.robot(), 1)?;
        }
        self.check_outputs(&out)?;
        let r = self.robots;
        let contacts: Vec<std::sync::atomic::AtomicU64> =
            (0..self.envs.len()).map(|_| AtomicU64::new(0)).collect();
        self.run_groups(out, |e, group, write| {
            let mut unused = Rng::new(0);
            let mut wheels = [[0.0f64; 2]; MAX_ROBOTS];
            for _ in 0..steps {
                for (i, robot) in group.iter().enumerate() {
                    let decision = controller.decide(
                        e * r + i,
                        robot.distance_sensors(),
                        robot.wheel_speeds(),
                        max_speed,
                        &mut unused,
                        None,
                    );
                    wheels[i] = decision.wheel_speeds.map(f64::from);
                }
                let _ = step_robots(group, |i| wheels[i]);
                for (i, robot) in group.iter().enumerate() {
                    if robot.colliding() {
                        contacts[e * r + i].fetch_add(1, std::sync::atomic::Ordering::Relaxed);
                    }
                }
            }
            for (i, robot) in group.iter().enumerate() {
                write(robot, i);
            }
        })?;
        Ok(contacts.into_iter().map(AtomicU64::into_inner).collect())
    }
}
