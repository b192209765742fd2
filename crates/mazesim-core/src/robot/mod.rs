//! Robot profiles as data: body, wheels, motors and sensors read from a TOML file.
//! The built-in profiles (`e-puck`, `e-puck-hardware`, `e-puck2`, `seed`, `alphabot2`) live in
//! `robots/` and are embedded.
//!
//! A profile may also describe the imperfections of one real robot (`motor_gains`,
//! `noise_scale`, `wall_reflectance`, `ground_gain`, `slip_on_contact`); each is optional and
//! neutral by default, so a profile without them runs as it always did. [`perturb`] makes
//! perturbed copies of a profile for sim-to-real transfer studies; [`text`] writes a profile back
//! as TOML.

pub mod perturb;
pub mod ranges;
pub mod text;

pub use perturb::Perturbation;

use std::collections::BTreeMap;
use std::sync::Arc;

use serde::{Deserialize, Serialize};

use crate::error::{Error, Result};
use crate::file_kind::{self, FileKind};
use crate::lut::LookupTable;
use crate::world::locate;
use crate::world::values::{Finite, NonNegative, Positive, Reflectance, SlipFraction};

const BUILTIN: &[(&str, &str)] = &[
    ("e-puck", include_str!("../../../../robots/e-puck.toml")),
    (
        "e-puck-hardware",
        include_str!("../../../../robots/e-puck-hardware.toml"),
    ),
    ("e-puck2", include_str!("../../../../robots/e-puck2.toml")),
    ("seed", include_str!("../../../../robots/seed.toml")),
    (
        "alphabot2",
        include_str!("../../../../robots/alphabot2.toml"),
    ),
];

/// Names of the built-in robot profiles.
pub fn robot_profile_names() -> Vec<String> {
    BUILTIN.iter().map(|(n, _)| n.to_string()).collect()
}

/// What a sensor model measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Deserialize, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum SensorKind {
    /// A ray cast to the walls, read through the Webots infra-red model: the distance over the
    /// reflection factor of what it meets.
    Infrared,
    /// A ray cast to the walls, read through its table by the distance alone, whatever colour
    /// it meets: Webots' `DistanceSensor` of type `generic`, `sonar` or `laser`.
    Range,
    /// A downward sensor reading the floor reflectance.
    Ground,
}

/// A sensor model: its lookup table and how it looks at the world.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorModel {
    /// Infra-red ray or ground sensor.
    pub kind: SensorKind,
    /// Unit of the output ("raw", "volts").
    pub unit: String,
    /// Distance (m) to output, with relative noise.
    pub table: LookupTable,
    /// Height above the floor (ground sensors).
    pub height: f64,
    /// Side of the square floor spot averaged (ground sensors).
    pub footprint: f64,
}

/// A ray sensor on the robot.
#[derive(Clone, PartialEq)]
pub struct DistanceSensor {
    /// Device name, e.g. `ps0`.
    pub name: String,
    /// Position in the robot frame.
    pub position: [f64; 2],
    /// Direction in the robot frame, radians CCW from forward.
    pub heading: f64,
    /// The same direction as a unit vector (cos, sin) in the robot frame.
    pub direction: [f64; 2],
    /// How far the ray rises above the floor's plane, radians in [0, `MAX_ELEVATION`] (0: a
    /// level ray). A ray tilted by `e` meets a wall at horizontal distance `h` after `h / cos e`
    /// of its length, so it reads the wall as that far, and it reaches `cos e` of its length
    /// across the floor. Webots' E-puck PROTO tilts each proximity sensor's ray by 0.16 rad
    /// (`E-puckDistanceSensor`: its DistanceSensor turned 0.16 rad about the mount's z axis).
    pub elevation: f64,
    /// Its model.
    pub model: Arc<SensorModel>,
}

/// The kinds of model a distance sensor reads through.
const DISTANCE_KINDS: &[SensorKind] = &[SensorKind::Infrared, SensorKind::Range];

/// The largest elevation of a distance sensor's ray, radians (60 degrees).
pub const MAX_ELEVATION: f64 = std::f64::consts::FRAC_PI_3;

