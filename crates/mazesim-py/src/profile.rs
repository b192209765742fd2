//! `RobotProfile` for Python: the built-in profiles, profiles read from TOML text, their
//! perturbed copies, and the `robot` argument of the simulators (a name, a profile or, for a
//! batch, one per environment).

use std::sync::Arc;

use mazesim_core::limits::{MAX_ENVS, MAX_ROBOTS};
use mazesim_core::{LookupTable, RobotProfile};
use numpy::PyArray2;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString, PyTuple};

use crate::args::{bounded_items, type_name, IntArg, Label, Real, SourceName, Text};
use crate::errors::{invalid, wrong_type, IntoPy};
use crate::guard::enter;
use crate::perturbation::perturbation_of;
use crate::world::rows_to_array;

/// A robot's body, wheels and sensors.
#[pyclass(name = "RobotProfile", module = "mazesim._core", frozen)]
pub struct PyRobotProfile {
    pub inner: Arc<RobotProfile>,
}

impl PyRobotProfile {
    /// A built-in profile by name.
    pub fn named(name: &str) -> PyResult<Self> {
        Ok(Self {
            inner: Arc::new(RobotProfile::builtin(name).py()?),
        })
    }

    /// A built-in profile by name, or a profile file by path (a copy of a built-in profile's
    /// TOML, edited): a built-in name wins over a file of that name in the current folder, as a
    /// built-in world's does. Neither: an `UnknownNameError` listing the built-in names, saying
    /// where the path was looked for and ending with the closest name or `.toml` file beside it.
    pub fn named_or_file(name: &str) -> PyResult<Self> {
        if mazesim_core::robot_profile_names()
            .iter()
            .any(|n| n == name)
        {
            return Self::named(name);
        }
        let path = std::path::Path::new(name);
        if path.is_file() {
            return Ok(Self {
                inner: Arc::new(RobotProfile::load(path).py()?),
            });
        }
        Err(Python::attach(|py| {
            py.import("mazesim._paths")
                .and_then(|paths| paths.getattr("unknown_robot_profile"))
                .and_then(|unknown| unknown.call1((name,)))
                .map_or_else(|failed| failed, PyErr::from_value)
        }))
    }

    /// The lookup tables of the distance sensors, device order.
    fn distance_tables(&self) -> impl Iterator<Item = &LookupTable> {
        self.inner.distance_sensors.iter().map(|s| &s.model.table)
    }
}

/// A `robot` argument as given: a built-in profile's name or a profile file's path (a str or an
/// `os.PathLike`), a `RobotProfile`, a list or tuple of them (one per environment of a batch), or
/// something else (its type's name, for the error).
#[derive(Debug, Clone)]
pub enum RobotArg {
    /// A built-in profile's name or a profile file's path.
    Name(String),
    /// A profile.
    Profile(Arc<RobotProfile>),
    /// A list or tuple of robot arguments.
    Many(Vec<RobotArg>),
    /// Anything else: the name of its type.
    Other(String),
}

impl RobotArg {
    /// The default robot of the simulators.
    pub fn default_robot() -> RobotArg {
        RobotArg::Name("e-puck".into())
    }

    /// The one profile this argument gives; `name` names the argument in the error.
    pub fn profile(&self, name: &str) -> PyResult<Arc<RobotProfile>> {
        match self {
            RobotArg::Name(n) => Ok(PyRobotProfile::named_or_file(n)?.inner),
            RobotArg::Profile(p) => Ok(p.clone()),
            RobotArg::Many(_) => Err(invalid(format!(
                "expected {name} to be a robot profile name, a profile file's path or a \
                 mazesim.RobotProfile, found a sequence"
            ))),
            RobotArg::Other(kind) => Err(wrong_type(format!(
                "expected {name} to be a robot profile name, a profile file's path or a \
                 mazesim.RobotProfile, found {kind}"
            ))),
        }
    }

