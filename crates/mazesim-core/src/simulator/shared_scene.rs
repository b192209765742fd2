//! Several robots in one rapier scene: how a world of several robots with movable bodies is
//! stepped. Robot 0's body holds the scene (every robot's ball, the walls and the movable
//! bodies); the other robots' bodies follow the poses it gives them. Each physics step, every
//! robot's driven velocity is first held back by the other robots at their poses before the step
//! (as among walls alone, so that a robot cannot shove another), then rapier moves all the robots
//! and the bodies together: robots push bodies, bodies push robots, and nothing goes through a
//! wall. Every robot's rays meet the movable bodies of that one scene.

use std::sync::Arc;

use super::{Drive, Others, Simulator};
use crate::physics::Body;
use crate::world::World;

impl Simulator {
    /// Whether this robot is one of several in one rapier scene (see the module notes).
    pub fn in_shared_scene(&self) -> bool {
        self.body.is_shared()
    }

    /// Takes `world` (nodes a supervisor imported or removed, robots among them) with a body of
    /// its own at its pose, at rest, among the world's walls and its movable bodies at their
    /// starts; `share_scene` then puts it into one scene with the others where there are several.
    pub(crate) fn join_world(&mut self, world: Arc<World>) {
        self.world = world;
        let radius = self.rig.drivetrain.body_radius;
        let (walls, bodies) = (self.world.solid_walls(), self.world.bodies());
        self.body = Body::new(walls, bodies, radius, self.pose, self.dt as f32);
        self.pose = self.body.pose();
        self.heading = self.body.heading();
        self.update_contact();
    }

    /// Takes the clock of the robots it joins: `time` seconds and `steps` control steps.
    pub(crate) fn join_clock(&mut self, time: f64, steps: u64) {
        self.time = time;
        self.steps = steps;
    }
}

/// Puts `robots`, the robots of one world with movable bodies, into one rapier scene at their
/// current poses, every movable body at its start.
pub fn share_scene(robots: &mut [Simulator]) {
    let Some(first) = robots.first() else {
        return;
    };
    let world = first.world.clone();
    let dt = first.dt as f32;
    let placed: Vec<(f32, [f32; 3])> = (robots.iter())
        .map(|r| (r.rig.drivetrain.body_radius, r.pose))
        .collect();
    let bodies = Body::shared(world.solid_walls(), world.bodies(), &placed, dt);
    for (robot, body) in robots.iter_mut().zip(bodies) {
        robot.body = body;
        robot.pose = robot.body.pose();
        robot.heading = robot.body.heading();
    }
}

/// Puts robot `index` of robots sharing a scene where its pose says, at rest (after `set_pose`).
pub fn place_in_scene(robots: &mut [Simulator], index: usize) {
    if index > 0 && index < robots.len() {
        let pose = robots[index].pose;
        robots[0].body.place_robot(index, pose);
    }
}

/// Reusable lists of one physics step in a shared scene.
#[derive(Default)]
pub struct SceneStep {
    motions: Vec<([f32; 2], f32)>,
    poses: Vec<[f32; 3]>,
}

/// One physics step of robots sharing a scene: robot `i` driven by `drives[i]`, held back by
/// `others(i)`, the robots at their poses before the step; `before` receives those poses.
pub fn move_in_scene<'a>(
    robots: &mut [Simulator],
    drives: &[Drive],
    others: impl Fn(usize, &Simulator) -> Others<'a>,
    before: &mut Vec<[f32; 3]>,
    work: &mut SceneStep,
) {
    before.clear();
    work.motions.clear();
    for (i, (robot, drive)) in robots.iter().zip(drives).enumerate() {
        before.push(robot.pose);
        let (linear, angular, held) = robot.driven(drive, others(i, robot));
        let [s, c] = robot.heading;
        work.motions
            .push((held.unwrap_or([c * linear, s * linear]), angular));
    }
    robots[0].body.step_shared(&work.motions, &mut work.poses);
    for (robot, &pose) in robots.iter_mut().zip(&work.poses) {
        robot.body.follow(pose);
        robot.pose = robot.body.pose();
        robot.heading = robot.body.heading();
    }
}
