//! The robots a world places: one at `[start]` (or the origin), or several listed in
//! `[[robots]]`, each with a unique name, a start pose and optionally a built-in profile.

use super::extent::{ExtentCheck, Place};
use super::spec::{CarriedSpec, RobotSpec};
use crate::error::Result;
use crate::limits::MAX_ROBOTS;

/// How far from a robot's centre a shape it carries may reach, metres.
pub const CARRIED_REACH: f64 = 0.5;

/// The most shapes one robot carries.
pub const MAX_CARRIED: usize = 16;

/// A shape a robot carries beside its body, in the robot's frame (x ahead, y to its left): a
/// box of half extents `half` turned by `yaw`, or, with `radius` above zero, an upright
/// cylinder. The other robots' infra-red rays meet it with its `reflectance` and their bodies
/// are held back by it, as Webots' rays meet every Shape a robot holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CarriedShape {
    /// Centre in the robot's frame, metres.
    pub center: [f32; 2],
    /// A box's half extents along its own axes, metres.
    pub half: [f32; 2],
    /// A box's rotation in the robot's frame, radians.
    pub yaw: f32,
    /// A cylinder's radius, metres; 0 for a box.
    pub radius: f32,
    /// Infra-red reflection factor.
    pub reflectance: f32,
}

impl CarriedShape {
    /// The farthest point of the shape from the robot's centre, metres.
    pub fn reach(&self) -> f32 {
        let [x, y] = self.center;
        let size = if self.radius > 0.0 {
            self.radius
        } else {
            (self.half[0] * self.half[0] + self.half[1] * self.half[1]).sqrt()
        };
        (x * x + y * y).sqrt() + size
    }
}

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
    /// The shapes it carries beside its body (none for a robot of its body alone).
    pub carried: Vec<CarriedShape>,
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
            carried: Vec::new(),
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
        let carried = carried_shapes(&r.carried, check, place, &field("carried"))?;
        placements.push(RobotPlacement {
            name: r.name.clone(),
            start: [r.x.get(), r.y.get(), r.yaw.get()],
            profile: r.profile.clone(),
            carried,
        });
    }
    Ok(placements)
}

/// Checks and converts a robot's `carried` shapes: at most [`MAX_CARRIED`], each a box or a
/// cylinder (not both, not neither) within [`CARRIED_REACH`] of the robot's centre.
fn carried_shapes(
    specs: &[CarriedSpec],
    check: &ExtentCheck<'_>,
    place: Place<'_>,
    field: &str,
) -> Result<Vec<CarriedShape>> {
    if specs.len() > MAX_CARRIED {
        return Err(check.refused(
            place,
            field,
            format!(
                "expected at most {MAX_CARRIED} carried shapes, found {}",
                specs.len()
            ),
        ));
    }
    let mut shapes = Vec::with_capacity(specs.len());
    for (k, s) in specs.iter().enumerate() {
        let [x, y] = [s.center[0].get() as f32, s.center[1].get() as f32];
        let (half, radius) = match (&s.size, &s.radius) {
            (Some(size), None) => (
                [size[0].get() as f32 / 2.0, size[1].get() as f32 / 2.0],
                0.0,
            ),
            (None, Some(r)) => ([0.0; 2], r.get() as f32),
            _ => {
                return Err(check.refused(
                    place,
                    &format!("{field}[{k}]"),
                    "expected either size (a box) or radius (a cylinder)".to_string(),
                ))
            }
        };
        let shape = CarriedShape {
            center: [x, y],
            half,
            yaw: s.yaw.get() as f32,
            radius,
            reflectance: s.reflectance.get() as f32,
        };
        if f64::from(shape.reach()) > CARRIED_REACH {
            return Err(check.refused(
                place,
                &format!("{field}[{k}]"),
                format!(
                    "expected a shape within {CARRIED_REACH} m of the robot's centre, found \
                     one reaching {:.3} m",
                    shape.reach()
                ),
            ));
        }
        shapes.push(shape);
    }
    Ok(shapes)
}
