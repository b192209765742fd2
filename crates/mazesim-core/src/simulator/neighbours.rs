//! The other robots of a world as one robot meets them: discs that hold its body back and that
//! its infra-red rays see.
//!
//! Contacts between robots are resolved like those with walls (`crate::contact`): each physics
//! step, the driven velocity is projected, neighbour after neighbour and pass after pass, onto
//! the velocities that close at most half of each gap in the step (the other robot may close the
//! other half), so two robots driven into each other stop at contact, a robot driven along
//! another slides past it, and robots that start a step overlapping are pushed apart, each by
//! half the overlap. Every robot of a world plans its step from the poses all had at its start,
//! so the result does not depend on the order the robots are stepped in.
//!
//! The infra-red rays of a robot meet another robot's body as a disc of the other's body radius
//! with reflection factor [`ROBOT_REFLECTANCE`], and the shapes the other carries beside its body
//! (a bumper, a box on it: `crate::world::CarriedShape`, a Webots world's robots' Shapes at the
//! sensors' height) with their own reflectance; a robot's body is held back by those shapes as by
//! the other's body. Ground sensors look at the floor only.

use crate::world::{CarriedShape, RayHit, RobotPlacement};

/// Infra-red reflection factor of a robot's body: 0.38, what Webots' infra-red model gives the
/// e-puck's shell. Webots reads a sensor ray's hit through `f = 0.2 + 0.8 * red * (1 - 0.5 *
/// roughness) * (1 - 0.5 * occlusion)` (reference manual, DistanceSensor, "Infra-Red Sensors"),
/// where `red` is the red of the hit shape's base colour times `1 - transparency`. At the
/// sensors' height (3.3 cm) the E-puck PROTO's body is its `EPUCK_BODY_LED` shell, a
/// `PBRAppearance` of base colour 0.5 grey, transparency 0.4, roughness 0.5 and no occlusion
/// map: `red = 0.5 * 0.6 = 0.3`, `f = 0.2 + 0.8 * 0.3 * 0.75 = 0.38`. Every profile's body reads
/// so: a robot of another colour is a profile option to come.
pub const ROBOT_REFLECTANCE: f32 = 0.38;

/// Passes of the velocity projection: a robot pressed by several others settles in a few.
const PASSES: usize = 8;

/// A gap to another robot below this (metres) counts as touching it.
pub const ROBOT_CONTACT_GAP: f32 = 2e-4;

/// One robot as the others see it: its centre, heading and body radius, and how far from its
/// centre the shapes it carries reach (its body radius when it carries none).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbour {
    /// Centre (x, y), metres.
    pub center: [f32; 2],
    /// Body radius, metres.
    pub radius: f32,
    /// Heading, radians.
    pub yaw: f32,
    /// The farthest its body and carried shapes reach from its centre, metres.
    pub extent: f32,
}

impl Neighbour {
    /// A robot of its body alone, a disc of `radius` at `center`.
    pub fn disc(center: [f32; 2], radius: f32) -> Neighbour {
        Neighbour {
            center,
            radius,
            yaw: 0.0,
            extent: radius,
        }
    }
}

/// The robots of a world as robot `me` sees them: all of `all` but itself.
#[derive(Debug, Clone, Copy)]
pub struct Others<'a> {
    /// Every robot of the world, in order.
    pub all: &'a [Neighbour],
    /// The index of the robot that looks.
    pub me: usize,
    /// The world's robot placements, whose `carried` shapes robot `i` of `all` carries; empty
    /// when no robot carries any.
    pub placements: &'a [RobotPlacement],
}

