//! Movable rigid bodies: boxes and discs the robot can push, compiled from `[[bodies]]`.

use super::extent::{ExtentCheck, Place};
use super::geometry::Bounds;
use super::spec::BodySpec;
use super::values::xy;
use crate::error::Result;

/// The footprint of a movable body, seen from above.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum BodyShape {
    /// A box of these half extents along its own axes, metres.
    Box {
        /// Half extents.
        half: [f64; 2],
    },
    /// A disc of this radius, metres.
    Circle {
        /// Radius.
        radius: f64,
    },
}

/// A movable rigid body at its start pose.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovableBody {
    /// Footprint.
    pub shape: BodyShape,
    /// Start pose (x, y, yaw).
    pub start: [f64; 3],
    /// Mass in kilograms.
    pub mass: f64,
    /// Coefficient of friction with the floor (see `physics` for the model).
    pub friction: f64,
    /// Infra-red reflection factor.
    pub reflectance: f64,
}

impl MovableBody {
    /// The box around the body at its start pose.
    pub fn bounds(&self) -> Bounds {
        let [x, y, yaw] = self.start;
        let reach = match self.shape {
            BodyShape::Box { half } => {
                let (s, c) = yaw.sin_cos();
                [
                    (c * half[0]).abs() + (s * half[1]).abs(),
                    (s * half[0]).abs() + (c * half[1]).abs(),
                ]
            }
            BodyShape::Circle { radius } => [radius, radius],
        };
        Bounds {
            min: [x - reach[0], y - reach[1]],
            max: [x + reach[0], y + reach[1]],
        }
    }
}

/// Compiles `[[bodies]]`, checking their count, angles and extent against `crate::limits`.
pub(super) fn compile(specs: &[BodySpec], check: &ExtentCheck<'_>) -> Result<Vec<MovableBody>> {
    check.body_count(specs.len())?;
    let mut bodies = Vec::with_capacity(specs.len());
    for (i, spec) in specs.iter().enumerate() {
        let field = format!("bodies[{i}]");
        let place = Place::Array("bodies", i);
        let body = match spec {
            BodySpec::Box {
                center,
                size,
                yaw,
                mass,
                friction,
                reflectance,
            } => {
                check.angle(place, &format!("{field}.yaw"), yaw.get())?;
                let [x, y] = xy(center);
                MovableBody {
                    shape: BodyShape::Box {
                        half: [size[0].get() / 2.0, size[1].get() / 2.0],
                    },
                    start: [x, y, yaw.get()],
                    mass: mass.get(),
                    friction: friction.get(),
                    reflectance: reflectance.get(),
                }
            }
            BodySpec::Circle {
                center,
                radius,
                mass,
                friction,
                reflectance,
            } => {
                let [x, y] = xy(center);
                MovableBody {
                    shape: BodyShape::Circle {
                        radius: radius.get(),
                    },
                    start: [x, y, 0.0],
                    mass: mass.get(),
                    friction: friction.get(),
                    reflectance: reflectance.get(),
                }
            }
        };
        check.within(place, &field, body.bounds())?;
        bodies.push(body);
    }
    Ok(bodies)
}
