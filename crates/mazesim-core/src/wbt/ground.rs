//! The ground the robot stands on: the surfaces a world offers as floor (a horizontal `Plane`
//! bounding object, a `RectangleArena`'s or a `Floor`'s floor, the level top of a static box)
//! and which of them is under the run's e-puck at its start.
//!
//! The import measures heights from z = 0: what lies on the floor (marks, textures) and what
//! the robot meets. A world that puts its floor elsewhere (an arena placed on a table, a whole
//! scene saved below the origin, a maze of planks raised on legs) is imported shifted so that
//! the surface under the robot's start is at 0: the floor is what the robot stands on.

use super::frames::{tilt, Frame, Vec3};
use super::import::{Importer, TILT_TOLERANCE};

/// A robot whose floor is this far (metres) from the world's origin stands on a floor that is
/// not at height 0.
const RAISED: f64 = 0.02;
/// How near (metres) a surface must be to the robot's origin (the bottom of its wheels) to be
/// the floor it stands on.
const ON_FLOOR: f64 = 0.01;

/// A horizontal surface the robot may stand on, in the world frame (Z up).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Surface {
    /// Its height (m).
    pub height: f64,
    /// The centre of its rectangle on the floor's plane.
    pub center: [f64; 2],
    /// The half-extent vectors of its rectangle on the floor's plane; `None`: unbounded (a
    /// `Plane` of a Y-up world, whose size is along axes the import does not keep).
    pub half_axes: Option<[[f64; 2]; 2]>,
}

impl Surface {
    /// Whether the point `(x, y)` of the floor's plane is on the surface's rectangle.
    pub fn covers(&self, x: f64, y: f64) -> bool {
        let Some(axes) = self.half_axes else {
            return true;
        };
        let d = [x - self.center[0], y - self.center[1]];
        axes.iter().all(|a| {
            let length2 = a[0] * a[0] + a[1] * a[1];
            length2 > 0.0 && ((d[0] * a[0] + d[1] * a[1]) / length2).abs() <= 1.0 + 1e-9
        })
    }
}

/// The height of the floor under the robot (origin `robot`, world frame) when it is not at 0:
/// the surface nearest the robot's origin, within [`ON_FLOOR`] of it, that covers its place,
/// when it is more than [`RAISED`] from 0. `None` for a robot on a floor at 0 (or on nothing
/// the import knows as floor).
pub fn floor_under(robot: Option<Vec3>, surfaces: &[Surface]) -> Option<f64> {
    let [x, y, z] = robot?;
    let under = surfaces
        .iter()
        .filter(|s| (s.height - z).abs() <= ON_FLOOR && s.covers(x, y))
        .min_by(|a, b| (a.height - z).abs().total_cmp(&(b.height - z).abs()))?;
    (under.height.abs() > RAISED).then_some(under.height)
}

/// The warning of a world imported shifted so that the floor at `height` is at 0.
pub fn shifted_warning(height: f64) -> String {
    if height > 0.0 {
        format!(
            "the e-puck stands on a floor {height:.3} m above the world's origin: the world is imported lowered by {height:.3} m, its floor at 0"
        )
    } else {
        format!(
            "the e-puck stands on a floor {:.3} m below the world's origin: the world is imported raised by {:.3} m, its floor at 0",
            -height, -height
        )
    }
}

impl<'d> Importer<'d> {
    /// Records the rectangle of `size` (along `frame`'s first two axes, Z up), centred on its
    /// origin, as a surface the robot may stand on, when it is level.
    pub fn floor_surface(&mut self, frame: &Frame, size: [f64; 2]) {
        if tilt(frame.axis(2)) > TILT_TOLERANCE {
            return;
        }
        let half = |i: usize| {
            let a = frame.axis(i);
            [a[0] * size[i] / 2.0, a[1] * size[i] / 2.0]
        };
        self.floors.push(Surface {
            height: frame.origin[2],
            center: [frame.origin[0], frame.origin[1]],
            half_axes: Some([half(0), half(1)]),
        });
    }

    /// Records a level plane at `frame`'s origin with no bounds.
    pub fn unbounded_floor(&mut self, frame: &Frame) {
        self.floors.push(Surface {
            height: frame.origin[2],
            center: [frame.origin[0], frame.origin[1]],
            half_axes: None,
        });
    }
}

#[cfg(test)]
mod tests {
    use super::{floor_under, Surface};
    use crate::wbt::WbtImport;

