//! The world file as written: what `World::load` parses and `World::save` writes back.
//! See `docs/world-format.md` for the format.

use serde::{Deserialize, Serialize};

use super::values::{
    BarcodeBits, Colour, Finite, FormatTag, FormatVersion, NonNegative, Point, Positive,
    Reflectance, Size,
};

fn default_time_step() -> Positive {
    Positive(32.0)
}

fn is_default_time_step(v: &Positive) -> bool {
    v.0 == 32.0
}

/// A whole world file (format version 1).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WorldSpec {
    /// Always `"mazesim-world"`.
    pub format: FormatTag,
    /// The format version, 1.
    pub version: FormatVersion,
    /// A free-text name.
    #[serde(default)]
    pub name: String,
    /// Physics step in milliseconds (Webots' `basicTimeStep`).
    #[serde(
        default = "default_time_step",
        skip_serializing_if = "is_default_time_step"
    )]
    pub basic_time_step_ms: Positive,
    /// Background floor.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub floor: Option<FloorSpec>,
    /// Robot start pose (a world of one robot).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub start: Option<StartSpec>,
    /// The robots of a world of several, each with its name, start and profile (instead of
    /// `start`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub robots: Vec<RobotSpec>,
    /// The goal disc.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub goal: Option<GoalSpec>,
    /// An ASCII cell maze.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub grid: Option<GridSpec>,
    /// How checkpoint barcodes are painted.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub barcode: Option<BarcodeSpec>,
    /// Box walls.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub walls: Vec<WallSpec>,
    /// Walls given by their centre line.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub segments: Vec<SegmentSpec>,
    /// Floor paint regions, in drawing order.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub paint: Vec<PaintSpec>,
    /// Barcode checkpoints.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub checkpoints: Vec<CheckpointSpec>,
    /// Movable rigid bodies the robot can push.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub bodies: Vec<BodySpec>,
}

/// `[floor]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct FloorSpec {
    /// Background reflectance factor.
    pub reflectance: Reflectance,
    /// Background colour as a camera sees it (`None`: the grey of its reflectance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour: Option<Colour>,
}

/// `[start]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StartSpec {
    /// x in metres.
    pub x: Finite,
    /// y in metres.
    pub y: Finite,
    /// Heading in radians.
    #[serde(default = "zero")]
    pub yaw: Finite,
}

/// `[[robots]]`: one robot of a world of several.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RobotSpec {
    /// Its name, unique in the world.
    pub name: String,
    /// Start x in metres.
    pub x: Finite,
    /// Start y in metres.
    pub y: Finite,
    /// Start heading in radians.
    #[serde(default = "zero")]
    pub yaw: Finite,
    /// The name of a built-in robot profile; the simulator's profile when absent.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub profile: Option<String>,
    /// Shapes the robot carries beside its body (a bumper, a box on it), in its own frame,
    /// which the other robots' infra-red rays and bodies meet; none by default.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub carried: Vec<CarriedSpec>,
}

/// `[[robots.carried]]`: a box (`size`) or an upright cylinder (`radius`) a robot carries, in
/// the robot's frame (x ahead, y to its left).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CarriedSpec {
    /// Centre in the robot's frame.
    pub center: Point,
    /// A box's extent along its own axes.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub size: Option<Size>,
    /// A cylinder's radius.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub radius: Option<Positive>,
    /// A box's rotation in the robot's frame, radians.
    #[serde(default = "zero", skip_serializing_if = "is_zero")]
    pub yaw: Finite,
    /// Infra-red reflection factor.
    #[serde(default = "white", skip_serializing_if = "is_white")]
    pub reflectance: Reflectance,
}

fn zero() -> Finite {
    Finite(0.0)
}

/// `[goal]`: a disc.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GoalSpec {
    /// Centre of the disc.
    pub center: Point,
    /// Radius in metres.
    pub radius: Positive,
}

/// `[grid]`: an ASCII cell maze.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct GridSpec {
    /// Side of a cell in metres; by default the generated mazes' (0.25).
    #[serde(default = "grid_cell_size")]
    pub cell_size: Positive,
    /// Wall thickness in metres; by default the generated mazes' (0.01).
    #[serde(default = "grid_wall_thickness")]
    pub wall_thickness: Positive,
    /// World position of the south-west corner.
    #[serde(default = "origin")]
    pub origin: Point,
    /// The maze drawing (see the format document).
    pub map: toml::Spanned<String>,
}

fn grid_cell_size() -> Positive {
    Positive(crate::generator::MazeParams::default().cell_size)
}

fn grid_wall_thickness() -> Positive {
    Positive(crate::generator::MazeParams::default().wall_thickness)
}

fn origin() -> Point {
    [Finite(0.0), Finite(0.0)]
}

/// `[barcode]`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BarcodeSpec {
    /// Length of one bar along the direction of travel.
    #[serde(default = "default_bar_length")]
    pub bar_length: Positive,
    /// Reflectance of a 1 bit.
    #[serde(default = "white")]
    pub white: Reflectance,
    /// Reflectance of a 0 bit.
    #[serde(default = "black")]
    pub black: Reflectance,
}

/// Bar length of the report's barcodes: 1.7 cm.
pub const DEFAULT_BAR_LENGTH: f64 = 0.017;

fn default_bar_length() -> Positive {
    Positive(DEFAULT_BAR_LENGTH)
}
fn white() -> Reflectance {
    Reflectance(1.0)
}
fn black() -> Reflectance {
    Reflectance(0.2)
}

impl Default for BarcodeSpec {
    fn default() -> Self {
        Self {
            bar_length: default_bar_length(),
            white: white(),
            black: black(),
        }
    }
}

