//! Devices mounted in the e-puck's extension slots (`turretSlot`, `groundSensorsSlot`,
//! `bodySlot`, and any other `...Slot` field, or numbered `...Slot1` field of a project's own
//! PROTO): a GPS or a Compass on the turret, extra distance
//! sensors, light sensors. Each is listed with its type, name, pose in the robot's frame (x
//! forward, y left, z up, metres; the slot's origin taken as the robot's) and its other fields;
//! anything else in a slot is a warning.

use super::frames::{apply, axis_angle, norm, Frame, ENU_TO_NUE, IDENTITY, NUE_TO_ENU};
use super::import::{Importer, JOINTS};
use super::shapes::snap;
use super::tree::Node;

/// Webots device node types and the default of their `name` field.
const DEVICE_TYPES: &[(&str, &str)] = &[
    ("Accelerometer", "accelerometer"),
    ("Altimeter", "altimeter"),
    ("Brake", "brake"),
    ("Camera", "camera"),
    ("Compass", "compass"),
    ("Connector", "connector"),
    ("Display", "display"),
    ("DistanceSensor", "distance sensor"),
    ("Emitter", "emitter"),
    ("GPS", "gps"),
    ("Gyro", "gyro"),
    ("InertialUnit", "inertial unit"),
    ("LED", "led"),
    ("Lidar", "lidar"),
    ("LightSensor", "light sensor"),
    ("LinearMotor", "linear motor"),
    ("Pen", "pen"),
    ("PositionSensor", "position sensor"),
    ("Radar", "radar"),
    ("RangeFinder", "range-finder"),
    ("Receiver", "receiver"),
    ("RotationalMotor", "rotational motor"),
    ("Speaker", "speaker"),
    ("TouchSensor", "touch sensor"),
    ("VacuumGripper", "vacuum gripper"),
];
/// Extension PROTOs of the E-puck whose devices every mazesim e-puck has: the
/// `E-puckGroundSensors` of the `groundSensorsSlot` (Webots 7's `EPuck_GroundSensorsModule`)
/// are its `gs0`, `gs1`, `gs2`.
const BUILT_IN_EXTENSIONS: &[&str] = &["E-puckGroundSensors", "EPuck_GroundSensorsModule"];
/// Webots' `Pi-puck` extension board (the e-puck2's turret): it adds three RGB LEDs to the
/// robot, named as the `LED.names` of Cyberbotics' e-puck remote-control library list them
/// (after `led0`..`led9`).
const PI_PUCK: &str = "Pi-puck";
const PI_PUCK_LEDS: [&str; 3] = ["pi-puck led 0", "pi-puck led 1", "pi-puck led 2"];
/// The ground sensors of the E-puck's ground sensors module (`BUILT_IN_EXTENSIONS`): an
/// E-puck without the module has none.
const GROUND_SENSORS: &[&str] = &["gs0", "gs1", "gs2"];
/// The devices of mazesim's e-puck: a plain `Robot` e-puck saved expanded lists them among its
/// children, and they are simulated as the e-puck's own.
const BUILT_IN_NAMES: &[&str] = &[
    "ps0",
    "ps1",
    "ps2",
    "ps3",
    "ps4",
    "ps5",
    "ps6",
    "ps7",
    "ls0",
    "ls1",
    "ls2",
    "ls3",
    "ls4",
    "ls5",
    "ls6",
    "ls7",
    "gs0",
    "gs1",
    "gs2",
    "led0",
    "led1",
    "led2",
    "led3",
    "led4",
    "led5",
    "led6",
    "led7",
    "led8",
    "led9",
    "left wheel motor",
    "right wheel motor",
    "left wheel sensor",
    "right wheel sensor",
    "camera",
    "accelerometer",
    "gyro",
    "emitter",
    "receiver",
    "speaker",
];
/// The LDS-01's field of view as Webots' RobotisLds01 PROTO writes it (not quite 2 pi).
#[allow(clippy::approx_constant)]
const LDS01_FIELD_OF_VIEW: f64 = 6.28318;
/// The field of view of Hokuyo's URG-04LX scanners as Webots' PROTOs write it: 240 degrees.
const HOKUYO_URG_FIELD_OF_VIEW: f64 = 4.18879;
/// What Webots' Hokuyo PROTOs share: a Lidar at the PROTO's origin whose `noise` and number of
/// ranges (the PROTO's `resolution`, the Lidar's `horizontalResolution`) a world may set.
const HOKUYO: DeviceProto = DeviceProto {
    proto: "",
    kind: "Lidar",
    default_name: "",
    translation: [0.0; 3],
    turn: 0.0,
    kept: &["noise", "horizontalResolution"],
    renamed: &[("resolution", "horizontalResolution")],
    fixed: &[],
};

