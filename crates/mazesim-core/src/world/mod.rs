//! Worlds: the file format (TOML, versioned), the compiled geometry the simulator uses, and the
//! built-in worlds.

mod binning;
pub mod bodies;
mod builtin;
mod extent;
pub mod floor;
pub mod geometry;
pub mod grid;
pub(crate) mod lengths;
pub mod locate;
pub mod moves;
pub mod nearby;
pub mod robots;
pub mod sensed;
pub mod spec;
pub mod values;
pub mod walls;

use std::path::Path;

pub use bodies::{BodyShape, MovableBody};
pub use builtin::{builtin_world_names, builtin_world_text};
pub use floor::{FloorPaint, PaintRegion};
pub use geometry::{Bounds, PaintShape, WallBox};
pub use grid::CellMaze;
pub use moves::Motion;
pub use nearby::{NearbyWalls, RayFan};
pub use robots::{CarriedShape, RobotPlacement};
pub use sensed::SensedWalls;
pub use spec::WorldSpec;
pub use walls::{RayHit, WallIndex};

use crate::error::{Error, Result};
use crate::file_kind::FileKind;
use extent::{ExtentCheck, Place};
use spec::{BarcodeSpec, PaintSpec};
use values::xy;

/// A barcode checkpoint on the floor.
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    /// Positive id.
    pub id: u32,
    /// Bits, first met first when travelling along `yaw`.
    pub code: Vec<bool>,
    /// Middle of the code.
    pub center: [f64; 2],
    /// Direction of travel in which the code reads as written.
    pub yaw: f64,
    /// Extent across the corridor.
    pub width: f64,
    /// Extent along the direction of travel (bars times bar length).
    pub length: f64,
    /// Unit vector along `yaw` (cos, sin).
    pub axis: [f64; 2],
}

/// The goal region: a disc.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Goal {
    /// Centre.
    pub center: [f64; 2],
    /// Radius.
    pub radius: f64,
}

/// A cell maze with its placement in the world.
#[derive(Debug, Clone, PartialEq)]
pub struct PlacedMaze {
    /// The cells.
    pub maze: CellMaze,
    /// South-west corner.
    pub origin: [f64; 2],
    /// Side of a cell.
    pub cell_size: f64,
}

/// A loaded world: its description as written and the geometry compiled from it.
#[derive(Debug, Clone)]
pub struct World {
    spec: WorldSpec,
    source: String,
    /// Every wall box in file order, when some are exact duplicates (`None`: as `solid_walls`).
    walls: Option<Box<[WallBox]>>,
    /// `walls` without exact duplicates (a wall written twice is one solid), in file order: what
    /// the physics and the sensors see.
    solid_walls: Vec<WallBox>,
    wall_index: WallIndex,
    /// The walls only infra-red rays and cameras meet (`None`: there are none).
    sensed: Option<Box<SensedWalls>>,
    floor: FloorPaint,
    checkpoints: Vec<Checkpoint>,
    goal: Option<Goal>,
    start: [f64; 3],
    /// The robots: one at `start`, or those of `[[robots]]` (the first at `start`).
    robots: Vec<RobotPlacement>,
    bounds: Bounds,
    maze: Option<PlacedMaze>,
    /// Movable bodies at their start poses, in file order.
    bodies: Vec<MovableBody>,
    /// Hash of the description as `to_toml` writes it: equal worlds have equal fingerprints.
    fingerprint: u64,
    /// The colour of each paint region of `[[paint]]` that gives one, in the floor's region
    /// order (the checkpoints' bars after them have none).
    paint_colours: Vec<Option<[f64; 3]>>,
}

impl PartialEq for World {
    /// Two worlds are equal when their descriptions are.
    fn eq(&self, other: &Self) -> bool {
        self.spec == other.spec
    }
}

/// Byte offset of the `n`-th `[[name]]` header in `text` (0 when not found).
fn table_offset(text: &str, name: &str, n: usize) -> usize {
    extent::line_offset(text, &format!("[[{name}]]"), n)
}

impl World {
    /// Parses a world file's text; `source` names it in error messages.
    pub fn from_toml(text: &str, source: &str) -> Result<World> {
        Self::parse(text, source, false)
    }

