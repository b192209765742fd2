//! The robots a world places: one at `[start]` (or the origin), or several listed in
//! `[[robots]]`, each with a unique name, a start pose and optionally a built-in profile.

use super::extent::{ExtentCheck, Place};
use super::spec::RobotSpec;
use crate::error::Result;
use crate::limits::MAX_ROBOTS;

/// The name of the one robot of a world written with `[start]`.
pub const SINGLE_ROBOT_NAME: &str = "robot";

/// One robot of a world: where it starts and which profile it is.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotPlacement {
    /// Its name, unique in the world.
    pub name: String,
    /// Start pose (x, y, yaw).
    pub start: [f64; 3],
    /// A built-in profile's name, or `None` for the simulator's profile.
    pub profile: Option<String>,
}

/// Compiles `[[robots]]` (checking the count, names, poses and profiles); `start` is the pose
/// of a world without them, which then holds one robot.
pub(super) fn compile(
    specs: &[RobotSpec],
    start: [f64; 3],
    has_start: bool,
    check: &ExtentCheck<'_>,
) -> Result<Vec<RobotPlacement>> {
    if specs.is_empty() {
        return Ok(vec![RobotPlacement {
            name: SINGLE_ROBOT_NAME.to_string(),
            start,
            profile: None,
        }]);
    }
    if has_start {
        return Err(check.refused(
            Place::Table("start"),
            "start",
            "expected either [start] (one robot) or [[robots]] (each robot's start), found both"
                .to_string(),
        ));
    }
    if specs.len() > MAX_ROBOTS {
        return Err(check.refused(
            Place::Array("robots", MAX_ROBOTS),
            "robots",
            format!(
                "expected at most {MAX_ROBOTS} robots, found {}",
                specs.len()
            ),
        ));
    }
    let names = crate::robot::robot_profile_names();
    let mut placements: Vec<RobotPlacement> = Vec::with_capacity(specs.len());
    for (i, r) in specs.iter().enumerate() {
        let place = Place::Array("robots", i);
        let field = |f: &str| format!("robots[{i}].{f}");
        if r.name.is_empty() || placements.iter().any(|p| p.name == r.name) {
            return Err(check.refused(
                place,
                &field("name"),
                format!(
                    "expected a non-empty robot name unique in the world, found {:?}",
                    r.name
                ),
            ));
        }
        check.point(place, &field("x"), [r.x.get(), r.y.get()])?;
        check.angle(place, &field("yaw"), r.yaw.get())?;
        if let Some(p) = &r.profile {
            if !names.iter().any(|n| n == p) {
                return Err(check.refused(
                    place,
                    &field("profile"),
                    format!(
                        "expected a built-in robot profile ({}), found {p:?}; a world names \
                         built-in profiles only: a profile file is given to the run instead, \
                         as --robot FILE of the mazesim commands (every robot without a \
                         profile of its own) or, for one robot, \
                         Simulator(world, robot_profiles=[RobotProfile.load(FILE), None, ...])",
                        names.join(", ")
                    ),
                ));
            }
        }
        placements.push(RobotPlacement {
            name: r.name.clone(),
            start: [r.x.get(), r.y.get(), r.yaw.get()],
            profile: r.profile.clone(),
        });
    }
    Ok(placements)
}
