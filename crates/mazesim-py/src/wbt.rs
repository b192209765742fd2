//! `import_wbt` / `import_wbt_text` for Python: a Webots world as a mazesim `World` plus the
//! import report as a dict (the JSON layout of `mazesim import-wbt --json`).

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use mazesim_core::wbt::{DeviceField, GreyImage, Obstacle, RobotChoice, WbtImport};
use mazesim_core::world::spec::BodySpec;
use mazesim_core::world::values::xy;
use mazesim_core::Error;
use numpy::{PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString};

use crate::args::{
    dict_argument, type_name, typed_argument, IntArg, Label, PathArg, SourceName, Text,
};
use crate::errors::{wrong_type, IntoPy};
use crate::guard::{enter, enter_detached};
use crate::world::{dicts, PyWorld};

/// A device field as a Python value: a number, a list of numbers, a list of rows, a string, a
/// list of strings or a bool.
fn device_field<'py>(py: Python<'py>, value: &DeviceField) -> PyResult<Bound<'py, PyAny>> {
    Ok(match value {
        DeviceField::Number(v) => v.into_pyobject(py)?.into_any(),
        DeviceField::Numbers(v) => v.clone().into_pyobject(py)?.into_any(),
        DeviceField::Table(rows) => rows
            .iter()
            .map(|r| r.to_vec())
            .collect::<Vec<_>>()
            .into_pyobject(py)?
            .into_any(),
        DeviceField::Text(v) => v.into_pyobject(py)?.into_any(),
        DeviceField::Texts(v) => v.clone().into_pyobject(py)?.into_any(),
        DeviceField::Flag(v) => v.into_pyobject(py)?.to_owned().into_any(),
    })
}

/// The robot's model and profile, its extension devices and the floor textures.
fn robot_and_floor(out: &Bound<'_, PyDict>, import: &WbtImport) -> PyResult<()> {
    let py = out.py();
    out.set_item("robot_model", import.robot_model.clone())?;
    out.set_item("robot_line", import.robot_line)?;
    out.set_item("robot_profile", &import.robot_profile)?;
    let robots = dicts(py, &import.robots, |d, robot| {
        d.set_item("pose", robot.pose.to_vec())?;
        d.set_item("model", &robot.model)?;
        d.set_item("profile", robot.profile)?;
        d.set_item("controller", robot.controller.clone())?;
        d.set_item("name", robot.name.clone())?;
        d.set_item("def_name", robot.def_name.clone())?;
        d.set_item("line", robot.line)?;
        d.set_item("y_up", robot.y_up)?;
        d.set_item("node_type", &robot.node_type)?;
        d.set_item("model_field", robot.model_field.clone())
    })?;
    out.set_item("robots", robots)?;
    let devices = dicts(py, &import.extension_devices, |d, device| {
        d.set_item("type", &device.kind)?;
        d.set_item("name", &device.name)?;
        d.set_item("slot", &device.slot)?;
        d.set_item("translation", device.translation.to_vec())?;
        d.set_item("yaw", device.yaw)?;
        d.set_item("pitch", device.pitch)?;
        d.set_item("axes", device.axes.map(|a| a.to_vec()).to_vec())?;
        let fields = PyDict::new(py);
        for (name, value) in &device.fields {
            fields.set_item(name, device_field(py, value)?)?;
        }
        d.set_item("fields", fields)
    })?;
    out.set_item("extension_devices", devices)?;
    out.set_item("missing_devices", import.missing_devices.clone())?;
    let textures = dicts(py, &import.floor_textures, |d, texture| {
        d.set_item("urls", texture.urls.clone())?;
        d.set_item("owner", &texture.owner)?;
        d.set_item("center", texture.center.to_vec())?;
        d.set_item("size", texture.size.to_vec())?;
        d.set_item("yaw", texture.yaw)?;
        d.set_item("tile", texture.tile.to_vec())?;
        d.set_item("repeat", texture.repeat.to_vec())?;
        d.set_item("candidates", texture.candidates.clone())
    })?;
    out.set_item("floor_textures", textures)?;
    let walls = dicts(py, &import.wall_textures, |d, texture| {
        d.set_item("urls", texture.urls.clone())?;
        d.set_item("owner", &texture.owner)?;
        d.set_item("red", texture.red)?;
        d.set_item("colour", texture.colour.to_vec())?;
        d.set_item("roughness", texture.roughness)?;
        d.set_item("candidates", texture.candidates.clone())
    })?;
    out.set_item("wall_textures", walls)?;
    out.set_item("floor_paint", import.paint.len())?;
    // What a supervisor moves with a node: the floor marks its line holds (paint indices).
    let held = (import.paint_owners.iter().enumerate())
        .filter(|(_, owners)| !owners.is_empty())
        .map(|(i, owners)| {
            let d = PyDict::new(out.py());
            d.set_item("paint", i)?;
            d.set_item("owners", owners.clone())?;
            Ok(d)
        })
        .collect::<PyResult<Vec<_>>>()?;
    out.set_item("floor_marks", held)?;
    Ok(())
}