    fn import(text: &str) -> WbtImport {
        WbtImport::from_text(text, "test.wbt").unwrap_or_else(|e| panic!("{e}"))
    }

    fn warned(import: &WbtImport, words: &str) -> bool {
        import.warnings.iter().any(|w| w.contains(words))
    }

    /// The world's one mark is painted and its warning says how the floor was shifted.
    fn painted_on_a_shifted_floor(w: &WbtImport, shifted: &str) {
        assert_eq!(w.paint.len(), 1, "{:?}", w.warnings);
        assert!(warned(w, shifted), "{:?}", w.warnings);
    }

    #[test]
    fn a_mark_on_an_arena_below_the_origin_is_painted() {
        // An arena placed 6 cm below the origin (Y-up), the e-puck on it, a black mark 2 mm
        // thick lying on its floor: measured from 0 the mark is 5.8 cm down and lost.
        let w = import(
            "#VRML_SIM R2021b utf8\nWorldInfo { coordinateSystem \"NUE\" }\n\
             RectangleArena { translation 0 -0.06 0 floorSize 2 2 }\n\
             E-puck { translation 0.05 -0.06 -0.7 }\n\
             Solid { translation 0.3 -0.059 0 children [ Shape { \
               appearance PBRAppearance { baseColor 0 0 0 } \
               geometry Box { size 0.5 0.002 0.02 } } ] }\n",
        );
        painted_on_a_shifted_floor(&w, "a floor 0.060 m below the world's origin");
        assert_eq!(w.obstacles.len(), 4, "the arena's walls stand on its floor");
    }

    #[test]
    fn a_mark_on_a_raised_plank_the_robot_stands_on_is_painted() {
        // A plank 0.49 m up on the ground's arena (Z-up), the e-puck on it, a black strip on it.
        let w = import(
            "#VRML_SIM R2023b utf8\n\
             RectangleArena { floorSize 3 3 }\n\
             Solid { translation 0 0 0.485 boundingObject Box { size 1.2 0.2 0.01 } }\n\
             E-puck { translation 0.3 0 0.4901 }\n\
             Pose { translation -0.2 0 0.4905 children [ Shape { \
               appearance PBRAppearance { baseColor 0 0 0 } \
               geometry Box { size 0.3 0.05 0.001 } } ] }\n",
        );
        painted_on_a_shifted_floor(&w, "a floor 0.490 m above the world's origin");
        assert!(!warned(&w, "passes over the robot"), "{:?}", w.warnings);
        // The same e-puck on the ground beside the plank stands on the arena's floor at 0.
        let ground = import(
            "#VRML_SIM R2023b utf8\n\
             RectangleArena { floorSize 3 3 }\n\
             Solid { translation 0 0 0.485 boundingObject Box { size 1.2 0.2 0.01 } }\n\
             E-puck { translation 0.3 1 0 }\n",
        );
        assert!(
            !warned(&ground, "the world's origin"),
            "{:?}",
            ground.warnings
        );
    }

    fn square(height: f64, center: [f64; 2], half: f64) -> Surface {
        Surface {
            height,
            center,
            half_axes: Some([[half, 0.0], [0.0, half]]),
        }
    }

    #[test]
    fn the_floor_is_the_surface_under_the_robot() {
        let ground = square(0.0, [0.0, 0.0], 2.0);
        let plank = square(0.495, [0.35, 0.0], 0.1);
        let surfaces = [ground, plank];
        assert_eq!(
            floor_under(Some([0.35, 0.05, 0.4949]), &surfaces),
            Some(0.495)
        );
        // Off the plank, at its height: nothing under the robot is floor.
        assert_eq!(floor_under(Some([0.8, 0.0, 0.4949]), &surfaces), None);
        assert_eq!(floor_under(Some([0.35, 0.0, 0.0]), &surfaces), None);
        let sunk = [square(-0.06, [0.0, 0.0], 1.0)];
        assert_eq!(floor_under(Some([0.05, -0.7, -0.06]), &sunk), Some(-0.06));
        let unbounded = Surface {
            height: 0.3,
            center: [5.0, 5.0],
            half_axes: None,
        };
        assert_eq!(
            floor_under(Some([0.0, 0.0, 0.305]), &[unbounded]),
            Some(0.3)
        );
        assert_eq!(floor_under(None, &[unbounded]), None);
    }
}