    /// Parses a world's text; `written_here` skips the check of its arrays' lengths, for a
    /// text written from a description (whose arrays have their fields' lengths).
    fn parse(text: &str, source: &str, written_here: bool) -> Result<World> {
        let limit = crate::limits::MAX_WORLD_FILE_BYTES;
        crate::io::check_text_length(text, source, limit, "the world file")?;
        let text: &str = &crate::io::toml_text(text);
        locate::check_table_count(text, source)?;
        let spec: WorldSpec = toml::from_str(text).map_err(|e| {
            let refused = locate::from_toml_error(source, text, &e);
            crate::file_kind::named_for_its_kind(text, source, FileKind::World, refused)
        })?;
        if !written_here {
            lengths::check(&spec, text, source)?;
        }
        Self::compile(spec, source, text)
    }

    /// Reads a world file; a world without a `name` is named after the file (`my-maze` for
    /// `my-maze.toml`), as an imported Webots world is.
    pub fn load(path: &Path) -> Result<World> {
        let limit = crate::limits::MAX_WORLD_FILE_BYTES;
        let text = crate::io::read_text_limited(path, limit, "the world file")?;
        let mut world = Self::from_toml(&text, &path.display().to_string())?;
        if world.spec.name.is_empty() {
            if let Some(stem) = path.file_stem() {
                world.spec.name = stem.to_string_lossy().into_owned();
            }
        }
        Ok(world)
    }

    /// A built-in world by name.
    pub fn builtin(name: &str) -> Result<World> {
        let text = builtin_world_text(name)?;
        Self::from_toml(text, &format!("builtin:{name}"))
    }

    /// Compiles a description made in code (for example by a generator).
    pub fn from_spec(spec: WorldSpec, source: &str) -> Result<World> {
        // Round-trip through the text so that errors can point at lines and the world saves as built.
        let text =
            toml::to_string_pretty(&spec).map_err(|e| Error::InvalidArgument(e.to_string()))?;
        Self::parse(&text, source, true)
    }

