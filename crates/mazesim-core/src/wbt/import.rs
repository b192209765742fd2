//! From the node tree to a 2D import: the scene walk (Solid, Pose, Transform, Group, joints),
//! `WorldInfo`, the robot's start pose and the budget that keeps a hostile file bounded.
//! Collision shapes are in `shapes.rs`, PROTO expansions in `protos.rs`.

use std::collections::HashSet;

use super::appearance::WallTexture;
use super::appearance::{BodyLook, Look};
use super::devices::ExtensionDevice;
use super::floor_marks::FloorMesh;
use super::floor_texture::FloorTexture;
use super::frames::{axis_angle, tilt, Frame, Vec3, ENU_TO_NUE, IDENTITY, NUE_TO_ENU};
use super::ground::{floor_under, shifted_warning, Surface};
use super::shapes::snap;
use super::tree::{Document, Node, NodeId};
use super::{Obstacle, RobotChoice, WbtImport, WorldRobot};
use crate::world::spec::BodySpec;
use crate::world::values::{Finite, NonNegative, Positive, Reflectance};

/// The floor friction of an imported movable body: the `coulombFriction` of Webots' default
/// contact (`ContactProperties`, whose `coulombFriction` defaults to 1), which every contact
/// between two solids of the `default` material (the Solid's `contactMaterial` default) uses.
pub const WEBOTS_COULOMB_FRICTION: f64 = 1.0;

/// Webots' default `WorldInfo.basicTimeStep` in milliseconds.
pub const DEFAULT_BASIC_TIME_STEP_MS: f64 = 32.0;
/// Node visits after which the walk stops (USE can make a small file expand exponentially).
const MAX_VISITS: usize = 200_000;
/// Deepest frame nesting the walk follows (chains of USE can nest deeper than the text).
const MAX_WALK_DEPTH: usize = 200;
/// A rotation that tips the vertical by more than this (radians) is reported as not vertical.
pub const TILT_TOLERANCE: f64 = 0.01;
/// Obstacles and robots farther than this from the origin (metres) are left out: mazesim's
/// wall index is a uniform grid of 0.1 m bins over the world's bounds.
pub const MAX_EXTENT: f64 = 50.0;

/// Nodes that draw or light the scene and never collide.
const VISUAL_NODES: &[&str] = &[
    "Viewpoint",
    "Background",
    "TexturedBackground",
    "TexturedBackgroundLight",
    "DirectionalLight",
    "PointLight",
    "SpotLight",
    "Fog",
    "CadShape",
];
/// Robot base nodes: their bodies are the robot, not obstacles.
const ROBOT_NODES: &[&str] = &["Robot", "DifferentialWheels", "Supervisor"];
/// Robot PROTOs of Webots' library that are not the e-puck, recognised even without a
/// `controller` field (any other node with one is taken for a robot too).
const OTHER_ROBOT_PROTOS: &[&str] = &[
    "Thymio2",
    "Khepera1",
    "Khepera3",
    "Khepera4",
    "Elisa3",
    "Hemisson",
    "Pioneer2",
    "Pioneer3dx",
    "Pioneer3at",
    "Create",
    "TurtleBot3Burger",
    "Rosbot",
    "Robotino3",
    "Moose",
    "Mir100",
    "Tiago",
    "BB-8",
    "Nao",
];
/// The footprints of robot PROTOs of Webots' library whose collision shapes lie inside the
/// PROTO (which mazesim does not read): the radius (m) of the disc round the robot's origin that
/// stands for the body, from each robot's published size (diameter, or length and width for
/// the rectangular ones, whose disc is about half their larger side): Thymio II 110 x 112 mm;
/// Khepera I 55 mm, Khepera III 130 mm, Khepera IV 140 mm; Elisa-3 50 mm; Hemisson 120 mm;
/// Pioneer 2 and 3-DX 455 x 381 mm, 3-AT 508 x 497 mm; iRobot Create 340 mm; TurtleBot3
/// Burger 138 x 178 mm; Robotino 3 450 mm.
const ROBOT_FOOTPRINTS: &[(&str, f64)] = &[
    ("Thymio2", 0.056),
    ("Khepera1", 0.0275),
    ("Khepera3", 0.065),
    ("Khepera4", 0.07),
    ("Elisa3", 0.025),
    ("Hemisson", 0.06),
    ("Pioneer2", 0.22),
    ("Pioneer3dx", 0.22),
    ("Pioneer3at", 0.25),
    ("Create", 0.17),
    ("TurtleBot3Burger", 0.09),
    ("Robotino3", 0.225),
];
/// Half the height of the column a robot's footprint stands as (m), round its origin: it meets
/// the e-puck's sensors whether the robot's origin is on the floor or at its wheels' axle.
const FOOTPRINT_HALF_HEIGHT: f64 = 0.1;
/// The controller the E-puck PROTO runs when its node leaves `controller` out (its declared
/// default from Webots V8.5 to R2025a).
pub const EPUCK_DEFAULT_CONTROLLER: &str = "e-puck_avoid_obstacles";
/// The e-puck PROTOs of Webots and webots_ros2.
/// Webots 7 named it `EPuck`.
const EPUCK_PROTOS: &[&str] = &["E-puck", "E-puck_enu", "E-Puck_enu", "EPuck"];
/// Joint nodes: the Solid of their `endPoint` (as of a `Slot`) is placed in the parent's frame,
/// and a robot's joints hold its devices in their `device` field.
pub const JOINTS: &[&str] = &["HingeJoint", "Hinge2Joint", "SliderJoint", "BallJoint"];

/// The mazesim profile that stands in for a robot that is not an e-puck.
pub const STAND_IN_PROFILE: &str = "e-puck";

/// A robot found in the world: its start pose, model and the profile that simulates it.
#[derive(Clone)]
pub struct FoundRobot {
    pub pose: [f64; 3],
    pub model: String,
    pub profile: &'static str,
    /// The line of its node type in the file.
    pub line: usize,
    /// Its body is modelled Y-up (see [`WorldRobot::y_up`]).
    pub y_up: bool,
}

/// Heaviest object with physics imported as a movable body, kilograms: ten times the e-puck's
/// 0.15 kg. Heavier ones stay static obstacles (the robot could hardly push them).
pub const MAX_BODY_MASS: f64 = 1.5;

/// Widest object with physics imported as a movable body (a box's side, a disc's diameter),
/// metres. Wider ones (walls, furniture) stay static obstacles.
pub const MAX_BODY_SIDE: f64 = 0.5;

/// Most a movable box's footprint may be longer than wide: a longer, thinner box (a maze wall
/// with physics) stays a static obstacle.
pub const MAX_BODY_ELONGATION: f64 = 4.0;

/// An obstacle with how it looks (see `appearance.rs`).
pub type ColouredObstacle = (Obstacle, Look);