/// The Lidar fields of a Hokuyo PROTO of `model`: one layer of `ranges` over `field_of_view`
/// (rad), from `range[0]` to `range[1]` metres.
const fn hokuyo_lidar(
    model: &'static str,
    ranges: f64,
    field_of_view: f64,
    range: [f64; 2],
) -> [(&'static str, ProtoValue); 6] {
    [
        ("horizontalResolution", ProtoValue::Number(ranges)),
        ("fieldOfView", ProtoValue::Number(field_of_view)),
        ("numberOfLayers", ProtoValue::Number(1.0)),
        ("minRange", ProtoValue::Number(range[0])),
        ("maxRange", ProtoValue::Number(range[1])),
        ("model", ProtoValue::Text(model)),
    ]
}
/// A device PROTO of Webots' own that holds one device node with fields of its own setting: a
/// world may mount it in a slot, or among a robot's children, as the device it holds.
struct DeviceProto {
    /// The PROTO's name.
    proto: &'static str,
    /// The node type it holds.
    kind: &'static str,
    /// The default of its `name` field.
    default_name: &'static str,
    /// The default of its `translation` field, metres.
    translation: [f64; 3],
    /// How far the PROTO turns its device about its own z axis, radians.
    turn: f64,
    /// The held node's fields a world may set through the PROTO (the others are the PROTO's).
    kept: &'static [&'static str],
    /// The PROTO's fields that set a held node's field of another name (PROTO's, node's).
    renamed: &'static [(&'static str, &'static str)],
    /// The held node's fields as the PROTO sets them: a kept field the world sets wins.
    fixed: &'static [(&'static str, ProtoValue)],
}

