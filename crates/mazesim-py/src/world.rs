//! `World` for Python.

use std::sync::Arc;

use mazesim_core::tasks::{cell_targets, grid_of, largest_connected_cells, open_sides};
use mazesim_core::world::{BodyShape, PaintShape, PlacedMaze, WallBox};
use mazesim_core::World;
use numpy::{PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::args::{IntArg, Label, PathArg, Real, SourceName, Text};
use crate::errors::{invalid, IntoPy};
use crate::guard::{enter, enter_detached};
use crate::simulator::{indices, pose_argument};

/// A maze world: walls, floor paint, checkpoints, goal and start pose.
#[pyclass(name = "World", module = "mazesim._core", frozen)]
pub struct PyWorld {
    pub inner: Arc<World>,
}

impl PyWorld {
    /// The world's cell maze, or InvalidArgumentError naming `method` when it has none.
    fn placed_maze(&self, method: &str) -> PyResult<&PlacedMaze> {
        self.inner.maze().ok_or_else(|| {
            invalid(format!(
                "World.{method}: expected a world with a [grid] cell maze, found none in {:?}",
                self.inner.name()
            ))
        })
    }
}

/// A goal disc (x, y, radius) as Python floats.
pub(crate) fn goal_tuple(g: mazesim_core::world::Goal) -> (f64, f64, f64) {
    (g.center[0], g.center[1], g.radius)
}

/// One dict per item of `items`, filled by `fill`.
pub(crate) fn dicts<'py, T>(
    py: Python<'py>,
    items: impl IntoIterator<Item = T>,
    fill: impl Fn(&Bound<'py, PyDict>, T) -> PyResult<()>,
) -> PyResult<Vec<Bound<'py, PyDict>>> {
    let dict = |item| {
        let d = PyDict::new(py);
        fill(&d, item)?;
        Ok(d)
    };
    items.into_iter().map(dict).collect()
}

/// Rows of `N` numbers as an `(len, N)` numpy array.
pub(crate) fn rows_to_array<'py, const N: usize>(
    py: Python<'py>,
    rows: impl IntoIterator<Item = [f64; N]>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    let len = flat.len() / N;
    numpy::PyArray1::from_vec(py, flat).reshape([len, N])
}

/// Rows of `wall_boxes`: cx, cy, sx, sy, yaw, reflectance of each wall.
fn box_rows(walls: &[WallBox]) -> impl Iterator<Item = [f64; 6]> + '_ {
    walls.iter().map(|w| {
        let [sx, sy] = [2.0 * w.half[0], 2.0 * w.half[1]];
        [w.center[0], w.center[1], sx, sy, w.yaw, w.reflectance]
    })
}

#[pymethods]
impl PyWorld {
    /// Worlds are made by `World.builtin`, `World.load`, `World.from_toml` or `generate_maze`:
    /// calling the class is an `InvalidArgumentError` saying so.
    #[new]
    #[pyo3(signature = (*_args, **_kwargs), text_signature = None)]
    fn new(
        _args: &Bound<'_, pyo3::types::PyTuple>,
        _kwargs: Option<&Bound<'_, pyo3::types::PyDict>>,
    ) -> PyResult<Self> {
        Err(crate::args::made_elsewhere(
            "World",
            "World.builtin(name), World.load(path), World.from_toml(text) or \
             mazesim.generate_maze(...)",
        ))
    }

    /// A built-in world by name (see `builtin_world_names()`).
    #[staticmethod]
    fn builtin(name: Text) -> PyResult<Self> {
        enter(|| {
            let name = name.value("name", "a str")?;
            Ok(Self {
                inner: Arc::new(World::builtin(&name).py()?),
            })
        })
    }