impl<'a> Others<'a> {
    /// No other robot: a world of one.
    pub const NONE: Others<'static> = Others {
        all: &[],
        me: 0,
        placements: &[],
    };

    /// The robots of `all` as robot `me` sees them, those of `placements` carrying their shapes
    /// (`placements` empty or one per robot).
    pub fn new(all: &'a [Neighbour], me: usize, placements: &'a [RobotPlacement]) -> Others<'a> {
        Others {
            all,
            me,
            placements,
        }
    }

    /// Each other robot with the shapes it carries, in its frame.
    fn with_carried(&self) -> impl Iterator<Item = (&'a Neighbour, &'a [CarriedShape])> + 'a {
        let me = self.me;
        let placements = self.placements;
        self.all
            .iter()
            .enumerate()
            .filter(move |&(i, _)| i != me)
            .map(move |(i, n)| (n, placements.get(i).map_or(&[][..], |p| &p.carried[..])))
    }

    /// Whether there is no other robot.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.all.len() <= 1
    }

    /// The other robots.
    pub fn iter(&self) -> impl Iterator<Item = &'a Neighbour> + 'a {
        let me = self.me;
        self.all
            .iter()
            .enumerate()
            .filter(move |&(i, _)| i != me)
            .map(|(_, n)| n)
    }

    /// The smallest gap between a disc of `radius` at `center` and another robot (infinite
    /// when there is none).
    pub fn gap(&self, center: [f32; 2], radius: f32) -> f32 {
        let bodies = self
            .iter()
            .map(|n| distance(center, n.center) - radius - n.radius)
            .fold(f32::INFINITY, f32::min);
        if self.placements.is_empty() {
            return bodies;
        }
        let mut least = bodies;
        for (n, carried) in self.with_carried() {
            for shape in carried {
                if let Some((d, _)) = nearest_on(n, shape, center) {
                    least = least.min(d - radius);
                }
            }
        }
        least
    }

    /// `velocity` of a disc of `radius` at `center`, held back by the other robots for a step of
    /// `dt` seconds (see the module notes); `None` when no other robot holds it back.
    pub fn yield_velocity(
        &self,
        center: [f32; 2],
        radius: f32,
        velocity: [f32; 2],
        dt: f32,
    ) -> Option<[f32; 2]> {
        let mut v = velocity;
        let mut held = false;
        for _ in 0..PASSES {
            let mut changed = false;
            for n in self.iter() {
                let d = distance(center, n.center);
                if d <= 0.0 {
                    continue;
                }
                let normal = [(center[0] - n.center[0]) / d, (center[1] - n.center[1]) / d];
                let gap = d - radius - n.radius;
                changed |= held_back(&mut v, normal, gap, dt);
            }
            if !self.placements.is_empty() {
                for (n, carried) in self.with_carried() {
                    for shape in carried {
                        if let Some((d, normal)) = nearest_on(n, shape, center) {
                            changed |= held_back(&mut v, normal, d - radius, dt);
                        }
                    }
                }
            }
            if !changed {
                break;
            }
            held = true;
        }
        held.then_some(v)
    }

    /// Whether another robot is within `reach` of the centre of robot `me` plus its own radius:
    /// beyond, it can neither touch robot `me` nor meet its rays.
    pub fn any_within(&self, reach: f32) -> bool {
        let at = self.all[self.me].center;
        self.iter().any(|n| {
            let (dx, dy) = (at[0] - n.center[0], at[1] - n.center[1]);
            let limit = reach + n.extent;
            dx * dx + dy * dy < limit * limit
        })
    }

    /// The nearest other robot a ray from `origin` along the unit `dir` meets within `limit`
    /// metres; a ray that starts inside one meets it at once.
    pub fn cast_ray(&self, origin: [f32; 2], dir: [f32; 2], limit: f32) -> Option<RayHit> {
        let mut nearest: Option<RayHit> = None;
        for n in self.iter() {
            let m = [origin[0] - n.center[0], origin[1] - n.center[1]];
            let b = m[0] * dir[0] + m[1] * dir[1];
            let c = m[0] * m[0] + m[1] * m[1] - n.radius * n.radius;
            if c > 0.0 && b > 0.0 {
                continue;
            }
            let discriminant = b * b - c;
            if discriminant < 0.0 {
                continue;
            }
            let t = (-b - discriminant.sqrt()).max(0.0);
            let within = nearest.map_or(limit, |h| h.distance);
            if t < within {
                nearest = Some(RayHit {
                    distance: t,
                    reflectance: ROBOT_REFLECTANCE,
                });
            }
        }
        if self.placements.is_empty() {
            return nearest;
        }
        for (n, carried) in self.with_carried() {
            for shape in carried {
                let within = nearest.map_or(limit, |h| h.distance);
                if let Some(t) = ray_to(n, shape, origin, dir, within) {
                    nearest = Some(RayHit {
                        distance: t,
                        reflectance: shape.reflectance,
                    });
                }
            }
        }
        nearest
    }
}

/// Projects `v` so that it closes at most half of `gap` along `-normal` in `dt`; whether it
/// changed.
#[inline]
fn held_back(v: &mut [f32; 2], normal: [f32; 2], gap: f32, dt: f32) -> bool {
    let closing = v[0] * normal[0] + v[1] * normal[1];
    let least = -gap / (2.0 * dt);
    if closing < least {
        let push = least - closing;
        *v = [v[0] + push * normal[0], v[1] + push * normal[1]];
        true
    } else {
        false
    }
}

/// A world point in the frame of `shape`, carried by `n`.
fn to_shape(n: &Neighbour, shape: &CarriedShape, p: [f32; 2]) -> [f32; 2] {
    let (s, c) = n.yaw.sin_cos();
    let (dx, dy) = (p[0] - n.center[0], p[1] - n.center[1]);
    let robot = [
        c * dx + s * dy - shape.center[0],
        -s * dx + c * dy - shape.center[1],
    ];
    let (s, c) = shape.yaw.sin_cos();
    [c * robot[0] + s * robot[1], -s * robot[0] + c * robot[1]]
}

