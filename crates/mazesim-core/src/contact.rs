//! The robot's round body among static walls: its contacts resolved here, in a few dozen
//! operations, instead of through rapier's whole pipeline (broad phase, narrow phase, islands,
//! solver, all per env).
//!
//! A step is a speculative contact solve followed by a position check:
//!
//! 1. Every wall the disc could reach in the step (its gap below the step's travel plus
//!    `CONTACT_MARGIN`) becomes a contact with its normal and gap, taken from the shared wall
//!    index of the world: nothing is stored per env.
//! 2. The driven velocity is projected, wall after wall and pass after pass, onto the velocities
//!    that close at most each contact's gap in the step (`v . n >= -gap / dt`): a wall stops the
//!    motion into it and lets the motion along it through (no friction, no restitution, as the
//!    robot's contacts with walls have in rapier). A disc that starts inside a wall is pushed
//!    out of it within the step.
//! 3. The disc moves by the projected velocity. Where the step, planned from the normals at its
//!    start, still ends inside a wall (sliding round a wall's corner), the disc is pushed out
//!    along that wall's normal at the end point.
//!
//! The rotation is the driven one: a frictionless contact through the centre of a disc exerts
//! no torque. With no wall within reach the step is exactly free flight (position += velocity *
//! dt), so it does not matter whether a caller skips this for a free step.

use crate::world::WallIndex;

/// At most this many walls in contact at once; more (a crowd of tiny boxes) keeps the nearest.
const MAX_CONTACTS: usize = 16;

/// Passes of the velocity projection and of the position check: two walls meeting at any angle
/// settle in a few.
const PASSES: usize = 8;

/// A wall within this gap (metres) beyond the step's travel is taken as a contact.
pub const CONTACT_MARGIN: f32 = 1e-3;

/// One wall the disc could reach this step.
#[derive(Debug, Clone, Copy, Default)]
struct Contact {
    wall: u32,
    /// Unit normal out of the wall at the point nearest the disc's centre.
    normal: [f32; 2],
    /// Gap between the disc and the wall (negative: overlap), metres.
    gap: f32,
}

/// The walls a disc at `center` could reach moving `travel` metres, nearest kept when crowded.
struct Contacts {
    list: [Contact; MAX_CONTACTS],
    count: usize,
}

impl Contacts {
    fn gather(walls: &WallIndex, center: [f32; 2], radius: f32, travel: f32) -> Self {
        let mut found = Contacts {
            list: [Contact::default(); MAX_CONTACTS],
            count: 0,
        };
        let within = travel + CONTACT_MARGIN;
        walls.for_each_around(center, radius + within, |i| {
            let wall = i as u32;
            if found.list[..found.count].iter().any(|c| c.wall == wall) {
                return;
            }
            let (distance, normal) = walls.wall_contact(i, center);
            let gap = distance - radius;
            if gap >= within {
                return;
            }
            let contact = Contact { wall, normal, gap };
            if found.count < MAX_CONTACTS {
                found.list[found.count] = contact;
                found.count += 1;
            } else if let Some(farthest) =
                found.list.iter_mut().max_by(|a, b| a.gap.total_cmp(&b.gap))
            {
                if gap < farthest.gap {
                    *farthest = contact;
                }
            }
        });
        found
    }

    fn as_slice(&self) -> &[Contact] {
        &self.list[..self.count]
    }
}