    /// The profiles of a batch of `n` environments: one for all, or one per environment from a
    /// list or tuple of `n`.
    pub fn profiles(&self, n: usize) -> PyResult<Vec<Arc<RobotProfile>>> {
        match self {
            RobotArg::Many(items) if items.len() == n => items
                .iter()
                .enumerate()
                .map(|(i, item)| item.profile(&format!("robot[{i}]")))
                .collect(),
            RobotArg::Many(items) => Err(invalid(format!(
                "expected robot to be a robot profile name, a profile file's path, a \
                 mazesim.RobotProfile or a sequence of {n} of them (one per environment), found {} of them",
                items.len()
            ))),
            RobotArg::Other(kind) => Err(wrong_type(format!(
                "expected robot to be a robot profile name, a profile file's path, a \
                 mazesim.RobotProfile or a sequence of {n} of them (one per environment), found {kind}"
            ))),
            one => Ok(vec![one.profile("robot")?]),
        }
    }
}

impl<'a, 'py> FromPyObject<'a, 'py> for RobotArg {
    type Error = PyErr;

    fn extract(obj: Borrowed<'a, 'py, PyAny>) -> PyResult<Self> {
        if let Ok(p) = obj.cast::<PyRobotProfile>() {
            return Ok(RobotArg::Profile(p.get().inner.clone()));
        }
        if let Ok(text) = obj.cast::<PyString>() {
            return Ok(match text.to_cow() {
                Ok(name) => RobotArg::Name(name.into_owned()),
                Err(_) => RobotArg::Other(type_name(&obj.to_owned())),
            });
        }
        if obj.hasattr("__fspath__").unwrap_or(false) {
            let path = obj.py().import("os")?.call_method1("fspath", (obj,));
            if let Ok(Ok(path)) = path.as_ref().map(|p| p.cast::<PyString>()) {
                if let Ok(path) = path.to_cow() {
                    return Ok(RobotArg::Name(path.into_owned()));
                }
            }
            return Ok(RobotArg::Other(type_name(&obj.to_owned())));
        }
        if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
            let items = bounded_items(&obj.to_owned(), "robot", "robot profiles", MAX_ENVS)?;
            // One level only: an item that is itself a sequence is not looked into (a list
            // nested a hundred thousand deep would overflow the stack).
            let one = |item: &Bound<'py, PyAny>| {
                if item.is_instance_of::<PyList>() || item.is_instance_of::<PyTuple>() {
                    return RobotArg::Other(type_name(item));
                }
                item.extract::<RobotArg>()
                    .unwrap_or_else(|_| RobotArg::Other(type_name(item)))
            };
            return Ok(RobotArg::Many(items.iter().map(one).collect()));
        }
        Ok(RobotArg::Other(type_name(&obj.to_owned())))
    }
}

/// The `robot_profiles` argument of a simulator: a list or tuple of one entry per robot of its
/// world, each a `RobotProfile`, a built-in profile's name, or None (the robot's placement's).
pub fn given_profiles(obj: &Bound<'_, PyAny>) -> PyResult<Vec<Option<Arc<RobotProfile>>>> {
    let expected = "robot profiles (a RobotProfile, a built-in profile's name or None per robot)";
    let items = bounded_items(obj, "robot_profiles", expected, MAX_ROBOTS)?;
    (items.iter().enumerate())
        .map(|(i, item)| {
            if item.is_none() {
                return Ok(None);
            }
            let arg = item.extract::<RobotArg>()?;
            Ok(Some(arg.profile(&format!("robot_profiles[{i}]"))?))
        })
        .collect()
}

/// The error for a sensor index at or above the robot's `count` sensors of that `kind`.
/// The `kind` sensor at `index` of `sensors`, or an error naming how many there are.
fn sensor_at<'a, T>(sensors: &'a [T], kind: &str, index: IntArg) -> PyResult<&'a T> {
    let index = index.count("index", usize::MAX)?;
    sensors.get(index).ok_or_else(|| {
        crate::errors::to_py(mazesim_core::Error::InvalidArgument(format!(
            "expected a {kind} sensor index below {}, found {index}",
            sensors.len()
        )))
    })
}