/// A direction of the world in the frame of `shape`, carried by `n`.
fn turn_to_shape(n: &Neighbour, shape: &CarriedShape, d: [f32; 2]) -> [f32; 2] {
    let (s, c) = (n.yaw + shape.yaw).sin_cos();
    [c * d[0] + s * d[1], -s * d[0] + c * d[1]]
}

/// The distance from `at` to the surface of `shape` (carried by `n`; negative inside a
/// cylinder) and the unit normal pointing from the shape to `at`, in the world; `None` when
/// `at` is the cylinder's axis or lies inside a box (no direction to be pushed along).
fn nearest_on(n: &Neighbour, shape: &CarriedShape, at: [f32; 2]) -> Option<(f32, [f32; 2])> {
    let local = to_shape(n, shape, at);
    let (away, gap) = if shape.radius > 0.0 {
        let d = (local[0] * local[0] + local[1] * local[1]).sqrt();
        (local, d - shape.radius)
    } else {
        let near = [
            local[0].clamp(-shape.half[0], shape.half[0]),
            local[1].clamp(-shape.half[1], shape.half[1]),
        ];
        let away = [local[0] - near[0], local[1] - near[1]];
        (away, (away[0] * away[0] + away[1] * away[1]).sqrt())
    };
    let length = (away[0] * away[0] + away[1] * away[1]).sqrt();
    if length <= 0.0 {
        return None;
    }
    let (s, c) = (n.yaw + shape.yaw).sin_cos();
    let [x, y] = [away[0] / length, away[1] / length];
    Some((gap, [c * x - s * y, s * x + c * y]))
}

/// Where a ray from `origin` along the unit `dir` meets `shape` (carried by `n`) before
/// `limit`, or `None`; a ray that starts inside it meets it at once.
fn ray_to(
    n: &Neighbour,
    shape: &CarriedShape,
    origin: [f32; 2],
    dir: [f32; 2],
    limit: f32,
) -> Option<f32> {
    let o = to_shape(n, shape, origin);
    let d = turn_to_shape(n, shape, dir);
    if shape.radius > 0.0 {
        let b = o[0] * d[0] + o[1] * d[1];
        let c = o[0] * o[0] + o[1] * o[1] - shape.radius * shape.radius;
        if c > 0.0 && b > 0.0 {
            return None;
        }
        let discriminant = b * b - c;
        if discriminant < 0.0 {
            return None;
        }
        let t = (-b - discriminant.sqrt()).max(0.0);
        return (t < limit).then_some(t);
    }
    let (mut enter, mut leave) = (0.0f32, limit);
    for axis in 0..2 {
        let h = shape.half[axis];
        if d[axis].abs() < 1e-12 {
            if o[axis].abs() > h {
                return None;
            }
            continue;
        }
        let (a, b) = ((-h - o[axis]) / d[axis], (h - o[axis]) / d[axis]);
        enter = enter.max(a.min(b));
        leave = leave.min(a.max(b));
        if enter > leave {
            return None;
        }
    }
    (enter < limit).then_some(enter)
}

