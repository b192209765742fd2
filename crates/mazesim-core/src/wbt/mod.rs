//! Webots `.wbt` worlds: a reader of the file format and an import into a mazesim world.
//!
//! Reading ([`Document::parse`]) follows the VRML97 syntax Webots writes: the `#VRML_SIM` header
//! of any version from V8.5 to R2025a, comments, commas as white space, `EXTERNPROTO`, `DEF` /
//! `USE` (the most recent earlier DEF) and `hidden` lines (engine state, skipped). Malformed text
//! is an [`Error::Format`](crate::Error::Format) with its line and column.
//!
//! Importing ([`WbtImport`]) walks the scene in 3D (Solid, Pose, Transform, Group, joints and the
//! common PROTOs), keeps every collision shape (`boundingObject`) that meets the robot's height
//! as a 2D obstacle in the world frame (z up, metres, radians), reads the e-puck's start pose
//! and `WorldInfo.basicTimeStep`. Worlds before R2022a are converted from NUE as Webots' own
//! converter does; later files that say `coordinateSystem "NUE"` are turned as a whole. Objects
//! with physics are kept as static obstacles, with a warning. The robot's model picks the
//! profile (`e-puck`, or `e-puck2` for `version "2"`; another robot gets the e-puck in its place,
//! with a warning), the devices in its extension slots are listed, and floor image textures are
//! found for [`WbtImport::paint_floor`]. Visual-only shapes lying on the floor (a line given as
//! a thin Box or an `.obj` Mesh outside any Solid) become floor paint, as Webots' infra-red
//! sensors see them; those standing in the proximity rays' way (a decorative wall, a goal object
//! the robot drives through) become sensed-only obstacles, seen by the infra-red sensors and the
//! camera and met by nothing else. Anything not understood (an unknown PROTO, a tilted shape, a mesh bounding
//! object, a visual-only shape above the floor out of the proximity rays) becomes a warning.
//!
//! ```
//! use mazesim_core::wbt::{Obstacle, WbtImport};
//!
//! let text = "#VRML_SIM R2023b utf8\nWorldInfo { basicTimeStep 16 }\n\
//!             WoodenBox { translation 0.3 0 0.05 size 0.1 0.1 0.1 }\n\
//!             E-puck { rotation 0 0 1 1.57 }\n";
//! let import = WbtImport::from_text(text, "boxes.wbt").unwrap();
//! assert_eq!(import.basic_time_step_ms, 16.0);
//! let [x, y, yaw] = import.robot.unwrap();
//! assert!(x.abs() < 1e-12 && y.abs() < 1e-12 && (yaw - 1.57).abs() < 1e-12);
//! let Obstacle::Box { center, size, .. } = import.obstacles[0] else { panic!("a box") };
//! assert!((center[0] - 0.3).abs() < 1e-12 && (size[0] - 0.1).abs() < 1e-12);
//! let world = import.to_world("boxes").unwrap();
//! assert_eq!(world.walls().len(), 1);
//! ```

mod appearance;
mod convert;
mod devices;
mod floor_marks;
mod floor_texture;
mod frames;
mod ground;
mod header;
mod import;
mod lexer;
mod parser;
mod protos;
mod sensed;
mod shapes;
mod start_pose;
mod tree;
mod wall_meshes;

use std::path::Path;

use crate::error::{Error, Result};

pub use appearance::{reflection_factor, BodyLook, Look, WallTexture};
pub use convert::polygon_sides;
pub use devices::{DeviceField, ExtensionDevice};
pub use floor_marks::{obj_triangles, FloorMesh};
pub use floor_texture::{grey_reflectance, FloorTexture, GreyImage};
pub use header::WbtVersion;
pub use import::EPUCK_DEFAULT_CONTROLLER;
pub use tree::{Document, Field, Node, NodeId, Value};

/// A 2D obstacle of an imported world, in metres and radians, world frame, z up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Obstacle {
    /// A box seen from above.
    Box {
        /// Centre.
        center: [f64; 2],
        /// Extent along the box's own x and y.
        size: [f64; 2],
        /// Rotation about z, in (-pi, pi].
        yaw: f64,
    },
    /// A disc (an upright cylinder, capsule or sphere).
    Circle {
        /// Centre.
        center: [f64; 2],
        /// Radius.
        radius: f64,
    },
}

/// Which robot of a world a run simulates: by default the first e-puck; with `controller`, the
/// first e-puck whose `controller` field names it; with `line`, the robot (any robot node, an
/// e-puck or not) whose node type is on that line of the file, as [`WorldRobot::line`] gives it.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct RobotChoice<'a> {
    /// The controller whose first e-puck runs.
    pub controller: Option<&'a str>,
    /// The line of the robot that runs (wins over `controller`).
    pub line: Option<usize>,
    /// The first line of the nodes a supervisor imported while the world runs (the running
    /// world's text gives them after the file's own lines): a robot there that is not an
    /// e-puck is warned of as what the run makes of it, an obstacle whose controller does not
    /// start.
    pub imported_from: Option<usize>,
}

