//! Expansions of the common Webots PROTOs into collision boxes. Each is written Z-up, as the
//! R2023b PROTO files define it; in files before R2022a the fields are converted (a size
//! `(x, y, z)` becomes `(z, x, y)`, a floor size `(x, z)` becomes `(z, x)`) and the expansion is
//! turned into the node's Y-up frame.
//!
//! Sources (cyberbotics/webots, R2023b unless noted): `projects/objects/floors/protos/
//! RectangleArena.proto`, `.../apartment_structure/protos/Wall.proto` (R2021c: size 1 2.4 0.2,
//! box raised by half its y), `.../factory/containers/protos/WoodenBox.proto` and
//! `CardboardBox.proto`, `.../solids/protos/SolidBox.proto`; cyberbotics/webots_ros2
//! `webots_ros2_epuck/protos/LegoTallWall.proto` and `LegoTallInterval.proto` (R2021c: Y-up boxes
//! 0.016 x 0.15 x 0.096 and 0.016 x 0.15 x 0.016).

use super::frames::{apply, y_up_size, Frame, Vec3, ENU_TO_NUE};
use super::import::Importer;
use super::tree::Node;

impl<'d> Importer<'d> {
    /// Expands a known PROTO; false when the type is not one.
    pub fn expand_proto(&mut self, node: &'d Node, frame: &Frame) -> bool {
        let look = self.proto_look(node);
        let outer = std::mem::replace(&mut self.look, look);
        let known = self.expand_known(node, frame);
        self.look = outer;
        known
    }

    fn expand_known(&mut self, node: &'d Node, frame: &Frame) -> bool {
        match node.type_name.as_str() {
            "RectangleArena" => self.rectangle_arena(node, frame),
            "Wall" => self.wall(node, frame),
            // WoodenBox clamps each size to [0.01, 3], CardboardBox to [0.01, 2.5].
            "WoodenBox" => self.container(node, frame, 3.0),
            "CardboardBox" => self.container(node, frame, 2.5),
            "SolidBox" => self.solid_box(node, frame),
            "LegoTallWall" => self.fixed_box(node, frame, [0.016, 0.15, 0.096]),
            "LegoTallInterval" => self.fixed_box(node, frame, [0.016, 0.15, 0.016]),
            _ => return false,
        }
        true
    }

    /// The Z-up frame of a PROTO instance; `default_translation` is the Z-up default.
    fn proto_frame(&mut self, node: &'d Node, frame: &Frame, default_translation: Vec3) -> Frame {
        let default = if self.y_up {
            apply(&ENU_TO_NUE, default_translation)
        } else {
            default_translation
        };
        let local = self.local_frame(node, default);
        self.z_up(&frame.then(&local))
    }

    /// A PROTO's `size` as a Z-up size, or `default` (Z-up).
    fn proto_size(&mut self, node: &'d Node, default: Vec3) -> Vec3 {
        if node.field("size").is_none() {
            return default;
        }
        let written = self.vector(
            node,
            "size",
            if self.y_up {
                [default[1], default[2], default[0]]
            } else {
                default
            },
        );
        if self.y_up {
            y_up_size(written)
        } else {
            written
        }
    }

    fn positive_or_default(&mut self, node: &'d Node, size: Vec3, default: Vec3) -> Vec3 {
        if size.iter().all(|s| *s > 0.0) {
            return size;
        }
        let label = self.label(node);
        self.warn(format!(
            "{label}: size {size:?} must be positive (as Webots requires); used {default:?}"
        ));
        default
    }

    fn box_at(&mut self, node: &'d Node, frame: &Frame, center: Vec3, size: Vec3) {
        let label = self.label(node);
        self.emit_box(
            &frame.then(&Frame::translation(center)),
            size.map(|s| s / 2.0),
            &label,
        );
    }