/// The largest `value` of any of `tables` (0 without a table).
fn largest<'a>(
    tables: impl Iterator<Item = &'a LookupTable>,
    value: impl Fn(&LookupTable) -> f64,
) -> f64 {
    tables.map(value).fold(0.0, f64::max)
}

#[pymethods]
impl PyRobotProfile {
    /// Profiles are made by `RobotProfile.builtin`, `RobotProfile.from_toml` or `perturbed`:
    /// calling the class is an `InvalidArgumentError` saying so.
    #[new]
    #[pyo3(signature = (*_args, **_kwargs), text_signature = None)]
    fn new(_args: &Bound<'_, PyTuple>, _kwargs: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        Err(crate::args::made_elsewhere(
            "RobotProfile",
            "RobotProfile.builtin(name), RobotProfile.from_toml(text) or profile.perturbed(...)",
        ))
    }

    /// A built-in profile by name (see `robot_profile_names()`).
    #[staticmethod]
    fn builtin(name: Text) -> PyResult<Self> {
        enter(|| Self::named(&name.value("name", "a str")?))
    }

    /// A built-in profile by name, or a profile file by path (a copy of a built-in profile's
    /// `to_toml()` text, edited); the `robot` argument of the simulators and environments, and
    /// the `--robot` option of the commands, take the same.
    #[staticmethod]
    fn load(name_or_path: &Bound<'_, PyAny>) -> PyResult<Self> {
        enter(|| match name_or_path.extract::<RobotArg>()? {
            RobotArg::Name(name) => Self::named_or_file(&name),
            RobotArg::Profile(_) | RobotArg::Many(_) | RobotArg::Other(_) => {
                Err(wrong_type(format!(
                    "expected name_or_path to be a robot profile name or a profile file's path \
                     (str or os.PathLike), found {}",
                    type_name(name_or_path)
                )))
            }
        })
    }

    /// Parses a profile file's text; `source` names it in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, source = SourceName::Value(Label("<string>".into()))),
        text_signature = "(text, source='<string>')")]
    fn from_toml(text: Text, source: SourceName) -> PyResult<Self> {
        enter(|| {
            let text = text.value("text", "a str")?;
            let source = source.value("source", "a str")?.0;
            Ok(Self {
                inner: Arc::new(RobotProfile::from_toml(&text, &source).py()?),
            })
        })
    }

    /// The profile as the TOML text of a profile file (`from_toml` reads it back).
    fn to_toml(&self) -> PyResult<String> {
        enter(|| self.inner.to_toml().py())
    }

    /// A copy of the profile as a real robot may differ from it, named `"<name>~perturbed"`:
    /// its `drive` (a `DrivePerturbation`) and `sensing` (a `SensingPerturbation`) perturbed,
    /// see `docs/perturbations.md`. Neutral perturbations simulate exactly as this profile.
    #[pyo3(signature = (drive = None, sensing = None, **former),
        text_signature = "($self, drive=None, sensing=None)")]
    fn perturbed(
        &self,
        drive: Option<&Bound<'_, PyAny>>,
        sensing: Option<&Bound<'_, PyAny>>,
        former: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        enter(|| {
            let perturbation = perturbation_of(drive, sensing, former)?;
            Ok(Self {
                inner: Arc::new(self.inner.perturbed(&perturbation).py()?),
            })
        })
    }

    /// A copy of the profile whose distance sensors' rays rise `elevation` radians above the
    /// floor's plane (0 to pi/3): a wall at horizontal distance `h` reads as `h / cos(elevation)`
    /// away, and a ray reaches `cos(elevation)` of its length across the floor. Webots' E-puck
    /// PROTO tilts its proximity sensors by 0.16 rad.
    fn with_infrared_elevation(&self, elevation: Real) -> PyResult<Self> {
        enter(|| {
            let elevation = elevation.value("elevation")?;
            Ok(Self {
                inner: Arc::new(self.inner.with_infrared_elevation(elevation).py()?),
            })
        })
    }

    /// Each distance sensor's ray elevation above the floor's plane, radians (0: level).
    fn distance_sensor_elevations(&self) -> PyResult<Vec<f64>> {
        enter(|| {
            Ok(self
                .inner
                .distance_sensors
                .iter()
                .map(|s| s.elevation)
                .collect())
        })
    }

    #[getter]
    fn name(&self) -> PyResult<String> {
        enter(|| Ok(self.inner.name.clone()))
    }
    #[getter]
    fn description(&self) -> PyResult<String> {
        enter(|| Ok(self.inner.description.clone()))
    }

    /// Pickles as its built-in name when it is that built-in profile, otherwise as its TOML text.
    /// Profiles are equal when they hold the same values (name included), wherever they were
    /// loaded from.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        enter(|| {
            Ok(other
                .cast::<PyRobotProfile>()
                .map(|o| *o.get().inner == *self.inner)
                .unwrap_or(false))
        })
    }

    /// Hashes the name: equal profiles have the same name.
    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut hasher = std::collections::hash_map::DefaultHasher::new();
        self.inner.name.hash(&mut hasher);
        hasher.finish()
    }

    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<Bound<'py, PyTuple>> {
        let py = slf.py();
        let profile = &slf.get().inner;
        let builtin = RobotProfile::builtin(&profile.name).ok();
        if builtin.as_ref() == Some(&**profile) {
            let args = (profile.name.clone(),);
            return (slf.get_type().getattr("builtin")?, args).into_pyobject(py);
        }
        let text = enter(|| profile.to_toml().py())?;
        let args = (text, format!("<pickled robot profile {:?}>", profile.name));
        (slf.get_type().getattr("from_toml")?, args).into_pyobject(py)
    }

    /// A profile is immutable: a copy is the profile itself.
    fn __copy__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __deepcopy__<'py>(slf: PyRef<'py, Self>, _memo: &Bound<'py, PyDict>) -> PyRef<'py, Self> {
        slf
    }
    #[getter]
    fn body_radius(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.body_radius))
    }
    #[getter]
    fn wheel_radius(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.wheel_radius))
    }
    #[getter]
    fn axle_length(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.axle_length))
    }
    #[getter]
    fn max_wheel_speed(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.max_wheel_speed))
    }
    #[getter]
    fn encoder_resolution(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.encoder_resolution))
    }
    /// Gains (left, right) of the motors: each wheel turns at its gain times the command.
    #[getter]
    fn motor_gains(&self) -> PyResult<(f64, f64)> {
        enter(|| Ok((self.inner.motor_gains[0], self.inner.motor_gains[1])))
    }
    /// Multiplies every sensor model's relative noise.
    #[getter]
    fn noise_scale(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.noise_scale))
    }
    /// Reflection factor of the walls as the infra-red sensors see them (1 = as the world has them).
    #[getter]
    fn wall_reflectance(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.wall_reflectance))
    }
    /// Multiplies every ground sensor reading.
    #[getter]
    fn ground_gain(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.ground_gain))
    }
    /// Fraction of the wheels' motion lost while the body touches a wall.
    #[getter]
    fn slip_on_contact(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.slip_on_contact))
    }
    #[getter]
    fn distance_sensor_names(&self) -> PyResult<Vec<String>> {
        enter(|| {
            Ok(self
                .inner
                .distance_sensors
                .iter()
                .map(|s| s.name.clone())
                .collect())
        })
    }
    #[getter]
    fn distance_sensor_unit(&self) -> PyResult<String> {
        enter(|| Ok(self.inner.distance_sensor_unit().to_string()))
    }
    /// Largest noise-free reading of any distance sensor (its table's largest output).
    #[getter]
    fn distance_sensor_max(&self) -> PyResult<f64> {
        enter(|| Ok(largest(self.distance_tables(), LookupTable::max_output)))
    }
    /// Range of the distance sensors in metres (the longest table's last input).
    #[getter]
    fn distance_sensor_range(&self) -> PyResult<f64> {
        enter(|| Ok(largest(self.distance_tables(), LookupTable::max_input)))
    }
    /// Largest noise-free reading of any ground sensor (its table's largest output).
    #[getter]
    fn ground_sensor_max(&self) -> PyResult<f64> {
        enter(|| {
            Ok(largest(
                self.inner.ground_sensors.iter().map(|s| &s.model.table),
                LookupTable::max_output,
            ))
        })
    }
    #[getter]
    fn ground_sensor_names(&self) -> PyResult<Vec<String>> {
        enter(|| {
            Ok(self
                .inner
                .ground_sensors
                .iter()
                .map(|s| s.name.clone())
                .collect())
        })
    }

    /// (N, 3) array: x, y, heading of each distance sensor in the robot frame.
    fn distance_sensor_poses<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let sensors = self.inner.distance_sensors.iter();
        enter(|| {
            rows_to_array(
                py,
                sensors.map(|s| [s.position[0], s.position[1], s.heading]),
            )
        })
    }

    /// (N, 2) array: nearest and farthest distance in metres of each distance sensor's table.
    fn distance_sensor_limits<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let limits = self
            .distance_tables()
            .map(|t| [t.min_input(), t.max_input()]);
        enter(|| rows_to_array(py, limits))
    }

    /// (K, 3) array: distance sensor `index`'s table, rows of distance in metres, noise-free
    /// reading off a white wall and relative noise.
    fn distance_sensor_table<'py>(
        &self,
        py: Python<'py>,
        index: IntArg,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        enter(|| {
            let sensor = sensor_at(&self.inner.distance_sensors, "distance", index)?;
            rows_to_array(py, sensor.model.table.rows())
        })
    }

    /// Distance in metres at which distance sensor `index` reads `reading` off a white wall
    /// (its table inverted, clamped to the table's distances).
    fn distance_from_reading(&self, index: IntArg, reading: Real) -> PyResult<f64> {
        enter(|| {
            let sensor = sensor_at(&self.inner.distance_sensors, "distance", index)?;
            let reading = reading.value("reading")?;
            if !reading.is_finite() {
                return Err(crate::errors::to_py(mazesim_core::Error::InvalidArgument(
                    format!(
                        "expected a finite reading of distance sensor {}, found {reading}",
                        sensor.name
                    ),
                )));
            }
            Ok(sensor.model.table.invert(reading))
        })
    }

    /// Noise-free reading of ground sensor `index` over a floor of reflectance factor `f`.
    fn ground_reading(&self, index: IntArg, reflectance: Real) -> PyResult<f64> {
        enter(|| {
            let sensor = sensor_at(&self.inner.ground_sensors, "ground", index)?;
            let reflectance = reflectance.value("reflectance")?;
            if !(reflectance > 0.0 && reflectance <= 1.0) {
                return Err(crate::errors::to_py(mazesim_core::Error::InvalidArgument(
                    format!("expected a reflectance factor in (0, 1], found {reflectance}"),
                )));
            }
            Ok(sensor.model.table.eval(sensor.model.height / reflectance).0)
        })
    }

    /// (N, 2) array: x, y of each ground sensor in the robot frame.
    fn ground_sensor_positions<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        enter(|| rows_to_array(py, self.inner.ground_sensors.iter().map(|s| s.position)))
    }

    fn __repr__(&self) -> PyResult<String> {
        enter(|| Ok(format!("RobotProfile(name={:?})", self.inner.name)))
    }
}
