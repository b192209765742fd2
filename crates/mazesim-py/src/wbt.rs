//! `import_wbt` / `import_wbt_text` for Python: a Webots world as a mazesim `World` plus the
//! import report as a dict (the JSON layout of `mazesim import-wbt --json`).

use std::path::{Path, PathBuf};
use std::sync::Arc;

use mazesim_core::wbt::{Obstacle, WbtImport};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList, PyString};

use crate::errors::IntoPy;
use crate::guard::{enter, enter_detached};
use crate::world::PyWorld;

/// The import as `{"obstacles": [...], "robot": {...} | None, "basic_time_step_ms": t,
/// "warnings": [...]}`, in metres and radians, world frame, z up.
fn report<'py>(py: Python<'py>, import: &WbtImport) -> PyResult<Bound<'py, PyDict>> {
    let obstacles = PyList::empty(py);
    for obstacle in &import.obstacles {
        let d = PyDict::new(py);
        match *obstacle {
            Obstacle::Box { center, size, yaw } => {
                d.set_item("kind", "box")?;
                d.set_item("center", center.to_vec())?;
                d.set_item("size", size.to_vec())?;
                d.set_item("yaw", yaw)?;
            }
            Obstacle::Circle { center, radius } => {
                d.set_item("kind", "circle")?;
                d.set_item("center", center.to_vec())?;
                d.set_item("radius", radius)?;
            }
        }
        obstacles.append(d)?;
    }
    let out = PyDict::new(py);
    out.set_item("obstacles", obstacles)?;
    match import.robot {
        Some([x, y, yaw]) => {
            let robot = PyDict::new(py);
            robot.set_item("x", x)?;
            robot.set_item("y", y)?;
            robot.set_item("yaw", yaw)?;
            out.set_item("robot", robot)?;
        }
        None => out.set_item("robot", py.None())?,
    }
    out.set_item("basic_time_step_ms", import.basic_time_step_ms)?;
    out.set_item("warnings", import.warnings.clone())?;
    Ok(out)
}

fn world_name(source: &Path) -> String {
    source
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .filter(|s| !s.is_empty() && !s.starts_with('<'))
        .unwrap_or_else(|| "imported".to_string())
}

fn finish<'py>(
    py: Python<'py>,
    import: &WbtImport,
    source: &Path,
) -> PyResult<(PyWorld, Bound<'py, PyDict>)> {
    let world = import.to_world(&world_name(source)).py()?;
    Ok((
        PyWorld {
            inner: Arc::new(world),
        },
        report(py, import)?,
    ))
}

/// Imports a Webots `.wbt` file: the mazesim World and the import report (a dict).
#[pyfunction]
pub fn import_wbt(py: Python<'_>, path: PathBuf) -> PyResult<(PyWorld, Bound<'_, PyDict>)> {
    enter(|| {
        let import = enter_detached(py, || WbtImport::load(&path))?;
        finish(py, &import, &path)
    })
}

/// Imports the text of a `.wbt` file; `source` names it in error messages and names the world.
/// Lone surrogates (not UTF-8) are read as U+FFFD, so that they end in a located format error.
#[pyfunction]
#[pyo3(signature = (text, source = "<string>"))]
pub fn import_wbt_text<'py>(
    py: Python<'py>,
    text: &Bound<'py, PyString>,
    source: &str,
) -> PyResult<(PyWorld, Bound<'py, PyDict>)> {
    enter(|| {
        let text = text.to_string_lossy();
        let import = enter_detached(py, || WbtImport::from_text(&text, source))?;
        finish(py, &import, Path::new(source))
    })
}
