//! Collision shapes: a Solid's `boundingObject` (Box, Cylinder, Capsule, Sphere, Plane, wrapped
//! in Pose / Transform / Group / Shape) turned into 2D footprints in the world frame.

use std::f64::consts::PI;

use super::frames::{norm, tilt, y_up_size, Frame, Vec3};
use super::ground::Surface;
use super::import::{Importer, MAX_EXTENT, TILT_TOLERANCE};
use super::tree::NodeId;
use super::Obstacle;

/// A shape whose top is at or below this height (metres) lies on the floor: not an obstacle.
pub const FLOOR_LEVEL: f64 = 0.001;
/// Height of the e-puck, about 5 cm (GCtronic: 70 mm across, ~50 mm high); a shape whose
/// bottom is at or above it passes over the robot.
pub const ROBOT_HEIGHT: f64 = 0.05;
/// A static shape whose top is at or below this height (metres) is a platform the e-puck stands
/// on, not a wall: the bottom of the E-puck PROTO's body (its bounding cylinder, 0.045 m high,
/// is centred 0.025 m up); below it only the wheels (radius 0.02 m) and the 1 cm thick bottom
/// plate of its bounding objects meet the shape, and Webots' ODE lifts a robot placed on it
/// (a thin region a world marks on the floor as a Solid with a bounding object).
pub const STOOD_ON: f64 = 0.0025;
/// The steepest slope (radians from level) of a ramp the e-puck drives on: Webots' default
/// contact (`ContactProperties.coulombFriction` 1) holds a wheel on an incline up to
/// atan(1) = 45 degrees.
pub const STEEPEST_RAMP: f64 = PI / 4.0;

fn scaled(v: Vec3, s: f64) -> Vec3 {
    v.map(|c| c * s)
}

/// Rounds away the floating-point noise of composed rotations (to a nanometre or nanoradian)
/// and turns -0 into 0, so that `0.1` reads `0.1` and not `0.10000000000000002`.
pub fn snap(v: f64) -> f64 {
    (v * 1e9).round() / 1e9 + 0.0
}

/// Normalises an angle to (-pi, pi].
pub fn wrap_angle(a: f64) -> f64 {
    let r = a.rem_euclid(2.0 * PI);
    if r > PI {
        r - 2.0 * PI
    } else {
        r
    }
}

impl<'d> Importer<'d> {
    /// Collects the footprints of a bounding object.
    pub fn bounding(&mut self, id: NodeId, frame: &Frame, owner: &str, depth: usize) {
        if !self.enter(depth) {
            return;
        }
        let node = self.node(id);
        match node.type_name.as_str() {
            "Group" => {
                for &child in self.nodes(node, "children") {
                    self.bounding(child, frame, owner, depth + 1);
                }
            }
            "Pose" | "Transform" => {
                let local = self.local_frame(node, [0.0; 3]);
                let frame = frame.then(&local);
                for &child in self.nodes(node, "children") {
                    self.bounding(child, &frame, owner, depth + 1);
                }
            }
            "Shape" => {
                for &geometry in self.nodes(node, "geometry") {
                    self.bounding(geometry, frame, owner, depth + 1);
                }
            }
            // Defaults of the Webots reference manual: Box size 2 2 2, Cylinder and Capsule
            // radius 1 height 2, Sphere radius 1.
            "Box" => {
                let size = self.vector(node, "size", [2.0; 3]);
                if size.iter().any(|s| *s <= 0.0) {
                    self.warn(format!("{owner}: a Box of size {size:?}: expected sizes above 0; skipped"));
                    return;
                }
                let size = if self.y_up { y_up_size(size) } else { size };
                self.emit_box(&self.z_up(frame), scaled(size, 0.5), owner);
            }
            "Cylinder" | "Capsule" => {
                let radius = self.number(node, "radius", 1.0);
                let height = self.number(node, "height", 2.0);
                if radius <= 0.0 || height < 0.0 {
                    self.warn(format!(
                        "{owner}: a {} of radius {radius} and height {height}: expected positive sizes; skipped",
                        node.type_name
                    ));
                    return;
                }
                let cap = if node.type_name == "Capsule" { radius } else { 0.0 };
                let what = node.type_name.to_ascii_lowercase();
                self.emit_round(&self.z_up(frame), radius, height / 2.0 + cap, owner, &what);
            }
            "Sphere" => {
                let radius = self.number(node, "radius", 1.0);
                if radius <= 0.0 {
                    self.warn(format!("{owner}: a Sphere of radius {radius}: expected a radius above 0; skipped"));
                    return;
                }
                // A sphere has no axis: its footprint is the disc of its largest radius.
                let largest = (0..3).map(|i| norm(frame.axis(i))).fold(0.0, f64::max);
                self.emit_round(
                    &Frame::new(frame.origin, super::frames::IDENTITY, [largest; 3]),
                    radius,
                    radius,
                    owner,
                    "sphere",
                );
            }
            "Plane" => {
                let normal = self.z_up(frame).axis(2);
                if tilt(normal) > TILT_TOLERANCE {
                    self.warn(format!(
                        "{owner}: a Plane that is not horizontal (tilted by {:.3} rad): not imported",
                        tilt(normal)
                    ));
                } else if self.y_up {
                    // A Y-up Plane's size is along axes the Z-up frame turns: unbounded.
                    self.unbounded_floor(&self.z_up(frame));
                } else {
                    let size = self.vector(node, "size", [1.0, 1.0]);
                    self.floor_surface(frame, size);
                }
                // A horizontal plane is a floor (or a ceiling): nothing to collide with in 2D.
            }
            "IndexedFaceSet" | "Mesh" if !self.sensing => self.mesh_walls(node, frame, owner),
            "IndexedFaceSet" | "Mesh" | "ElevationGrid" => self.warn(format!(
                "{owner}: a {} bounding object (a mesh): not imported; give the Solid Box or Cylinder bounding objects",
                node.type_name
            )),
            other => self.warn(format!(
                "{owner}: line {}: `{other}` is not a bounding object mazesim reads; skipped",
                node.line
            )),
        }
    }