/// The grey images handed in for the floor textures: `{file: (height, width) float64 array of
/// grey levels in [0, 1]}`.
fn grey_images(images: Option<&Bound<'_, PyAny>>) -> PyResult<BTreeMap<String, GreyImage>> {
    let images = match images {
        None => None,
        Some(obj) => Some(dict_argument(
            obj,
            "floor_images",
            " of file name -> grey-level array",
        )?),
    };
    let mut out = BTreeMap::new();
    for (key, value) in images.into_iter().flat_map(|d| d.iter()) {
        let file: String = key.extract().map_err(|_| {
            wrong_type(format!(
                "expected the keys of floor_images to be file names (str), found {}",
                type_name(&key)
            ))
        })?;
        let wrong = |found: String| {
            Error::InvalidArgument(format!(
                "floor image {file:?}: expected a C-contiguous (height, width) float64 array of grey levels in [0, 1], found {found}"
            ))
        };
        let Ok(array) = value.cast::<PyArrayDyn<f64>>() else {
            return Err(wrong(value.get_type().name()?.to_string())).py();
        };
        let shape = array.shape().to_vec();
        if shape.len() != 2 || !array.is_c_contiguous() || shape.contains(&0) {
            return Err(wrong(format!("shape {shape:?}"))).py();
        }
        let levels = array.readonly().as_slice()?.to_vec();
        if levels.iter().any(|g| !(0.0..=1.0).contains(g)) {
            return Err(wrong("a level outside [0, 1]".to_string())).py();
        }
        out.insert(
            file,
            GreyImage {
                width: shape[1],
                height: shape[0],
                levels,
            },
        );
    }
    Ok(out)
}

/// The mean colours handed in for the wall textures: `{file: (red, green, blue), each in
/// [0, 1]}`.
fn wall_colours(colours: Option<&Bound<'_, PyAny>>) -> PyResult<BTreeMap<String, [f64; 3]>> {
    let colours = match colours {
        None => None,
        Some(obj) => Some(dict_argument(
            obj,
            "wall_colours",
            " of file name -> mean (red, green, blue)",
        )?),
    };
    let mut out = BTreeMap::new();
    for (key, value) in colours.into_iter().flat_map(|d| d.iter()) {
        let file: String = key.extract().map_err(|_| {
            wrong_type(format!(
                "expected the keys of wall_colours to be file names (str), found {}",
                type_name(&key)
            ))
        })?;
        let colour: (f64, f64, f64) = value.extract().map_err(|_| {
            wrong_type(format!(
                "wall texture {file:?}: expected its mean colour as three floats (red, green, \
                 blue), found {}",
                type_name(&value)
            ))
        })?;
        let colour = [colour.0, colour.1, colour.2];
        if !colour.iter().all(|c| (0.0..=1.0).contains(c)) {
            return Err(Error::InvalidArgument(format!(
                "wall texture {file:?}: expected its mean colour's red, green and blue in \
                 [0, 1], found {colour:?}"
            )))
            .py();
        }
        out.insert(file, colour);
    }
    Ok(out)
}