    fn compile(spec: WorldSpec, source: &str, text: &str) -> Result<World> {
        let check = ExtentCheck { source, text };
        check.time_step(spec.basic_time_step_ms.get())?;
        let polyline_segments = spec::paint_regions(&spec.paint);
        check.counts(
            spec.walls.len() + spec.segments.len(),
            polyline_segments + spec.checkpoints.len() * values::BARCODE_BITS,
            spec.checkpoints.len(),
        )?;
        let mut walls: Vec<WallBox> = Vec::new();
        let (mut sensed, mut sensed_colours) = (Vec::new(), Vec::new());
        let mut maze = None;
        let mut start = None;
        let mut goal = None;
        if let Some(g) = &spec.grid {
            let parsed = CellMaze::parse(g.map.get_ref()).map_err(|p| {
                // The drawing starts on the line after the opening quotes.
                let (map_line, _) = locate::line_column(text, g.map.span().start);
                let skip = usize::from(text[g.map.span().start..].starts_with("\"\"\"\n"));
                let line_offset: usize = text
                    .split_inclusive('\n')
                    .take(map_line - 1 + skip + p.row)
                    .map(str::len)
                    .sum();
                locate::format_error(
                    source,
                    text,
                    line_offset + p.column,
                    Some("grid.map"),
                    p.message,
                )
            })?;
            let origin = xy(&g.origin);
            let cs = g.cell_size.get();
            grid::check_cell_walls(cs, g.wall_thickness.get()).map_err(|(size, message)| {
                check.refused(Place::Table("grid"), &format!("grid.{size}"), message)
            })?;
            check.within(
                Place::Table("grid"),
                "grid",
                Bounds {
                    min: origin,
                    max: [
                        origin[0] + cs * parsed.cols as f64,
                        origin[1] + cs * parsed.rows as f64,
                    ],
                }
                .grown(g.wall_thickness.get()),
            )?;
            walls.extend(parsed.wall_boxes(origin, cs, g.wall_thickness.get()));
            if let Some((c, r)) = parsed.start {
                let p = parsed.cell_center(origin, cs, c, r);
                start = Some([p[0], p[1], 0.0]);
            }
            if let Some((c, r)) = parsed.goal {
                goal = Some(Goal {
                    center: parsed.cell_center(origin, cs, c, r),
                    radius: cs / 3.0,
                });
            }
            maze = Some(PlacedMaze {
                maze: parsed,
                origin,
                cell_size: cs,
            });
        }
        for (i, w) in spec.walls.iter().enumerate() {
            let field = format!("walls[{i}]");
            check.angle(Place::Array("walls", i), &field, w.yaw.get())?;
            let wall = WallBox {
                center: xy(&w.center),
                half: [w.size[0].get() / 2.0, w.size[1].get() / 2.0],
                yaw: w.yaw.get(),
                reflectance: w.reflectance.get(),
            };
            check.within(Place::Array("walls", i), &field, wall.bounds())?;
            if w.sensed_only {
                sensed.push(wall);
                sensed_colours.push(w.colour.as_ref().map(values::rgb));
            } else {
                walls.push(wall);
            }
        }
        for (i, s) in spec.segments.iter().enumerate() {
            let wall = WallBox::from_segment(
                xy(&s.from),
                xy(&s.to),
                s.thickness.get(),
                s.reflectance.get(),
            );
            check.within(
                Place::Array("segments", i),
                &format!("segments[{i}]"),
                wall.bounds(),
            )?;
            walls.push(wall);
        }
        check.counts(walls.len(), 0, 0)?;
        let mut regions = Vec::new();
        let mut paint_colours = Vec::new();
        for (i, p) in spec.paint.iter().enumerate() {
            let first = regions.len();
            if let PaintSpec::Rect { yaw, .. } = p {
                check.angle(
                    Place::Array("paint", i),
                    &format!("paint[{i}].yaw"),
                    yaw.get(),
                )?;
            }
            match p {
                PaintSpec::Rect {
                    center,
                    size,
                    yaw,
                    reflectance,
                    ..
                } => regions.push(PaintRegion {
                    shape: PaintShape::Rect {
                        center: xy(center),
                        half: [size[0].get() / 2.0, size[1].get() / 2.0],
                        yaw: yaw.get(),
                    },
                    reflectance: reflectance.get(),
                }),
                PaintSpec::Circle {
                    center,
                    radius,
                    reflectance,
                    ..
                } => regions.push(PaintRegion {
                    shape: PaintShape::Circle {
                        center: xy(center),
                        radius: radius.get(),
                    },
                    reflectance: reflectance.get(),
                }),
                PaintSpec::Polyline {
                    points,
                    width,
                    closed,
                    reflectance,
                    ..
                } => {
                    if points.len() < 2 {
                        return Err(locate::format_error(
                            source,
                            text,
                            table_offset(text, "paint", i),
                            Some(&format!("paint[{i}].points")),
                            format!(
                                "expected at least 2 points in a polyline, found {}",
                                points.len()
                            ),
                        ));
                    }
                    let pts: Vec<[f64; 2]> = points.iter().map(xy).collect();
                    let mut pairs: Vec<([f64; 2], [f64; 2])> =
                        pts.windows(2).map(|w| (w[0], w[1])).collect();
                    if *closed {
                        pairs.push((pts[pts.len() - 1], pts[0]));
                    }
                    for (a, b) in pairs {
                        regions.push(PaintRegion {
                            shape: PaintShape::Capsule {
                                a,
                                b,
                                radius: width.get() / 2.0,
                            },
                            reflectance: reflectance.get(),
                        });
                    }
                }
            }
            paint_colours.resize(regions.len(), p.colour().map(|c| values::rgb(&c)));
            let painted = regions[first..]
                .iter()
                .fold(Bounds::EMPTY, |b, r| b.union(r.shape.bounds()));
            check.within(Place::Array("paint", i), &format!("paint[{i}]"), painted)?;
        }
        let barcode = spec.barcode.clone().unwrap_or_default();
        check.within(
            Place::Table("barcode"),
            "barcode.bar_length",
            Bounds {
                min: [0.0, 0.0],
                max: [barcode.bar_length.get() * values::BARCODE_BITS as f64, 0.0],
            },
        )?;
        let mut checkpoints: Vec<Checkpoint> = Vec::new();
        for (i, c) in spec.checkpoints.iter().enumerate() {
            let refused_id = match c.id {
                0 => Some("expected a positive checkpoint id, found 0".to_string()),
                id if checkpoints.iter().any(|k| k.id == id) => Some(format!(
                    "expected a unique checkpoint id, found {id} a second time"
                )),
                _ => None,
            };
            if let Some(message) = refused_id {
                let at = table_offset(text, "checkpoints", i);
                let field = format!("checkpoints[{i}].id");
                return Err(locate::format_error(
                    source,
                    text,
                    at,
                    Some(&field),
                    message,
                ));
            }
            let field = format!("checkpoints[{i}]");
            check.angle(Place::Array("checkpoints", i), &field, c.yaw.get())?;
            check.point(Place::Array("checkpoints", i), &field, xy(&c.center))?;
            let reach = c
                .width
                .get()
                .max(barcode.bar_length.get() * values::BARCODE_BITS as f64);
            check.within(
                Place::Array("checkpoints", i),
                &field,
                Bounds {
                    min: xy(&c.center),
                    max: xy(&c.center),
                }
                .grown(reach),
            )?;
            let cp = checkpoint_from(c, &barcode);
            regions.extend(barcode_bars(&cp, &barcode));
            checkpoints.push(cp);
        }
        if let Some(s) = &spec.start {
            check.point(Place::Table("start"), "start", [s.x.get(), s.y.get()])?;
            check.angle(Place::Table("start"), "start.yaw", s.yaw.get())?;
            start = Some([s.x.get(), s.y.get(), s.yaw.get()]);
        }
        if let Some(g) = &spec.goal {
            let (center, radius) = (xy(&g.center), g.radius.get());
            let disc = Bounds {
                min: center,
                max: center,
            };
            check.within(Place::Table("goal"), "goal", disc.grown(radius))?;
            goal = Some(Goal { center, radius });
        }
        let start = start.unwrap_or([0.0, 0.0, 0.0]);
        let robots = robots::compile(&spec.robots, start, spec.start.is_some(), &check)?;
        let start = robots[0].start;
        let bodies = bodies::compile(&spec.bodies, &check)?;
        let mut bounds = walls.iter().fold(Bounds::EMPTY, |b, w| b.union(w.bounds()));
        bounds = regions
            .iter()
            .fold(bounds, |b, r| b.union(r.shape.bounds()));
        bounds = robots.iter().fold(bounds, |b, r| {
            b.union(Bounds {
                min: [r.start[0], r.start[1]],
                max: [r.start[0], r.start[1]],
            })
        });
        if let Some(g) = goal {
            bounds = bounds.union(Bounds {
                min: [g.center[0] - g.radius, g.center[1] - g.radius],
                max: [g.center[0] + g.radius, g.center[1] + g.radius],
            });
        }
        bounds = bodies.iter().fold(bounds, |b, m| b.union(m.bounds()));
        let sensed = SensedWalls::new(sensed, sensed_colours);
        bounds = sensed.as_ref().map_or(bounds, |s| bounds.union(s.bounds()));
        let background = spec.floor.as_ref().map_or(1.0, |f| f.reflectance.get());
        regions.shrink_to_fit();
        checkpoints.shrink_to_fit();
        let mut solid_walls = distinct(&walls);
        solid_walls.shrink_to_fit();
        let walls = (walls.len() != solid_walls.len()).then(|| walls.into_boxed_slice());
        let wall_index = WallIndex::new(&solid_walls);
        check.crowding(wall_index.crowded_pairs(), solid_walls.len())?;
        let fingerprint = fingerprint_of(&spec)?;
        Ok(World {
            fingerprint,
            solid_walls,
            wall_index,
            sensed,
            floor: FloorPaint::new(background, regions),
            spec,
            source: source.to_string(),
            walls,
            checkpoints,
            goal,
            start,
            robots,
            bounds,
            maze,
            bodies,
            paint_colours,
        })
    }