    /// Whether a shape spanning `center_z +- half_z` meets the robot's height (a falling one, of
    /// an object with physics, meets it once on the floor).
    fn meets_robot(&mut self, center_z: f64, half_z: f64, owner: &str) -> bool {
        // A falling shape comes to rest on the floor.
        self.shape_top = if self.falls {
            2.0 * half_z
        } else {
            center_z + half_z
        };
        if self.sensing {
            return self.meets_proximity_rays(center_z, half_z);
        }
        let top = center_z + half_z;
        if top <= FLOOR_LEVEL {
            // Floor the robot drives on, without an edge to climb: a sheet lying on it or a slab
            // the floor is made of (its top within 1 mm of the floor's). Its Solid's visible
            // shapes are floor marks (`Importer::solid`); a shape buried deeper adds nothing.
            if top >= -FLOOR_LEVEL {
                self.stood_on += 1;
            }
            return false;
        }
        if top <= STOOD_ON && !self.falls {
            self.stood_on += 1;
            self.warn(format!(
                "{owner}: a collision shape {:.1} mm high: the robot stands and drives on it, imported as floor (Webots' ODE may stop an e-puck driving onto it at its edge)",
                top * 1000.0
            ));
            return false;
        }
        if center_z - half_z >= ROBOT_HEIGHT && !self.falls {
            self.warn(format!(
                "{owner}: a collision shape {:.3} m above the floor passes over the robot: not imported",
                center_z - half_z
            ));
            return false;
        }
        self.shape_height = 2.0 * half_z;
        true
    }

    /// Adds the footprint of a box with half-extents `half` along the axes of `frame`.
    pub fn emit_box(&mut self, frame: &Frame, half: Vec3, owner: &str) {
        let axes = [0, 1, 2].map(|i| scaled(frame.axis(i), half[i]));
        if !self.sensing && !self.falls && self.is_ramp(frame.origin, &axes, owner) {
            return;
        }
        let half_z: f64 = axes.iter().map(|a| a[2].abs()).sum();
        if !self.sensing && !self.falls {
            self.box_top(frame.origin, &axes);
        }
        if self.meets_robot(frame.origin[2], half_z, owner) {
            self.footprint(frame.origin, axes, owner, "box");
        }
    }

    /// Records the top face of a static box (centre `center`, half-axes `axes`) standing level
    /// (one axis within [`TILT_TOLERANCE`] of vertical) as a surface the robot may stand on.
    fn box_top(&mut self, center: Vec3, axes: &[Vec3; 3]) {
        let Some(up) = (0..3).find(|&i| tilt(axes[i]) <= TILT_TOLERANCE) else {
            return;
        };
        let [a, b] = match up {
            0 => [axes[1], axes[2]],
            1 => [axes[0], axes[2]],
            _ => [axes[0], axes[1]],
        };
        self.floors.push(Surface {
            height: center[2] + axes[up][2].abs(),
            center: [center[0], center[1]],
            half_axes: Some([[a[0], a[1]], [b[0], b[1]]]),
        });
    }

    /// Whether a static box (centre `center`, half-axes `axes`) is a ramp: its upper face, tilted
    /// by at most [`STEEPEST_RAMP`], rises from the floor (its lowest edge within [`STOOD_ON`]
    /// of it), so the robot drives onto it and up it (or stands on it, as a robot saved on a
    /// sloping slab does) as on ground: in 2D it is floor, not a wall (said in a warning).
    fn is_ramp(&mut self, center: Vec3, axes: &[Vec3; 3], owner: &str) -> bool {
        let up = (0..3)
            .min_by(|&i, &j| tilt(axes[i]).total_cmp(&tilt(axes[j])))
            .unwrap_or(2);
        let slope = tilt(axes[up]);
        if slope <= TILT_TOLERANCE || slope > STEEPEST_RAMP {
            return false;
        }
        let face_height = center[2] + axes[up][2].abs();
        let lowest_edge = face_height
            - (0..3)
                .filter(|&i| i != up)
                .map(|i| axes[i][2].abs())
                .sum::<f64>();
        let highest_edge = 2.0 * face_height - lowest_edge;
        if lowest_edge > STOOD_ON || highest_edge <= STOOD_ON {
            return false;
        }
        self.warn(format!(
            "{owner}: a ramp (a box whose top rises from the floor to {highest_edge:.3} m at {:.0} degrees): the robot drives on it, imported as floor",
            slope.to_degrees()
        ));
        true
    }