/// The import as `{"obstacles": [...], "sensed_only": [...], "bodies": [...], "robot": {...} | None, "basic_time_step_ms": t,
/// (each obstacle and body with its `owners`, the lines of the nodes that hold it, and its
/// infra-red `reflectance`, each body with the `colour` a camera sees (None: the grey of its
/// reflectance), whether it is a `sphere` (a ball) and its `height`, and each obstacle with its `walls`, the first of its walls in the
/// world and how many; `sensed_only` the obstacles only infra-red rays and cameras meet, as
/// obstacles without owners, each with its `reflectance`),
/// "warnings": [...], "one_controller_warnings": [...], "robot_model", "robot_line", "robot_profile", "extension_devices", "missing_devices", "floor_textures",
/// "wall_textures", "floor_paint"}`, in metres and radians, world frame, z up.
fn report<'py>(py: Python<'py>, import: &WbtImport) -> PyResult<Bound<'py, PyDict>> {
    let footprint = |d: &Bound<'py, PyDict>, obstacle: &Obstacle| -> PyResult<()> {
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
        Ok(())
    };
    let obstacles = dicts(py, &import.obstacles, footprint)?;
    let sensed_only = dicts(py, &import.sensed_obstacles, footprint)?;
    let bodies = dicts(py, &import.bodies, |d, body| {
        let (mass, friction, reflectance) = match body {
            BodySpec::Box {
                center,
                size,
                yaw,
                mass,
                friction,
                reflectance,
            } => {
                d.set_item("kind", "box")?;
                d.set_item("center", xy(center).to_vec())?;
                d.set_item("size", [size[0].get(), size[1].get()].to_vec())?;
                d.set_item("yaw", yaw.get())?;
                (mass, friction, reflectance)
            }
            BodySpec::Circle {
                center,
                radius,
                mass,
                friction,
                reflectance,
            } => {
                d.set_item("kind", "circle")?;
                d.set_item("center", xy(center).to_vec())?;
                d.set_item("radius", radius.get())?;
                (mass, friction, reflectance)
            }
        };
        d.set_item("mass", mass.get())?;
        d.set_item("friction", friction.get())?;
        d.set_item("reflectance", reflectance.0)
    })?;
    // What a supervisor moves with a node: the obstacles and bodies its line holds.
    let walls = import.obstacle_walls();
    for ((d, owners), (first, count)) in obstacles.iter().zip(&import.obstacle_owners).zip(walls) {
        d.set_item("owners", owners.clone())?;
        d.set_item("walls", vec![first, count])?;
    }
    for (d, look) in obstacles.iter().zip(&import.obstacle_looks) {
        d.set_item("reflectance", look.reflectance)?;
    }
    for (d, look) in sensed_only.iter().zip(&import.sensed_looks) {
        d.set_item("reflectance", look.reflectance)?;
    }
    let sensed_walls = import.sensed_walls();
    for ((d, owners), (first, count)) in sensed_only
        .iter()
        .zip(&import.sensed_owners)
        .zip(sensed_walls)
    {
        d.set_item("owners", owners.clone())?;
        d.set_item("walls", vec![first, count])?;
    }
    for (d, owners) in bodies.iter().zip(&import.body_owners) {
        d.set_item("owners", owners.clone())?;
    }
    for (d, look) in bodies.iter().zip(&import.body_looks) {
        d.set_item("colour", look.colour.map(|c| c.to_vec()))?;
        d.set_item("sphere", look.sphere)?;
        d.set_item("height", look.height)?;
    }
    let out = PyDict::new(py);
    out.set_item("obstacles", obstacles)?;
    out.set_item("sensed_only", sensed_only)?;
    out.set_item("bodies", bodies)?;
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
    out.set_item(
        "one_controller_warnings",
        import.one_controller_warnings.clone(),
    )?;
    robot_and_floor(&out, import)?;
    Ok(out)
}

/// The `floor_images` and `wall_colours` arguments of an import.
type Textures<'a, 'py> = (Option<&'a Bound<'py, PyAny>>, Option<&'a Bound<'py, PyAny>>);

fn world_name(source: &Path) -> String {
    source
        .file_stem()
        .map(|s| s.to_string_lossy().into_owned())
        .filter(|s| !s.is_empty() && !s.starts_with('<'))
        .unwrap_or_else(|| "imported".to_string())
}

fn finish<'py>(
    py: Python<'py>,
    mut import: WbtImport,
    source: &Path,
    (floor_images, colours): Textures<'_, 'py>,
) -> PyResult<(PyWorld, Bound<'py, PyDict>)> {
    import.paint_floor(&grey_images(floor_images)?);
    import.shade_walls(&wall_colours(colours)?);
    let import = &import;
    let world = import
        .to_world_of(&world_name(source), &source.display().to_string())
        .py()?;
    Ok((
        PyWorld {
            inner: Arc::new(world),
        },
        report(py, import)?,
    ))
}