    /// Reads a world file.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathArg) -> PyResult<Self> {
        let path = path.value("path", "a str or os.PathLike")?;
        let world = enter_detached(py, || World::load(&path))?;
        Ok(Self {
            inner: Arc::new(world),
        })
    }

    /// Parses a world file's text; `source` names it in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, source = SourceName::Value(Label("<string>".into()))), text_signature = "(text, source='<string>')")]
    fn from_toml(py: Python<'_>, text: Text, source: SourceName) -> PyResult<Self> {
        let text = text.value("text", "a str")?;
        let source = source.value("source", "a str")?.0;
        let world = enter_detached(py, || World::from_toml(&text, &source))?;
        Ok(Self {
            inner: Arc::new(world),
        })
    }

    /// The world file text.
    fn to_toml(&self) -> PyResult<String> {
        enter(|| self.inner.to_toml().py())
    }

    /// Pickles as its world file text and source name.
    fn __reduce__<'py>(slf: &Bound<'py, Self>) -> PyResult<(Bound<'py, PyAny>, (String, String))> {
        let text = slf.get().to_toml()?;
        let source = slf.get().inner.source().to_string();
        Ok((slf.get_type().getattr("from_toml")?, (text, source)))
    }

    /// A world is immutable: a copy is the world itself.
    fn __copy__(slf: PyRef<'_, Self>) -> PyRef<'_, Self> {
        slf
    }

    fn __deepcopy__<'py>(slf: PyRef<'py, Self>, _memo: &Bound<'py, PyDict>) -> PyRef<'py, Self> {
        slf
    }

    /// Writes the world file atomically; a name not ending in `.toml` is refused (a `.wbt` one
    /// would be read back as a Webots world), a device such as `/dev/stdout` is written into.
    fn save(&self, py: Python<'_>, path: PathArg) -> PyResult<()> {
        let path = path.value("path", "a str or os.PathLike")?;
        enter_detached(py, || self.inner.save(&path))
    }

    #[getter]
    fn name(&self) -> PyResult<String> {
        enter(|| Ok(self.inner.name().to_string()))
    }

    #[getter]
    fn basic_time_step_ms(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.basic_time_step() * 1000.0))
    }

    #[getter]
    fn bounds(&self) -> PyResult<(f64, f64, f64, f64)> {
        enter(|| {
            Ok({
                let b = self.inner.bounds();
                (b.min[0], b.min[1], b.max[0], b.max[1])
            })
        })
    }

    #[getter]
    fn start(&self) -> PyResult<(f64, f64, f64)> {
        let s = self.inner.start();
        Ok((s[0], s[1], s[2]))
    }

    /// The robots the world places, in order: dicts of "name", "start" (x, y, yaw) and
    /// "profile" (a built-in profile's name, or None for the simulator's).
    #[getter]
    fn robots<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        enter(|| {
            dicts(py, self.inner.robots(), |d, r| {
                d.set_item("name", &r.name)?;
                d.set_item("start", (r.start[0], r.start[1], r.start[2]))?;
                d.set_item("profile", r.profile.as_deref())
            })
        })
    }

    #[getter]
    fn goal(&self) -> PyResult<Option<(f64, f64, f64)>> {
        enter(|| Ok(self.inner.goal().map(goal_tuple)))
    }

    /// (N, 6) array: cx, cy, sx, sy, yaw, reflectance of every wall box (the sensed-only walls
    /// are `sensed_wall_boxes`).
    fn wall_boxes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        enter(|| rows_to_array(py, box_rows(self.inner.walls())))
    }

    /// (N, 3) array: red, green, blue in [0, 1] of every wall box as a camera sees it, in the
    /// order of `wall_boxes`; NaN for a wall that gives no colour (drawn in the grey of its
    /// reflectance).
    fn wall_colours<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        enter(|| {
            let rows = self
                .inner
                .wall_colours()
                .into_iter()
                .map(|c| c.unwrap_or([f64::NAN; 3]));
            rows_to_array(py, rows)
        })
    }

    /// (N,) array: how high the top of every wall box stands above the floor (m), in the order
    /// of `wall_boxes`; inf for a wall that gives no height (higher than any sensor's ray).
    fn wall_tops<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        enter(|| Ok(PyArray1::from_vec(py, self.inner.wall_tops())))
    }

    /// (N,) array as `wall_tops` of the sensed-only walls, in the order of
    /// `sensed_wall_boxes`.
    fn sensed_wall_tops<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray1<f64>>> {
        enter(|| Ok(PyArray1::from_vec(py, self.inner.sensed_wall_tops())))
    }

    /// (N, 6) array as `wall_boxes` of the sensed-only walls (`sensed_only = true`: seen by
    /// infra-red rays and cameras, met by nothing else), in `[[walls]]` order; (0, 6) when none.
    fn sensed_wall_boxes<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        enter(|| {
            let walls = self.inner.sensed_walls().map_or(&[][..], |s| s.walls());
            rows_to_array(py, box_rows(walls))
        })
    }

    /// (N, 3) array as `wall_colours` of the sensed-only walls, in the order of
    /// `sensed_wall_boxes`.
    fn sensed_wall_colours<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        enter(|| {
            let colours = self.inner.sensed_walls().map_or(&[][..], |s| s.colours());
            rows_to_array(py, colours.iter().map(|c| c.unwrap_or([f64::NAN; 3])))
        })
    }

    /// The bare floor's colour as a camera sees it, (red, green, blue) in [0, 1], or None (the
    /// grey of its reflectance).
    #[getter]
    fn floor_colour(&self) -> PyResult<Option<(f64, f64, f64)>> {
        enter(|| Ok(self.inner.floor_colour().map(|[r, g, b]| (r, g, b))))
    }

    /// Floor paint regions in drawing order, as dicts ("colour": (red, green, blue) in [0, 1]
    /// as a camera sees it, or None for the grey of its reflectance).
    fn paint_regions<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        enter(|| {
            let regions = self.inner.floor().regions().iter().enumerate();
            dicts(py, regions, |d, (i, r)| {
                let colour = self.inner.paint_colour(i).map(|[r, g, b]| (r, g, b));
                d.set_item("colour", colour)?;
                match r.shape {
                    PaintShape::Rect { center, half, yaw } => {
                        d.set_item("shape", "rect")?;
                        d.set_item("center", (center[0], center[1]))?;
                        d.set_item("size", (2.0 * half[0], 2.0 * half[1]))?;
                        d.set_item("yaw", yaw)?;
                    }
                    PaintShape::Circle { center, radius } => {
                        d.set_item("shape", "circle")?;
                        d.set_item("center", (center[0], center[1]))?;
                        d.set_item("radius", radius)?;
                    }
                    PaintShape::Capsule { a, b, radius } => {
                        d.set_item("shape", "capsule")?;
                        d.set_item("a", (a[0], a[1]))?;
                        d.set_item("b", (b[0], b[1]))?;
                        d.set_item("radius", radius)?;
                    }
                }
                d.set_item("reflectance", r.reflectance)
            })
        })
    }

    /// Movable bodies at their start poses as dicts: shape ("box" with size and yaw, or
    /// "circle" with radius), center, mass, friction, reflectance.
    fn bodies<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        enter(|| {
            dicts(py, self.inner.bodies(), |d, b| {
                let [x, y, yaw] = b.start;
                match b.shape {
                    BodyShape::Box { half } => {
                        d.set_item("shape", "box")?;
                        d.set_item("center", (x, y))?;
                        d.set_item("size", (2.0 * half[0], 2.0 * half[1]))?;
                        d.set_item("yaw", yaw)?;
                    }
                    BodyShape::Circle { radius } => {
                        d.set_item("shape", "circle")?;
                        d.set_item("center", (x, y))?;
                        d.set_item("radius", radius)?;
                    }
                }
                d.set_item("mass", b.mass)?;
                d.set_item("friction", b.friction)?;
                d.set_item("reflectance", b.reflectance)
            })
        })
    }

    /// The `[[checkpoints]]` tables `generate_maze` would place on this world's `[grid]` maze, one
    /// on every way into every junction, as world-file text to paste into a maze drawn by hand
    /// (after the grey `[floor]` of generated mazes when the world has none); "" when the world
    /// has no grid or its maze no junction.
    fn junction_checkpoints(&self) -> PyResult<String> {
        enter(|| mazesim_core::generator::junction_checkpoints_toml(&self.inner).py())
    }

    /// Checkpoints as dicts: id, code, center, yaw, width.
    fn checkpoints<'py>(&self, py: Python<'py>) -> PyResult<Vec<Bound<'py, PyDict>>> {
        enter(|| {
            dicts(py, self.inner.checkpoints(), |d, c| {
                d.set_item("id", c.id)?;
                let code: String = c.code.iter().map(|&b| if b { '1' } else { '0' }).collect();
                d.set_item("code", code)?;
                d.set_item("center", (c.center[0], c.center[1]))?;
                d.set_item("yaw", c.yaw)?;
                d.set_item("width", c.width)
            })
        })
    }

    /// The cell maze of a `[grid]` world, or None: a dict of "rows", "cols", "cell_size",
    /// "origin" and the wall arrays "horizontal" ((rows + 1, cols) bool: grid line k, 0 = north,
    /// above cell column c) and "vertical" ((rows, cols + 1) bool: beside cell row r, line k,
    /// 0 = west), plus "start" and "goal" cells (column, row) when marked.
    fn cell_maze<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        enter(|| {
            let Some(placed) = self.inner.maze() else {
                return Ok(None);
            };
            let m = &placed.maze;
            let d = PyDict::new(py);
            d.set_item("rows", m.rows)?;
            d.set_item("cols", m.cols)?;
            d.set_item("cell_size", placed.cell_size)?;
            d.set_item("origin", (placed.origin[0], placed.origin[1]))?;
            let h = numpy::PyArray1::from_slice(py, &m.horizontal).reshape([m.rows + 1, m.cols])?;
            let v = numpy::PyArray1::from_slice(py, &m.vertical).reshape([m.rows, m.cols + 1])?;
            d.set_item("horizontal", h)?;
            d.set_item("vertical", v)?;
            d.set_item("start", m.start)?;
            d.set_item("goal", m.goal)?;
            Ok(Some(d))
        })
    }

    /// (rows * cols, 5) float64: the goal-distance table's interpolation targets of every cell
    /// (row-major from the north-west) towards the cell `goal_cell` (its row-major index): per
    /// side (east, north, west, south) the path distance at the side's midpoint, then the goal
    /// point's.
    fn distance_targets<'py>(
        &self,
        py: Python<'py>,
        goal_cell: IntArg,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        enter(|| {
            let placed = self.placed_maze("distance_targets")?;
            let maze = &placed.maze;
            let cells = maze.rows * maze.cols;
            let goal = goal_cell.count("goal_cell", cells.saturating_sub(1))?;
            let targets = cell_targets(grid_of(maze), &open_sides(maze), placed.cell_size, goal);
            rows_to_array(py, targets)
        })
    }

    /// (n, 2) int64: the (row, column) cells of the largest set of cells joined by open sides,
    /// row-major from the north-west (the first such set if two are as large).
    fn connected_cells<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<i64>>> {
        enter(|| {
            let maze = &self.placed_maze("connected_cells")?.maze;
            let cells = largest_connected_cells(grid_of(maze), &open_sides(maze));
            let flat: Vec<i64> = cells
                .iter()
                .flat_map(|&cell| [(cell / maze.cols) as i64, (cell % maze.cols) as i64])
                .collect();
            numpy::PyArray1::from_vec(py, flat).reshape([cells.len(), 2])
        })
    }

    /// Background floor reflectance (where nothing is painted).
    #[getter]
    fn floor_background(&self) -> PyResult<f64> {
        enter(|| Ok(self.inner.floor().background()))
    }

    /// Floor reflectance factor at (x, y).
    fn floor_reflectance(&self, x: Real, y: Real) -> PyResult<f64> {
        let (x, y) = (x.coordinate("x")?, y.coordinate("y")?);
        enter(|| Ok(self.inner.floor().reflectance_at([x, y])))
    }

    /// This world with the `[[paint]]` entries `paint` (indices) moved by the rigid motion that
    /// takes the pose `from_pose` (x, y, yaw) to `to_pose`, as a supervisor moves the node that
    /// holds a floor mark; refused when an index is past the paint or the paint would leave the
    /// limits.
    #[pyo3(text_signature = "($self, paint, from_pose, to_pose)")]
    fn with_paint_moved(
        &self,
        paint: &Bound<'_, PyAny>,
        from_pose: &Bound<'_, PyAny>,
        to_pose: &Bound<'_, PyAny>,
    ) -> PyResult<Self> {
        let paint = indices(paint, "paint", mazesim_core::limits::MAX_PAINT_REGIONS)?;
        let motion = mazesim_core::world::Motion {
            from: pose_argument(from_pose, "from_pose")?,
            to: pose_argument(to_pose, "to_pose")?,
        };
        let world = enter(|| self.inner.with_paint_moved(&paint, motion).py())?;
        Ok(PyWorld {
            inner: Arc::new(world),
        })
    }

    fn __eq__(&self, other: &Bound<'_, PyAny>) -> PyResult<bool> {
        enter(|| {
            Ok({
                other
                    .cast::<PyWorld>()
                    .map(|o| *o.get().inner == *self.inner)
                    .unwrap_or(false)
            })
        })
    }

    fn __repr__(&self) -> PyResult<String> {
        enter(|| {
            Ok({
                format!(
                    "World(name={:?}, walls={}, checkpoints={}, source={:?})",
                    self.inner.name(),
                    self.inner.walls().len(),
                    self.inner.checkpoints().len(),
                    self.inner.source()
                )
            })
        })
    }
}