/// Where a disc of `radius` at `center`, driven at `velocity` (m/s) for `dt` seconds, ends among
/// the walls of `walls` (see the module notes).
pub fn slide(
    walls: &WallIndex,
    center: [f32; 2],
    radius: f32,
    velocity: [f32; 2],
    dt: f32,
) -> [f32; 2] {
    let [vx, vy] = velocity;
    let travel = (vx * vx + vy * vy).sqrt() * dt;
    let contacts = Contacts::gather(walls, center, radius, travel);
    let contacts = contacts.as_slice();
    let mut v = velocity;
    for _ in 0..PASSES {
        let mut changed = false;
        for c in contacts {
            let [nx, ny] = c.normal;
            let closing = v[0] * nx + v[1] * ny;
            let least = -c.gap / dt;
            if closing < least {
                let push = least - closing;
                v = [v[0] + push * nx, v[1] + push * ny];
                changed = true;
            }
        }
        if !changed {
            break;
        }
    }
    let mut at = [center[0] + v[0] * dt, center[1] + v[1] * dt];
    for _ in 0..PASSES {
        let mut moved = false;
        for c in contacts {
            let (distance, [nx, ny]) = walls.wall_contact(c.wall as usize, at);
            let depth = radius - distance;
            if depth > 0.0 {
                at = [at[0] + depth * nx, at[1] + depth * ny];
                moved = true;
            }
        }
        if !moved {
            break;
        }
    }
    at
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::WallBox;

    fn walls(boxes: &[([f64; 2], [f64; 2], f64)]) -> WallIndex {
        let list: Vec<WallBox> = boxes
            .iter()
            .map(|&(center, half, yaw)| WallBox {
                center,
                half,
                yaw,
                reflectance: 1.0,
            })
            .collect();
        WallIndex::new(&list)
    }

    /// The gap between a disc of `radius` at `p` and the nearest wall.
    fn gap(w: &WallIndex, p: [f32; 2], radius: f32) -> f32 {
        w.signed_distance(p, 1.0) - radius
    }

    #[test]
    fn far_from_walls_a_step_is_free_flight() {
        let w = walls(&[([1.0, 0.0], [0.005, 0.5], 0.0)]);
        let v = [0.1234f32, -0.05];
        let end = slide(&w, [0.0, 0.0], 0.037, v, 0.032);
        assert_eq!(end, [0.0 + v[0] * 0.032, 0.0 + v[1] * 0.032]);
    }

    #[test]
    fn a_wall_stops_the_disc_at_contact_and_lets_it_slide_along() {
        // Face at x = 0.295; the disc of radius 0.037 starts 2 mm from it, moving at 0.126 m/s at
        // 45 degrees into the wall.
        let w = walls(&[([0.3, 0.0], [0.005, 1.0], 0.0)]);
        let start = [0.295 - 0.037 - 0.002, 0.0];
        let v = [0.0891f32, 0.0891];
        let end = slide(&w, start, 0.037, v, 0.032);
        assert!((end[0] - (0.295 - 0.037)).abs() < 1e-6, "{end:?}");
        assert_eq!(
            end[1],
            v[1] * 0.032,
            "the motion along the wall goes through"
        );
        assert!(gap(&w, end, 0.037) > -1e-6);
    }

    #[test]
    fn a_disc_inside_a_wall_is_pushed_out_within_a_step() {
        let w = walls(&[([0.3, 0.0], [0.005, 1.0], 0.0)]);
        let end = slide(&w, [0.295 - 0.037 + 0.002, 0.0], 0.037, [0.0, 0.0], 0.032);
        assert!(gap(&w, end, 0.037).abs() < 1e-6, "{end:?}");
    }

    #[test]
    fn a_corner_of_two_walls_at_any_angle_holds_the_disc() {
        for yaw in [0.0, 0.4, 0.9, 1.3] {
            let w = walls(&[
                ([0.3, 0.0], [0.005, 1.0], 0.0),
                ([0.3, 0.0], [1.0, 0.005], yaw),
            ]);
            let mut p = [0.1f32, 0.12];
            let mut worst = f32::INFINITY;
            for _ in 0..200 {
                p = slide(&w, p, 0.037, [0.12, -0.03], 0.032);
                worst = worst.min(gap(&w, p, 0.037));
            }
            assert!(worst > -1e-5, "yaw {yaw}: penetration {}", -worst);
        }
    }

    #[test]
    fn sliding_round_the_end_of_a_wall_never_sinks_in() {
        // A short wall; the disc is driven along its face and round its end.
        let w = walls(&[([0.0, 0.0], [0.005, 0.1], 0.0)]);
        let mut worst = f32::INFINITY;
        for k in 0..400 {
            let angle = k as f32 * 0.05;
            let centre = [-0.05f32, 0.0];
            let p0 = [centre[0] + 0.05 * angle.cos(), 0.1 * angle.sin()];
            let p = slide(&w, [p0[0] - 0.05, p0[1]], 0.037, [0.126, 0.05], 0.032);
            worst = worst.min(gap(&w, p, 0.037));
        }
        assert!(worst > -1e-5, "penetration {}", -worst);
    }
}
