//! The perturbations of `RobotProfile.perturbed` as typed, frozen values checked when they are
//! made: how the robot drives (`DrivePerturbation`: wheels, axle, motors, slip) and how it senses
//! (`SensingPerturbation`: noise, infra-red mounting, wall reflectance, ground gain). The former
//! keywords of `perturbed` still work, with a `DeprecationWarning`, for one release.

use mazesim_core::Perturbation;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyType};

use crate::args::{bounded_items, typed_argument, unknown_key, warn_deprecated, Keywords, Real};
use crate::errors::{invalid, IntoPy};
use crate::guard::enter;

/// The keywords `perturbed` took before its two perturbations.
const FORMER_KEYWORDS: &str = "wheel_radius_scale axle_length_scale motor_gains noise_scale \
    ir_angle_error ir_offset_error wall_reflectance ground_gain slip_on_contact";

fn gains_argument(gains: &Bound<'_, PyAny>) -> PyResult<[f64; 2]> {
    let items: Vec<Real> = bounded_items(gains, "motor_gains", "real numbers (left, right)", 2)?
        .iter()
        .map(|g| g.extract::<Real>())
        .collect::<PyResult<_>>()?;
    match items.as_slice() {
        [left, right] => Ok([
            left.value("motor_gains[0]")?,
            right.value("motor_gains[1]")?,
        ]),
        other => Err(invalid(format!(
            "expected motor_gains to be a (left, right) pair of real numbers, found {} values",
            other.len()
        ))),
    }
}

/// The constructor's arguments of a `DrivePerturbation`.
type DriveArguments = (f64, f64, (f64, f64), f64);

/// How a real robot's drive may differ from its profile: its wheel radius and effective wheel
/// distance scaled, its motors' gains (left, right) and the share of its wheels' motion lost
/// while it touches a wall. The neutral values change nothing.
#[pyclass(name = "DrivePerturbation", module = "mazesim._core", frozen)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PyDrivePerturbation {
    /// Multiplies the wheel radius, in (0, 10].
    #[pyo3(get)]
    wheel_radius_scale: f64,
    /// Multiplies the effective wheel distance, in (0, 10].
    #[pyo3(get)]
    axle_length_scale: f64,
    /// Multiply the (left, right) motor gains, each in (0, 10].
    #[pyo3(get)]
    motor_gains: (f64, f64),
    /// Fraction of the wheels' motion lost while the body touches a wall, in [0, 1).
    #[pyo3(get)]
    slip_on_contact: f64,
}

#[pymethods]
impl PyDrivePerturbation {
    #[new]
    #[pyo3(signature = (wheel_radius_scale = Real::Number(1.0), axle_length_scale = Real::Number(1.0), motor_gains = None, slip_on_contact = Real::Number(0.0)),
        text_signature = "(wheel_radius_scale=1.0, axle_length_scale=1.0, motor_gains=(1.0, 1.0), slip_on_contact=0.0)")]
    pub fn new(
        wheel_radius_scale: Real,
        axle_length_scale: Real,
        motor_gains: Option<&Bound<'_, PyAny>>,
        slip_on_contact: Real,
    ) -> PyResult<Self> {
        enter(|| {
            let [left, right] = motor_gains
                .filter(|g| !g.is_none())
                .map_or(Ok([1.0, 1.0]), gains_argument)?;
            let drive = Self {
                wheel_radius_scale: wheel_radius_scale.value("wheel_radius_scale")?,
                axle_length_scale: axle_length_scale.value("axle_length_scale")?,
                motor_gains: (left, right),
                slip_on_contact: slip_on_contact.value("slip_on_contact")?,
            };
            drive.applied(Perturbation::default()).check_values().py()?;
            Ok(drive)
        })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyDrivePerturbation>()
            .is_ok_and(|o| *o.get() == *self)
    }

    fn __hash__(&self) -> u64 {
        hash_of(&[
            self.wheel_radius_scale,
            self.axle_length_scale,
            self.motor_gains.0,
            self.motor_gains.1,
            self.slip_on_contact,
        ])
    }

    /// Pickles (and copies) as the constructor's arguments.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, PyType>, DriveArguments) {
        let d = slf.get();
        let arguments = (
            d.wheel_radius_scale,
            d.axle_length_scale,
            d.motor_gains,
            d.slip_on_contact,
        );
        (slf.get_type(), arguments)
    }

    fn __repr__(&self) -> String {
        format!(
            "DrivePerturbation(wheel_radius_scale={:?}, axle_length_scale={:?}, \
             motor_gains=({:?}, {:?}), slip_on_contact={:?})",
            self.wheel_radius_scale,
            self.axle_length_scale,
            self.motor_gains.0,
            self.motor_gains.1,
            self.slip_on_contact
        )
    }
}