/// What a ray rising `elevation` radians reads as the distance of a wall met at horizontal
/// distance `horizontal`: `horizontal / cos(elevation)` (the same value, untouched, for a level
/// ray).
#[inline]
pub fn slant_distance(elevation: f64, horizontal: f32) -> f32 {
    if elevation == 0.0 {
        horizontal
    } else {
        (horizontal as f64 / elevation.cos()) as f32
    }
}

impl std::fmt::Debug for DistanceSensor {
    /// Written as before elevations existed when the ray is level, so the fingerprints of level
    /// profiles (which snapshots carry) stay as they were.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let mut out = f.debug_struct("DistanceSensor");
        out.field("name", &self.name)
            .field("position", &self.position)
            .field("heading", &self.heading)
            .field("direction", &self.direction);
        if self.elevation != 0.0 {
            out.field("elevation", &self.elevation);
        }
        out.field("model", &self.model).finish()
    }
}

/// A downward floor sensor on the robot.
#[derive(Debug, Clone, PartialEq)]
pub struct GroundSensor {
    /// Device name, e.g. `gs0`.
    pub name: String,
    /// Position in the robot frame.
    pub position: [f64; 2],
    /// Its model.
    pub model: Arc<SensorModel>,
}

/// A robot: body, wheels, motors, sensors.
#[derive(Debug, Clone, PartialEq)]
pub struct RobotProfile {
    /// Profile name.
    pub name: String,
    /// One line about it.
    pub description: String,
    /// Radius of the round body (collision shape).
    pub body_radius: f64,
    /// Wheel radius.
    pub wheel_radius: f64,
    /// Effective distance between the wheels: the yaw rate is `wheel_radius * (wr - wl) /
    /// axle_length`. A kinematic constant (Webots' e-puck turns as if it were 0.05685 m).
    pub axle_length: f64,
    /// Motor limit in rad/s; faster commands are clamped.
    pub max_wheel_speed: f64,
    /// Position sensor resolution in radians (0 = exact).
    pub encoder_resolution: f64,
    /// Ray sensors in device order.
    pub distance_sensors: Vec<DistanceSensor>,
    /// Floor sensors in device order.
    pub ground_sensors: Vec<GroundSensor>,
    /// Gain of the left and right motor: a wheel turns at its gain times the commanded (clamped)
    /// speed, and its encoder counts that true rotation. `[1, 1]`: a matched pair.
    pub motor_gains: [f64; 2],
    /// Multiplies the relative noise of every sensor model (0: noiseless readings).
    pub noise_scale: f64,
    /// Reflection factor of the walls as this robot's infra-red sensors see them, in (0, 1]: it
    /// multiplies that of whatever a ray meets, so 1 leaves the world's walls as they are (white
    /// in Webots' tables) and lower values read them darker (see `crate::sensors`).
    pub wall_reflectance: f64,
    /// Multiplies every ground sensor reading: a drift of the sensors' gain, which a fixed
    /// threshold sees as a threshold drifted by its inverse.
    pub ground_gain: f64,
    /// Fraction of the wheels' motion lost while the body touches a wall (wheel slip on
    /// contact), in [0, 1); the encoders go on counting the wheels' rotation.
    pub slip_on_contact: f64,
}

/// A profile file as TOML holds it (read by `from_toml`, written by `text::to_toml`).
#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ProfileFile {
    name: String,
    #[serde(default)]
    description: String,
    body_radius: Positive,
    wheel_radius: Positive,
    axle_length: Positive,
    max_wheel_speed: Positive,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    encoder_resolution: Option<Positive>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    motor_gains: Option<[Positive; 2]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    noise_scale: Option<NonNegative>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    wall_reflectance: Option<Reflectance>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    ground_gain: Option<Positive>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    slip_on_contact: Option<SlipFraction>,
    models: BTreeMap<String, ModelFile>,
    #[serde(default)]
    distance_sensors: Vec<SensorFile>,
    #[serde(default)]
    ground_sensors: Vec<SensorFile>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct ModelFile {
    kind: SensorKind,
    unit: String,
    table: Vec<[Finite; 3]>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    height: Option<Positive>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    footprint: Option<Positive>,
}

#[derive(Deserialize, Serialize)]
#[serde(deny_unknown_fields)]
struct SensorFile {
    name: String,
    position: [Finite; 2],
    #[serde(default, skip_serializing_if = "Option::is_none")]
    heading: Option<Finite>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    elevation: Option<Finite>,
    model: String,
}