/// The state of one import.
pub struct Importer<'d> {
    pub doc: &'d Document,
    /// PROTOs and primitives are Y-up (files before R2022a).
    pub y_up: bool,
    /// The inside of the robot whose devices are being listed is modelled Y-up (see
    /// [`WorldRobot::y_up`]): its devices' frames are turned to the robot's Z-up frame.
    pub body_y_up: bool,
    pub obstacles: Vec<Obstacle>,
    /// How each of `obstacles` looks (see `appearance.rs`).
    pub obstacle_looks: Vec<Look>,
    /// How high the top of each of `obstacles` stands above the floor (m; see `WbtImport`).
    pub obstacle_tops: Vec<f64>,
    /// How the Solid whose collision shapes are being read looks.
    pub look: Look,
    /// Obstacles only infra-red rays and cameras meet (visual-only shapes in the proximity
    /// rays' way, see `sensed.rs`), and how they look.
    pub sensed_obstacles: Vec<Obstacle>,
    pub sensed_looks: Vec<Look>,
    pub sensed_tops: Vec<f64>,
    /// Per sensed-only obstacle, the lines of the nodes that hold it.
    pub sensed_owners: Vec<Vec<usize>>,
    /// Set while reading a visual-only shape as a sensed-only obstacle.
    pub sensing: bool,
    /// The floor's colour (see `appearance.rs`).
    pub floor_colour: Option<[f64; 3]>,
    /// The reflection factor of the floor whose colour is `floor_colour`.
    pub floor_reflectance: Option<f64>,
    /// Whether the world's first floor was met (a later one is a floor mark).
    pub floor_seen: bool,
    /// Per obstacle, the lines of the nodes that hold it (see [`WbtImport::obstacle_owners`]).
    pub obstacle_owners: Vec<Vec<usize>>,
    /// Movable bodies: objects with physics light and small enough to push (see `movable`).
    pub bodies: Vec<BodySpec>,
    /// Per movable body, the lines of the nodes that hold it.
    pub body_owners: Vec<Vec<usize>>,
    /// How each movable body looks to a camera.
    pub body_looks: Vec<BodyLook>,
    /// The lines of the nodes the walk is inside, outermost first.
    holders: Vec<usize>,
    /// The e-puck (or e-puck2) the world runs with.
    pub robot: Option<FoundRobot>,
    /// The first robot that is not an e-puck: the e-puck stands in for it when there is none.
    pub other_robot: Option<FoundRobot>,
    /// Where its warning is in `warnings`, and what the warning says of it (`line L: Type`,
    /// its type, whether it has collision shapes).
    other_robot_warning: Option<(usize, String, String, bool)>,
    /// Every robot of the world, in file order, with the collision shapes (and their colours)
    /// of those that are not e-pucks (kept as static obstacles unless the e-puck stands in for
    /// that robot) and the lines of the nodes that hold each shape.
    pub robots: Vec<(WorldRobot, Vec<ColouredObstacle>, Vec<Vec<usize>>)>,
    pub devices: Vec<ExtensionDevice>,
    /// The names of the devices met while the run's robot's devices are listed (its children's
    /// devices, and the ground sensors of a ground sensors module in its slots).
    pub held_devices: Vec<String>,
    /// Whether the run's robot holds a node whose devices mazesim cannot see (a PROTO it does
    /// not read), which leaves the e-puck's devices it lacks unknown.
    pub unseen_devices: bool,
    /// The e-puck's own devices the run's robot's node does not hold (see
    /// [`WbtImport::missing_devices`]).
    pub missing_devices: Vec<String>,
    pub floor_textures: Vec<FloorTexture>,
    /// The textures of walls' appearances (see `appearance.rs`).
    pub wall_textures: Vec<WallTexture>,
    /// Paint of the visual-only shapes lying on the floor (see `floor_marks.rs`).
    pub floor_marks: Vec<crate::world::spec::PaintSpec>,
    /// Per floor mark, the lines of the nodes that hold it (a supervisor moves it with them).
    pub floor_mark_owners: Vec<Vec<usize>>,
    /// Per floor mark, the height of its top (m): the higher is painted over the lower.
    pub floor_mark_tops: Vec<f64>,
    /// Meshes of visual-only shapes, read after the walk.
    pub floor_meshes: Vec<FloorMesh>,
    /// Whether the nearest Solid around the walk has a `boundingObject` (its shapes are then
    /// simulated through it).
    pub bounded: bool,
    pub warnings: Vec<String>,
    /// The warnings given so far: one given again (the same words of the same node, as a
    /// `CircleArena` stand-in's many wall segments would each give) is not repeated.
    warned: HashSet<String>,
    /// Those of `warnings` that a run of the whole world does not share.
    pub one_controller_warnings: Vec<String>,
    /// Set while reading the collision shapes of an object with physics: it falls onto the
    /// floor in Webots, so its height does not let the robot pass under it.
    pub falls: bool,
    /// How many collision shapes so far were low enough for the robot to drive on (imported
    /// as floor: a sheet or a slab whose top is within [`super::shapes::FLOOR_LEVEL`] of the
    /// floor where the world puts it, with or without physics; a pad of at most 2.5 mm without):
    /// a Solid whose collision shapes all were is a mark on the floor.
    pub stood_on: usize,
    /// The vertical extent (m) of the last collision shape kept as an obstacle: a movable
    /// body's height as it rests on the floor.
    pub shape_height: f64,
    /// How high the top of the shape being emitted stands above the floor (m): set by the
    /// checks each shape passes before it is emitted (infinite when none has).
    pub shape_top: f64,
    visits: usize,
    too_deep: bool,
    /// The e-puck whose `controller` field names the controller of the run, if one does.
    chosen: Option<&'d Node>,
    /// The first line of the nodes a supervisor imported while the world runs (see
    /// [`RobotChoice::imported_from`]).
    imported_from: Option<usize>,
    /// The surfaces met that the robot may stand on (see `ground.rs`), world frame.
    pub floors: Vec<Surface>,
    /// The folder of the world file, where the files of `Mesh` bounding objects are read.
    pub world_dir: std::path::PathBuf,
    /// The origin of the last robot pose read, and of the run's e-puck's (see
    /// [`floor_under`]).
    pose_at: Vec3,
    robot_at: Option<Vec3>,
}

/// Imports a parsed world.
pub fn import(doc: &Document, choice: RobotChoice<'_>, world_dir: &std::path::Path) -> WbtImport {
    let first = walk(doc, &choice, 0.0, world_dir);
    match floor_under(first.0.robot_at, &first.0.floors) {
        Some(height) => {
            let mut shifted = walk(doc, &choice, height, world_dir);
            shifted.0.warnings.push(shifted_warning(height));
            finish(shifted)
        }
        None => finish(first),
    }
}

