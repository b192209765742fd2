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
mod navigator;
mod profile;
mod run;
mod simulator;
mod subtasks;
mod tasks;
mod wbt;
mod world;

use pyo3::prelude::*;

use args::{bounded_items, Flag, Given, IntArg, Keywords, Real};
use errors::IntoPy;
use guard::enter;
use pyo3::types::PyDict;

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

/// Converts a Sharp GP2Y0A41SK0F reading in volts to a distance in cm (inverted table); NaN or
/// infinite volts raise InvalidArgumentError.
#[pyfunction]
fn sharp_volts_to_cm(volts: Real) -> PyResult<f64> {
    enter(|| mazesim_core::sharp_volts_to_cm(volts.value("volts")?).py())
}

/// A generated maze world (seeded; see mazesim-core's generator).
#[pyfunction]
#[pyo3(signature = (width = IntArg::Int(5), height = IntArg::Int(5), seed = IntArg::ZERO, **layout),
    text_signature = "(width=5, height=5, seed=0, *, cell_size=0.25, wall_thickness=0.01, loops=0.0, checkpoints=True, floor_reflectance=0.36, junction=True)")]
fn generate_maze(
    width: IntArg,
    height: IntArg,
    seed: IntArg,
    layout: Option<&Bound<'_, PyDict>>,
) -> PyResult<world::PyWorld> {
    enter(|| {
        const LAYOUT: &str =
            "cell_size wall_thickness loops checkpoints floor_reflectance junction";
        let kw = Keywords::new(layout, "generate_maze", LAYOUT)?;
        let real = |key: &str, default: f64| kw.get(key, Real::Number(default))?.value(key);
        let flag = |key: &str| kw.get(key, Flag::Value(true))?.value(key, "a bool");
        let params = mazesim_core::generator::MazeParams {
            width: width.count("width", usize::MAX)?,
            height: height.count("height", usize::MAX)?,
            cell_size: real("cell_size", 0.25)?,
            wall_thickness: real("wall_thickness", 0.01)?,
            loops: real("loops", 0.0)?,
            checkpoints: flag("checkpoints")?,
            junction: flag("junction")?,
            floor_reflectance: real("floor_reflectance", 0.36)?,
        };
        let seed = seed.seed("seed")?;
        let w = mazesim_core::generator::generate(&params, seed).py()?;
        Ok(world::PyWorld {
            inner: std::sync::Arc::new(w),
        })
    })
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

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(builtin_world_names, m)?)?;
    m.add_function(wrap_pyfunction!(robot_profile_names, m)?)?;
    m.add_function(wrap_pyfunction!(sharp_volts_to_cm, m)?)?;
    m.add_function(wrap_pyfunction!(generate_maze, m)?)?;
    m.add_function(wrap_pyfunction!(default_codes, m)?)?;
    m.add_function(wrap_pyfunction!(validate_codes, m)?)?;
    m.add_function(wrap_pyfunction!(wbt::import_wbt, m)?)?;
    m.add_function(wrap_pyfunction!(wbt::import_wbt_text, m)?)?;
    m.add_function(wrap_pyfunction!(guard::_panic_for_tests, m)?)?;
    m.add_function(wrap_pyfunction!(run::lower_level_states, m)?)?;
    m.add_function(wrap_pyfunction!(lower::q_batch_update, m)?)?;
    m.add_function(wrap_pyfunction!(lower::train_lower_round, m)?)?;
    m.add_class::<batch::PyBatch>()?;
    m.add_class::<world::PyWorld>()?;
    m.add_class::<profile::PyRobotProfile>()?;
    m.add_class::<simulator::PySimulator>()?;
    m.add_class::<tasks::PyTaskFeatures>()?;
    m.add_class::<navigator::PyNavigator>()?;
    // Wrong arguments (how many, which names) raise InvalidArgumentError, not pyo3's TypeError.
    let classes = [
        m.py().get_type::<batch::PyBatch>(),
        m.py().get_type::<world::PyWorld>(),
        m.py().get_type::<profile::PyRobotProfile>(),
        m.py().get_type::<simulator::PySimulator>(),
        m.py().get_type::<tasks::PyTaskFeatures>(),
        m.py().get_type::<navigator::PyNavigator>(),
    ];
    arity::guard_module(m, &classes)
}