impl RobotProfile {
    /// A built-in profile by name.
    pub fn builtin(name: &str) -> Result<RobotProfile> {
        let (_, text) =
            BUILTIN
                .iter()
                .find(|(n, _)| *n == name)
                .ok_or_else(|| Error::UnknownName {
                    kind: "robot profile",
                    name: name.to_string(),
                    available: robot_profile_names(),
                })?;
        Self::from_toml(text, &format!("builtin-robot:{name}"))
    }

    /// Reads a profile file (a copy of a built-in profile's TOML, edited); errors name the file.
    pub fn load(path: &std::path::Path) -> Result<RobotProfile> {
        let limit = crate::limits::MAX_WORLD_FILE_BYTES;
        let text = crate::io::read_text_limited(path, limit, "the robot profile file")?;
        Self::from_toml(&text, &path.display().to_string())
    }

    /// Parses a profile file's text; `source` names it in errors.
    pub fn from_toml(text: &str, source: &str) -> Result<RobotProfile> {
        let limit = crate::limits::MAX_WORLD_FILE_BYTES;
        crate::io::check_text_length(text, source, limit, "the robot profile")?;
        let text: &str = &crate::io::toml_text(text);
        let file: ProfileFile = toml::from_str(text).map_err(|e| {
            let refused = locate::from_toml_error(source, text, &e);
            file_kind::named_for_its_kind(text, source, FileKind::RobotProfile, refused)
        })?;
        crate::world::lengths::check(&file, text, source)?;
        let bad = |field: String, message: String| {
            let key = field.rsplit('.').next().unwrap_or(&field);
            let key = key.split('[').next().unwrap_or(key);
            let offset = text.find(key).unwrap_or(0);
            locate::format_error(source, text, offset, Some(&field), message)
        };
        ranges::check(&file).map_err(|(field, message)| bad(field, message))?;
        let mut models: BTreeMap<String, Arc<SensorModel>> = BTreeMap::new();
        for (name, m) in &file.models {
            let rows: Vec<[f64; 3]> = m.table.iter().map(|r| [r[0].0, r[1].0, r[2].0]).collect();
            let table = LookupTable::new(&rows)
                .map_err(|e| bad(format!("models.{name}.table"), e.to_string()))?;
            if m.kind == SensorKind::Ground && m.height.is_none() {
                return Err(bad(
                    format!("models.{name}.height"),
                    "expected the height of a ground sensor above the floor, found none".into(),
                ));
            }
            let spot = m.footprint.map_or(0.0, |f| f.0);
            if spot * std::f64::consts::FRAC_1_SQRT_2 > crate::world::floor::SPOT_MARGIN {
                return Err(bad(
                    format!("models.{name}.footprint"),
                    format!(
                        "expected a ground spot of at most {:.4} m a side, found {spot}",
                        crate::world::floor::SPOT_MARGIN * std::f64::consts::SQRT_2
                    ),
                ));
            }
            models.insert(
                name.clone(),
                Arc::new(SensorModel {
                    kind: m.kind,
                    unit: m.unit.clone(),
                    table,
                    height: m.height.map_or(0.0, |h| h.0),
                    footprint: m.footprint.map_or(0.0, |f| f.0),
                }),
            );
        }
        let find = |s: &SensorFile,
                    kinds: &[SensorKind],
                    list: &str,
                    i: usize|
         -> Result<Arc<SensorModel>> {
            let m = models.get(&s.model).ok_or_else(|| {
                bad(
                    format!("{list}[{i}].model"),
                    format!(
                        "expected one of the models {:?}, found {:?}",
                        models.keys().collect::<Vec<_>>(),
                        s.model
                    ),
                )
            })?;
            if !kinds.contains(&m.kind) {
                let expected: Vec<String> = kinds.iter().map(|k| format!("{k:?}")).collect();
                return Err(bad(
                    format!("{list}[{i}].model"),
                    format!(
                        "expected a {} model for {list}, found {:?} of kind {:?}",
                        expected.join(" or "),
                        s.model,
                        m.kind
                    ),
                ));
            }
            Ok(m.clone())
        };
        let mut distance_sensors = Vec::new();
        for (i, s) in file.distance_sensors.iter().enumerate() {
            let heading = s.heading.map_or(0.0, |h| h.0);
            let elevation = s.elevation.map_or(0.0, |e| e.0);
            if !(0.0..=MAX_ELEVATION).contains(&elevation) {
                return Err(bad(
                    format!("distance_sensors[{i}].elevation"),
                    format!(
                        "expected an elevation in [0, {MAX_ELEVATION:.6}] rad, found {elevation}"
                    ),
                ));
            }
            distance_sensors.push(DistanceSensor {
                name: s.name.clone(),
                position: [s.position[0].0, s.position[1].0],
                heading,
                direction: [heading.cos(), heading.sin()],
                elevation,
                model: find(s, DISTANCE_KINDS, "distance_sensors", i)?,
            });
        }
        if let Some(extra) = file
            .ground_sensors
            .iter()
            .position(|s| s.elevation.is_some())
        {
            return Err(bad(
                format!("ground_sensors[{extra}].elevation"),
                "expected no elevation on a ground sensor (it looks straight down), found one"
                    .into(),
            ));
        }
        let mut ground_sensors = Vec::new();
        for (i, s) in file.ground_sensors.iter().enumerate() {
            ground_sensors.push(GroundSensor {
                name: s.name.clone(),
                position: [s.position[0].0, s.position[1].0],
                model: find(s, &[SensorKind::Ground], "ground_sensors", i)?,
            });
        }
        let profile = RobotProfile {
            name: file.name,
            description: file.description,
            body_radius: file.body_radius.0,
            wheel_radius: file.wheel_radius.0,
            axle_length: file.axle_length.0,
            max_wheel_speed: file.max_wheel_speed.0,
            encoder_resolution: file.encoder_resolution.map_or(0.0, |r| r.0),
            distance_sensors,
            ground_sensors,
            motor_gains: file.motor_gains.map_or([1.0, 1.0], |g| [g[0].0, g[1].0]),
            noise_scale: file.noise_scale.map_or(1.0, |v| v.0),
            wall_reflectance: file.wall_reflectance.map_or(1.0, |v| v.0),
            ground_gain: file.ground_gain.map_or(1.0, |v| v.0),
            slip_on_contact: file.slip_on_contact.map_or(0.0, |v| v.0),
        };
        profile
            .check_top_speeds()
            .map_err(|(field, message)| bad(field.into(), message))?;
        profile
            .check_noise_scale()
            .map_err(|message| bad("noise_scale".into(), message))?;
        Ok(profile)
    }