/// Walks the whole world, lowered by `lowered_by` metres.
fn walk<'d>(
    doc: &'d Document,
    choice: &RobotChoice<'_>,
    lowered_by: f64,
    world_dir: &std::path::Path,
) -> (Importer<'d>, f64) {
    let mut importer = Importer {
        doc,
        y_up: !doc.version.has_z_up_protos(),
        body_y_up: !doc.version.has_z_up_protos(),
        obstacles: Vec::new(),
        obstacle_looks: Vec::new(),
        obstacle_tops: Vec::new(),
        look: Look::UNREAD,
        sensed_obstacles: Vec::new(),
        sensed_looks: Vec::new(),
        sensed_tops: Vec::new(),
        sensed_owners: Vec::new(),
        sensing: false,
        shape_height: 0.0,
        shape_top: f64::INFINITY,
        floor_colour: None,
        floor_reflectance: None,
        floor_seen: false,
        obstacle_owners: Vec::new(),
        bodies: Vec::new(),
        body_owners: Vec::new(),
        body_looks: Vec::new(),
        holders: Vec::new(),
        robot: None,
        other_robot: None,
        other_robot_warning: None,
        robots: Vec::new(),
        devices: Vec::new(),
        held_devices: Vec::new(),
        unseen_devices: false,
        missing_devices: Vec::new(),
        floor_textures: Vec::new(),
        wall_textures: Vec::new(),
        floor_marks: Vec::new(),
        floor_mark_owners: Vec::new(),
        floor_mark_tops: Vec::new(),
        floor_meshes: Vec::new(),
        bounded: false,
        warnings: doc.warnings.clone(),
        warned: HashSet::new(),
        one_controller_warnings: Vec::new(),
        falls: false,
        stood_on: 0,
        visits: 0,
        too_deep: false,
        chosen: None,
        imported_from: choice.imported_from,
        floors: Vec::new(),
        world_dir: world_dir.to_path_buf(),
        pose_at: [0.0; 3],
        robot_at: None,
    };
    importer.chosen = match choice.line {
        Some(line) => importer.robot_on_line(line),
        None => choice
            .controller
            .and_then(|name| importer.epuck_of_controller(name)),
    };
    let (basic_time_step_ms, root) = importer.world_info();
    let root = Frame::translation([0.0, 0.0, -lowered_by]).then(&root);
    for &id in &doc.roots {
        importer.scene(id, &root, 0);
    }
    (importer, basic_time_step_ms)
}