fn is_zero(v: &Finite) -> bool {
    v.0 == 0.0
}
fn is_white(v: &Reflectance) -> bool {
    v.0 == 1.0
}

/// `[[walls]]`: a box.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct WallSpec {
    /// Centre.
    pub center: Point,
    /// Extent along the box's own axes.
    pub size: Size,
    /// Rotation in radians.
    #[serde(default = "zero", skip_serializing_if = "is_zero")]
    pub yaw: Finite,
    /// Infra-red reflection factor.
    #[serde(default = "white", skip_serializing_if = "is_white")]
    pub reflectance: Reflectance,
    /// Colour as a camera sees it (`None`: the grey of its reflectance).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub colour: Option<Colour>,
    /// How high its top stands above the floor, metres (`None`: higher than any sensor's ray
    /// goes). A distance sensor's ray that rises over it, or falls onto its top, meets it
    /// there (a Webots world's walls give theirs).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub height: Option<Positive>,
    /// Seen and not touched: infra-red rays and cameras meet it, nothing collides with it and
    /// range sensors and ground sensors pass it by (a Webots Solid without a `boundingObject`,
    /// such as a goal object the robot drives through).
    #[serde(default, skip_serializing_if = "is_false")]
    pub sensed_only: bool,
}

/// `[[segments]]`: a wall along a centre line.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    /// One end of the centre line.
    pub from: Point,
    /// The other end.
    pub to: Point,
    /// Thickness in metres.
    pub thickness: Positive,
    /// Infra-red reflection factor.
    #[serde(default = "white", skip_serializing_if = "is_white")]
    pub reflectance: Reflectance,
}

fn is_false(v: &bool) -> bool {
    !*v
}

/// How many of the world's paint regions ([`crate::limits::MAX_PAINT_REGIONS`]) `paint`
/// takes: one per region, a polyline one per point.
pub fn paint_regions(paint: &[PaintSpec]) -> usize {
    paint
        .iter()
        .map(|p| match p {
            PaintSpec::Polyline { points, .. } => points.len(),
            _ => 1,
        })
        .sum()
}

/// `[[paint]]`: a floor region.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "lowercase", deny_unknown_fields)]
pub enum PaintSpec {
    /// A rectangle.
    Rect {
        /// Centre.
        center: Point,
        /// Extent along its own axes.
        size: Size,
        /// Rotation.
        #[serde(default = "zero", skip_serializing_if = "is_zero")]
        yaw: Finite,
        /// Floor reflectance.
        reflectance: Reflectance,
        /// Colour as a camera sees it (`None`: the grey of its reflectance).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        colour: Option<Colour>,
    },
    /// A disc.
    Circle {
        /// Centre.
        center: Point,
        /// Radius.
        radius: Positive,
        /// Floor reflectance.
        reflectance: Reflectance,
        /// Colour as a camera sees it (`None`: the grey of its reflectance).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        colour: Option<Colour>,
    },
    /// A stroke along points, round joints.
    Polyline {
        /// At least two points.
        points: Vec<Point>,
        /// Stroke width.
        width: Positive,
        /// Joins the last point to the first.
        #[serde(default, skip_serializing_if = "is_false")]
        closed: bool,
        /// Floor reflectance.
        reflectance: Reflectance,
        /// Colour as a camera sees it (`None`: the grey of its reflectance).
        #[serde(default, skip_serializing_if = "Option::is_none")]
        colour: Option<Colour>,
    },
}

impl PaintSpec {
    /// The colour a camera sees, when the region gives one.
    pub fn colour(&self) -> Option<Colour> {
        match self {
            PaintSpec::Rect { colour, .. }
            | PaintSpec::Circle { colour, .. }
            | PaintSpec::Polyline { colour, .. } => *colour,
        }
    }
}

/// `[[checkpoints]]`: a barcode across a corridor.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct CheckpointSpec {
    /// Positive, unique id.
    pub id: u32,
    /// The bits, first met first when travelling along `yaw`.
    pub code: BarcodeBits,
    /// Middle of the code.
    pub center: Point,
    /// Direction of travel in which the code reads as written.
    pub yaw: Finite,
    /// Extent across the corridor.
    pub width: Positive,
}

/// Floor friction coefficient of a movable body when the file gives none.
pub const DEFAULT_BODY_FRICTION: f64 = 0.5;

fn default_friction() -> NonNegative {
    NonNegative(DEFAULT_BODY_FRICTION)
}

/// `[[bodies]]`: a movable rigid body (a box or a ball seen from above) the robot can push.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "shape", rename_all = "lowercase", deny_unknown_fields)]
pub enum BodySpec {
    /// A box.
    Box {
        /// Start position of the centre.
        center: Point,
        /// Extent along its own axes.
        size: Size,
        /// Start rotation in radians.
        #[serde(default = "zero", skip_serializing_if = "is_zero")]
        yaw: Finite,
        /// Mass in kilograms.
        mass: Positive,
        /// Coefficient of friction with the floor.
        #[serde(default = "default_friction")]
        friction: NonNegative,
        /// Infra-red reflection factor.
        #[serde(default = "white", skip_serializing_if = "is_white")]
        reflectance: Reflectance,
    },
    /// A disc (a ball or a cylinder standing up).
    Circle {
        /// Start position of the centre.
        center: Point,
        /// Radius in metres.
        radius: Positive,
        /// Mass in kilograms.
        mass: Positive,
        /// Coefficient of friction with the floor.
        #[serde(default = "default_friction")]
        friction: NonNegative,
        /// Infra-red reflection factor.
        #[serde(default = "white", skip_serializing_if = "is_white")]
        reflectance: Reflectance,
    },
}
