//! Moving a group of a world's walls while it runs: an imported object a supervisor moves (a
//! Solid kept as static walls, a robot kept as an obstacle) takes its walls along.

use std::f64::consts::PI;

use super::spec::PaintSpec;
use super::values::{Finite, Point};
use super::{distinct, fingerprint_of, FloorPaint, PaintShape, World};
use crate::error::{Error, Result};
use crate::world::{SensedWalls, WallIndex};

/// The rigid motion of the plane that takes the pose `from` (x, y, yaw) to the pose `to`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Motion {
    /// The pose moved from.
    pub from: [f64; 3],
    /// The pose moved to.
    pub to: [f64; 3],
}

impl Motion {
    /// Where the motion takes the pose `pose` (x, y, yaw; the yaw kept in (-pi, pi] when it was).
    pub fn apply(&self, pose: [f64; 3]) -> [f64; 3] {
        let [fx, fy, fyaw] = self.from;
        let [tx, ty, tyaw] = self.to;
        let turn = tyaw - fyaw;
        if turn == 0.0 {
            return [pose[0] - fx + tx, pose[1] - fy + ty, pose[2]];
        }
        let (s, c) = turn.sin_cos();
        let (dx, dy) = (pose[0] - fx, pose[1] - fy);
        let mut yaw = pose[2] + turn;
        if yaw > PI {
            yaw -= 2.0 * PI * ((yaw + PI) / (2.0 * PI)).floor();
        } else if yaw <= -PI {
            yaw += 2.0 * PI * ((PI - yaw) / (2.0 * PI)).floor();
        }
        [tx + c * dx - s * dy, ty + s * dx + c * dy, yaw]
    }

    /// Checks both poses against the limits (`crate::limits`).
    pub fn check(&self) -> Result<()> {
        let [x, y, yaw] = self.from;
        crate::limits::check_pose("pose moved from", x, y, yaw)?;
        let [x, y, yaw] = self.to;
        crate::limits::check_pose("pose moved to", x, y, yaw)
    }
}

impl World {
    /// This world with the `[[walls]]` entries `walls` (indices into the description's walls)
    /// moved by `motion`: its description, its walls and their index say where they are now;
    /// the rest (floor, bodies, robots, checkpoints) is shared as it was. Refused, naming what
    /// was expected and found: an index past the walls, or a wall moved beyond the limits.
    pub fn with_walls_moved(&self, walls: &[usize], motion: Motion) -> Result<World> {
        motion.check()?;
        let count = self.spec.walls.len();
        if let Some(&bad) = walls.iter().find(|&&i| i >= count) {
            return Err(Error::InvalidArgument(format!(
                "expected wall indices below the world's {count} [[walls]] entries, found {bad}"
            )));
        }
        // The compiled walls: the grid's first, then the solid `[[walls]]`, then `[[segments]]`;
        // the sensed-only `[[walls]]` apart, in their own order.
        let mut every = self.walls().to_vec();
        let solid = self.spec.walls.iter().filter(|w| !w.sensed_only).count();
        let offset = every.len() - solid - self.spec.segments.len();
        let mut sensed = self
            .sensed
            .as_ref()
            .map_or(Vec::new(), |s| s.walls().to_vec());
        let mut spec = self.spec.clone();
        for &i in walls {
            let before = &self.spec.walls[..i];
            let kept_apart = self.spec.walls[i].sensed_only;
            let wall = if kept_apart {
                &mut sensed[before.iter().filter(|w| w.sensed_only).count()]
            } else {
                &mut every[offset + before.iter().filter(|w| !w.sensed_only).count()]
            };
            let [x, y, yaw] = motion.apply([wall.center[0], wall.center[1], wall.yaw]);
            wall.center = [x, y];
            wall.yaw = yaw;
            let b = wall.bounds();
            let limit = crate::limits::MAX_COORDINATE;
            if ![b.min, b.max]
                .as_flattened()
                .iter()
                .all(|v| v.abs() <= limit)
            {
                return Err(Error::InvalidArgument(format!(
                    "expected wall {i} moved within [-{limit}, {limit}] m on x and y, found it \
                     spanning x in [{:?}, {:?}], y in [{:?}, {:?}]",
                    b.min[0], b.max[0], b.min[1], b.max[1]
                )));
            }
            spec.walls[i].center = [Finite(x), Finite(y)];
            spec.walls[i].yaw = Finite(yaw);
        }
        let solid_walls = distinct(&every);
        let wall_index = WallIndex::new(&solid_walls);
        let bounds = solid_walls
            .iter()
            .chain(&sensed)
            .fold(self.bounds, |b, w| b.union(w.bounds()));
        let sensed_moved = walls.iter().any(|&i| self.spec.walls[i].sensed_only);
        let sensed = match &self.sensed {
            Some(kept) if sensed_moved => SensedWalls::new(sensed, kept.colours().to_vec()),
            kept => kept.clone(),
        };
        let fingerprint = fingerprint_of(&spec)?;
        Ok(World {
            spec,
            source: self.source.clone(),
            walls: (every.len() != solid_walls.len()).then(|| every.into_boxed_slice()),
            solid_walls,
            wall_index,
            sensed,
            floor: self.floor.clone(),
            checkpoints: self.checkpoints.clone(),
            goal: self.goal,
            start: self.start,
            robots: self.robots.clone(),
            bounds,
            maze: self.maze.clone(),
            bodies: self.bodies.clone(),
            paint_colours: self.paint_colours.clone(),
            fingerprint,
        })
    }
}