/// A field value as a device PROTO writes it.
enum ProtoValue {
    Number(f64),
    Text(&'static str),
    Table(&'static [[f64; 3]]),
}

impl ProtoValue {
    fn field(&self) -> DeviceField {
        match self {
            Self::Number(number) => DeviceField::Number(*number),
            Self::Text(text) => DeviceField::Text((*text).to_string()),
            Self::Table(rows) => DeviceField::Table(rows.to_vec()),
        }
    }
}

/// The `lookupTable` of Webots' `SharpGP2D120` and `SharpGP2Y0A41SK0F` PROTOs (distance in
/// metres, volts, relative noise), from the sensors' datasheets: 4 to 30 cm.
const SHARP_4_30_CM: &[[f64; 3]] = &[
    [0.030, 3.03, 0.005],
    [0.035, 2.78, 0.005],
    [0.040, 2.72, 0.005],
    [0.050, 2.33, 0.005],
    [0.060, 2.01, 0.005],
    [0.070, 1.76, 0.005],
    [0.080, 1.55, 0.005],
    [0.090, 1.40, 0.005],
    [0.100, 1.25, 0.005],
    [0.120, 1.04, 0.005],
    [0.140, 0.92, 0.005],
    [0.160, 0.82, 0.005],
    [0.180, 0.73, 0.005],
    [0.200, 0.66, 0.005],
    [0.250, 0.53, 0.005],
    [0.300, 0.42, 0.005],
    [0.350, 0.37, 0.005],
    [0.400, 0.31, 0.005],
];
/// The `lookupTable` of Webots' `SharpGP2Y0A02YK0F` PROTO: 20 to 150 cm.
const SHARP_20_150_CM: &[[f64; 3]] = &[
    [0.15, 2.75, 0.015],
    [0.20, 2.51, 0.015],
    [0.30, 1.99, 0.015],
    [0.40, 1.52, 0.015],
    [0.50, 1.25, 0.015],
    [0.60, 1.04, 0.015],
    [0.70, 0.87, 0.015],
    [0.80, 0.79, 0.015],
    [0.90, 0.74, 0.015],
    [1.00, 0.69, 0.015],
    [1.10, 0.60, 0.015],
    [1.20, 0.55, 0.015],
    [1.30, 0.50, 0.015],
    [1.40, 0.47, 0.015],
    [1.50, 0.45, 0.015],
];
/// The `model` of Webots' `E-puckDistanceSensor` PROTO, which tells the device its table: the
/// e-puck's proximity sensors' own.
const EPUCK_DISTANCE_SENSOR_MODEL: &str = "e-puck distance sensor";
/// Webots' device PROTOs mazesim reads as the device they hold:
/// - `E-puckDistanceSensor` (R2022a and later), the e-puck's own proximity sensor: a
///   `DistanceSensor` named `ds` by default, at the PROTO's `translation` (default 0 0.005 0),
///   turned 0.16 rad about its z axis, of `type "infra-red"` and `aperture 0.1`, in a Solid of
///   `model` [`EPUCK_DISTANCE_SENSOR_MODEL`];
/// - Sharp's infra-red rangers of `projects/devices/sharp` (`SharpGP2D120`, `SharpGP2Y0A41SK0F`,
///   `SharpGP2Y0A02YK0F`): a generic `DistanceSensor` of the datasheet's table, reading volts,
///   named after the sensor (`Sharp's IR sensor GP2D120`);
/// - Robotis' `RobotisLds01` laser distance sensor: a `Lidar` named `LDS-01` of one layer of
///   360 ranges all round, 0.12 to 3.5 m (the Coursera and CU Boulder course worlds mount it
///   among an e-puck's children);
/// - Hokuyo's laser scanners of `projects/devices/hokuyo` (`HokuyoUrg04lx`, `HokuyoUrg04lxug01`,
///   `HokuyoUtm30lx`): a `Lidar` of one layer named after the scanner, of the field of view and
///   range of Webots' guide (Lidar sensors), whose PROTO field `resolution` sets the Lidar's
///   `horizontalResolution`.
const DEVICE_PROTOS: &[DeviceProto] = &[
    DeviceProto {
        proto: "E-puckDistanceSensor",
        kind: "DistanceSensor",
        default_name: "ds",
        translation: [0.0, 0.005, 0.0],
        turn: 0.16,
        kept: &["numberOfRays"],
        renamed: &[],
        fixed: &[
            ("type", ProtoValue::Text("infra-red")),
            ("aperture", ProtoValue::Number(0.1)),
            ("model", ProtoValue::Text(EPUCK_DISTANCE_SENSOR_MODEL)),
        ],
    },
    DeviceProto {
        proto: "SharpGP2D120",
        kind: "DistanceSensor",
        default_name: "Sharp's IR sensor GP2D120",
        translation: [0.0; 3],
        turn: 0.0,
        kept: &["model"],
        renamed: &[],
        fixed: &[
            ("model", ProtoValue::Text("GP2D120")),
            ("lookupTable", ProtoValue::Table(SHARP_4_30_CM)),
        ],
    },
    DeviceProto {
        proto: "SharpGP2Y0A41SK0F",
        kind: "DistanceSensor",
        default_name: "Sharp's IR sensor GP2Y0A41SK0F",
        translation: [0.0; 3],
        turn: 0.0,
        kept: &["model"],
        renamed: &[],
        fixed: &[
            ("model", ProtoValue::Text("GP2Y0A41SK0F")),
            ("lookupTable", ProtoValue::Table(SHARP_4_30_CM)),
        ],
    },
    DeviceProto {
        proto: "SharpGP2Y0A02YK0F",
        kind: "DistanceSensor",
        default_name: "Sharp's IR sensor GP2Y0A02YK0F",
        translation: [0.0; 3],
        turn: 0.0,
        kept: &["model"],
        renamed: &[],
        fixed: &[
            ("model", ProtoValue::Text("GP2Y0A02YK0F")),
            ("lookupTable", ProtoValue::Table(SHARP_20_150_CM)),
        ],
    },
    // Robotis' LDS-01 laser distance sensor, as Webots' RobotisLds01 PROTO sets its Lidar
    // (projects/devices/robotis/protos/RobotisLds01.proto; Webots' guide, Lidar sensors): one
    // layer of 360 ranges all round, 0.12 to 3.5 m. Its turret's two motors are not simulated.
    DeviceProto {
        proto: "RobotisLds01",
        kind: "Lidar",
        default_name: "LDS-01",
        translation: [0.0, 0.0, 0.02],
        turn: 0.0,
        kept: &["noise"],
        renamed: &[],
        fixed: &[
            ("horizontalResolution", ProtoValue::Number(360.0)),
            ("fieldOfView", ProtoValue::Number(LDS01_FIELD_OF_VIEW)),
            ("numberOfLayers", ProtoValue::Number(1.0)),
            ("near", ProtoValue::Number(0.07)),
            ("minRange", ProtoValue::Number(0.12)),
            ("maxRange", ProtoValue::Number(3.5)),
            ("noise", ProtoValue::Number(0.0043)),
        ],
    },
    // Hokuyo's scanners as Webots' PROTOs set their Lidar (projects/devices/hokuyo/protos;
    // Webots' guide, Lidar sensors): one layer at the PROTO's origin; the PROTO's `resolution`
    // is the Lidar's `horizontalResolution` (its ranges), its `noise` the Lidar's.
    DeviceProto {
        proto: "HokuyoUrg04lx",
        default_name: "Hokuyo URG-04LX",
        fixed: &hokuyo_lidar(
            "Hokuyo URG-04LX",
            667.0,
            HOKUYO_URG_FIELD_OF_VIEW,
            [0.06, 4.096],
        ),
        ..HOKUYO
    },
    DeviceProto {
        proto: "HokuyoUrg04lxug01",
        default_name: "Hokuyo URG-04LX-UG01",
        fixed: &hokuyo_lidar(
            "Hokuyo URG-04LX-UG01",
            667.0,
            HOKUYO_URG_FIELD_OF_VIEW,
            [0.2, 5.6],
        ),
        ..HOKUYO
    },
    DeviceProto {
        proto: "HokuyoUtm30lx",
        default_name: "Hokuyo UTM-30LX",
        fixed: &hokuyo_lidar("Hokuyo UTM-30LX", 1080.0, 4.71238, [0.1, 30.0]),
        ..HOKUYO
    },
];
/// Device types whose node an e-puck saved expanded keeps with its own fields (a radio's
/// channel and range, a camera's size and field of view): they replace the e-puck's devices of
/// the same name.
const OWN_FIELD_TYPES: &[&str] = &["Emitter", "Receiver", "Camera"];
/// Nodes that only hold and place other nodes.
const CONTAINERS: &[&str] = &["Solid", "Pose", "Transform", "Group"];
/// The base nodes of a robot's `children`, `device` and `endPoint` fields that hold no device
/// but through their own such fields, where the walk of a robot's devices sees them: with the
/// device types and PROTOs, every node whose devices mazesim knows.
const SEEN_THROUGH: &[&str] = &[
    "Solid",
    "Pose",
    "Transform",
    "Group",
    "Shape",
    "CadShape",
    "Slot",
    "Robot",
    "HingeJoint",
    "Hinge2Joint",
    "SliderJoint",
    "BallJoint",
    "Track",
    "TrackWheel",
    "Propeller",
    "Charger",
    "Billboard",
    "Fluid",
    "SolidReference",
    "Skin",
    "PointLight",
    "SpotLight",
    "DirectionalLight",
    "Pi-puck",
    // Webots' solid PROTOs (projects/objects/solids), parts of a robot's body that hold no
    // device: an expanded E-puck's ring is a SolidPipe.
    "SolidBox",
    "SolidPipe",
    "SolidRoundedBox",
    "SolidTorus",
];
/// Fields that place or hold a node rather than describe the device.
const STRUCTURE_FIELDS: &[&str] = &[
    "translation",
    "rotation",
    "scale",
    "name",
    "children",
    "boundingObject",
    "physics",
];

/// The value of a device field as the world gives it.
#[derive(Debug, Clone, PartialEq)]
pub enum DeviceField {
    /// One number.
    Number(f64),
    /// Several numbers (a vector, a colour).
    Numbers(Vec<f64>),
    /// A `lookupTable`: rows of (input, output, relative noise).
    Table(Vec<[f64; 3]>),
    /// One string.
    Text(String),
    /// Several strings.
    Texts(Vec<String>),
    /// `TRUE` or `FALSE`.
    Flag(bool),
}

/// A device in one of the robot's extension slots.
#[derive(Debug, Clone, PartialEq)]
pub struct ExtensionDevice {
    /// The Webots node type, e.g. `GPS`.
    pub kind: String,
    /// Its `name` field, or Webots' default name for the type.
    pub name: String,
    /// The slot it is mounted in, e.g. `turretSlot`.
    pub slot: String,
    /// Position in the robot's frame (x forward, y left, z up), metres.
    pub translation: [f64; 3],
    /// Direction of its x axis in the robot's frame, radians counter-clockwise from forward.
    pub yaw: f64,
    /// How far its x axis points below the horizontal, radians (pi/2: straight at the floor, as
    /// a ground sensor; negative: upwards).
    pub pitch: f64,
    /// Its own x, y and z axes (unit vectors, in this order) in the robot's frame (x forward,
    /// y left, z up): the frame a device reading a vector in its own coordinates (a Receiver's
    /// emitter direction) reads in. A device of a file before R2022a has the axes of the
    /// robot's Y-up inside composed with its mount's rotations (unturned: x right, y up, z back).
    pub axes: [[f64; 3]; 3],
    /// Its other fields with values (numbers, strings, booleans), in file order.
    pub fields: Vec<(String, DeviceField)>,
}

/// Where the E-puck PROTO mounts its `groundSensorsSlot`, in the robot's frame: since R2022a
/// (Z-up) 3 cm forward and 0.3 mm above the floor, unrotated; before (Y-up, e.g. V8.6's
/// E-puck.proto) at the same place but turned by -1.57 rad about z, so that a child's x axis
/// points at the floor (and its y axis to the robot's right). Its `turretSlot`: since R2022a
/// 9.5 mm behind the robot's centre and 48.6 mm above the floor, on top of the turret
/// (`TURRET_SLOT`), unrotated; before, taken at the same place. Any other slot, or robot, is
/// taken at the robot's origin.
fn slot_frame(robot_type: &str, slot: &str, y_up: bool) -> Frame {
    if robot_type == "E-puck" && slot == "turretSlot" {
        let origin = [-0.0095, 0.0, 0.0486];
        return Frame::translation(if y_up {
            apply(&ENU_TO_NUE, origin)
        } else {
            origin
        });
    }
    if robot_type != "E-puck" || slot != "groundSensorsSlot" {
        return Frame::IDENTITY;
    }
    if y_up {
        let turn = axis_angle([0.0, 0.0, 1.0], -1.57).unwrap_or(IDENTITY);
        Frame::new([0.0, 0.0003, -0.03], turn, [1.0; 3])
    } else {
        Frame::translation([0.03, 0.0, 0.0003])
    }
}

/// Whether a robot node's field is an extension slot: its name ends in `Slot`, or in `Slot`
/// and a number, as a project's own PROTO numbers the slots it adds (`extensionSlot1`,
/// `extensionSlot2`). Webots reads none of these names: a PROTO mounts whatever nodes such a
/// field holds among the robot's children.
pub fn is_slot_field(name: &str) -> bool {
    name.trim_end_matches(|c: char| c.is_ascii_digit())
        .ends_with("Slot")
}

impl<'d> Importer<'d> {
    /// Lists the devices in every slot field of a robot node ([`is_slot_field`]).
    pub fn extension_slots(&mut self, robot: &'d Node) {
        for field in &robot.fields {
            if !is_slot_field(&field.name) {
                continue;
            }
            let frame = slot_frame(&robot.type_name, &field.name, self.y_up);
            for &id in &field.value.nodes {
                self.slot_node(self.node(id), &field.name, &frame, 0);
            }
        }
    }

    /// Lists the devices among a plain robot node's children (anywhere below them, through
    /// solids, poses, groups and joints), under the slot name `children`: for an e-puck
    /// (`e_puck`), those that are not the e-puck's own, and its Emitter and Receiver, whose
    /// fields (channel, range, buffer size) an e-puck saved expanded keeps as Webots reads them,
    /// and its Camera, whose size and field of view it keeps likewise;
    /// for another robot, all of them.
    pub fn robot_children(&mut self, robot: &'d Node, e_puck: bool) {
        let mut stack: Vec<(&'d Node, Frame, usize)> = self
            .nodes(robot, "children")
            .iter()
            .rev()
            .map(|&id| (self.node(id), Frame::IDENTITY, 0))
            .collect();
        while let Some((node, frame, depth)) = stack.pop() {
            if !self.enter(depth) {
                continue;
            }
            let kind = node.type_name.as_str();
            if let Some(proto) = DEVICE_PROTOS.iter().find(|p| p.proto == kind) {
                let name = self.strings(node, "name").first().cloned();
                let name = name.unwrap_or_else(|| proto.default_name.to_string());
                if !(e_puck && BUILT_IN_NAMES.contains(&name.as_str())) {
                    self.device_proto(node, "children", &frame, proto);
                }
                self.held_devices.push(name);
                continue;
            }
            if BUILT_IN_EXTENSIONS.contains(&kind) {
                // An e-puck saved expanded keeps its ground sensors module among its children.
                let held = GROUND_SENSORS.iter().map(|name| (*name).to_string());
                self.held_devices.extend(held);
                continue;
            }
            let local = if JOINTS.contains(&kind) {
                Frame::IDENTITY
            } else {
                self.local_frame(node, [0.0; 3])
            };
            let frame = frame.then(&local);
            let device = DEVICE_TYPES.iter().find(|(t, _)| *t == kind);
            if device.is_none() {
                // A PROTO mazesim does not read (Webots 6's `EPuck_DistanceSensor`) named as
                // one of the e-puck's devices holds that device; one named otherwise may hold
                // any device, which makes the robot's devices unknown.
                let named = self.strings(node, "name").first().cloned();
                let e_puck_named = named.filter(|n| BUILT_IN_NAMES.contains(&n.as_str()));
                let unseen = e_puck_named.is_none() && !SEEN_THROUGH.contains(&kind);
                self.unseen_devices |= unseen;
                self.held_devices.extend(e_puck_named);
                if unseen {
                    // Said as a slot's unknown node is: a controller's getDevice of what it
                    // holds finds nothing, and the run should say why.
                    let label = self.label(node);
                    self.warn(format!(
                        "{label}: in the robot's children: not a device mazesim lists; not imported"
                    ));
                }
            }
            if let Some(&(_, default_name)) = device {
                let name = self.strings(node, "name").first().cloned();
                let name = name.unwrap_or_else(|| default_name.to_string());
                let own_fields = OWN_FIELD_TYPES.contains(&kind);
                if !(e_puck && !own_fields && BUILT_IN_NAMES.contains(&name.as_str())) {
                    self.device(node, "children", &frame, default_name);
                }
                self.held_devices.push(name);
            }
            let mut below: Vec<&'d Node> = Vec::new();
            for field in ["children", "device", "endPoint"] {
                below.extend(self.nodes(node, field).iter().map(|&id| self.node(id)));
            }
            for child in below.into_iter().rev() {
                stack.push((child, frame, depth + 1));
            }
        }
    }

    /// The e-puck's own devices (`BUILT_IN_NAMES`) the run's robot's node does not hold, once
    /// its slots and children are listed: for a plain robot node (`plain`: an e-puck saved
    /// expanded, a project's robot, a robot that is no e-puck) each one not among its devices;
    /// for an E-puck PROTO node, which holds the others, its ground sensors unless a ground
    /// sensors module is in a slot. Webots' `getDevice` finds none of them. None is missing
    /// when the robot holds a node whose devices mazesim cannot see (a PROTO it does not read:
    /// it may hold any device).
    pub fn devices_not_held(&self, plain: bool) -> Vec<String> {
        if self.unseen_devices {
            return Vec::new();
        }
        let names: &[&str] = if plain {
            BUILT_IN_NAMES
        } else {
            GROUND_SENSORS
        };
        names
            .iter()
            .filter(|name| !self.held_devices.iter().any(|held| held == *name))
            .map(|name| (*name).to_string())
            .collect()
    }

    fn slot_node(&mut self, node: &'d Node, slot: &str, frame: &Frame, depth: usize) {
        if !self.enter(depth) {
            return;
        }
        let kind = node.type_name.as_str();
        if BUILT_IN_EXTENSIONS.contains(&kind) {
            let held = GROUND_SENSORS.iter().map(|name| (*name).to_string());
            self.held_devices.extend(held);
            return;
        }
        if kind == PI_PUCK {
            return self.pi_puck(node, slot, frame);
        }
        if let Some(proto) = DEVICE_PROTOS.iter().find(|p| p.proto == kind) {
            return self.device_proto(node, slot, frame, proto);
        }
        // A joint has no place of its own: its devices sit at its parent's, its end point where
        // its own translation puts it.
        let joint = JOINTS.contains(&kind);
        let local = if joint {
            Frame::IDENTITY
        } else {
            self.local_frame(node, [0.0; 3])
        };
        let frame = frame.then(&local);
        if let Some(&(_, default_name)) = DEVICE_TYPES.iter().find(|(t, _)| *t == kind) {
            self.device(node, slot, &frame, default_name);
        } else if joint {
            // Its motors and position sensors (`device`) and its end point's devices are listed
            // below, as a plain robot's joints' are (the run turns such a joint freely).
        } else if CONTAINERS.contains(&kind) {
            if !self.nodes(node, "boundingObject").is_empty() {
                let label = self.label(node);
                self.warn(format!(
                    "{label}: in the robot's {slot}: its collision shape is not added to the robot's body \
                     (in a run of the whole world the other robots' infra-red rays and bodies meet \
                     the Box, Cylinder and Sphere shapes it holds, as carried shapes)"
                ));
            }
        } else {
            self.unseen_devices |= !SEEN_THROUGH.contains(&kind);
            let label = self.label(node);
            let what = if kind == "Shape" || kind == "CadShape" {
                "a visual node: other robots' cameras see it (a Box, Cylinder, Capsule or Sphere) and, in a run of the whole world, their infra-red rays and bodies meet it where it spans their sensors' height; nothing else simulates it"
            } else {
                "not a device mazesim lists; not imported"
            };
            self.warn(format!("{label}: in the robot's {slot}: {what}"));
        }
        for field in ["children", "device", "endPoint"] {
            for &child in self.nodes(node, field) {
                self.slot_node(self.node(child), slot, &frame, depth + 1);
            }
        }
    }

    /// The Pi-puck extension board: the three RGB LEDs it adds to the robot (see
    /// [`PI_PUCK_LEDS`]), at the board's place; the board itself has nothing else simulated.
    fn pi_puck(&mut self, node: &'d Node, slot: &str, frame: &Frame) {
        let local = self.local_frame(node, [0.0; 3]);
        let frame = frame.then(&local);
        for name in PI_PUCK_LEDS {
            self.device(node, slot, &frame, name);
            if let Some(device) = self.devices.last_mut() {
                device.kind = "LED".into();
                device.name = name.into();
                device.fields.clear();
            }
        }
    }

    /// A device PROTO of Webots' own (in a slot, or among a robot's children, below `frame`),
    /// as the device it holds.
    fn device_proto(&mut self, node: &'d Node, slot: &str, frame: &Frame, proto: &DeviceProto) {
        let local = self.local_frame(node, proto.translation);
        let turn = axis_angle([0.0, 0.0, 1.0], proto.turn).unwrap_or(IDENTITY);
        let frame = frame.then(&local).then(&Frame::rotation(turn));
        self.device(node, slot, &frame, proto.default_name);
        if let Some(device) = self.devices.last_mut() {
            device.kind = proto.kind.into();
            for (name, _) in &mut device.fields {
                if let Some(&(_, held)) = proto.renamed.iter().find(|(own, _)| own == name) {
                    *name = held.to_string();
                }
            }
            device
                .fields
                .retain(|(name, _)| proto.kept.contains(&name.as_str()));
            for (name, value) in proto.fixed {
                if !device.fields.iter().any(|(set, _)| set == name) {
                    device.fields.push(((*name).to_string(), value.field()));
                }
            }
        }
    }

    fn device(&mut self, node: &'d Node, slot: &str, frame: &Frame, default_name: &str) {
        let name = self
            .strings(node, "name")
            .first()
            .cloned()
            .unwrap_or_else(|| default_name.to_string());
        // A robot whose inside is Y-up (every robot of a file before R2022a, some after): turn
        // it to the robot's Z-up frame.
        let to_z_up = |v| {
            if self.body_y_up {
                apply(&NUE_TO_ENU, v)
            } else {
                v
            }
        };
        let origin = to_z_up(frame.origin);
        let x_axis = to_z_up(frame.axis(0));
        let axes = [0, 1, 2].map(|i| {
            let axis = to_z_up(frame.axis(i));
            let length = norm(axis);
            axis.map(|c| snap(if length > 0.0 { c / length } else { c }))
        });
        let fields = node
            .fields
            .iter()
            .filter(|f| !STRUCTURE_FIELDS.contains(&f.name.as_str()))
            .filter_map(|f| {
                let v = &f.value;
                // An empty `lookupTable []` is kept: Webots reads through no table then (a
                // DistanceSensor reads 0, a LightSensor its raw irradiance), not the default.
                let table = f.name == "lookupTable" && v.strings.is_empty() && v.bools.is_empty();
                let value = if table {
                    let rows = v.numbers.chunks_exact(3).map(|r| [r[0], r[1], r[2]]);
                    DeviceField::Table(rows.collect())
                } else if v.numbers.len() == 1 {
                    DeviceField::Number(v.numbers[0])
                } else if !v.numbers.is_empty() {
                    DeviceField::Numbers(v.numbers.clone())
                } else if v.strings.len() == 1 {
                    DeviceField::Text(v.strings[0].clone())
                } else if !v.strings.is_empty() {
                    DeviceField::Texts(v.strings.clone())
                } else if let [flag] = v.bools[..] {
                    DeviceField::Flag(flag)
                } else {
                    return None;
                };
                Some((f.name.clone(), value))
            })
            .collect();
        self.devices.push(ExtensionDevice {
            kind: node.type_name.clone(),
            name,
            slot: slot.to_string(),
            translation: origin.map(snap),
            yaw: snap(x_axis[1].atan2(x_axis[0])),
            pitch: snap((-x_axis[2]).atan2(x_axis[0].hypot(x_axis[1]))),
            axes,
            fields,
        });
    }
}

#[cfg(test)]
mod tests {
    use crate::wbt::WbtImport;

    fn missing(text: &str) -> Vec<String> {
        let w = WbtImport::from_text(text, "test.wbt").unwrap_or_else(|e| panic!("{e}"));
        w.missing_devices
    }

    #[test]
    fn a_robot_node_lacks_the_e_puck_devices_it_holds_no_node_of() {
        // A custom robot taken for an e-puck: two wheel motors, one LED, no sensors.
        let lacking = missing(
            "#VRML_SIM R2023b utf8\nRobot { children [\n\
             HingeJoint { device [ RotationalMotor { name \"left wheel motor\" } ] }\n\
             HingeJoint { device [ RotationalMotor { name \"right wheel motor\" } ] }\n\
             Pose { children [ LED { name \"led0\" } ] } ] }\n",
        );
        for held in ["left wheel motor", "right wheel motor", "led0"] {
            assert!(
                !lacking.iter().any(|name| name == held),
                "{held}: {lacking:?}"
            );
        }
        for lacked in [
            "ps0",
            "ps7",
            "gs0",
            "camera",
            "left wheel sensor",
            "speaker",
            "led1",
        ] {
            assert!(
                lacking.iter().any(|name| name == lacked),
                "{lacked}: {lacking:?}"
            );
        }
        // Webots 6's e-puck: a DifferentialWheels (no wheel motors) whose sensors are PROTOs
        // mazesim does not read, named as the e-puck's.
        let old = missing(
            "#VRML_SIM V6.0 utf8\nDifferentialWheels { name \"e-puck\" children [\n\
             EPuck_DistanceSensor { name \"ps0\" } Camera { } ] }\n",
        );
        assert!(
            !old.iter().any(|name| name == "ps0" || name == "camera"),
            "{old:?}"
        );
        assert!(old.iter().any(|name| name == "ps1"), "{old:?}");
        assert!(old.iter().any(|name| name == "left wheel motor"), "{old:?}");
        // An e-puck saved expanded keeps its ground sensors module among its children.
        let expanded = missing(
            "#VRML_SIM R2023b utf8\nRobot { name \"e-puck\" children [\n\
             Pose { children [ E-puckGroundSensors { } ] } ] }\n",
        );
        assert!(!expanded.iter().any(|name| name == "gs0"), "{expanded:?}");
        assert!(expanded.iter().any(|name| name == "ps0"), "{expanded:?}");
    }

    #[test]
    fn a_robot_holding_a_proto_mazesim_does_not_read_lacks_nothing_known() {
        // The PROTO may hold any device: none is said missing, in children or in a slot.
        let unread =
            "#VRML_SIM R2023b utf8\nRobot { name \"e-puck\" children [ MySensorBoard { } ] }\n";
        assert!(missing(unread).is_empty());
        let slot = "#VRML_SIM R2023b utf8\nE-puck { groundSensorsSlot [ MyGroundModule { } ] }\n";
        assert!(missing(slot).is_empty());
    }

    #[test]
    fn an_e_puck_lacks_its_ground_sensors_without_their_module() {
        let ground = ["gs0", "gs1", "gs2"].map(String::from).to_vec();
        assert_eq!(missing("#VRML_SIM R2023b utf8\nE-puck { }\n"), ground);
        let module =
            "#VRML_SIM R2023b utf8\nE-puck { groundSensorsSlot [ E-puckGroundSensors { } ] }\n";
        assert!(missing(module).is_empty());
        // A sensor of its own named gs0 in the slot is an extension device, not the module's.
        let own = "#VRML_SIM R2023b utf8\nE-puck { groundSensorsSlot [ DistanceSensor { name \"gs0\" } ] }\n";
        assert_eq!(missing(own), ground);
        let old = "#VRML_SIM V8.5 utf8\nE-puck { groundSensorsSlot [ E-puckGroundSensors { } ] }\n";
        assert!(missing(old).is_empty());
    }

    #[test]
    fn a_joint_in_a_slot_gives_the_robot_its_motor_and_sensor_and_its_end_points_devices() {
        // A lidar's motor on a HingeJoint in the turret slot was dropped ("not a device mazesim
        // lists"): the controller's getDevice gave None and it stopped at its first call.
        let w = WbtImport::from_text(
            "#VRML_SIM R2023b utf8\nE-puck { turretSlot [ HingeJoint {\n\
             jointParameters HingeJointParameters { axis 0 0 1 }\n\
             device [ RotationalMotor { name \"turret motor\" } PositionSensor { name \"turret sensor\" } ]\n\
             endPoint Solid { translation 0 0 0.01 children [ DistanceSensor { name \"top\" } ] }\n\
             } ] }\n",
            "test.wbt",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let found: Vec<_> = w
            .extension_devices
            .iter()
            .map(|d| (d.kind.as_str(), d.name.as_str(), d.slot.as_str()))
            .collect();
        assert_eq!(
            found,
            [
                ("RotationalMotor", "turret motor", "turretSlot"),
                ("PositionSensor", "turret sensor", "turretSlot"),
                ("DistanceSensor", "top", "turretSlot"),
            ]
        );
        assert!(
            !w.warnings.iter().any(|m| m.contains("not a device")),
            "{:?}",
            w.warnings
        );
    }

    #[test]
    fn a_pi_puck_board_gives_the_robot_its_three_leds() {
        let w = WbtImport::from_text(
            "#VRML_SIM R2023b utf8\nE-puck { version \"2\" turretSlot [ Pi-puck { } ] }\n",
            "test.wbt",
        )
        .unwrap_or_else(|e| panic!("{e}"));
        let leds: Vec<_> = w
            .extension_devices
            .iter()
            .map(|d| (d.kind.as_str(), d.name.as_str(), d.slot.as_str()))
            .collect();
        let names = ["pi-puck led 0", "pi-puck led 1", "pi-puck led 2"];
        assert_eq!(leds, names.map(|name| ("LED", name, "turretSlot")));
        assert!(
            !w.warnings.iter().any(|m| m.contains("Pi-puck")),
            "{:?}",
            w.warnings
        );
    }
}
