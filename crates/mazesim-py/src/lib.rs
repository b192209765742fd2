//! The `mazesim._core` extension module: a thin pyo3 layer over `mazesim-core`
//! (type conversion, numpy buffers, error mapping). No simulation logic lives here.

mod errors;
mod simulator;
mod world;

use pyo3::prelude::*;

/// Names of the worlds embedded in the package.
#[pyfunction]
fn builtin_world_names() -> Vec<String> {
    mazesim_core::builtin_world_names()
}

/// Names of the robot profiles embedded in the package.
#[pyfunction]
fn robot_profile_names() -> Vec<String> {
    mazesim_core::robot_profile_names()
}

/// Converts a Sharp GP2Y0A41SK0F reading in volts to a distance in cm (inverted table).
#[pyfunction]
fn sharp_volts_to_cm(volts: f64) -> f64 {
    mazesim_core::sharp_volts_to_cm(volts)
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_function(wrap_pyfunction!(builtin_world_names, m)?)?;
    m.add_function(wrap_pyfunction!(robot_profile_names, m)?)?;
    m.add_function(wrap_pyfunction!(sharp_volts_to_cm, m)?)?;
    m.add_class::<world::PyWorld>()?;
    m.add_class::<world::PyRobotProfile>()?;
    m.add_class::<simulator::PySimulator>()?;
    Ok(())
}