impl PyDrivePerturbation {
    /// `p` with this drive's perturbations.
    fn applied(&self, p: Perturbation) -> Perturbation {
        Perturbation {
            wheel_radius_scale: self.wheel_radius_scale,
            axle_length_scale: self.axle_length_scale,
            motor_gains: [self.motor_gains.0, self.motor_gains.1],
            slip_on_contact: self.slip_on_contact,
            ..p
        }
    }
}

/// How a real robot's senses may differ from its profile: every sensor's noise scaled, its
/// infra-red sensors turned (radians) and moved (metres) outward, the walls' reflection factor
/// as they see it and every ground reading's gain. The neutral values change nothing.
#[pyclass(name = "SensingPerturbation", module = "mazesim._core", frozen)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PySensingPerturbation {
    /// Multiplies every sensor model's relative noise, in [0, 100].
    #[pyo3(get)]
    noise_scale: f64,
    /// Turns every infra-red sensor outward by this many radians (negative: inward).
    #[pyo3(get)]
    ir_angle_error: f64,
    /// Moves every infra-red sensor along its heading by this many metres (negative: inward);
    /// at most the body radius of the profile it perturbs either way.
    #[pyo3(get)]
    ir_offset_error: f64,
    /// Multiplies the walls' reflection factor, in (0, 1].
    #[pyo3(get)]
    wall_reflectance: f64,
    /// Multiplies every ground sensor reading, in (0, 10].
    #[pyo3(get)]
    ground_gain: f64,
}

#[pymethods]
impl PySensingPerturbation {
    #[new]
    #[pyo3(signature = (noise_scale = Real::Number(1.0), ir_angle_error = Real::Number(0.0), ir_offset_error = Real::Number(0.0), wall_reflectance = Real::Number(1.0), ground_gain = Real::Number(1.0)),
        text_signature = "(noise_scale=1.0, ir_angle_error=0.0, ir_offset_error=0.0, wall_reflectance=1.0, ground_gain=1.0)")]
    pub fn new(
        noise_scale: Real,
        ir_angle_error: Real,
        ir_offset_error: Real,
        wall_reflectance: Real,
        ground_gain: Real,
    ) -> PyResult<Self> {
        enter(|| {
            let sensing = Self {
                noise_scale: noise_scale.value("noise_scale")?,
                ir_angle_error: ir_angle_error.value("ir_angle_error")?,
                ir_offset_error: ir_offset_error.value("ir_offset_error")?,
                wall_reflectance: wall_reflectance.value("wall_reflectance")?,
                ground_gain: ground_gain.value("ground_gain")?,
            };
            sensing
                .applied(Perturbation::default())
                .check_values()
                .py()?;
            Ok(sensing)
        })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PySensingPerturbation>()
            .is_ok_and(|o| *o.get() == *self)
    }

    fn __hash__(&self) -> u64 {
        hash_of(&[
            self.noise_scale,
            self.ir_angle_error,
            self.ir_offset_error,
            self.wall_reflectance,
            self.ground_gain,
        ])
    }

    /// Pickles (and copies) as the constructor's arguments.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> (Bound<'py, PyType>, (f64, f64, f64, f64, f64)) {
        let s = slf.get();
        let arguments = (
            s.noise_scale,
            s.ir_angle_error,
            s.ir_offset_error,
            s.wall_reflectance,
            s.ground_gain,
        );
        (slf.get_type(), arguments)
    }

    fn __repr__(&self) -> String {
        format!(
            "SensingPerturbation(noise_scale={:?}, ir_angle_error={:?}, ir_offset_error={:?}, \
             wall_reflectance={:?}, ground_gain={:?})",
            self.noise_scale,
            self.ir_angle_error,
            self.ir_offset_error,
            self.wall_reflectance,
            self.ground_gain
        )
    }
}