impl<'a> From<Option<&'a str>> for RobotChoice<'a> {
    fn from(controller: Option<&'a str>) -> Self {
        RobotChoice {
            controller,
            ..RobotChoice::default()
        }
    }
}

/// A robot of a `.wbt` world, as Webots runs it: its own node, controller and start pose.
#[derive(Debug, Clone, PartialEq)]
pub struct WorldRobot {
    /// Start pose (x, y, yaw).
    pub pose: [f64; 3],
    /// The model as found: `E-puck`, `e-puck2`, or the type name of another robot.
    pub model: String,
    /// The profile that simulates it (`e-puck`, `e-puck2`), or `None` for a robot that is not
    /// an e-puck: its controller runs, its body stays where it is (its collision shapes, when
    /// the file gives them, are static obstacles).
    pub profile: Option<&'static str>,
    /// Its `controller` field (`None` when the field is absent: Webots' default, `<generic>`
    /// in old files, `void` since R2022b).
    pub controller: Option<String>,
    /// Its `name` field, when the file gives one.
    pub name: Option<String>,
    /// Its DEF name, when it has one.
    pub def_name: Option<String>,
    /// The line of its node type in the file.
    pub line: usize,
    /// Its body is modelled Y-up: forward along its node's local -z, up its local y, left its
    /// local -x, as every robot of a file before R2022a and a body built so and stood upright
    /// by its `rotation` in a later file; its start pose and its devices' frames are read so.
    pub y_up: bool,
    /// The type of its node once a project's PROTOs are expanded (`E-puck`, `Robot`,
    /// `Pioneer3dx`...): a project's own robot PROTO is the base node its body is.
    pub node_type: String,
    /// Its node's own `model` field, when the node (or the PROTO it expands from) writes one.
    pub model_field: Option<String>,
}

/// What a `.wbt` world holds for mazesim.
#[derive(Debug, Clone, PartialEq)]
pub struct WbtImport {
    /// The static obstacles, in file order.
    pub obstacles: Vec<Obstacle>,
    /// How each obstacle looks: the colour a camera sees (`None`: the grey of its reflection
    /// factor) and its infra-red reflection factor, in the order of `obstacles` (see
    /// `appearance.rs`).
    pub obstacle_looks: Vec<Look>,
    /// How high the top of each obstacle stands above the floor (m), in the order of
    /// `obstacles`; infinite where the import does not know (another robot's body).
    pub obstacle_tops: Vec<f64>,
    /// Obstacles only infra-red rays and cameras meet, in file order: visual-only shapes (of
    /// no Solid with a `boundingObject`) in the e-puck's proximity rays' way (see `sensed.rs`).
    /// The world keeps them as `sensed_only` walls, after the others.
    pub sensed_obstacles: Vec<Obstacle>,
    /// How each of `sensed_obstacles` looks.
    pub sensed_looks: Vec<Look>,
    /// How high the top of each of `sensed_obstacles` stands above the floor (m).
    pub sensed_tops: Vec<f64>,
    /// Per sensed-only obstacle, the lines of the nodes that hold it, as `obstacle_owners`:
    /// a supervisor moving one of those nodes moves it.
    pub sensed_owners: Vec<Vec<usize>>,
    /// The colour of the floor, when the world gives one (see `appearance.rs`).
    pub floor_colour: Option<[f64; 3]>,
    /// The infra-red reflection factor of that floor (its appearance's red and roughness, as
    /// a wall's); the floor of no colour read reflects as white.
    pub floor_reflectance: Option<f64>,
    /// Per obstacle, the lines of the nodes that hold it, outermost first (the file's node
    /// that places it, the Solid whose collision shape it is, and those between): moving one
    /// of those nodes moves it.
    pub obstacle_owners: Vec<Vec<usize>>,
    /// The movable bodies (light, small objects with physics), in file order.
    pub bodies: Vec<crate::world::spec::BodySpec>,
    /// Per movable body, the lines of the nodes that hold it, as `obstacle_owners`.
    pub body_owners: Vec<Vec<usize>>,
    /// How each movable body looks to a camera.
    pub body_looks: Vec<BodyLook>,
    /// The robot's start pose (x, y, yaw), if the world has one: the e-puck's, or that of the
    /// robot the e-puck stands in for.
    pub robot: Option<[f64; 3]>,
    /// The robot's model as found: `E-puck`, `e-puck2` for an E-puck of `version "2"`, or the
    /// type name of a robot that is not an e-puck; `None` without a robot.
    pub robot_model: Option<String>,
    /// The line of the robot's node in the file (its node type's line); `None` without a robot.
    pub robot_line: Option<usize>,
    /// The mazesim robot profile that simulates it: `e-puck` or `e-puck2`.
    pub robot_profile: String,
    /// Every robot of the world, in file order: e-pucks and others (see [`WorldRobot`]).
    pub robots: Vec<WorldRobot>,
    /// Devices in the robot's extension slots.
    pub extension_devices: Vec<ExtensionDevice>,
    /// The e-puck's own devices (`ps0`, `gs0`, `left wheel motor`, `camera`...) that the run's
    /// robot's node does not hold, which Webots' `getDevice` does not find: those a plain robot
    /// node (an e-puck saved expanded, a project's robot, a robot that is no e-puck) lacks among
    /// its children, and an E-puck PROTO's ground sensors without their module in a slot.
    pub missing_devices: Vec<String>,
    /// Image textures on the floor, painted by [`WbtImport::paint_floor`].
    pub floor_textures: Vec<FloorTexture>,
    /// Image textures of walls' appearances, which [`WbtImport::shade_walls`] reads the
    /// infra-red reflection factor of (see `appearance.rs`).
    pub wall_textures: Vec<WallTexture>,
    /// Meshes of visual-only shapes (`Mesh` in a `Shape` that no `Solid` with a
    /// `boundingObject` owns), painted on the floor when they lie on it; read by the import.
    pub floor_meshes: Vec<FloorMesh>,
    /// Floor paint: the textures painted so far, then the marks of visual-only shapes lying
    /// on the floor.
    pub paint: Vec<crate::world::spec::PaintSpec>,
    /// Per entry of `paint`, the lines of the nodes that hold it: a supervisor that moves one
    /// of them moves the paint (none for a floor texture's or a mesh's paint).
    pub paint_owners: Vec<Vec<usize>>,
    /// `WorldInfo.basicTimeStep` (Webots' default 32 ms when absent).
    pub basic_time_step_ms: f64,
    /// Everything not imported or approximated, one sentence each, with its line.
    pub warnings: Vec<String>,
    /// Those of `warnings` that concern a run of one controller only (the world's other
    /// e-pucks, which a run of the whole world simulates).
    pub one_controller_warnings: Vec<String>,
}

