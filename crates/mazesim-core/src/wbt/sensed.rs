//! Visual-only shapes that stand in the infra-red rays' way: a `Shape` that belongs to no
//! `Solid` with a `boundingObject` collides with nothing in Webots, but "infra-red rays
//! collision detection uses the Solid nodes themselves" (the reference manual's DistanceSensor
//! page), so the e-puck's proximity sensors and its camera see it: a decorative wall, a marker
//! post, a goal object the robot drives through.
//!
//! A `Box`, `Cylinder`, `Capsule` or `Sphere` of such a shape whose height reaches the band the
//! e-puck's proximity rays sweep ([`PROXIMITY_RAYS_LOW`] to [`PROXIMITY_RAYS_HIGH`]) becomes a
//! sensed-only obstacle: its footprint is read as a collision shape's is (`shapes.rs`), in the
//! colour of its appearance, and the world keeps it as a `sensed_only` wall. Lower shapes stay
//! floor marks or warnings (`floor_marks.rs`); higher ones pass over the robot.

use super::appearance::Look;
use super::frames::Frame;
use super::import::Importer;
use super::tree::Node;

/// The lowest height the e-puck's proximity rays sweep, metres: the E-puck PROTO's sensors are
/// 3.3 cm above the floor; a visual-only shape whose top is below it is under their rays.
pub const PROXIMITY_RAYS_LOW: f64 = 0.033;
/// The highest, metres: each ray rises 0.16 rad over its 7 cm, to 4.4 cm; a shape whose bottom
/// is above it passes over the rays.
pub const PROXIMITY_RAYS_HIGH: f64 = 0.044;

impl<'d> Importer<'d> {
    /// Reads the primitive geometry of the visual-only `shape` (in its parent's `frame`) as a
    /// sensed-only obstacle of the shape's look (colour and reflection factor), when it reaches the proximity rays' band;
    /// returns whether it reached it (otherwise nothing is emitted, the caller warns).
    pub fn sensed_shape(&mut self, shape: &'d Node, frame: &Frame) -> bool {
        let Some(&geometry) = self.nodes(shape, "geometry").first() else {
            return false;
        };
        let label = self.label(shape);
        let before = self.sensed_obstacles.len();
        let look = self.field_look(shape, "appearance").unwrap_or(Look::UNREAD);
        let outer = std::mem::replace(&mut self.look, look);
        self.sensing = true;
        self.bounding(geometry, frame, &label, 1);
        self.sensing = false;
        self.look = outer;
        self.sensed_obstacles.len() > before
    }

    /// Whether a visual-only shape spanning `center_z +- half_z` meets the proximity rays.
    pub fn meets_proximity_rays(&self, center_z: f64, half_z: f64) -> bool {
        center_z + half_z >= PROXIMITY_RAYS_LOW && center_z - half_z <= PROXIMITY_RAYS_HIGH
    }
}