    /// Adds the footprint of a round shape (cylinder, capsule, sphere) of `radius` whose axis,
    /// frame axis z, reaches `half_height` from its centre.
    pub(super) fn emit_round(
        &mut self,
        frame: &Frame,
        radius: f64,
        half_height: f64,
        owner: &str,
        what: &str,
    ) {
        let [rx, ry, axis] = [
            scaled(frame.axis(0), radius),
            scaled(frame.axis(1), radius),
            scaled(frame.axis(2), half_height),
        ];
        let half_z = axis[2].abs() + rx[2].hypot(ry[2]);
        if !self.meets_robot(frame.origin[2], half_z, owner) {
            return;
        }
        if tilt(axis) > TILT_TOLERANCE && half_height > 0.0 {
            self.footprint(frame.origin, [rx, ry, axis], owner, what);
            return;
        }
        let (a, b) = (rx[0].hypot(rx[1]), ry[0].hypot(ry[1]));
        if (a - b).abs() > 1e-9 * a.max(b) {
            self.warn(format!(
                "{owner}: a {what} scaled into an ellipse ({a:.4} x {b:.4} m): imported as a circle of radius {:.4} m",
                a.max(b)
            ));
        }
        self.push(
            Obstacle::Circle {
                center: [frame.origin[0], frame.origin[1]],
                radius: a.max(b),
            },
            owner,
        );
    }

    /// The 2D box enclosing a 3D box of half-axes `axes` seen from above. For a box standing
    /// upright (one axis vertical) it is the exact footprint, turned by the first horizontal axis.
    fn footprint(&mut self, center: Vec3, axes: [Vec3; 3], owner: &str, what: &str) {
        let up = (0..3)
            .min_by(|&i, &j| tilt(axes[i]).total_cmp(&tilt(axes[j])))
            .unwrap_or(2);
        let lean = tilt(axes[up]);
        if lean > TILT_TOLERANCE {
            self.warn(format!(
                "{owner}: a {what} that does not stand upright (tilted by {lean:.3} rad): its footprint is approximated by the enclosing box"
            ));
        }
        let along = (0..3)
            .filter(|&i| i != up)
            .map(|i| [axes[i][0], axes[i][1]])
            .find(|v| v[0].hypot(v[1]) > 1e-12)
            .unwrap_or([1.0, 0.0]);
        let yaw = along[1].atan2(along[0]);
        let (s, c) = yaw.sin_cos();
        let half_u: f64 = axes.iter().map(|a| (a[0] * c + a[1] * s).abs()).sum();
        let half_v: f64 = axes.iter().map(|a| (-a[0] * s + a[1] * c).abs()).sum();
        self.push(
            Obstacle::Box {
                center: [center[0], center[1]],
                size: [2.0 * half_u, 2.0 * half_v],
                yaw: wrap_angle(yaw),
            },
            owner,
        );
    }

    /// Adds an obstacle after the checks the world format needs (finite, positive, near).
    pub(super) fn push(&mut self, obstacle: Obstacle, owner: &str) {
        let obstacle = match obstacle {
            Obstacle::Box { center, size, yaw } => Obstacle::Box {
                center: center.map(snap),
                size: size.map(snap),
                yaw: wrap_angle(snap(yaw)),
            },
            Obstacle::Circle { center, radius } => Obstacle::Circle {
                center: center.map(snap),
                radius: snap(radius),
            },
        };
        let (center, reach) = match obstacle {
            Obstacle::Box { center, size, .. } => (center, size[0].hypot(size[1]) / 2.0),
            Obstacle::Circle { center, radius } => (center, radius),
        };
        let sizes_ok = match obstacle {
            Obstacle::Box { size, yaw, .. } => size.iter().all(|s| *s > 1e-9) && yaw.is_finite(),
            Obstacle::Circle { radius, .. } => radius > 1e-9,
        };
        if !sizes_ok || !reach.is_finite() {
            self.warn(format!(
                "{owner}: a collision shape of zero or invalid size: skipped"
            ));
            return;
        }
        if center
            .iter()
            .any(|c| c.is_nan() || c.abs() + reach > MAX_EXTENT)
        {
            self.warn(format!(
                "{owner}: a collision shape at ({:.3}, {:.3}) reaches farther than {MAX_EXTENT} m from the origin: not imported",
                center[0], center[1]
            ));
            return;
        }
        if let Obstacle::Circle { radius, .. } = obstacle {
            self.warn(format!(
                "{owner}: a round obstacle of radius {radius:.4} m: kept as a circle; the mazesim world approximates it by a polygon of walls"
            ));
        }
        self.emit(obstacle);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn angles_wrap_into_the_half_open_interval() {
        assert!((wrap_angle(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-12);
        assert!((wrap_angle(-PI) - PI).abs() < 1e-12);
        assert!((wrap_angle(0.5) - 0.5).abs() < 1e-12);
    }
}
