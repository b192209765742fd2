//! Perturbed copies of a robot profile: the same robot as a real one may differ from its model,
//! for sim-to-real transfer studies and domain randomisation.
//!
//! Each perturbation is physics or sensing of the simulator, not a change of what a controller
//! is told:
//!
//! | perturbation | what changes |
//! |---|---|
//! | `wheel_radius_scale` | the wheel radius: straight travel per wheel turn scales by it |
//! | `axle_length_scale` | the effective wheel distance: the turn rate scales by its inverse |
//! | `motor_gains` | each wheel turns at its gain times the commanded speed (encoders count it) |
//! | `noise_scale` | every sensor model's relative noise |
//! | `ir_angle_error` | each infra-red sensor turned outward by this angle (radians) |
//! | `ir_offset_error` | each infra-red sensor moved along its heading (metres, + = outward) |
//! | `wall_reflectance` | the walls' reflection factor as the infra-red sensors see it |
//! | `ground_gain` | every ground sensor reading multiplied (a drifted threshold, seen inversely) |
//! | `slip_on_contact` | fraction of the wheels' motion lost while the body touches a wall |
//!
//! "Outward" for an angle error means away from the robot's forward axis, mirrored left and
//! right: a sensor looking to the left (heading in (0, pi)) turns counter-clockwise, one looking
//! to the right clockwise, and one on the axis (heading 0 or pi) counter-clockwise.
//!
//! Factors compose with the profile's own: gains, scales and reflectance multiply, and slips
//! combine as independent losses (`a + b - a * b`).

use super::RobotProfile;
use crate::error::{Error, Result};

/// The perturbations of [`RobotProfile::perturbed`]; `Default` is neutral (no change).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Perturbation {
    /// Multiplies the wheel radius; above zero.
    pub wheel_radius_scale: f64,
    /// Multiplies the effective wheel distance; above zero.
    pub axle_length_scale: f64,
    /// Multiply the left and right motor gains; above zero.
    pub motor_gains: [f64; 2],
    /// Multiplies the sensor noise; zero or more.
    pub noise_scale: f64,
    /// Turns every infra-red sensor outward by this many radians (negative: inward).
    pub ir_angle_error: f64,
    /// Moves every infra-red sensor along its heading by this many metres (negative: inward).
    pub ir_offset_error: f64,
    /// Multiplies the walls' reflection factor; in (0, 1].
    pub wall_reflectance: f64,
    /// Multiplies the ground sensor readings; above zero.
    pub ground_gain: f64,
    /// Fraction of the wheels' motion lost on contact; in [0, 1).
    pub slip_on_contact: f64,
}

impl Default for Perturbation {
    fn default() -> Self {
        Self {
            wheel_radius_scale: 1.0,
            axle_length_scale: 1.0,
            motor_gains: [1.0, 1.0],
            noise_scale: 1.0,
            ir_angle_error: 0.0,
            ir_offset_error: 0.0,
            wall_reflectance: 1.0,
            ground_gain: 1.0,
            slip_on_contact: 0.0,
        }
    }
}

/// `Ok` when `ok(value)`, otherwise an `InvalidArgument` naming `name`, what was `expected` and
/// the value found.
pub(crate) fn check_value(
    name: &str,
    value: f64,
    expected: &str,
    ok: impl Fn(f64) -> bool,
) -> Result<()> {
    if value.is_finite() && ok(value) {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "expected {name} to be {expected}, found {value}"
        )))
    }
}

/// Largest scale or gain of a perturbation: far beyond any real robot's error, small enough that
/// the motion stays what the physics was made for.
pub const MAX_FACTOR: f64 = 10.0;

const ABOVE_ZERO: &str = "a finite number above zero";
const FACTOR: &str = "a number above zero and at most 10";

impl Perturbation {
    /// Checks every field against the profile it perturbs: finite, scales and gains in
    /// (0, `MAX_FACTOR`], noise scale at or above zero, an angle error of at most pi and an
    /// offset error of at most the body radius either way, reflectance in (0, 1], slip in
    /// [0, 1). The error names the first bad field.
    pub fn check(&self, robot: &RobotProfile) -> Result<()> {
        self.check_values()?;
        let radius = robot.body_radius;
        check_value(
            "ir_offset_error",
            self.ir_offset_error,
            &format!("a distance of at most the body radius ({radius} m) either way"),
            |v| v.abs() <= radius,
        )
    }