fn distance(a: [f32; 2], b: [f32; 2]) -> f32 {
    let (dx, dy) = (a[0] - b[0], a[1] - b[1]);
    (dx * dx + dy * dy).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pair(gap: f32) -> [Neighbour; 2] {
        [
            Neighbour::disc([0.0, 0.0], 0.037),
            Neighbour::disc([0.074 + gap, 0.0], 0.037),
        ]
    }

    #[test]
    fn a_ray_meets_the_near_side_of_another_robot() {
        let all = pair(0.02);
        let others = Others::new(&all, 0, &[]);
        let hit = others.cast_ray([0.03, 0.0], [1.0, 0.0], 0.07).unwrap();
        assert!((hit.distance - (0.074 + 0.02 - 0.037 - 0.03)).abs() < 1e-6);
        assert_eq!(hit.reflectance, ROBOT_REFLECTANCE);
        assert!(others.cast_ray([0.03, 0.0], [-1.0, 0.0], 0.07).is_none());
        assert!(others.cast_ray([0.03, 0.0], [1.0, 0.0], 0.01).is_none());
        // The robot itself is never seen.
        let me = Others::new(&all, 1, &[]);
        assert!(me.cast_ray([0.064, 0.0], [1.0, 0.0], 0.07).is_none());
    }

    #[test]
    fn two_robots_driven_together_close_half_the_gap_each() {
        let all = pair(0.002);
        let dt = 0.032;
        let a = Others::new(&all, 0, &[])
            .yield_velocity(all[0].center, 0.037, [0.126, 0.03], dt)
            .unwrap();
        assert!((a[0] * dt - 0.001).abs() < 1e-7, "{a:?}");
        assert_eq!(a[1], 0.03, "the motion along the other goes through");
        // Overlapping robots are pushed apart by half the overlap each.
        let all = pair(-0.004);
        let a = Others::new(&all, 0, &[])
            .yield_velocity(all[0].center, 0.037, [0.0, 0.0], dt)
            .unwrap();
        assert!((a[0] * dt + 0.002).abs() < 1e-7, "{a:?}");
    }

    /// Two robots 0.3 m apart on the x axis, the second facing -x with a white bumper (a box
    /// 2 cm deep and 10 cm wide) 6 cm ahead of its centre and a black post (a cylinder) behind.
    fn bumpered() -> crate::world::World {
        crate::world::World::from_toml(
            r#"
format = "mazesim-world"
version = 1

[[robots]]
name = "a"
x = 0.0
y = 0.0

[[robots]]
name = "b"
x = 0.3
y = 0.0
yaw = 3.141592653589793

[[robots.carried]]
center = [0.06, 0.0]
size = [0.02, 0.1]
reflectance = 1.0

[[robots.carried]]
center = [-0.05, 0.0]
radius = 0.01
reflectance = 0.2
"#,
            "bumpered",
        )
        .unwrap()
    }

    fn placed(world: &crate::world::World) -> Vec<Neighbour> {
        world
            .robots()
            .iter()
            .map(|p| {
                let reach = p.carried.iter().map(|s| s.reach()).fold(0.037, f32::max);
                Neighbour {
                    center: [p.start[0] as f32, p.start[1] as f32],
                    radius: 0.037,
                    yaw: p.start[2] as f32,
                    extent: reach,
                }
            })
            .collect()
    }

    #[test]
    fn a_ray_meets_the_shapes_another_robot_carries() {
        let world = bumpered();
        let all = placed(&world);
        let others = Others::new(&all, 0, world.robots());
        // The bumper's near face is at x = 0.3 - 0.06 - 0.01 = 0.23, before the body (0.263).
        let hit = others.cast_ray([0.03, 0.0], [1.0, 0.0], 0.5).unwrap();
        assert!((hit.distance - 0.2).abs() < 1e-5, "{hit:?}");
        assert_eq!(hit.reflectance, 1.0);
        // The bumper, 10 cm wide, hides the body from the front; from the side the ray meets
        // the body, and from behind the black post.
        let edge = others.cast_ray([0.0, 0.045], [1.0, 0.0], 0.5).unwrap();
        assert_eq!(edge.reflectance, 1.0, "{edge:?}");
        assert!(others.cast_ray([0.0, 0.055], [1.0, 0.0], 0.5).is_none());
        let side = others.cast_ray([0.3, -0.2], [0.0, 1.0], 0.5).unwrap();
        assert!((side.distance - (0.2 - 0.037)).abs() < 1e-5, "{side:?}");
        assert_eq!(side.reflectance, ROBOT_REFLECTANCE);
        let post = others.cast_ray([0.4, 0.0], [-1.0, 0.0], 0.5).unwrap();
        assert!((post.distance - (0.4 - 0.36)).abs() < 1e-5, "{post:?}");
        assert_eq!(post.reflectance, 0.2);
        // The same robots without their placements are their bodies alone.
        let bare = Others::new(&all, 0, &[]).cast_ray([0.03, 0.0], [1.0, 0.0], 0.5);
        assert!((bare.unwrap().distance - (0.3 - 0.037 - 0.03)).abs() < 1e-5);
        // A robot never meets its own carried shapes.
        let own = Others::new(&all, 1, world.robots());
        assert!(own.cast_ray([0.27, 0.0], [-1.0, 0.0], 0.02).is_none());
    }

    #[test]
    fn a_robot_is_held_back_by_the_shapes_another_carries() {
        let world = bumpered();
        let mut all = placed(&world);
        // Robot a 2 mm short of the bumper's face at x = 0.23.
        all[0].center = [0.23 - 0.037 - 0.002, 0.0];
        let others = Others::new(&all, 0, world.robots());
        let dt = 0.032;
        let v = others
            .yield_velocity(all[0].center, 0.037, [0.126, 0.0], dt)
            .unwrap();
        assert!((v[0] * dt - 0.001).abs() < 1e-6, "{v:?}");
        assert!((others.gap(all[0].center, 0.037) - 0.002).abs() < 1e-6);
        assert!(others.any_within(0.0));
        // Without the bumper it would drive on.
        let bare = Others::new(&all, 0, &[]);
        assert!(bare
            .yield_velocity(all[0].center, 0.037, [0.126, 0.0], dt)
            .is_none());
    }
}