    /// This profile with every distance sensor's ray rising `elevation` radians above the
    /// floor's plane (see [`DistanceSensor::elevation`]); 0 gives level rays.
    pub fn with_infrared_elevation(&self, elevation: f64) -> Result<RobotProfile> {
        if !(elevation.is_finite() && (0.0..=MAX_ELEVATION).contains(&elevation)) {
            return Err(Error::InvalidArgument(format!(
                "expected an infra-red elevation in [0, {MAX_ELEVATION:.6}] rad, found {elevation}"
            )));
        }
        let mut tilted = self.clone();
        for sensor in &mut tilted.distance_sensors {
            sensor.elevation = elevation;
        }
        Ok(tilted)
    }

    /// Top speed (m/s) and top turn rate (rad/s) of the robot: its wheel radius times its motor
    /// limit times its faster motor's gain, and twice that over its axle length.
    pub fn top_speeds(&self) -> (f64, f64) {
        let gain = self.motor_gains[0].max(self.motor_gains[1]);
        let speed = self.wheel_radius * self.max_wheel_speed * gain;
        (speed, 2.0 * speed / self.axle_length)
    }

    /// Refuses a robot faster than `limits::MAX_ROBOT_SPEED` or turning faster than
    /// `limits::MAX_TURN_RATE`: its motion would leave what the physics resolves. The error
    /// names the field a file would change: `wheel_radius` for the top speed, `axle_length`
    /// for the turn rate (a top speed within its limit turns too fast only on a short axle).
    pub(crate) fn check_top_speeds(&self) -> std::result::Result<(), (&'static str, String)> {
        use crate::limits::{MAX_ROBOT_SPEED, MAX_TURN_RATE};
        let (speed, turn) = self.top_speeds();
        if !(speed.is_finite() && speed <= MAX_ROBOT_SPEED) {
            return Err((
                "wheel_radius",
                format!(
                    "expected a robot whose top speed (wheel radius x max wheel speed x motor \
                     gain) is at most {MAX_ROBOT_SPEED} m/s, found {speed} m/s"
                ),
            ));
        }
        if !(turn.is_finite() && turn <= MAX_TURN_RATE) {
            return Err((
                "axle_length",
                format!(
                    "expected a robot whose top turn rate (2 x top speed / axle length) is at \
                     most {MAX_TURN_RATE} rad/s, found {turn} rad/s (axle length {} m)",
                    self.axle_length
                ),
            ));
        }
        Ok(())
    }