    /// Checks every field that does not depend on the robot (all but the offset error's bound
    /// by the body radius; the offset error must be finite). The error names the first bad
    /// field.
    pub fn check_values(&self) -> Result<()> {
        let positive = |v: f64| v > 0.0 && v <= MAX_FACTOR;
        check_value(
            "wheel_radius_scale",
            self.wheel_radius_scale,
            FACTOR,
            positive,
        )?;
        check_value(
            "axle_length_scale",
            self.axle_length_scale,
            FACTOR,
            positive,
        )?;
        for (side, gain) in ["left", "right"].iter().zip(self.motor_gains) {
            let name = format!("motor_gains ({side})");
            check_value(&name, gain, FACTOR, positive)?;
        }
        check_value(
            "noise_scale",
            self.noise_scale,
            &format!("a number in [0, {}]", crate::limits::MAX_NOISE_SCALE),
            |v| (0.0..=crate::limits::MAX_NOISE_SCALE).contains(&v),
        )?;
        check_value(
            "ir_angle_error",
            self.ir_angle_error,
            "an angle in [-pi, pi] (radians)",
            |v| v.abs() <= std::f64::consts::PI,
        )?;
        check_value(
            "ir_offset_error",
            self.ir_offset_error,
            "a finite distance (metres)",
            |_| true,
        )?;
        check_value(
            "wall_reflectance",
            self.wall_reflectance,
            "a reflectance factor in (0, 1]",
            |v| v > 0.0 && v <= 1.0,
        )?;
        check_value("ground_gain", self.ground_gain, FACTOR, positive)?;
        check_value(
            "slip_on_contact",
            self.slip_on_contact,
            "a fraction in [0, 1)",
            |v| (0.0..1.0).contains(&v),
        )
    }
}

/// `heading` turned outward by `error` radians: away from the forward axis, mirrored left and
/// right, counter-clockwise for a heading on the axis.
fn turned_outward(heading: f64, error: f64) -> f64 {
    if heading.sin() < 0.0 {
        heading - error
    } else {
        heading + error
    }
}

