//! The `mazesim._core` extension module: a thin pyo3 layer over `mazesim-core`
//! (type conversion, numpy buffers, error mapping). No simulation logic lives here.

mod args;
mod arity;
mod batch;
mod buffers;
mod errors;
mod guard;
mod lock;
mod lower;
mod lower_settings;
mod maze;
mod navigator;
mod once_made;
mod perturbation;
mod profile;
mod run;
mod run_settings;
mod simulator;
mod subtasks;
mod tasks;
mod wbt;
mod world;

use mazesim_core::simulator::ROBOT_REFLECTANCE;
use mazesim_core::wbt::EPUCK_DEFAULT_CONTROLLER;
use pyo3::prelude::*;

use args::{bounded_items, Given, Real};
use errors::IntoPy;
use guard::enter;

/// Names of the worlds embedded in the package.
#[pyfunction]
fn builtin_world_names() -> PyResult<Vec<String>> {
    enter(|| Ok(mazesim_core::builtin_world_names()))
}

/// Names of the robot profiles embedded in the package.
#[pyfunction]
fn robot_profile_names() -> PyResult<Vec<String>> {
    enter(|| Ok(mazesim_core::robot_profile_names()))
}

/// Converts a Sharp GP2Y0A41SK0F reading in volts to a distance in cm (inverted table); NaN,
/// infinite or negative volts raise InvalidArgumentError.
#[pyfunction]
fn sharp_volts_to_cm(volts: Real) -> PyResult<f64> {
    enter(|| mazesim_core::sharp_volts_to_cm(volts.value("volts")?).py())
}

/// The default five-bit barcode book: 12 codes, none a palindrome or another's reverse.
#[pyfunction]
fn default_codes() -> PyResult<Vec<String>> {
    enter(|| Ok(mazesim_core::codebook::default_codes()))
}

/// Checks a barcode book (no palindrome, duplicate or reverse clash); raises InvalidArgumentError.
#[pyfunction]
fn validate_codes(codes: &Bound<'_, PyAny>) -> PyResult<()> {
    enter(|| {
        let expected = "str of 0 and 1";
        let most = mazesim_core::codebook::MAX_CODES;
        let codes = bounded_items(codes, "codes", expected, most)?
            .iter()
            .map(|c| {
                c.extract::<Given<String>>()?
                    .value("each of codes", "a str")
            })
            .collect::<PyResult<Vec<String>>>()?;
        mazesim_core::codebook::validate(&codes).py()
    })
}

/// What kind of mazesim file `text` is, from its first lines (a world file, a robot profile, a
/// Webots world or PROTO, a policy, a checkpoint, a run, a transfer study's result): its name
/// with its article and where such a file is taken, or None when it is none of them.
#[pyfunction]
fn file_kind(text: Given<String>) -> PyResult<Option<(String, String)>> {
    enter(|| {
        let text = text.value("text", "a str")?;
        let kind = mazesim_core::file_kind::FileKind::sniff(&text);
        Ok(kind.map(|k| (k.name().to_string(), k.where_taken().to_string())))
    })
}

/// Whether this process is writing the temporary file `name` (a file name) now, after marking it
/// as being written (`writing` True) or no longer (False) when `writing` is given: the one set
/// of writes in progress that the Python writer (`mazesim._atomic`) shares with the core's, so
/// that neither removes the other's temporary as an orphan. The name is taken as the file
/// system gives it (a byte that is not UTF-8 comes as a lone surrogate) and kept as the core
/// keeps its own, decoded with any such byte replaced.
#[pyfunction]
#[pyo3(signature = (name, writing=None))]
fn _temporary_writing(name: std::ffi::OsString, writing: Option<bool>) -> bool {
    let name = name.to_string_lossy();
    if let Some(now) = writing {
        mazesim_core::temporary_files::set_writing(&name, now);
    }
    mazesim_core::temporary_files::is_writing(&name)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    once_made::ready(m.py())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("EPUCK_DEFAULT_CONTROLLER", EPUCK_DEFAULT_CONTROLLER)?;
    m.add("ROBOT_REFLECTANCE", f64::from(ROBOT_REFLECTANCE))?;
    m.add_function(wrap_pyfunction!(builtin_world_names, m)?)?;
    m.add_function(wrap_pyfunction!(robot_profile_names, m)?)?;
    m.add_function(wrap_pyfunction!(sharp_volts_to_cm, m)?)?;
    m.add_function(wrap_pyfunction!(maze::generate_maze, m)?)?;
    m.add_function(wrap_pyfunction!(default_codes, m)?)?;
    m.add_function(wrap_pyfunction!(validate_codes, m)?)?;
    m.add_function(wrap_pyfunction!(file_kind, m)?)?;
    m.add_function(wrap_pyfunction!(_temporary_writing, m)?)?;
    m.add_function(wrap_pyfunction!(wbt::import_wbt, m)?)?;
    m.add_function(wrap_pyfunction!(wbt::import_wbt_text, m)?)?;
    m.add_function(wrap_pyfunction!(guard::_panic_for_tests, m)?)?;
    m.add_function(wrap_pyfunction!(run::lower_level_states, m)?)?;
    m.add_function(wrap_pyfunction!(run::sharp_distances, m)?)?;
    m.add_function(wrap_pyfunction!(lower::q_batch_update, m)?)?;
    m.add_function(wrap_pyfunction!(lower::train_lower_round, m)?)?;
    m.add_class::<batch::PyBatch>()?;
    m.add_class::<world::PyWorld>()?;
    m.add_class::<profile::PyRobotProfile>()?;
    m.add_class::<simulator::PySimulator>()?;
    m.add_class::<tasks::PyTaskFeatures>()?;
    m.add_class::<tasks::PyStepBounds>()?;
    m.add_class::<run_settings::PyEpisodeLimits>()?;
    m.add_class::<run_settings::PyAvoidCollisionSettings>()?;
    m.add_class::<run_settings::PyTabularSettings>()?;
    m.add_class::<run_settings::PyRunSettings>()?;
    m.add_class::<maze::PyMazeLayout>()?;
    m.add_class::<lower_settings::PyLowerRoundSettings>()?;
    m.add_class::<perturbation::PyDrivePerturbation>()?;
    m.add_class::<perturbation::PySensingPerturbation>()?;
    m.add_class::<navigator::PyNavigator>()?;
    // Wrong arguments (how many, which names) raise InvalidArgumentError, not pyo3's TypeError.
    let classes = [
        m.py().get_type::<batch::PyBatch>(),
        m.py().get_type::<world::PyWorld>(),
        m.py().get_type::<profile::PyRobotProfile>(),
        m.py().get_type::<simulator::PySimulator>(),
        m.py().get_type::<tasks::PyTaskFeatures>(),
        m.py().get_type::<tasks::PyStepBounds>(),
        m.py().get_type::<run_settings::PyEpisodeLimits>(),
        m.py().get_type::<run_settings::PyAvoidCollisionSettings>(),
        m.py().get_type::<run_settings::PyTabularSettings>(),
        m.py().get_type::<run_settings::PyRunSettings>(),
        m.py().get_type::<maze::PyMazeLayout>(),
        m.py().get_type::<lower_settings::PyLowerRoundSettings>(),
        m.py().get_type::<perturbation::PyDrivePerturbation>(),
        m.py().get_type::<perturbation::PySensingPerturbation>(),
        m.py().get_type::<navigator::PyNavigator>(),
    ];
    arity::guard_module(m, &classes)
}