/// Imports a Webots `.wbt` file: the mazesim World and the import report (a dict).
/// `floor_images` maps texture files (as the report's `floor_textures` candidates name them) to
/// their grey levels; the textures without one are reported missing. `wall_colours` maps wall
/// texture files (the report's `wall_textures` candidates) to their images' mean colour (red,
/// green, blue in [0, 1]), which the walls' infra-red reflection factor (by its red) and the
/// colour a camera sees follow. `controller` names the
/// controller that will run: of several e-pucks, the first whose `controller` field is it is
/// the robot; `robot_line` picks the robot (an e-puck or not) whose node is on that line (the
/// `line` of an entry of the report's `robots`).
#[pyfunction]
#[pyo3(signature = (path, floor_images = None, controller = None, robot_line = None, wall_colours = None))]
pub fn import_wbt<'py>(
    py: Python<'py>,
    path: PathArg,
    floor_images: Option<&Bound<'py, PyAny>>,
    controller: Option<Text>,
    robot_line: Option<IntArg>,
    wall_colours: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyWorld, Bound<'py, PyDict>)> {
    enter(|| {
        let path: PathBuf = path.value("path", "a str or os.PathLike")?;
        let robot = (controller, robot_line, None);
        import_chosen(py, robot, (floor_images, wall_colours), &path, |choice| {
            WbtImport::load_for(&path, choice)
        })
    })
}

/// Imports with `load`, the GIL released, the robot that the `controller` and `robot_line`
/// arguments choose (the nodes from line `imported_from` on imported while the world runs),
/// and makes the world named after `source` and the report.
fn import_chosen<'py>(
    py: Python<'py>,
    (controller, robot_line, imported_from): (Option<Text>, Option<IntArg>, Option<IntArg>),
    textures: Textures<'_, 'py>,
    source: &Path,
    load: impl FnOnce(RobotChoice<'_>) -> mazesim_core::Result<WbtImport> + Send,
) -> PyResult<(PyWorld, Bound<'py, PyDict>)> {
    let controller = controller
        .map(|c| c.value("controller", "a str or None"))
        .transpose()?;
    let line = line_number(robot_line, "robot_line")?;
    let imported_from = line_number(imported_from, "imported_from")?;
    let import = enter_detached(py, || {
        load(RobotChoice {
            controller: controller.as_deref(),
            line,
            imported_from,
        })
    })?;
    finish(py, import, source, textures)
}

/// A line number argument (`robot_line`, `imported_from`): a line of the file (from 1), or
/// None.
fn line_number(line: Option<IntArg>, name: &str) -> PyResult<Option<usize>> {
    line.map(|line| {
        line.within(name, 1u64, u64::from(u32::MAX))
            .map(|l| l as usize)
    })
    .transpose()
}

/// Imports the text of a `.wbt` file; `source` names it in error messages and names the world.
/// Lone surrogates (not UTF-8) are read as U+FFFD, so that they end in a located format error.
#[pyfunction]
#[pyo3(signature = (text, source = SourceName::Value(Label("<string>".into())), floor_images = None, controller = None, robot_line = None, imported_from = None, wall_colours = None),
    text_signature = "(text, source='<string>', floor_images=None, controller=None, robot_line=None, imported_from=None, wall_colours=None)")]
pub fn import_wbt_text<'py>(
    py: Python<'py>,
    text: &Bound<'py, PyAny>,
    source: SourceName,
    floor_images: Option<&Bound<'py, PyAny>>,
    controller: Option<Text>,
    robot_line: Option<IntArg>,
    imported_from: Option<IntArg>,
    wall_colours: Option<&Bound<'py, PyAny>>,
) -> PyResult<(PyWorld, Bound<'py, PyDict>)> {
    enter(|| {
        let text = typed_argument::<PyString>(text, "text", "a str")?;
        let text = text.to_string_lossy();
        let source = source.value("source", "a str")?.0;
        let robot = (controller, robot_line, imported_from);
        let textures = (floor_images, wall_colours);
        import_chosen(py, robot, textures, Path::new(&source), |choice| {
            WbtImport::from_text_for(&text, &source, choice)
        })
    })
}
