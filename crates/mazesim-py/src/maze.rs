//! `generate_maze` for Python, and how its mazes are built (`MazeLayout`: the cells' and walls'
//! sizes, the floor, the barcodes) as a typed, frozen value checked when it is made. The layout's
//! former keywords of `generate_maze` still work, with a `DeprecationWarning`, for one release.

use mazesim_core::generator::{self, MazeParams};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{typed_argument, unknown_key, warn_deprecated, Flag, IntArg, Keywords, Real};
use crate::errors::{invalid, IntoPy};
use crate::guard::enter;
use crate::world::PyWorld;

/// The keywords of `generate_maze` that its `layout` replaces.
const FORMER_KEYWORDS: &str = "cell_size wall_thickness checkpoints floor_reflectance";

/// How a generated maze is built: the side of its cells and the thickness of its walls (metres),
/// its floor's reflectance and whether barcode checkpoints are painted before its junctions.
#[pyclass(name = "MazeLayout", module = "mazesim._core", frozen)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PyMazeLayout {
    /// Side of a cell, metres.
    #[pyo3(get)]
    cell_size: f64,
    /// Thickness of a wall, metres (less than the cell's side).
    #[pyo3(get)]
    wall_thickness: f64,
    /// Whether barcode checkpoints are painted on the ways into junctions.
    #[pyo3(get)]
    checkpoints: bool,
    /// Reflectance of the floor, in (0, 1] (grey, so that codes show their ends).
    #[pyo3(get)]
    floor_reflectance: f64,
}

impl Default for PyMazeLayout {
    fn default() -> Self {
        let params = MazeParams::default();
        Self {
            cell_size: params.cell_size,
            wall_thickness: params.wall_thickness,
            checkpoints: params.checkpoints,
            floor_reflectance: params.floor_reflectance,
        }
    }
}

impl PyMazeLayout {
    /// The generator's parameters of a `width` x `height` maze of this layout.
    fn params(&self, width: usize, height: usize, loops: f64, junction: bool) -> MazeParams {
        MazeParams {
            width,
            height,
            cell_size: self.cell_size,
            wall_thickness: self.wall_thickness,
            loops,
            checkpoints: self.checkpoints,
            junction,
            floor_reflectance: self.floor_reflectance,
        }
    }
}

#[pymethods]
impl PyMazeLayout {
    #[new]
    #[pyo3(signature = (cell_size = Real::Number(0.25), wall_thickness = Real::Number(0.01), checkpoints = Flag::Value(true), floor_reflectance = Real::Number(0.36)),
        text_signature = "(cell_size=0.25, wall_thickness=0.01, checkpoints=True, floor_reflectance=0.36)")]
    pub fn new(
        cell_size: Real,
        wall_thickness: Real,
        checkpoints: Flag,
        floor_reflectance: Real,
    ) -> PyResult<Self> {
        enter(|| {
            let layout = Self {
                cell_size: cell_size.value("cell_size")?,
                wall_thickness: wall_thickness.value("wall_thickness")?,
                checkpoints: checkpoints.value("checkpoints", "a bool")?,
                floor_reflectance: floor_reflectance.value("floor_reflectance")?,
            };
            layout.params(5, 5, 0.0, true).check().py()?;
            Ok(layout)
        })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyMazeLayout>()
            .is_ok_and(|o| *o.get() == *self)
    }

    fn __hash__(&self) -> u64 {
        self.cell_size.to_bits()
            ^ self.wall_thickness.to_bits().rotate_left(17)
            ^ self.floor_reflectance.to_bits().rotate_left(34)
            ^ u64::from(self.checkpoints)
    }

    /// Pickles (and copies) as the constructor's arguments.
    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> (Bound<'py, pyo3::types::PyType>, (f64, f64, bool, f64)) {
        let l = slf.get();
        let arguments = (
            l.cell_size,
            l.wall_thickness,
            l.checkpoints,
            l.floor_reflectance,
        );
        (slf.get_type(), arguments)
    }

    fn __repr__(&self) -> String {
        format!(
            "MazeLayout(cell_size={:?}, wall_thickness={:?}, checkpoints={}, \
             floor_reflectance={:?})",
            self.cell_size,
            self.wall_thickness,
            if self.checkpoints { "True" } else { "False" },
            self.floor_reflectance
        )
    }
}

/// The layout of a `generate_maze` call: `layout`, or (deprecated, with a warning) the
/// layout's former keywords.
fn layout_of(
    layout: Option<&Bound<'_, PyAny>>,
    former: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyMazeLayout> {
    let layout = layout.filter(|l| !l.is_none());
    let first = former.map(|f| unknown_key(f, "")).transpose()?.flatten();
    if let (Some(former), Some(key)) = (former, first) {
        let kw = Keywords::new(Some(former), "generate_maze", FORMER_KEYWORDS)?;
        if layout.is_some() {
            return Err(invalid(format!(
                "expected either layout or generate_maze's former keywords, found layout and \
                 '{key}'"
            )));
        }
        warn_deprecated(
            former.py(),
            format!(
                "generate_maze's keyword '{key}' is deprecated and will be removed: pass \
                 layout=MazeLayout(...)"
            ),
        )?;
        let defaults = PyMazeLayout::default();
        let real = |key: &str, default: f64| kw.get(key, Real::Number(default));
        return PyMazeLayout::new(
            real("cell_size", defaults.cell_size)?,
            real("wall_thickness", defaults.wall_thickness)?,
            kw.get("checkpoints", Flag::Value(defaults.checkpoints))?,
            real("floor_reflectance", defaults.floor_reflectance)?,
        );
    }
    match layout {
        None => Ok(PyMazeLayout::default()),
        Some(l) => {
            typed_argument::<PyMazeLayout>(l, "layout", "a MazeLayout or None").map(|l| *l.get())
        }
    }
}

/// A seeded maze world (see mazesim-core's generator): `width` x `height` cells, a share `loops`
/// of extra openings, drawn again while it has no junction (unless `junction` is false), built
/// as `layout` says.
#[pyfunction]
#[pyo3(signature = (width = IntArg::Int(5), height = IntArg::Int(5), seed = IntArg::ZERO, *, loops = Real::Number(0.0), junction = Flag::Value(true), layout = None, **former),
    text_signature = "(width=5, height=5, seed=0, *, loops=0.0, junction=True, layout=None)")]
pub fn generate_maze(
    width: IntArg,
    height: IntArg,
    seed: IntArg,
    loops: Real,
    junction: Flag,
    layout: Option<&Bound<'_, PyAny>>,
    former: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyWorld> {
    enter(|| {
        let width = width.count("width", usize::MAX)?;
        let height = height.count("height", usize::MAX)?;
        let seed = seed.seed("seed")?;
        let loops = loops.value("loops")?;
        let junction = junction.value("junction", "a bool")?;
        let params = layout_of(layout, former)?.params(width, height, loops, junction);
        let world = generator::generate(&params, seed).py()?;
        Ok(PyWorld {
            inner: std::sync::Arc::new(world),
        })
    })
}