/// The import a walk gives, with the world's basic time step.
fn finish((mut importer, basic_time_step_ms): (Importer<'_>, f64)) -> WbtImport {
    if let (Some(_), Some((index, label, kind, shaped))) =
        (&importer.robot, &importer.other_robot_warning)
    {
        importer.warnings[*index] = not_an_epuck(label, kind, NotAnEpuck::Kept { shaped: *shaped });
    }
    let robot = importer.robot.take().or(importer.other_robot.take());
    let stand_in_line = robot
        .as_ref()
        .filter(|r| r.profile == STAND_IN_PROFILE)
        .map(|r| r.line);
    let mut robots = Vec::with_capacity(importer.robots.len());
    for (found, shapes, owners) in std::mem::take(&mut importer.robots) {
        if found.profile.is_none() && Some(found.line) != stand_in_line {
            for (shape, look) in shapes {
                importer.obstacles.push(shape);
                importer.obstacle_looks.push(look);
                importer.obstacle_tops.push(f64::INFINITY);
            }
            importer.obstacle_owners.extend(owners);
        }
        robots.push(found);
    }
    if robot.is_none() {
        importer
            .warnings
            .push("no robot in the world: the e-puck starts at (0, 0) facing +x".into());
    }
    let (paint, paint_owners) = importer.marks_from_below();
    let mut import = WbtImport {
        obstacles: importer.obstacles,
        obstacle_looks: importer.obstacle_looks,
        obstacle_tops: importer.obstacle_tops,
        sensed_obstacles: importer.sensed_obstacles,
        sensed_looks: importer.sensed_looks,
        sensed_tops: importer.sensed_tops,
        sensed_owners: importer.sensed_owners,
        floor_colour: importer.floor_colour,
        floor_reflectance: importer.floor_reflectance,
        obstacle_owners: importer.obstacle_owners,
        bodies: importer.bodies,
        body_owners: importer.body_owners,
        body_looks: importer.body_looks,
        robot: robot.as_ref().map(|r| r.pose),
        robot_model: robot.as_ref().map(|r| r.model.clone()),
        robot_line: robot.as_ref().map(|r| r.line),
        robot_profile: robot.map_or(STAND_IN_PROFILE, |r| r.profile).to_string(),
        robots,
        extension_devices: importer.devices,
        missing_devices: importer.missing_devices,
        floor_textures: importer.floor_textures,
        wall_textures: importer.wall_textures,
        floor_meshes: importer.floor_meshes,
        paint,
        paint_owners,
        basic_time_step_ms,
        warnings: importer.warnings,
        one_controller_warnings: importer.one_controller_warnings,
    };
    import.push_starts_out_of_walls();
    import
}

impl<'d> Importer<'d> {
    /// `line L: Type "name"` for messages.
    pub fn label(&self, node: &Node) -> String {
        let name = self
            .strings(node, "name")
            .first()
            .cloned()
            .or_else(|| node.def_name.clone());
        match name {
            Some(n) => format!("line {}: {} \"{}\"", node.line, node.type_name, n),
            None => format!("line {}: {}", node.line, node.type_name),
        }
    }

    pub fn warn(&mut self, message: String) {
        if self.warned.insert(message.clone()) {
            self.warnings.push(message);
        }
    }

    /// A warning of a run of one controller only: a run of the whole world simulates what it
    /// says is left out.
    fn warn_one_controller(&mut self, message: String) {
        if !self.warned.contains(&message) {
            self.one_controller_warnings.push(message.clone());
            self.warn(message);
        }
    }

    /// Counts a visit; false once the budget or the depth limit is exhausted.
    pub fn enter(&mut self, depth: usize) -> bool {
        self.visits += 1;
        if self.visits == MAX_VISITS {
            self.warn(format!(
                "the world expands (through USE) to more than {MAX_VISITS} nodes; the rest is not imported"
            ));
        }
        if depth == MAX_WALK_DEPTH && !self.too_deep {
            self.too_deep = true;
            self.warn(format!(
                "nodes nest deeper than {MAX_WALK_DEPTH} levels (through USE); the deeper ones are not imported"
            ));
        }
        self.visits < MAX_VISITS && depth < MAX_WALK_DEPTH
    }

    pub fn node(&self, id: NodeId) -> &'d Node {
        self.doc.node(id)
    }

    /// The numbers of a field, if present.
    pub fn numbers(&self, node: &'d Node, field: &str) -> Option<&'d [f64]> {
        node.field(field).map(|f| f.value.numbers.as_slice())
    }

    pub fn strings(&self, node: &'d Node, field: &str) -> &'d [String] {
        node.field(field)
            .map_or(&[], |f| f.value.strings.as_slice())
    }

    pub fn nodes(&self, node: &'d Node, field: &str) -> &'d [NodeId] {
        node.field(field).map_or(&[], |f| f.value.nodes.as_slice())
    }

    /// A field of `N` numbers, or `default` (with a warning when present but of another size).
    pub fn vector<const N: usize>(
        &mut self,
        node: &'d Node,
        field: &str,
        default: [f64; N],
    ) -> [f64; N] {
        match self.numbers(node, field) {
            None => default,
            Some(values) => match <[f64; N]>::try_from(values) {
                Ok(v) => v,
                Err(_) => {
                    let label = self.label(node);
                    self.warn(format!(
                        "{label}: field `{field}`: expected {N} numbers, found {}; used {default:?}",
                        values.len()
                    ));
                    default
                }
            },
        }
    }

    /// A single number field, or `default`.
    pub fn number(&mut self, node: &'d Node, field: &str, default: f64) -> f64 {
        self.vector::<1>(node, field, [default])[0]
    }

    /// The frame a node sets: `translation`, `rotation` (axis, angle) and `scale`.
    pub fn local_frame(&mut self, node: &'d Node, default_translation: Vec3) -> Frame {
        let translation = self.vector(node, "translation", default_translation);
        let [x, y, z, angle] = self.vector(node, "rotation", [0.0, 0.0, 1.0, 0.0]);
        let rotation = axis_angle([x, y, z], angle).unwrap_or_else(|| {
            if angle != 0.0 {
                let label = self.label(node);
                self.warn(format!(
                    "{label}: rotation axis ({x}, {y}, {z}) has no direction; rotation ignored"
                ));
            }
            IDENTITY
        });
        let mut scale = self.vector(node, "scale", [1.0; 3]);
        if scale.contains(&0.0) {
            let label = self.label(node);
            self.warn(format!(
                "{label}: scale {scale:?} has a zero component; scale ignored"
            ));
            scale = [1.0; 3];
        }
        Frame::new(translation, rotation, scale)
    }

    /// The frame in which a Z-up definition (PROTO expansion, primitive) is written: for files
    /// before R2022a, `frame` is Y-up and the definition is turned into it.
    pub fn z_up(&self, frame: &Frame) -> Frame {
        if self.y_up {
            frame.then(&Frame::rotation(ENU_TO_NUE))
        } else {
            *frame
        }
    }

    /// Reads `WorldInfo`: the basic time step and the frame of the whole world.
    fn world_info(&mut self) -> (f64, Frame) {
        let infos: Vec<NodeId> = self
            .doc
            .roots
            .iter()
            .copied()
            .filter(|&id| self.node(id).type_name == "WorldInfo")
            .collect();
        if infos.len() > 1 {
            let line = self.node(infos[1]).line;
            self.warn(format!(
                "line {line}: a second WorldInfo; only the first is read"
            ));
        }
        let mut step = DEFAULT_BASIC_TIME_STEP_MS;
        // Files before R2022a default to NUE, later ones to ENU.
        let mut system = if self.y_up { "NUE" } else { "ENU" }.to_string();
        if let Some(&id) = infos.first() {
            let info = self.node(id);
            let asked = self.number(info, "basicTimeStep", DEFAULT_BASIC_TIME_STEP_MS);
            // The world's own range, so that a step the world would refuse is a warning here.
            let (least, most) = crate::limits::BASIC_TIME_STEP_MS;
            if (least..=most).contains(&asked) {
                step = asked;
            } else {
                self.warn(format!(
                    "line {}: basicTimeStep: expected a number of milliseconds in [{least}, {most}], found {asked}; used {DEFAULT_BASIC_TIME_STEP_MS}",
                    info.line
                ));
            }
            if let Some(s) = self.strings(info, "coordinateSystem").first() {
                system = s.clone();
            }
        }
        let frame = match system.as_str() {
            "NUE" => Frame::rotation(NUE_TO_ENU),
            "ENU" => Frame::IDENTITY,
            other => {
                self.warn(format!(
                    "coordinateSystem \"{other}\": expected \"ENU\" or \"NUE\"; read as ENU"
                ));
                Frame::IDENTITY
            }
        };
        (step, frame)
    }

    /// Walks a node of the scene (outside bounding objects); what it emits is held by it (its
    /// line joins `holders` meanwhile).
    pub fn scene(&mut self, id: NodeId, frame: &Frame, depth: usize) {
        let line = self.node(id).line;
        self.holders.push(line);
        self.scene_node(id, frame, depth);
        self.holders.pop();
    }

    /// The lines of the nodes the walk is inside, each once: what holds what it emits now.
    pub fn owners(&self) -> Vec<usize> {
        let mut owners = self.holders.clone();
        owners.dedup();
        owners
    }

    /// Records an obstacle, with the look of the Solid being read, held by the nodes the walk
    /// is inside.
    pub fn emit(&mut self, obstacle: Obstacle) {
        let owners = self.owners();
        if self.sensing {
            self.sensed_obstacles.push(obstacle);
            self.sensed_looks.push(self.look);
            self.sensed_tops.push(self.shape_top);
            self.sensed_owners.push(owners);
            return;
        }
        self.obstacles.push(obstacle);
        self.obstacle_looks.push(self.look);
        self.obstacle_tops.push(self.shape_top);
        self.obstacle_owners.push(owners);
    }

    fn scene_node(&mut self, id: NodeId, frame: &Frame, depth: usize) {
        if !self.enter(depth) {
            return;
        }
        let node = self.node(id);
        let kind = node.type_name.as_str();
        if kind == "WorldInfo" || VISUAL_NODES.contains(&kind) {
            return;
        }
        if kind == "Shape" && self.bounded {
            self.textured_shape(node, frame);
        } else if kind == "Shape" {
            self.visual_shape(node, frame);
        } else if kind == "Floor" {
            self.floor(node, frame);
        } else if EPUCK_PROTOS.contains(&kind)
            || (ROBOT_NODES.contains(&kind) && self.looks_like_epuck(node))
        {
            self.epuck(node, frame);
        } else if ROBOT_NODES.contains(&kind) || self.is_robot_proto(node) {
            self.other_robot(node, frame);
        } else if JOINTS.contains(&kind) || kind == "Slot" {
            for &child in self.nodes(node, "endPoint") {
                self.scene(child, frame, depth + 1);
            }
        } else if kind == "Group" {
            self.scene_children(node, frame, depth);
        } else if kind == "Pose" || kind == "Transform" {
            let local = self.local_frame(node, [0.0; 3]);
            self.scene_children(node, &frame.then(&local), depth);
        } else if kind == "Solid" || kind == "Charger" {
            self.solid(node, frame, depth);
        } else if !self.expand_proto(node, frame) {
            let label = self.label(node);
            let what = if self.doc.declares_proto(kind) {
                "an unknown PROTO"
            } else {
                "a node type mazesim does not import"
            };
            self.warn(format!(
                "{label}: {what}: not imported (known PROTOs: RectangleArena, Floor, Wall, WoodenBox, CardboardBox, SolidBox, LegoTallWall, LegoTallInterval, E-puck)"
            ));
        }
    }

    fn scene_children(&mut self, node: &'d Node, frame: &Frame, depth: usize) {
        for &child in self.nodes(node, "children") {
            self.scene(child, frame, depth + 1);
        }
    }

    /// Whether a Solid (or PROTO with a `physics` field) moves: it has a Physics node.
    pub fn is_dynamic(&self, node: &'d Node) -> bool {
        !self.nodes(node, "physics").is_empty()
    }

    /// Warns that an object with physics (or a mass) is kept as a static obstacle: too heavy, too
    /// large or not one box or disc to be a movable body.
    pub fn warn_static(&mut self, node: &'d Node) {
        let label = self.label(node);
        self.warn(format!(
            "{label}: an object with physics: imported as a static obstacle (mazesim moves only one box or disc of at most {MAX_BODY_SIDE} m and {MAX_BODY_MASS} kg that is not a thin wall; the robot cannot push it)"
        ));
    }

    fn solid(&mut self, node: &'d Node, frame: &Frame, depth: usize) {
        let local = self.local_frame(node, [0.0; 3]);
        let frame = frame.then(&local);
        let falls = self.is_dynamic(node);
        let first = self.obstacles.len();
        let (first_sensed, first_body) = (self.sensed_obstacles.len(), self.bodies.len());
        let stood_on = self.stood_on;
        let look = self.solid_look(node);
        let outer_look = std::mem::replace(&mut self.look, look);
        for &shape in self.nodes(node, "boundingObject") {
            let label = self.label(node);
            self.falls = falls;
            self.bounding(shape, &frame, &label, depth + 1);
            self.falls = false;
        }
        self.look = outer_look;
        if falls && !self.nodes(node, "boundingObject").is_empty() {
            let mass = self.physics_mass(node);
            let sphere = self.sphere_bounded(node);
            if !self.make_movable(first, mass, sphere) && self.obstacles.len() > first {
                self.warn_static(node);
            }
        }
        // A Solid whose collision shapes are all floor the robot drives on (a pad or a tile a
        // few millimetres thick) shows its visible shapes to the ground sensors and the camera
        // as floor marks, as a Solid of no bounding object does.
        let floor_only = self.stood_on > stood_on
            && (
                self.obstacles.len(),
                self.sensed_obstacles.len(),
                self.bodies.len(),
            ) == (first, first_sensed, first_body);
        let outer = self.bounded;
        self.bounded = !self.nodes(node, "boundingObject").is_empty() && !floor_only;
        self.scene_children(node, &frame, depth);
        self.bounded = outer;
    }

    /// The mass of a Solid with physics, kilograms: its Physics `mass` when positive, otherwise
    /// `density` (default 1000 kg/m^3) times the volume of its bounding object when that is one
    /// Box, Sphere or Cylinder (bare or as a Shape's geometry); `None` otherwise.
    fn physics_mass(&mut self, node: &'d Node) -> Option<f64> {
        let &physics = self.nodes(node, "physics").first()?;
        let physics = self.node(physics);
        let mass = self.number(physics, "mass", -1.0);
        if mass > 0.0 {
            return Some(mass);
        }
        let density = self.number(physics, "density", 1000.0);
        let &[bounding] = self.nodes(node, "boundingObject") else {
            return None;
        };
        let mut geometry = self.node(bounding);
        if geometry.type_name == "Shape" {
            geometry = self.node(*self.nodes(geometry, "geometry").first()?);
        }
        let volume = match geometry.type_name.as_str() {
            "Box" => self.vector(geometry, "size", [2.0; 3]).iter().product(),
            "Sphere" => {
                let r = self.number(geometry, "radius", 1.0);
                4.0 / 3.0 * std::f64::consts::PI * r * r * r
            }
            "Cylinder" => {
                let r = self.number(geometry, "radius", 1.0);
                std::f64::consts::PI * r * r * self.number(geometry, "height", 2.0)
            }
            _ => return None,
        };
        let mass = density * volume;
        (mass.is_finite() && mass > 0.0).then_some(mass)
    }

    /// Whether a Solid's bounding object is one `Sphere` (bare or as a Shape's geometry).
    fn sphere_bounded(&self, node: &'d Node) -> bool {
        let &[bounding] = self.nodes(node, "boundingObject") else {
            return false;
        };
        let mut geometry = self.node(bounding);
        if geometry.type_name == "Shape" {
            match self.nodes(geometry, "geometry").first() {
                Some(&id) => geometry = self.node(id),
                None => return false,
            }
        }
        geometry.type_name == "Sphere"
    }

    /// Turns the obstacles emitted since index `first` into one movable body of `mass` kg, when
    /// they are one box (not longer than `MAX_BODY_ELONGATION` times its width) or one disc no
    /// wider than `MAX_BODY_SIDE` and `mass` is at most `MAX_BODY_MASS`; returns whether it did (otherwise the obstacles stay static).
    /// A `sphere` (its bounding object is one `Sphere`) is a ball to the camera.
    pub fn make_movable(&mut self, first: usize, mass: Option<f64>, sphere: bool) -> bool {
        let Some(mass) = mass.filter(|m| m.is_finite() && *m > 0.0 && *m <= MAX_BODY_MASS) else {
            return false;
        };
        if self.obstacles.len() != first + 1 {
            return false;
        }
        let look = self.obstacle_looks[first];
        let reflectance = Reflectance(look.reflectance);
        let body = match self.obstacles[first] {
            Obstacle::Box { center, size, yaw }
                if size.iter().all(|s| *s <= MAX_BODY_SIDE)
                    && size[0].min(size[1]) * MAX_BODY_ELONGATION >= size[0].max(size[1]) =>
            {
                BodySpec::Box {
                    center: center.map(Finite),
                    size: size.map(Positive),
                    yaw: Finite(yaw),
                    mass: Positive(mass),
                    friction: NonNegative(WEBOTS_COULOMB_FRICTION),
                    reflectance,
                }
            }
            Obstacle::Circle { center, radius } if 2.0 * radius <= MAX_BODY_SIDE => {
                BodySpec::Circle {
                    center: center.map(Finite),
                    radius: Positive(radius),
                    mass: Positive(mass),
                    friction: NonNegative(WEBOTS_COULOMB_FRICTION),
                    reflectance,
                }
            }
            _ => return false,
        };
        self.obstacles.truncate(first);
        self.obstacle_looks.truncate(first);
        self.obstacle_tops.truncate(first);
        self.body_owners.extend(self.obstacle_owners.drain(first..));
        let sphere = sphere && matches!(body, BodySpec::Circle { .. });
        self.body_looks.push(BodyLook {
            colour: look.colour,
            sphere,
            height: self.shape_height,
        });
        self.bodies.push(body);
        true
    }

    /// A raw robot node counts as an e-puck when its name or model says so, when it carries
    /// the e-puck's proximity sensor `ps0` or its two wheel motors (`RotationalMotor`s named
    /// `left wheel motor` and `right wheel motor`, as a two-wheeled robot built by hand in
    /// Webots' own example worlds has), or when it is a two-wheeled robot of its own build
    /// ([`Importer::two_wheeled`]: the run gives it its own wheels, axle and body). Every run
    /// decides by this one test, whether it runs the whole world or one controller.
    fn looks_like_epuck(&self, node: &'d Node) -> bool {
        self.says_epuck(node, true) || self.two_wheeled(node)
    }

    /// Whether a robot node holds exactly two `RotationalMotor`s, each the device of a
    /// `HingeJoint` among its own children (or under its `Pose`, `Transform`, `Group` and
    /// `Solid` children, not in another joint's end point), the two joints turning about
    /// parallel axes, their wheels (end points, else anchors) at distinct places: a differential
    /// drive, as Webots' tutorials
    /// build one by hand (its motors named as the author likes, `motor_1` or `left_motor`).
    fn two_wheeled(&self, node: &'d Node) -> bool {
        const PARALLEL: f64 = 0.999;
        let mut joints: Vec<&'d Node> = Vec::new();
        let mut motors = 0usize;
        let mut stack: Vec<(NodeId, bool)> = self
            .nodes(node, "children")
            .iter()
            .map(|&id| (id, true))
            .collect();
        let mut budget = 10_000usize;
        while let (Some((id, own)), true) = (stack.pop(), budget > 0) {
            budget -= 1;
            let n = self.node(id);
            match n.type_name.as_str() {
                "RotationalMotor" => motors += 1,
                "HingeJoint" if own => {
                    let device = self.nodes(n, "device").iter().map(|&d| self.node(d));
                    if device.filter(|d| d.type_name == "RotationalMotor").count() == 1 {
                        joints.push(n);
                    }
                }
                _ => {}
            }
            let inside = own
                && matches!(
                    n.type_name.as_str(),
                    "Pose" | "Transform" | "Group" | "Solid"
                );
            for field in &n.fields {
                stack.extend(field.value.nodes.iter().map(|&child| (child, inside)));
            }
        }
        let [left, right] = joints.as_slice() else {
            return false;
        };
        if motors != 2 {
            return false;
        }
        // Each wheel's axis, and where it sits: its end point's translation (two hinges may
        // share one anchor on the axle's line, as Webots' MyBot's), else its anchor.
        let axis_anchor = |joint: &'d Node| {
            let three = |node: Option<&NodeId>, name: &str| {
                node.and_then(|&n| self.numbers(self.node(n), name))
                    .and_then(|v| <[f64; 3]>::try_from(v).ok())
            };
            let parameters = self.nodes(joint, "jointParameters").first();
            let at = three(self.nodes(joint, "endPoint").first(), "translation")
                .or_else(|| three(parameters, "anchor"));
            let axis = three(parameters, "axis").unwrap_or([1.0, 0.0, 0.0]);
            (axis, at.unwrap_or([0.0; 3]))
        };
        let ((a, p), (b, q)) = (axis_anchor(left), axis_anchor(right));
        let norm = |v: [f64; 3]| v.iter().map(|c| c * c).sum::<f64>().sqrt();
        let dot: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
        let apart = norm([p[0] - q[0], p[1] - q[1], p[2] - q[2]]);
        norm(a) > 0.0 && norm(b) > 0.0 && dot.abs() >= PARALLEL * norm(a) * norm(b) && apart > 0.0
    }

    /// Whether a robot node's name or model says e-puck, or it carries the e-puck's `ps0`, or
    /// (`wheels`) its two wheel motors by their names.
    fn says_epuck(&self, node: &'d Node, wheels_say: bool) -> bool {
        let says = |field: &str| {
            self.strings(node, field).iter().any(|s| {
                let s = s.to_ascii_lowercase();
                s.contains("e-puck") || s.contains("epuck")
            })
        };
        if says("name") || says("model") {
            return true;
        }
        let mut stack: Vec<NodeId> = self.nodes(node, "children").to_vec();
        let mut budget = 10_000usize;
        let mut wheels = [false; 2];
        while let (Some(id), true) = (stack.pop(), budget > 0) {
            budget -= 1;
            let n = self.node(id);
            let named = |name: &str| self.strings(n, "name").iter().any(|s| s == name);
            if n.type_name == "DistanceSensor" && named("ps0") {
                return true;
            }
            if wheels_say && n.type_name == "RotationalMotor" {
                wheels[0] |= named("left wheel motor");
                wheels[1] |= named("right wheel motor");
                if wheels == [true; 2] {
                    return true;
                }
            }
            for field in &n.fields {
                stack.extend(field.value.nodes.iter().copied());
            }
        }
        false
    }

    /// Whether a node that is no base node is a robot PROTO: a known one, or one with a
    /// `controller` field.
    fn is_robot_proto(&self, node: &'d Node) -> bool {
        OTHER_ROBOT_PROTOS.contains(&node.type_name.as_str()) || node.field("controller").is_some()
    }

    /// The robot node (an e-puck or another robot) whose node type is on `line`.
    fn robot_on_line(&self, line: usize) -> Option<&'d Node> {
        self.doc.nodes.iter().find(|node| {
            let kind = node.type_name.as_str();
            node.line == line
                && (EPUCK_PROTOS.contains(&kind)
                    || ROBOT_NODES.contains(&kind)
                    || self.is_robot_proto(node))
        })
    }

    /// The first e-puck whose `controller` field is `name`.
    fn epuck_of_controller(&self, name: &str) -> Option<&'d Node> {
        self.doc.nodes.iter().find(|node| {
            let kind = node.type_name.as_str();
            (EPUCK_PROTOS.contains(&kind)
                || (ROBOT_NODES.contains(&kind) && self.looks_like_epuck(node)))
                && self.strings(node, "controller").iter().any(|c| c == name)
        })
    }

    /// The e-puck (or e-puck2): its start pose, model and the devices in its slots. Every e-puck
    /// is listed in `robots`; the first (or the one of the chosen controller) is `robot`.
    fn epuck(&mut self, node: &'d Node, frame: &Frame) {
        let label = self.label(node);
        let version_2 = self.strings(node, "version").iter().any(|v| v == "2");
        // A plain robot node recognised as an e-puck, and Webots 7's `EPuck`, are the E-puck.
        let plain = ROBOT_NODES.contains(&node.type_name.as_str());
        let (model, profile) = match (node.type_name.as_str(), version_2) {
            (_, true) => ("e-puck2".to_string(), "e-puck2"),
            ("EPuck", false) => ("E-puck".to_string(), "e-puck"),
            // A two-wheeled robot that neither its name, its model nor a `ps0` says is an e-puck
            // keeps its node type as its model: a run gives the e-puck's profile its wheels,
            // axle and body where they are not the e-puck's.
            (kind, false) if plain && !self.says_epuck(node, false) => (kind.to_string(), "e-puck"),
            (_, false) if plain => ("E-puck".to_string(), "e-puck"),
            (kind, false) => (kind.to_string(), "e-puck"),
        };
        let Some((pose, y_up)) = self.robot_pose(node, frame) else {
            return;
        };
        let found = FoundRobot {
            pose,
            model,
            profile,
            line: node.line,
            y_up,
        };
        self.list_robot(node, &found, Some(profile), (Vec::new(), Vec::new()));
        // A node that leaves `controller` out runs its PROTO's default (the E-puck PROTO's
        // `e-puck_avoid_obstacles`, declared so since V8.5); a plain robot node's is `<generic>`.
        let controller = |n: &'d Node| {
            let kind = n.type_name.as_str();
            let default = if EPUCK_PROTOS.contains(&kind) {
                Some(EPUCK_DEFAULT_CONTROLLER)
            } else {
                ROBOT_NODES.contains(&kind).then_some("<generic>")
            };
            let given = self.strings(n, "controller").first().cloned();
            given.or(default.map(str::to_string))
        };
        if let Some(chosen) = self.chosen.filter(|chosen| !std::ptr::eq(*chosen, node)) {
            let (mine, theirs) = (controller(node), controller(chosen).unwrap_or_default());
            let runs = if mine.as_deref() == Some(theirs.as_str()) {
                format!("another e-puck running \"{theirs}\" too")
            } else {
                format!("an e-puck running \"{}\"", mine.unwrap_or_default())
            };
            self.warn_one_controller(format!(
                "{label}: {runs}: a run of the controller \"{theirs}\" alone simulates only its first e-puck (line {}); a run of the whole world runs every robot",
                chosen.line
            ));
            return;
        }
        if let Some(first) = &self.robot {
            let line = first.line;
            self.warn_one_controller(format!(
                "{label}: a second e-puck: a run of one controller simulates only the first (line {line}); a run of the whole world runs every robot"
            ));
            return;
        }
        self.body_y_up = found.y_up;
        self.robot = Some(found);
        self.robot_at = Some(self.pose_at);
        self.extension_slots(node);
        if plain {
            self.robot_children(node, true);
        }
        self.missing_devices = self.devices_not_held(plain);
    }

    /// Lists a robot in `robots`, with its controller and name, and for a robot that is not an
    /// e-puck the collision shapes that stand for it.
    fn list_robot(
        &mut self,
        node: &'d Node,
        found: &FoundRobot,
        profile: Option<&'static str>,
        shapes: (Vec<ColouredObstacle>, Vec<Vec<usize>>),
    ) {
        let robot = WorldRobot {
            pose: found.pose,
            model: found.model.clone(),
            profile,
            controller: self.strings(node, "controller").first().cloned(),
            name: self.strings(node, "name").first().cloned(),
            def_name: node.def_name.clone(),
            line: node.line,
            y_up: found.y_up,
            node_type: node.type_name.clone(),
            model_field: self.strings(node, "model").first().cloned(),
        };
        self.robots.push((robot, shapes.0, shapes.1));
    }

    /// A robot that is not an e-puck: the e-puck stands in for it at its pose (if the world has
    /// no e-puck), with a warning; otherwise its own collision shapes (those of a plain `Robot`
    /// node) are static obstacles.
    fn other_robot(&mut self, node: &'d Node, frame: &Frame) {
        let label = self.label(node);
        let Some((pose, y_up)) = self.robot_pose(node, frame) else {
            return;
        };
        let found = FoundRobot {
            pose,
            model: node.type_name.clone(),
            profile: STAND_IN_PROFILE,
            line: node.line,
            y_up,
        };
        let shapes = self.robot_shapes(node, frame, &label);
        let shaped = !shapes.0.is_empty();
        self.list_robot(node, &found, None, shapes);
        let kind = node.type_name.as_str();
        if self.chosen.is_some_and(|chosen| std::ptr::eq(chosen, node)) {
            // The robot of the run: its controller runs on a robot that stays where it is.
            self.warn(not_an_epuck(&label, kind, NotAnEpuck::Chosen));
            self.body_y_up = found.y_up;
            self.robot = Some(found);
            self.robot_children(node, false);
            self.missing_devices = self.devices_not_held(true);
            return;
        }
        if self.robot.is_some() || self.other_robot_warning.is_some() || self.chosen.is_some() {
            let imported = self.imported_from.is_some_and(|first| node.line >= first);
            let what = if imported {
                NotAnEpuck::Imported { shaped }
            } else {
                NotAnEpuck::Kept { shaped }
            };
            self.warn(not_an_epuck(&label, kind, what));
            return;
        }
        // Said again at the end if the world's e-puck comes later.
        let index = self.warnings.len();
        self.other_robot_warning = Some((index, label.clone(), kind.to_string(), shaped));
        self.warn(not_an_epuck(&label, kind, NotAnEpuck::StandIn));
        self.other_robot = Some(found);
    }

    /// The collision shapes of a plain robot node (its `boundingObject`), in the world frame.
    fn robot_shapes(
        &mut self,
        node: &'d Node,
        frame: &Frame,
        label: &str,
    ) -> (Vec<ColouredObstacle>, Vec<Vec<usize>>) {
        let local = self.local_frame(node, [0.0; 3]);
        let frame = frame.then(&local);
        let first = self.obstacles.len();
        let look = self.solid_look(node);
        let outer = std::mem::replace(&mut self.look, look);
        for &shape in self.nodes(node, "boundingObject") {
            self.bounding(shape, &frame, label, 1);
        }
        self.robot_part_shapes(node, &frame);
        let footprint = ROBOT_FOOTPRINTS
            .iter()
            .find(|(name, _)| *name == node.type_name);
        if let (true, Some(&(kind, radius))) = (self.obstacles.len() == first, footprint) {
            // A library robot's shapes are inside its PROTO: its footprint stands for them.
            let origin = self.z_up(&frame).origin;
            let column = Frame::new(origin, IDENTITY, [1.0; 3]);
            self.emit_round(&column, radius, FOOTPRINT_HALF_HEIGHT, label, "footprint");
            if self.obstacles.len() > first {
                self.warn(format!(
                    "{label}: its collision shapes are inside the {kind} PROTO: it stands as a disc of radius {radius} m round its origin (the {kind}'s size), a static obstacle"
                ));
            }
        }
        self.look = outer;
        let owners = self.obstacle_owners.split_off(first);
        let shapes = self.obstacles.split_off(first);
        let looks = self.obstacle_looks.split_off(first);
        self.obstacle_tops.truncate(first);
        (shapes.into_iter().zip(looks).collect(), owners)
    }

    /// The collision shapes of a robot's parts: every Solid among its children (a device, a
    /// wheel at a joint's `endPoint`, a Solid in a `Pose`) with a `boundingObject`, which Webots
    /// collides with as it does with the robot's own. A robot inside the robot is left out.
    fn robot_part_shapes(&mut self, robot: &'d Node, frame: &Frame) {
        let mut stack: Vec<(&'d Node, Frame, usize)> = self
            .nodes(robot, "children")
            .iter()
            .rev()
            .map(|&id| (self.node(id), *frame, 1))
            .collect();
        while let Some((node, frame, depth)) = stack.pop() {
            let kind = node.type_name.as_str();
            if !self.enter(depth) || kind == "Shape" || VISUAL_NODES.contains(&kind) {
                continue;
            }
            if EPUCK_PROTOS.contains(&kind)
                || ROBOT_NODES.contains(&kind)
                || self.is_robot_proto(node)
            {
                continue;
            }
            let (frame, held) = if JOINTS.contains(&kind) || kind == "Slot" {
                (frame, "endPoint")
            } else if kind == "Group" {
                (frame, "children")
            } else {
                let local = self.local_frame(node, [0.0; 3]);
                (frame.then(&local), "children")
            };
            let shapes = self.nodes(node, "boundingObject");
            if !shapes.is_empty() {
                let label = self.label(node);
                let look = self.solid_look(node);
                let outer = std::mem::replace(&mut self.look, look);
                self.holders.push(node.line);
                for &shape in shapes {
                    self.bounding(shape, &frame, &label, depth + 1);
                }
                self.holders.pop();
                self.look = outer;
            }
            for &child in self.nodes(node, held).iter().rev() {
                stack.push((self.node(child), frame, depth + 1));
            }
        }
    }

    /// A robot's start pose (its origin and where its forward axis points), and whether its
    /// body is modelled Y-up ([`Importer::robot_y_up`]).
    fn robot_pose(&mut self, node: &'d Node, frame: &Frame) -> Option<([f64; 3], bool)> {
        let label = self.label(node);
        let local = self.local_frame(node, [0.0; 3]);
        let placed = frame.then(&local);
        let y_up = self.robot_y_up(&placed);
        // A Y-up body's forward is its local -z, its up its local y: turned as a Y-up file's.
        let body = if y_up {
            placed.then(&Frame::rotation(ENU_TO_NUE))
        } else {
            placed
        };
        let up = body.vector([0.0, 0.0, 1.0]);
        if up[2] < 0.0 {
            // `tilt` measures from the vertical either way: a robot on its back is not level.
            self.warn(format!(
                "{label}: the robot stands upside down (its up axis {:.3} rad from the world's); mazesim simulates it upright, where in Webots it lies on its back, its wheels off the floor",
                up[2].clamp(-1.0, 1.0).acos()
            ));
        } else if tilt(up) > TILT_TOLERANCE {
            self.warn(format!(
                "{label}: the robot is tilted by {:.3} rad from upright; its heading is taken from its projected forward axis",
                tilt(up)
            ));
        }
        let forward = body.vector([1.0, 0.0, 0.0]);
        let yaw = if forward[0].hypot(forward[1]) > 1e-9 {
            forward[1].atan2(forward[0])
        } else {
            self.warn(format!(
                "{label}: the robot faces straight up or down; heading 0 used"
            ));
            0.0
        };
        let [x, y, _] = body.origin;
        self.pose_at = body.origin;
        if x.abs() > MAX_EXTENT || y.abs() > MAX_EXTENT {
            self.warn(format!(
                "{label}: the robot stands at ({x}, {y}), farther than {MAX_EXTENT} m from the origin; not imported"
            ));
            return None;
        }
        Some(([snap(x), snap(y), snap(yaw)], y_up))
    }

    /// Whether a robot node placed at `placed` (its own frame in the world's Z-up frame) has a
    /// body modelled Y-up, decided robot by robot from where its node's axes point: Y-up when
    /// its local y points up (as every robot of a file before R2022a, and a body built so and
    /// stood upright by its `rotation` in a later file: a world Webots converted to R2022a, or
    /// a project's own PROTO such as RoboCup Junior's e-puck-based robots), Z-up when its local
    /// z does; a robot tilted so that neither does takes the file's convention.
    fn robot_y_up(&self, placed: &Frame) -> bool {
        let upright = |v: Vec3| v[2] > 0.0 && tilt(v) <= TILT_TOLERANCE;
        if upright(placed.vector([0.0, 1.0, 0.0])) {
            true
        } else if upright(placed.vector([0.0, 0.0, 1.0])) {
            false
        } else {
            self.y_up
        }
    }
}