    /// The description as written in a world file.
    pub fn to_toml(&self) -> Result<String> {
        toml::to_string_pretty(&self.spec)
            .map_err(|e| Error::InvalidArgument(format!("cannot write the world: {e}")))
    }

    /// A hash of the description (`crate::fingerprint`): worlds that are equal have the same
    /// fingerprint, and worlds with the same fingerprint are equal but for a one-in-2^64 chance.
    pub fn fingerprint(&self) -> u64 {
        self.fingerprint
    }

    /// Bytes the world holds: its own size and its buffers on the heap, the description's
    /// included (`crate::footprint`; the description's small buffers are counted by their length).
    pub fn heap_bytes(&self) -> usize {
        use crate::footprint::{string_bytes, vec_bytes};
        use std::mem::size_of_val;
        let spec = &self.spec;
        let described = string_bytes(&spec.name)
            + spec
                .grid
                .as_ref()
                .map_or(0, |g| string_bytes(g.map.get_ref()))
            + vec_bytes(&spec.walls)
            + vec_bytes(&spec.segments)
            + vec_bytes(&spec.paint)
            + vec_bytes(&spec.checkpoints)
            + vec_bytes(&spec.bodies)
            + vec_bytes(&spec.robots)
            + spec
                .checkpoints
                .iter()
                .map(|c| string_bytes(&c.code.0))
                .sum::<usize>();
        let maze = self.maze.as_ref().map_or(0, |m| {
            vec_bytes(&m.maze.horizontal) + vec_bytes(&m.maze.vertical)
        });
        size_of_val(self)
            + described
            + string_bytes(&self.source)
            + self.walls.as_ref().map_or(0, |w| size_of_val(&**w))
            + vec_bytes(&self.solid_walls)
            + self.wall_index.heap_bytes()
            + self.sensed.as_ref().map_or(0, |s| s.heap_bytes())
            + self.floor.heap_bytes()
            + vec_bytes(&self.checkpoints)
            + self
                .checkpoints
                .iter()
                .map(|c| vec_bytes(&c.code))
                .sum::<usize>()
            + maze
            + vec_bytes(&self.bodies)
            + vec_bytes(&self.robots)
    }