impl World {
    /// This world with the `[[paint]]` entries `paint` (indices into the description's paint)
    /// moved by `motion`, as a supervisor moves the node that holds a floor mark: its
    /// description and its floor say where they are now; the rest is shared as it was.
    /// Refused, naming what was expected and found: an index past the paint, or paint moved
    /// beyond the limits.
    pub fn with_paint_moved(&self, paint: &[usize], motion: Motion) -> Result<World> {
        motion.check()?;
        let count = self.spec.paint.len();
        if let Some(&bad) = paint.iter().find(|&&i| i >= count) {
            return Err(Error::InvalidArgument(format!(
                "expected paint indices below the world's {count} [[paint]] entries, found {bad}"
            )));
        }
        // Each entry's regions, in order (a polyline has one per stroke), then the barcodes'.
        let mut first = Vec::with_capacity(count + 1);
        first.push(0);
        for p in &self.spec.paint {
            let strokes = match p {
                PaintSpec::Polyline { points, closed, .. } => {
                    points.len().saturating_sub(1) + usize::from(*closed && points.len() > 1)
                }
                _ => 1,
            };
            first.push(first[first.len() - 1] + strokes);
        }
        let mut spec = self.spec.clone();
        let mut regions = self.floor.regions().to_vec();
        let limit = crate::limits::MAX_COORDINATE;
        let mut bounds = self.bounds;
        let point = |p: &mut Point| {
            let [x, y, _] = motion.apply([p[0].0, p[1].0, 0.0]);
            *p = [Finite(x), Finite(y)];
        };
        for &i in paint {
            match &mut spec.paint[i] {
                PaintSpec::Rect { center, yaw, .. } => {
                    let [x, y, turned] = motion.apply([center[0].0, center[1].0, yaw.get()]);
                    *center = [Finite(x), Finite(y)];
                    *yaw = Finite(turned);
                }
                PaintSpec::Circle { center, .. } => point(center),
                PaintSpec::Polyline { points, .. } => points.iter_mut().for_each(point),
            }
            for region in &mut regions[first[i]..first[i + 1]] {
                region.shape = moved_shape(region.shape, motion);
                let b = region.shape.bounds();
                if ![b.min, b.max]
                    .as_flattened()
                    .iter()
                    .all(|v| v.abs() <= limit)
                {
                    return Err(Error::InvalidArgument(format!(
                        "expected paint {i} moved within [-{limit}, {limit}] m on x and y, found \
                         it spanning x in [{:?}, {:?}], y in [{:?}, {:?}]",
                        b.min[0], b.max[0], b.min[1], b.max[1]
                    )));
                }
                bounds = bounds.union(b);
            }
        }
        let fingerprint = fingerprint_of(&spec)?;
        Ok(World {
            spec,
            floor: FloorPaint::new(self.floor.background(), regions),
            bounds,
            fingerprint,
            ..self.clone()
        })
    }
}