/// What a run does with a robot node that is not an e-puck (see [`not_an_epuck`]).
enum NotAnEpuck {
    /// The robot of a run of its controller alone.
    Chosen,
    /// The first robot of a world without an e-puck: a run of one controller simulates the
    /// e-puck at its pose; a run of the whole world does not.
    StandIn,
    /// Any other: its controller runs on a body that does not move; `shaped` when it has
    /// collision shapes mazesim reads (static obstacles then).
    Kept { shaped: bool },
    /// One a supervisor imported while the world runs: kept as [`NotAnEpuck::Kept`] is, but
    /// no run starts its controller (a run of the whole world starts those of imported
    /// e-pucks alone).
    Imported { shaped: bool },
}

/// The warning of a robot node that is not an e-puck, saying what the run does with it: the one
/// place that words it.
fn not_an_epuck(label: &str, kind: &str, what: NotAnEpuck) -> String {
    let (runs, shaped) = match what {
        NotAnEpuck::Chosen => ("its controller runs, its body does not move; its devices are those of its children", None),
        NotAnEpuck::StandIn => ("a run of one controller simulates the e-puck in its place, at its pose, its own body, wheels and devices not imported; a run of the whole world simulates nothing in its place: its controller runs, its body does not move", None),
        NotAnEpuck::Kept { shaped } => ("its controller runs, its body does not move", Some(shaped)),
        NotAnEpuck::Imported { shaped } => ("imported while the world runs: its controller does not start, its body does not move", Some(shaped)),
    };
    let kept = match shaped {
        None => "",
        Some(true) => "; its collision shapes are static obstacles",
        Some(false) if ROBOT_NODES.contains(&kind) => "; neither it nor a Solid among its children has a boundingObject, so it is no obstacle (nothing collides with it in Webots either)",
        Some(false) => "; it has no collision shape mazesim reads (a PROTO's are inside the PROTO), so it is no obstacle",
    };
    format!("{label}: a robot that is not an e-puck ({kind}): {runs}{kept}")
}