/// The `World` a `world` argument names, or an `InvalidArgumentError` saying what was found.
pub fn world_argument(world: &Bound<'_, PyAny>, name: &str) -> PyResult<Arc<World>> {
    match world.cast::<PyWorld>() {
        Ok(w) => Ok(w.get().inner.clone()),
        Err(_) => Err(not_a_world(world, name, "a mazesim.World")),
    }
}

/// The items of a `worlds` argument (a sequence of at most `most` worlds, as `bounded_items`
/// takes it); a world's name or path given instead is told how to load it.
pub fn world_items<'py>(
    worlds: &Bound<'py, PyAny>,
    expected: &str,
    most: usize,
) -> PyResult<Vec<Bound<'py, PyAny>>> {
    if load_hint(worlds).is_some() {
        return Err(not_a_world(
            worlds,
            "worlds",
            &format!("a sequence of {expected}"),
        ));
    }
    crate::args::bounded_items(worlds, "worlds", expected, most)
}

/// The wrong-type error for an argument that is not a World: when it is text or a path (a
/// world's name or file, the usual mix-up), the message says how to load that world.
pub fn not_a_world(given: &Bound<'_, PyAny>, name: &str, expected: &str) -> PyErr {
    let kind = crate::args::type_name(given);
    let hint = load_hint(given).unwrap_or_default();
    crate::errors::wrong_type(format!(
        "expected {name} to be {expected}, found {kind}{hint}"
    ))
}

/// "; load it with mazesim.load_world(...)" for a str or path-like argument, else None.
fn load_hint(given: &Bound<'_, PyAny>) -> Option<String> {
    let path_like = given.hasattr("__fspath__").unwrap_or(false);
    if !given.is_instance_of::<pyo3::types::PyString>() && !path_like {
        return None;
    }
    let shown = given
        .repr()
        .map(|r| r.to_string_lossy().into_owned())
        .unwrap_or_else(|_| "NAME_OR_PATH".into());
    Some(format!(
        "; a World is made from a built-in name or a world file by \
         mazesim.load_world({shown})"
    ))
}