    /// Writes the world file atomically (a temporary file in the same folder, then a rename).
    /// A name not ending in `.toml` is refused (see [`crate::file_kind::check_world_file_name`]).
    pub fn save(&self, path: &Path) -> Result<()> {
        crate::file_kind::check_world_file_name(path)?;
        crate::io::write_atomic(path, self.to_toml()?.as_bytes())
    }

    /// The description.
    pub fn spec(&self) -> &WorldSpec {
        &self.spec
    }

    /// Where it was read from.
    pub fn source(&self) -> &str {
        &self.source
    }

    /// The world's name.
    pub fn name(&self) -> &str {
        &self.spec.name
    }

    /// Physics step in seconds.
    pub fn basic_time_step(&self) -> f64 {
        self.spec.basic_time_step_ms.get() / 1000.0
    }

    /// Every wall as a box (the sensed-only ones are [`World::sensed_walls`]).
    pub fn walls(&self) -> &[WallBox] {
        self.walls.as_deref().unwrap_or(&self.solid_walls)
    }

    /// The colour of each wall of [`World::walls`] as a camera sees it, in the same order:
    /// that of its `[[walls]]` entry when it gives one, `None` otherwise (the grid's walls and
    /// the segments have none: a camera draws them in the grey of their reflectance).
    pub fn wall_colours(&self) -> Vec<Option<[f64; 3]>> {
        let solid = self.spec.walls.iter().filter(|w| !w.sensed_only);
        let listed = solid.clone().count() + self.spec.segments.len();
        let grid = self.walls().len().saturating_sub(listed);
        let mut colours = vec![None; grid];
        colours.extend(solid.map(|w| w.colour.as_ref().map(values::rgb)));
        colours.resize(self.walls().len(), None);
        colours
    }

    /// How high the top of each wall of [`World::walls`] stands above the floor (m), in the
    /// same order: that of its `[[walls]]` entry when it gives one, infinite otherwise (the
    /// grid's walls and the segments stand higher than any sensor's ray goes).
    pub fn wall_tops(&self) -> Vec<f64> {
        let solid = self.spec.walls.iter().filter(|w| !w.sensed_only);
        let listed = solid.clone().count() + self.spec.segments.len();
        let grid = self.walls().len().saturating_sub(listed);
        let mut tops = vec![f64::INFINITY; grid];
        tops.extend(solid.map(|w| w.height.map_or(f64::INFINITY, |h| h.get())));
        tops.resize(self.walls().len(), f64::INFINITY);
        tops
    }

    /// How high the top of each sensed-only wall stands above the floor (m), in the order of
    /// the sensed-only walls; infinite where its entry gives none.
    pub fn sensed_wall_tops(&self) -> Vec<f64> {
        let sensed = self.spec.walls.iter().filter(|w| w.sensed_only);
        sensed
            .map(|w| w.height.map_or(f64::INFINITY, |h| h.get()))
            .collect()
    }