    /// Refuses a noise scale above `limits::MAX_NOISE_SCALE`: the readings would not stay
    /// finite.
    pub(crate) fn check_noise_scale(&self) -> std::result::Result<(), String> {
        use crate::limits::MAX_NOISE_SCALE;
        let scale = self.noise_scale;
        if (0.0..=MAX_NOISE_SCALE).contains(&scale) {
            Ok(())
        } else {
            Err(format!(
                "expected a robot whose noise scale is a number in [0, {MAX_NOISE_SCALE}], \
                 found {scale}"
            ))
        }
    }

    /// Unit of the distance sensors' readings ("raw" or "volts"), or "" without any.
    pub fn distance_sensor_unit(&self) -> &str {
        self.distance_sensors
            .first()
            .map_or("", |s| s.model.unit.as_str())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_profiles_load_with_their_sensors() {
        let e = RobotProfile::builtin("e-puck").unwrap();
        assert_eq!(e.distance_sensors.len(), 8);
        assert_eq!(e.ground_sensors.len(), 3);
        assert_eq!(e.distance_sensors[0].position, [0.03, -0.01]);
        assert_eq!(e.distance_sensors[7].heading, 0.2992);
        assert_eq!(e.distance_sensor_unit(), "raw");
        let s = RobotProfile::builtin("seed").unwrap();
        assert_eq!(s.distance_sensors.len(), 6);
        assert_eq!(s.ground_sensors.len(), 1);
        assert_eq!(s.distance_sensor_unit(), "volts");
        let a = RobotProfile::builtin("alphabot2").unwrap();
        assert_eq!(a.ground_sensors.len(), 5);
        assert_eq!(a.wheel_radius, 0.021);
    }

    #[test]
    fn unknown_profile_lists_the_known_ones() {
        let err = RobotProfile::builtin("khepera").unwrap_err().to_string();
        assert!(err.contains("e-puck") && err.contains("alphabot2"), "{err}");
    }

    #[test]
    fn unknown_model_is_a_located_error() {
        let text = "name = \"x\"\nbody_radius = 0.03\nwheel_radius = 0.02\naxle_length = 0.05\nmax_wheel_speed = 6\n[models]\n[[distance_sensors]]\nname = \"a\"\nposition = [0, 0]\nmodel = \"nope\"\n";
        let err = RobotProfile::from_toml(text, "r.toml")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("distance_sensors[0].model") && err.contains("nope"),
            "{err}"
        );
    }

    #[test]
    fn a_range_model_serves_distance_sensors_not_ground_sensors() {
        let head = "name = \"x\"\nbody_radius = 0.03\nwheel_radius = 0.02\naxle_length = 0.05\nmax_wheel_speed = 6\n[models.r]\nkind = \"range\"\nunit = \"raw\"\ntable = [[0, 0, 0], [0.1, 1000, 0]]\nheight = 0.01\n";
        let ray =
            format!("{head}[[distance_sensors]]\nname = \"a\"\nposition = [0, 0]\nmodel = \"r\"\n");
        let profile = RobotProfile::from_toml(&ray, "r.toml").unwrap();
        assert_eq!(profile.distance_sensors[0].model.kind, SensorKind::Range);
        let again = RobotProfile::from_toml(&profile.to_toml().unwrap(), "again").unwrap();
        assert_eq!(again, profile);
        let ground =
            format!("{head}[[ground_sensors]]\nname = \"g\"\nposition = [0, 0]\nmodel = \"r\"\n");
        let err = RobotProfile::from_toml(&ground, "r.toml")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("expected a Ground model") && err.contains("Range"),
            "{err}"
        );
    }
}