impl RobotProfile {
    /// A copy of this profile perturbed by `p` (see the module notes), named `"<name>~perturbed"`
    /// so that its fingerprint, and the snapshots of its simulators, differ from this one's.
    /// Neutral perturbations give a profile that simulates exactly as this one. Bad values are
    /// refused with `Error::InvalidArgument` naming them.
    pub fn perturbed(&self, p: &Perturbation) -> Result<RobotProfile> {
        p.check(self)?;
        let mut out = self.clone();
        out.name = format!("{}~perturbed", self.name);
        out.wheel_radius *= p.wheel_radius_scale;
        out.axle_length *= p.axle_length_scale;
        out.motor_gains = [
            self.motor_gains[0] * p.motor_gains[0],
            self.motor_gains[1] * p.motor_gains[1],
        ];
        out.noise_scale *= p.noise_scale;
        out.wall_reflectance *= p.wall_reflectance;
        out.ground_gain *= p.ground_gain;
        out.slip_on_contact += p.slip_on_contact - self.slip_on_contact * p.slip_on_contact;
        for sensor in &mut out.distance_sensors {
            if p.ir_angle_error != 0.0 {
                sensor.heading = turned_outward(sensor.heading, p.ir_angle_error);
                sensor.direction = [sensor.heading.cos(), sensor.heading.sin()];
            }
            if p.ir_offset_error != 0.0 {
                let [dx, dy] = sensor.direction;
                sensor.position[0] += p.ir_offset_error * dx;
                sensor.position[1] += p.ir_offset_error * dy;
            }
        }
        let results = [
            ("wheel radius", out.wheel_radius),
            ("axle length", out.axle_length),
            ("left motor gain", out.motor_gains[0]),
            ("right motor gain", out.motor_gains[1]),
            ("ground gain", out.ground_gain),
        ];
        for (what, value) in results {
            check_value(&format!("the perturbed {what}"), value, ABOVE_ZERO, |v| {
                v > 0.0
            })?;
        }
        out.check_top_speeds()
            .map_err(|(_, message)| message)
            .and_then(|()| out.check_noise_scale())
            .map_err(|message| {
                Error::InvalidArgument(format!("{message} after the perturbation"))
            })?;
        super::ranges::check(&out.file()).map_err(|(field, message)| {
            Error::InvalidArgument(format!("the perturbed profile's {field}: {message}"))
        })?;
        Ok(out)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn seed() -> RobotProfile {
        RobotProfile::builtin("seed").unwrap()
    }

    #[test]
    fn neutral_perturbation_changes_only_the_name() {
        let base = seed();
        let mut same = base.perturbed(&Perturbation::default()).unwrap();
        assert_eq!(same.name, "seed~perturbed");
        same.name = base.name.clone();
        assert_eq!(same, base);
    }

    #[test]
    fn angle_error_turns_sensors_outward_mirrored() {
        let base = seed();
        let p = Perturbation {
            ir_angle_error: 0.1,
            ..Default::default()
        };
        let turned = base.perturbed(&p).unwrap();
        let headings: Vec<f64> = turned.distance_sensors.iter().map(|s| s.heading).collect();
        let before: Vec<f64> = base.distance_sensors.iter().map(|s| s.heading).collect();
        // front (0) and back (pi) turn CCW, left and left-front CCW, right and right-front CW.
        let signs = [1.0, 1.0, 1.0, -1.0, 1.0, -1.0];
        for ((h, b), s) in headings.iter().zip(&before).zip(signs) {
            assert!((h - b - s * 0.1).abs() < 1e-12, "{h} {b}");
        }
        let front = &turned.distance_sensors[0];
        assert!((front.direction[1] - 0.1f64.sin()).abs() < 1e-12);
        assert_eq!(front.position, base.distance_sensors[0].position);
    }

    #[test]
    fn offset_error_moves_sensors_along_their_headings() {
        let base = seed();
        let p = Perturbation {
            ir_offset_error: 0.004,
            ..Default::default()
        };
        let moved = base.perturbed(&p).unwrap();
        for (m, b) in moved.distance_sensors.iter().zip(&base.distance_sensors) {
            let r = |s: &super::super::DistanceSensor| s.position[0].hypot(s.position[1]);
            assert!((r(m) - r(b) - 0.004).abs() < 1e-12, "{}", m.name);
            assert_eq!(m.heading, b.heading);
        }
    }

    #[test]
    fn factors_compose_and_bad_values_name_their_argument() {
        let p = Perturbation {
            wheel_radius_scale: 1.05,
            motor_gains: [1.0, 0.95],
            slip_on_contact: 0.5,
            wall_reflectance: 0.5,
            ..Default::default()
        };
        let once = seed().perturbed(&p).unwrap();
        assert_eq!(once.slip_on_contact, 0.5);
        assert_eq!(once.motor_gains, [1.0, 0.95]);
        let twice = once.perturbed(&p).unwrap();
        assert_eq!(twice.slip_on_contact, 0.75);
        assert_eq!(twice.wall_reflectance, 0.25);
        assert!((twice.wheel_radius - 0.0205 * 1.05 * 1.05).abs() < 1e-15);
        type Setter = fn(&mut Perturbation);
        let bad: [(Setter, &str); 10] = [
            (|p| p.wheel_radius_scale = 0.0, "wheel_radius_scale"),
            (|p| p.axle_length_scale = f64::NAN, "axle_length_scale"),
            (|p| p.motor_gains = [1.0, -1.0], "motor_gains (right)"),
            (|p| p.noise_scale = -0.5, "noise_scale"),
            (|p| p.noise_scale = 1e300, "noise_scale"),
            (|p| p.ir_angle_error = f64::INFINITY, "ir_angle_error"),
            (|p| p.ir_offset_error = 0.05, "ir_offset_error"),
            (|p| p.ground_gain = 11.0, "ground_gain"),
            (|p| p.wall_reflectance = 1.5, "wall_reflectance"),
            (|p| p.slip_on_contact = 1.0, "slip_on_contact"),
        ];
        let fast = seed()
            .perturbed(&Perturbation {
                wheel_radius_scale: 10.0,
                ..Default::default()
            })
            .unwrap();
        let err = fast
            .perturbed(&Perturbation {
                wheel_radius_scale: 10.0,
                ..Default::default()
            })
            .unwrap_err()
            .to_string();
        assert!(err.contains("top speed") && err.contains("12.87"), "{err}");
        for (set, name) in bad {
            let mut p = Perturbation::default();
            set(&mut p);
            let err = seed().perturbed(&p).unwrap_err().to_string();
            assert!(err.contains(name) && err.contains("found"), "{err}");
        }
    }

    #[test]
    fn noise_stays_bounded_through_repeated_perturbations() {
        let loud = Perturbation {
            noise_scale: crate::limits::MAX_NOISE_SCALE,
            ..Default::default()
        };
        let once = seed().perturbed(&loud).unwrap();
        assert_eq!(once.noise_scale, 100.0);
        let err = once.perturbed(&loud).unwrap_err().to_string();
        assert!(
            err.contains("noise scale") && err.contains("after the perturbation"),
            "{err}"
        );
        let text = seed()
            .to_toml()
            .unwrap()
            .replace("noise_scale = 1.0", "noise_scale = 1e300");
        let err = RobotProfile::from_toml(&text, "<test>")
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("noise_scale") && err.contains("[0, 100]"),
            "{err}"
        );
    }
}