impl WbtImport {
    /// Imports a world file's text; `source` names it in error messages, and floor textures
    /// are looked for beside it.
    pub fn from_text(text: &str, source: &str) -> Result<WbtImport> {
        Self::from_text_for(text, source, RobotChoice::default())
    }

    /// [`WbtImport::from_text`] for the run of one robot (see [`RobotChoice`]): of several
    /// e-pucks, the first whose `controller` field names the controller is the robot (Webots
    /// runs each robot's own controller), or the robot on the chosen line.
    pub fn from_text_for<'a>(
        text: &str,
        source: &str,
        choice: impl Into<RobotChoice<'a>>,
    ) -> Result<WbtImport> {
        let limit = crate::limits::MAX_WBT_FILE_BYTES;
        crate::io::check_text_length(text, source, limit, "the Webots world")?;
        let document = Document::parse(text, source)?;
        let dir = Path::new(source).parent().unwrap_or(Path::new(""));
        let mut import = import::import(&document, choice.into(), dir);
        import.locate_textures(dir);
        import.paint_floor_meshes(dir);
        Ok(import)
    }

    /// Imports a world file's bytes, which must be UTF-8 text.
    pub fn from_bytes(bytes: &[u8], source: &str) -> Result<WbtImport> {
        Self::from_bytes_for(bytes, source, RobotChoice::default())
    }

    /// [`WbtImport::from_bytes`] for the run of one controller (see
    /// [`WbtImport::from_text_for`]).
    pub fn from_bytes_for<'a>(
        bytes: &[u8],
        source: &str,
        choice: impl Into<RobotChoice<'a>>,
    ) -> Result<WbtImport> {
        match std::str::from_utf8(bytes) {
            Ok(text) => Self::from_text_for(text, source, choice),
            Err(e) => {
                let valid = std::str::from_utf8(&bytes[..e.valid_up_to()]).unwrap_or_default();
                let line = valid.matches('\n').count() + 1;
                let column = valid.rsplit('\n').next().unwrap_or("").chars().count() + 1;
                Err(Error::format_at(
                    source,
                    line,
                    column,
                    "(text)",
                    format!(
                        "expected UTF-8 text, found the byte 0x{:02X}",
                        bytes[e.valid_up_to()]
                    ),
                ))
            }
        }
    }

    /// Reads and imports a `.wbt` file.
    pub fn load(path: &Path) -> Result<WbtImport> {
        Self::load_for(path, RobotChoice::default())
    }

    /// [`WbtImport::load`] for the run of one controller (see [`WbtImport::from_text_for`]).
    pub fn load_for<'a>(path: &Path, choice: impl Into<RobotChoice<'a>>) -> Result<WbtImport> {
        let limit = crate::limits::MAX_WBT_FILE_BYTES;
        let bytes = crate::io::read_limited(path, limit, "the Webots world")?;
        Self::from_bytes_for(&bytes, &path.display().to_string(), choice)
    }
}

#[cfg(test)]
mod tests;