    fn rectangle_arena(&mut self, node: &'d Node, frame: &Frame) {
        let frame = self.proto_frame(node, frame, [0.0; 3]);
        let mut floor = self.vector(node, "floorSize", [1.0, 1.0]);
        if self.y_up {
            floor = [floor[1], floor[0]];
        }
        if floor.iter().any(|s| *s <= 0.0) {
            let label = self.label(node);
            self.warn(format!(
                "{label}: floorSize {floor:?} must be positive; used [1.0, 1.0]"
            ));
            floor = [1.0, 1.0];
        }
        let mut thickness = self.number(node, "wallThickness", 0.01);
        if thickness <= 0.0 {
            thickness = 0.01;
        }
        let mut height = self.number(node, "wallHeight", 0.1);
        if height <= 0.0 {
            height = 0.1;
        }
        self.arena_floor(node, &frame, floor);
        self.floor_surface(&frame, floor);
        let [fx, fy] = floor;
        let (x, y, z) = (
            fx / 2.0 + thickness / 2.0,
            fy / 2.0 + thickness / 2.0,
            height / 2.0,
        );
        for sign in [1.0, -1.0] {
            self.box_at(node, &frame, [sign * x, 0.0, z], [thickness, fy, height]);
        }
        for sign in [1.0, -1.0] {
            self.box_at(
                node,
                &frame,
                [0.0, sign * y, z],
                [fx + 2.0 * thickness, thickness, height],
            );
        }
    }

    /// `Wall`: its translation is the centre of its bottom face.
    fn wall(&mut self, node: &'d Node, frame: &Frame) {
        let frame = self.proto_frame(node, frame, [0.0; 3]);
        let default = [0.2, 1.0, 2.4];
        let size = self.proto_size(node, default);
        let size = self.positive_or_default(node, size, default);
        self.box_at(node, &frame, [0.0, 0.0, size[2] / 2.0], size);
    }

    /// `WoodenBox` and `CardboardBox`: a box centred on the translation; static when mass <= 0, a
    /// movable body when light and small enough (`Importer::make_movable`).
    fn container(&mut self, node: &'d Node, frame: &Frame, max_size: f64) {
        let label = self.label(node);
        let mass = self.number(node, "mass", 0.0);
        if self.number(node, "lidAngle", 0.0) != 0.0 {
            self.warn(format!("{label}: an open lid: imported as a closed box"));
        }
        let frame = self.proto_frame(node, frame, [0.0, 0.0, 0.3]);
        let size = self.proto_size(node, [0.6; 3]);
        let clamped = size.map(|s| s.clamp(0.01, max_size));
        if clamped != size {
            self.warn(format!(
                "{label}: size {size:?} clamped to {clamped:?} as Webots does (0.01 to {max_size} m)"
            ));
        }
        let first = self.obstacles.len();
        // With a mass it has physics: placed in the air, it falls onto the floor.
        self.falls = mass > 0.0;
        self.box_at(node, &frame, [0.0; 3], clamped);
        self.falls = false;
        if mass > 0.0 && !self.make_movable(first, Some(mass), false) {
            self.warn_static(node);
        }
    }

    fn solid_box(&mut self, node: &'d Node, frame: &Frame) {
        if node
            .field("enableBoundingObject")
            .is_some_and(|f| f.value.bools == [false])
        {
            return;
        }
        let falls = self.is_dynamic(node);
        if falls {
            self.warn_static(node);
        }
        let frame = self.proto_frame(node, frame, [0.0, 0.0, 1.0]);
        let size = self.proto_size(node, [2.0; 3]);
        let size = self.positive_or_default(node, size, [2.0; 3]);
        self.falls = falls;
        self.box_at(node, &frame, [0.0; 3], size);
        self.falls = false;
    }

    /// A PROTO of one fixed box centred on its translation; `y_up_size` is its size as the Y-up
    /// (R2021c) PROTO writes it, the Z-up size follows from it.
    fn fixed_box(&mut self, node: &'d Node, frame: &Frame, y_up_box: Vec3) {
        let frame = self.proto_frame(node, frame, [0.0, 0.0, 0.025]);
        let size = if self.y_up {
            y_up_size(y_up_box)
        } else {
            // The R2022a+ PROTOs stand the box up without turning it: 0.016 x 0.096 x 0.15.
            [y_up_box[0], y_up_box[2], y_up_box[1]]
        };
        self.box_at(node, &frame, [0.0; 3], size);
    }
}