/// Where `motion` takes a painted shape.
fn moved_shape(shape: PaintShape, motion: Motion) -> PaintShape {
    let point = |p: [f64; 2]| {
        let [x, y, _] = motion.apply([p[0], p[1], 0.0]);
        [x, y]
    };
    match shape {
        PaintShape::Rect { center, half, yaw } => {
            let [x, y, yaw] = motion.apply([center[0], center[1], yaw]);
            PaintShape::Rect {
                center: [x, y],
                half,
                yaw,
            }
        }
        PaintShape::Circle { center, radius } => PaintShape::Circle {
            center: point(center),
            radius,
        },
        PaintShape::Capsule { a, b, radius } => PaintShape::Capsule {
            a: point(a),
            b: point(b),
            radius,
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const TWO_WALLS: &str = r#"
format = "mazesim-world"
version = 1
[start]
x = 0.0
y = 0.0
[[walls]]
center = [0.3, 0.0]
size = [0.02, 0.4]
[[walls]]
center = [-0.3, 0.0]
size = [0.02, 0.4]
"#;

    #[test]
    fn a_motion_takes_its_from_pose_to_its_to_pose() {
        let motion = Motion {
            from: [1.0, 2.0, 0.5],
            to: [-1.0, 0.5, 2.0],
        };
        let moved = motion.apply([1.0, 2.0, 0.5]);
        for (got, want) in moved.iter().zip([-1.0, 0.5, 2.0]) {
            assert!((got - want).abs() < 1e-12, "{moved:?}");
        }
        // A point 1 m ahead of `from` ends 1 m ahead of `to`.
        let ahead = motion.apply([1.0 + 0.5f64.cos(), 2.0 + 0.5f64.sin(), 0.0]);
        assert!((ahead[0] - (-1.0 + 2.0f64.cos())).abs() < 1e-12);
        assert!((ahead[1] - (0.5 + 2.0f64.sin())).abs() < 1e-12);
    }

    #[test]
    fn moved_walls_are_where_the_index_finds_them() {
        let world = World::from_toml(TWO_WALLS, "two").unwrap();
        let ahead = world.wall_index().cast_ray([0.0, 0.0], [1.0, 0.0], 1.0);
        assert!((ahead.unwrap().distance - 0.29).abs() < 1e-5);
        let motion = Motion {
            from: [0.3, 0.0, 0.0],
            to: [0.1, 0.0, 0.0],
        };
        let moved = world.with_walls_moved(&[0], motion).unwrap();
        let ahead = moved.wall_index().cast_ray([0.0, 0.0], [1.0, 0.0], 1.0);
        assert!((ahead.unwrap().distance - 0.09).abs() < 1e-5);
        assert_eq!(moved.spec().walls[0].center[0].0, 0.1);
        assert_eq!(moved.walls()[1], world.walls()[1]);
        assert_ne!(moved.fingerprint(), world.fingerprint());
        // Moved back, it is the world it was.
        let back = Motion {
            from: motion.to,
            to: motion.from,
        };
        assert_eq!(moved.with_walls_moved(&[0], back).unwrap(), world);
    }

    #[test]
    fn a_wall_index_past_the_walls_or_a_move_beyond_the_limits_is_refused() {
        let world = World::from_toml(TWO_WALLS, "two").unwrap();
        let still = Motion {
            from: [0.0; 3],
            to: [0.0; 3],
        };
        let error = world.with_walls_moved(&[2], still).unwrap_err().to_string();
        assert!(
            error.contains("below the world's 2 [[walls]] entries, found 2"),
            "{error}"
        );
        let far = Motion {
            from: [0.0; 3],
            to: [2000.0, 0.0, 0.0],
        };
        assert!(world.with_walls_moved(&[0], far).is_err());
    }

    const PAINTED: &str = r#"
format = "mazesim-world"
version = 1
[start]
x = 0.0
y = 0.0
[[paint]]
shape = "rect"
center = [0.5, 0.0]
size = [0.1, 0.04]
reflectance = 0.2
[[paint]]
shape = "polyline"
points = [[0.0, 0.5], [0.2, 0.5], [0.2, 0.7]]
width = 0.02
reflectance = 0.3
[[paint]]
shape = "circle"
center = [-0.5, 0.0]
radius = 0.05
reflectance = 0.4
"#;

    #[test]
    fn moved_paint_is_read_where_it_is_now_and_the_rest_where_it_was() {
        let world = World::from_toml(PAINTED, "painted").unwrap();
        let floor = world.floor();
        assert_eq!(floor.reflectance_at([0.5, 0.0]), 0.2);
        // The rectangle and the polyline (two strokes) turn a quarter turn about (0, 0).
        let motion = Motion {
            from: [0.0; 3],
            to: [0.0, 0.0, std::f64::consts::FRAC_PI_2],
        };
        let moved = world.with_paint_moved(&[0, 1], motion).unwrap();
        let floor = moved.floor();
        assert_eq!(floor.reflectance_at([0.5, 0.0]), floor.background());
        assert_eq!(floor.reflectance_at([0.0, 0.5]), 0.2);
        // Across the turned rectangle: 0.1 m long now along y, 0.04 m wide along x.
        assert_eq!(floor.reflectance_at([0.0, 0.54]), 0.2);
        assert_eq!(floor.reflectance_at([0.03, 0.5]), floor.background());
        // The polyline's second stroke, from (0.2, 0.5) to (0.2, 0.7), is now from (-0.5, 0.2)
        // to (-0.7, 0.2).
        assert_eq!(floor.reflectance_at([-0.6, 0.2]), 0.3);
        assert_eq!(floor.reflectance_at([0.2, 0.6]), floor.background());
        // The circle stays.
        assert_eq!(floor.reflectance_at([-0.5, 0.0]), 0.4);
        assert_ne!(moved.fingerprint(), world.fingerprint());
        let back = Motion {
            from: motion.to,
            to: motion.from,
        };
        let again = moved.with_paint_moved(&[0, 1], back).unwrap();
        for (a, b) in again.floor().regions().iter().zip(world.floor().regions()) {
            let (PaintShape::Rect { center: p, .. }
            | PaintShape::Circle { center: p, .. }
            | PaintShape::Capsule { a: p, .. }) = a.shape;
            let (PaintShape::Rect { center: q, .. }
            | PaintShape::Circle { center: q, .. }
            | PaintShape::Capsule { a: q, .. }) = b.shape;
            assert!((p[0] - q[0]).abs() < 1e-12 && (p[1] - q[1]).abs() < 1e-12);
        }
    }

    #[test]
    fn a_paint_index_past_the_paint_or_a_move_beyond_the_limits_is_refused() {
        let world = World::from_toml(PAINTED, "painted").unwrap();
        let still = Motion {
            from: [0.0; 3],
            to: [0.0; 3],
        };
        let error = world.with_paint_moved(&[3], still).unwrap_err().to_string();
        assert!(
            error.contains("below the world's 3 [[paint]] entries, found 3"),
            "{error}"
        );
        let far = Motion {
            from: [0.0; 3],
            to: [999.9, 0.0, 0.0],
        };
        // The rectangle's centre would be at x 1000.4.
        let error = world.with_paint_moved(&[0], far).unwrap_err().to_string();
        assert!(error.contains("expected paint 0 moved within"), "{error}");
        assert!(world.with_paint_moved(&[2], far).is_ok());
    }
}
