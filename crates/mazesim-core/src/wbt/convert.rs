//! An import as a mazesim world description: boxes become `[[walls]]`, circles become rings of
//! thin walls (the world format has boxes only), the e-puck's pose becomes `[start]`, floor
//! textures become `[[paint]]` rectangles.

use std::f64::consts::PI;

use super::shapes::snap;
use super::{Look, Obstacle, WbtImport};
use crate::error::{Error, Location, Result};
use crate::world::spec::{FloorSpec, StartSpec, WallSpec, WorldSpec};
use crate::world::values::{
    self, Finite, FormatTag, FormatVersion, Positive, Reflectance, WORLD_FORMAT_TAG,
    WORLD_FORMAT_VERSION,
};
use crate::World;

/// Largest distance (metres) between a circle and the polygon that stands in for it.
const POLYGON_TOLERANCE: f64 = 5e-4;
/// Fewest and most sides of that polygon.
const POLYGON_SIDES: (usize, usize) = (8, 256);
/// Thickness of the polygon's walls (thinner circles are filled to the centre).
const RING_THICKNESS: f64 = 0.01;

/// The number of sides of a regular polygon within [`POLYGON_TOLERANCE`] of a circle.
pub fn polygon_sides(radius: f64) -> usize {
    let (fewest, most) = POLYGON_SIDES;
    (fewest..=most)
        .find(|&n| {
            let half_angle = PI / n as f64;
            // The polygon straddles the circle: apothem below it, corners above it.
            radius * (1.0 - half_angle.cos()) / (1.0 + half_angle.cos()) <= POLYGON_TOLERANCE
        })
        .unwrap_or(most)
}

fn wall(center: [f64; 2], size: [f64; 2], yaw: f64, look: Look) -> WallSpec {
    WallSpec {
        center: [Finite(center[0]), Finite(center[1])],
        size: [Positive(size[0]), Positive(size[1])],
        yaw: Finite(yaw),
        reflectance: Reflectance(look.reflectance),
        colour: look.colour.map(values::colour),
        height: None,
        sensed_only: false,
    }
}

/// A ring of walls whose outline is a regular polygon straddling the circle: its apothem lies
/// as far inside the circle as its corners lie outside.
pub fn circle_walls(center: [f64; 2], radius: f64, look: Look) -> Vec<WallSpec> {
    let n = polygon_sides(radius);
    let half_angle = PI / n as f64;
    let apothem = 2.0 * radius * half_angle.cos() / (1.0 + half_angle.cos());
    let thickness = RING_THICKNESS.min(apothem);
    let side = 2.0 * apothem * half_angle.tan();
    (0..n)
        .map(|k| {
            let angle = 2.0 * PI * k as f64 / n as f64;
            let (s, c) = angle.sin_cos();
            let distance = apothem - thickness / 2.0;
            wall(
                [center[0] + c * distance, center[1] + s * distance],
                [thickness, side],
                angle,
                look,
            )
        })
        .collect()
}

/// Per obstacle, its first wall (counted from `first`) and how many walls it is: a box is one,
/// a circle a ring of `polygon_sides`.
fn walls_of(obstacles: &[Obstacle], mut first: usize) -> Vec<(usize, usize)> {
    obstacles
        .iter()
        .map(|obstacle| {
            let count = match *obstacle {
                Obstacle::Box { .. } => 1,
                Obstacle::Circle { radius, .. } => polygon_sides(radius),
            };
            first += count;
            (first - count, count)
        })
        .collect()
}

impl WbtImport {
    /// Per obstacle, its first wall among the world's `[[walls]]` (`to_spec`'s, in order) and
    /// how many walls it is: a box is one, a circle a ring of `polygon_sides`.
    pub fn obstacle_walls(&self) -> Vec<(usize, usize)> {
        walls_of(&self.obstacles, 0)
    }

    /// Per sensed-only obstacle, its first wall among the world's `[[walls]]` (after every
    /// solid obstacle's, as `to_spec` lays them) and how many walls it is.
    pub fn sensed_walls(&self) -> Vec<(usize, usize)> {
        let solid = self
            .obstacle_walls()
            .last()
            .map_or(0, |&(first, n)| first + n);
        walls_of(&self.sensed_obstacles, solid)
    }

