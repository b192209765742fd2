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
//! with reflection factor [`ROBOT_REFLECTANCE`]; ground sensors look at the floor only.

use crate::world::RayHit;

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

/// One robot as the others see it: its centre and body radius.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Neighbour {
    /// Centre (x, y), metres.
    pub center: [f32; 2],
    /// Body radius, metres.
    pub radius: f32,
}

/// The robots of a world as robot `me` sees them: all of `all` but itself.
#[derive(Debug, Clone, Copy)]
pub struct Others<'a> {
    /// Every robot of the world, in order.
    pub all: &'a [Neighbour],
    /// The index of the robot that looks.
    pub me: usize,
}

impl<'a> Others<'a> {
    /// No other robot: a world of one.
    pub const NONE: Others<'static> = Others { all: &[], me: 0 };

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
        self.iter()
            .map(|n| distance(center, n.center) - radius - n.radius)
            .fold(f32::INFINITY, f32::min)
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
                let closing = v[0] * normal[0] + v[1] * normal[1];
                let least = -gap / (2.0 * dt);
                if closing < least {
                    let push = least - closing;
                    v = [v[0] + push * normal[0], v[1] + push * normal[1]];
                    changed = true;
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
            let limit = reach + n.radius;
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
        nearest
    }
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
            Neighbour {
                center: [0.0, 0.0],
                radius: 0.037,
            },
            Neighbour {
                center: [0.074 + gap, 0.0],
                radius: 0.037,
            },
        ]
    }

    #[test]
    fn a_ray_meets_the_near_side_of_another_robot() {
        let all = pair(0.02);
        let others = Others { all: &all, me: 0 };
        let hit = others.cast_ray([0.03, 0.0], [1.0, 0.0], 0.07).unwrap();
        assert!((hit.distance - (0.074 + 0.02 - 0.037 - 0.03)).abs() < 1e-6);
        assert_eq!(hit.reflectance, ROBOT_REFLECTANCE);
        assert!(others.cast_ray([0.03, 0.0], [-1.0, 0.0], 0.07).is_none());
        assert!(others.cast_ray([0.03, 0.0], [1.0, 0.0], 0.01).is_none());
        // The robot itself is never seen.
        let me = Others { all: &all, me: 1 };
        assert!(me.cast_ray([0.064, 0.0], [1.0, 0.0], 0.07).is_none());
    }

    #[test]
    fn two_robots_driven_together_close_half_the_gap_each() {
        let all = pair(0.002);
        let dt = 0.032;
        let a = Others { all: &all, me: 0 }
            .yield_velocity(all[0].center, 0.037, [0.126, 0.03], dt)
            .unwrap();
        assert!((a[0] * dt - 0.001).abs() < 1e-7, "{a:?}");
        assert_eq!(a[1], 0.03, "the motion along the other goes through");
        // Overlapping robots are pushed apart by half the overlap each.
        let all = pair(-0.004);
        let a = Others { all: &all, me: 0 }
            .yield_velocity(all[0].center, 0.037, [0.0, 0.0], dt)
            .unwrap();
        assert!((a[0] * dt + 0.002).abs() < 1e-7, "{a:?}");
    }
}