    /// The colour of paint region `index` of [`World::floor`] as a camera sees it (`None`: the
    /// grey of its reflectance).
    pub fn paint_colour(&self, index: usize) -> Option<[f64; 3]> {
        self.paint_colours.get(index).copied().flatten()
    }

    /// The colour of the bare floor as a camera sees it (`None`: the grey of its reflectance).
    pub fn floor_colour(&self) -> Option<[f64; 3]> {
        self.spec
            .floor
            .as_ref()
            .and_then(|f| f.colour.as_ref().map(values::rgb))
    }

    /// The walls only infra-red rays and cameras meet (`sensed_only = true`; see `sensed.rs`),
    /// when the world has some.
    pub fn sensed_walls(&self) -> Option<&SensedWalls> {
        self.sensed.as_deref()
    }

    /// The walls as solids: `walls` with exact duplicates merged, in file order.
    pub fn solid_walls(&self) -> &[WallBox] {
        &self.solid_walls
    }

    /// The solid walls indexed for ray casts.
    pub fn wall_index(&self) -> &WallIndex {
        &self.wall_index
    }

    /// Floor paint, barcodes included.
    pub fn floor(&self) -> &FloorPaint {
        &self.floor
    }

    /// Checkpoints in file order.
    pub fn checkpoints(&self) -> &[Checkpoint] {
        &self.checkpoints
    }

    /// The goal disc, if any.
    pub fn goal(&self) -> Option<Goal> {
        self.goal
    }

    /// Start pose (x, y, yaw): that of the first robot.
    pub fn start(&self) -> [f64; 3] {
        self.start
    }

    /// The robots the world places, at least one (see `robots`).
    pub fn robots(&self) -> &[RobotPlacement] {
        &self.robots
    }

    /// Bounds of walls, paint, start and goal.
    pub fn bounds(&self) -> Bounds {
        self.bounds
    }

    /// Movable bodies at their start poses, in file order.
    pub fn bodies(&self) -> &[MovableBody] {
        &self.bodies
    }

    /// The cell maze, when the world has a `[grid]`.
    pub fn maze(&self) -> Option<&PlacedMaze> {
        self.maze.as_ref()
    }
}

/// The fingerprint of a description (`World::fingerprint`): the hash of its TOML text.
fn fingerprint_of(spec: &WorldSpec) -> Result<u64> {
    toml::to_string(spec)
        .map(|text| crate::fingerprint::fnv1a(text.as_bytes()))
        .map_err(|e| Error::InvalidArgument(format!("cannot write the world: {e}")))
}

/// `walls` without exact duplicates, first occurrences in order.
fn distinct(walls: &[WallBox]) -> Vec<WallBox> {
    let key = |w: &WallBox| {
        [
            w.center[0],
            w.center[1],
            w.half[0],
            w.half[1],
            w.yaw,
            w.reflectance,
        ]
        .map(f64::to_bits)
    };
    let mut seen = std::collections::HashSet::with_capacity(walls.len());
    walls
        .iter()
        .filter(|w| seen.insert(key(w)))
        .copied()
        .collect()
}

fn checkpoint_from(c: &spec::CheckpointSpec, barcode: &BarcodeSpec) -> Checkpoint {
    let code = c.code.bits();
    Checkpoint {
        id: c.id,
        length: code.len() as f64 * barcode.bar_length.get(),
        code,
        center: xy(&c.center),
        yaw: c.yaw.get(),
        axis: [c.yaw.get().cos(), c.yaw.get().sin()],
        width: c.width.get(),
    }
}

/// The painted bars of a checkpoint, first bit first along its yaw.
fn barcode_bars(cp: &Checkpoint, barcode: &BarcodeSpec) -> Vec<PaintRegion> {
    let n = cp.code.len() as f64;
    let bar = barcode.bar_length.get();
    let (s, c) = cp.yaw.sin_cos();
    cp.code
        .iter()
        .enumerate()
        .map(|(i, &bit)| {
            let along = (i as f64 - (n - 1.0) / 2.0) * bar;
            PaintRegion {
                shape: PaintShape::Rect {
                    center: [cp.center[0] + c * along, cp.center[1] + s * along],
                    half: [bar / 2.0, cp.width / 2.0],
                    yaw: cp.yaw,
                },
                reflectance: if bit {
                    barcode.white.get()
                } else {
                    barcode.black.get()
                },
            }
        })
        .collect()
}

#[cfg(test)]
mod tests;