impl PySensingPerturbation {
    /// `p` with these sensing perturbations.
    fn applied(&self, p: Perturbation) -> Perturbation {
        Perturbation {
            noise_scale: self.noise_scale,
            ir_angle_error: self.ir_angle_error,
            ir_offset_error: self.ir_offset_error,
            wall_reflectance: self.wall_reflectance,
            ground_gain: self.ground_gain,
            ..p
        }
    }
}

/// A hash of the bits of `values` (equal values, equal hashes).
fn hash_of(values: &[f64]) -> u64 {
    values
        .iter()
        .enumerate()
        .fold(0, |h, (k, v)| h ^ v.to_bits().rotate_left(13 * k as u32))
}

/// `value` as the perturbation `T`, or `name`'s error.
fn given<T>(value: Option<&Bound<'_, PyAny>>, name: &str, class: &str) -> PyResult<Option<T>>
where
    T: pyo3::PyClass<Frozen = pyo3::pyclass::boolean_struct::True> + Copy + Sync,
{
    let Some(value) = value.filter(|v| !v.is_none()) else {
        return Ok(None);
    };
    typed_argument::<T>(value, name, &format!("a {class} or None")).map(|v| Some(*v.get()))
}

/// The perturbation of a `perturbed` call: its `drive` and `sensing`, or (deprecated, with a
/// warning) its former keywords.
pub fn perturbation_of(
    drive: Option<&Bound<'_, PyAny>>,
    sensing: Option<&Bound<'_, PyAny>>,
    former: Option<&Bound<'_, PyDict>>,
) -> PyResult<Perturbation> {
    let drive = given::<PyDrivePerturbation>(drive, "drive", "DrivePerturbation")?;
    let sensing = given::<PySensingPerturbation>(sensing, "sensing", "SensingPerturbation")?;
    let first = former.map(|f| unknown_key(f, "")).transpose()?.flatten();
    let (Some(former), Some(key)) = (former, first) else {
        let neutral = Perturbation::default();
        let p = drive.map_or(neutral, |d| d.applied(neutral));
        return Ok(sensing.map_or(p, |s| s.applied(p)));
    };
    let kw = Keywords::new(Some(former), "perturbed", FORMER_KEYWORDS)?;
    if drive.is_some() || sensing.is_some() {
        return Err(invalid(format!(
            "expected either drive and sensing or perturbed's former keywords, found both \
             (and '{key}')"
        )));
    }
    warn_deprecated(
        former.py(),
        format!(
            "RobotProfile.perturbed's keyword '{key}' is deprecated and will be removed: pass \
             drive=DrivePerturbation(...) and sensing=SensingPerturbation(...)"
        ),
    )?;
    let real = |key: &str, neutral: f64| kw.get(key, Real::Number(neutral));
    let drive = PyDrivePerturbation::new(
        real("wheel_radius_scale", 1.0)?,
        real("axle_length_scale", 1.0)?,
        kw.object("motor_gains")?.as_ref(),
        real("slip_on_contact", 0.0)?,
    )?;
    let sensing = PySensingPerturbation::new(
        real("noise_scale", 1.0)?,
        real("ir_angle_error", 0.0)?,
        real("ir_offset_error", 0.0)?,
        real("wall_reflectance", 1.0)?,
        real("ground_gain", 1.0)?,
    )?;
    Ok(sensing.applied(drive.applied(Perturbation::default())))
}