    /// The mazesim world description of this import.
    pub fn to_spec(&self, name: &str) -> WorldSpec {
        // The solid obstacles first (`obstacle_walls` counts them), then the sensed-only ones.
        let solid = (self.obstacles.iter().enumerate())
            .map(|(i, o)| (o, &self.obstacle_looks, &self.obstacle_tops, i, false));
        let sensed = (self.sensed_obstacles.iter().enumerate())
            .map(|(i, o)| (o, &self.sensed_looks, &self.sensed_tops, i, true));
        let mut walls = Vec::new();
        for (obstacle, looks, tops, i, sensed_only) in solid.chain(sensed) {
            let look = looks.get(i).copied().unwrap_or(Look::UNREAD);
            let top = tops.get(i).copied().filter(|t| t.is_finite() && *t > 0.0);
            let first = walls.len();
            match *obstacle {
                Obstacle::Box { center, size, yaw } => walls.push(wall(center, size, yaw, look)),
                Obstacle::Circle { center, radius } => {
                    walls.extend(circle_walls(center, radius, look))
                }
            }
            for w in &mut walls[first..] {
                w.sensed_only = sensed_only;
                w.height = top.map(|t| Positive(snap(t)));
            }
        }
        WorldSpec {
            format: FormatTag(WORLD_FORMAT_TAG.to_string()),
            version: FormatVersion(WORLD_FORMAT_VERSION),
            name: name.to_string(),
            basic_time_step_ms: Positive(self.basic_time_step_ms),
            floor: self.floor_colour.map(|colour| FloorSpec {
                reflectance: Reflectance(self.floor_reflectance.unwrap_or(1.0)),
                colour: Some(values::colour(colour)),
            }),
            start: self.robot.map(|[x, y, yaw]| StartSpec {
                x: Finite(x),
                y: Finite(y),
                yaw: Finite(yaw),
            }),
            robots: Vec::new(),
            goal: None,
            grid: None,
            barcode: None,
            walls,
            segments: Vec::new(),
            paint: self.paint.clone(),
            checkpoints: Vec::new(),
            bodies: self.bodies.clone(),
        }
    }

    /// The mazesim world of this import, named `name` (which also names it in messages).
    pub fn to_world(&self, name: &str) -> Result<World> {
        self.to_world_of(name, name)
    }

    /// The mazesim world of this import of the file `source`, named `name`. A world mazesim
    /// refuses (more walls crowded together than its limits allow...) is a format error of
    /// `source` as a whole, saying what was refused: the world text it was checked as is made
    /// here, so a line of it would point nowhere the user can look.
    pub fn to_world_of(&self, name: &str, source: &str) -> Result<World> {
        World::from_spec(self.to_spec(name), name).map_err(|error| match error {
            Error::Format { field, message, .. } => Error::Format {
                location: Location::whole(source),
                field: format!("(imported world).{field}"),
                message,
            },
            other => other,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_circle_becomes_a_closed_ring_within_tolerance() {
        assert_eq!(polygon_sides(0.005), 8);
        assert_eq!(polygon_sides(1e6), 256);
        for radius in [0.02, 0.05, 0.3] {
            let walls = circle_walls([1.0, 2.0], radius, Look::UNREAD);
            let n = walls.len();
            let half_angle = PI / n as f64;
            let apothem = 2.0 * radius * half_angle.cos() / (1.0 + half_angle.cos());
            let corner = apothem / half_angle.cos();
            assert!(radius - apothem <= POLYGON_TOLERANCE + 1e-12);
            assert!(corner - radius <= POLYGON_TOLERANCE + 1e-12);
            for w in &walls {
                // The outer face of every wall lies on the apothem.
                let d = (w.center[0].0 - 1.0).hypot(w.center[1].0 - 2.0) + w.size[0].0 / 2.0;
                assert!((d - apothem).abs() < 1e-12);
            }
        }
    }
}
