//! A robot saved with its body in a wall (a world saved mid-run, a start pose written by a
//! script): Webots' physics pushes the body out at the first steps, so the import starts the
//! robot at the nearest pose clear of the walls, with a warning.

use super::WbtImport;
use crate::robot::RobotProfile;
use crate::simulator::{pushed_out, wall_overlap, START_OVERLAP};

impl WbtImport {
    /// Moves each e-puck's start whose body overlaps a wall by more than the simulator accepts
    /// (`START_OVERLAP`) to the nearest pose clear of the walls (`pushed_out`),
    /// warning once per robot moved. A robot that is not an e-puck keeps its pose: the e-puck
    /// that stands in for it has no body among the walls.
    pub(super) fn push_starts_out_of_walls(&mut self) {
        if self.robots.iter().all(|r| r.profile.is_none()) {
            return;
        }
        let Ok(world) = self.to_world("start poses") else {
            return; // the world is refused: the import's own world says why
        };
        let radius = |profile: &str| RobotProfile::builtin(profile).map(|p| p.body_radius);
        let run_robot_is_epuck =
            (self.robots.iter()).any(|r| Some(r.line) == self.robot_line && r.profile.is_some());
        let mut moved = Vec::new();
        if let (Some(pose), Ok(r), true) =
            (self.robot, radius(&self.robot_profile), run_robot_is_epuck)
        {
            if let Some((clear, depth)) = clear_pose(&world, r, pose) {
                moved.push((self.robot_line, pose, clear, depth));
                self.robot = Some(clear);
            }
        }
        for robot in &mut self.robots {
            let Some(Ok(r)) = robot.profile.map(radius) else {
                continue;
            };
            if let Some((clear, depth)) = clear_pose(&world, r, robot.pose) {
                if Some(robot.line) != self.robot_line {
                    moved.push((Some(robot.line), robot.pose, clear, depth));
                }
                robot.pose = clear;
            }
        }
        for (line, [x, y, _], [cx, cy, _], depth) in moved {
            let place = line.map_or_else(String::new, |l| format!("line {l}: "));
            self.warnings.push(format!(
                "{place}the robot is saved at ({x:.4}, {y:.4}) with its body {depth:.4} m into a wall, which Webots' physics pushes it out of at the first steps: it starts at ({cx:.4}, {cy:.4}), the nearest pose clear of the walls"
            ));
        }
    }
}

/// The nearest pose clear of the walls for a body of `radius` saved at `pose`, with how deep
/// the saved body lies in a wall; `None` when it is clear already or no pose within
/// `PUSH_OUT_LIMIT_MM` is.
fn clear_pose(world: &crate::World, radius: f64, pose: [f64; 3]) -> Option<([f64; 3], f64)> {
    let [x, y, yaw] = pose;
    let (depth, _) = wall_overlap(world, radius, [x, y]);
    if depth <= START_OVERLAP {
        return None;
    }
    let [cx, cy] = pushed_out([x, y], |p| {
        wall_overlap(world, radius, p).0 <= START_OVERLAP
    })?;
    Some(([cx, cy, yaw], depth))
}
