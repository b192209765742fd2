//! A seeded maze generator: W x H cells, perfect (one path between any two cells) or with extra
//! loops, with a barcode checkpoint on every way into every junction (as long as the code book
//! lasts) and a goal in the cell farthest from the start. Cheap enough to draw thousands of
//! distinct mazes for training.
//!
//! A carved maze can be one single corridor from the start to the goal, with no junction and so
//! nowhere for a checkpoint (of the first draws, about 55 % of 3 x 3 mazes, 12 % of 4 x 4 and 3 %
//! of 5 x 5): with [`MazeParams::junction`] such a draw is replaced by the next one, so every maze
//! larger than 2 x 2 (which never has a junction) has checkpoints.

use std::collections::VecDeque;

use crate::codebook;
use crate::error::{Error, Result};
use crate::rng::Rng;
use crate::world::spec::{BarcodeSpec, CheckpointSpec, FloorSpec, GridSpec, WorldSpec};
use crate::world::values::{BarcodeBits, Finite, FormatTag, FormatVersion, Positive, Reflectance};
use crate::world::{CellMaze, World};

/// What to generate.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MazeParams {
    /// Cells west to east.
    pub width: usize,
    /// Cells north to south.
    pub height: usize,
    /// Side of a cell in metres.
    pub cell_size: f64,
    /// Wall thickness in metres.
    pub wall_thickness: f64,
    /// Share in [0, 1] of the remaining inner walls removed after carving (0 = a perfect maze).
    pub loops: f64,
    /// Place barcode checkpoints on the ways into junctions.
    pub checkpoints: bool,
    /// Draw again while the maze is a single corridor without a junction (see the module); false
    /// keeps the first draw, as the pools of mazes drawn before this option existed.
    pub junction: bool,
    /// Floor reflectance (grey, so codes show their ends).
    pub floor_reflectance: f64,
}

impl Default for MazeParams {
    fn default() -> Self {
        Self {
            width: 5,
            height: 5,
            cell_size: 0.25,
            wall_thickness: 0.01,
            loops: 0.0,
            checkpoints: true,
            junction: true,
            floor_reflectance: 0.36,
        }
    }
}

const DX: [isize; 4] = [1, 0, -1, 0];
const DY: [isize; 4] = [0, -1, 0, 1];

fn set_wall(m: &mut CellMaze, c: usize, r: usize, dir: usize, wall: bool) {
    match dir {
        0 => m.vertical[r * (m.cols + 1) + c + 1] = wall,
        1 => m.horizontal[r * m.cols + c] = wall,
        2 => m.vertical[r * (m.cols + 1) + c] = wall,
        _ => m.horizontal[(r + 1) * m.cols + c] = wall,
    }
}

fn neighbour(m: &CellMaze, c: usize, r: usize, dir: usize) -> Option<(usize, usize)> {
    let nc = c as isize + DX[dir];
    let nr = r as isize + DY[dir];
    (nc >= 0 && nr >= 0 && (nc as usize) < m.cols && (nr as usize) < m.rows)
        .then_some((nc as usize, nr as usize))
}

/// Carves the cells (a depth-first backtracker driven by `rng`), then opens loops.
pub fn carve(params: &MazeParams, rng: &mut Rng) -> CellMaze {
    let (w, h) = (params.width, params.height);
    let mut m = CellMaze {
        rows: h,
        cols: w,
        horizontal: vec![true; (h + 1) * w],
        vertical: vec![true; h * (w + 1)],
        start: Some((0, h - 1)),
        goal: None,
    };
    let mut seen = vec![false; w * h];
    let mut stack = vec![(0usize, h - 1)];
    seen[(h - 1) * w] = true;
    while let Some(&(c, r)) = stack.last() {
        let options: Vec<usize> = (0..4)
            .filter(|&d| neighbour(&m, c, r, d).is_some_and(|(nc, nr)| !seen[nr * w + nc]))
            .collect();
        if options.is_empty() {
            stack.pop();
            continue;
        }
        let d = options[(rng.next_u64() % options.len() as u64) as usize];
        let (nc, nr) = neighbour(&m, c, r, d).expect("option has a neighbour");
        set_wall(&mut m, c, r, d, false);
        seen[nr * w + nc] = true;
        stack.push((nc, nr));
    }
    if params.loops > 0.0 {
        for r in 0..h {
            for c in 0..w {
                for d in [0usize, 3] {
                    if neighbour(&m, c, r, d).is_some()
                        && !m.open(c, r, d)
                        && rng.uniform() < params.loops
                    {
                        set_wall(&mut m, c, r, d, false);
                    }
                }
            }
        }
    }
    m
}

/// Steps from `from` to every cell (None where unreachable).
pub fn distances(m: &CellMaze, from: (usize, usize)) -> Vec<Option<usize>> {
    let mut dist = vec![None; m.rows * m.cols];
    let mut queue = VecDeque::from([from]);
    dist[from.1 * m.cols + from.0] = Some(0);
    while let Some((c, r)) = queue.pop_front() {
        let here = dist[r * m.cols + c].expect("queued cells have a distance");
        for d in 0..4 {
            if m.open(c, r, d) {
                let (nc, nr) = neighbour(m, c, r, d).expect("open sides have a neighbour");
                if dist[nr * m.cols + nc].is_none() {
                    dist[nr * m.cols + nc] = Some(here + 1);
                    queue.push_back((nc, nr));
                }
            }
        }
    }
    dist
}

fn openings(m: &CellMaze, c: usize, r: usize) -> usize {
    (0..4).filter(|&d| m.open(c, r, d)).count()
}

/// Whether some cell of the maze is a junction (three or four openings).
fn has_junction(m: &CellMaze) -> bool {
    (0..m.rows).any(|r| (0..m.cols).any(|c| openings(m, c, r) >= 3))
}

/// The most draws [`generate`] makes for a maze with a junction (a 3 x 3 maze, the likeliest to
/// be a single corridor, is one about 55 % of the time: 1000 draws all failing is beyond chance).
const MAX_DRAWS: usize = 1000;

impl MazeParams {
    /// Checks the sizes, the share of loops and the floor reflectance: 2 to 200 cells a side,
    /// 0 < wall thickness < cell size, loops in [0, 1], reflectance in (0, 1].
    pub fn check(&self) -> Result<()> {
        let params = self;
        if params.width < 2 || params.height < 2 || params.width > 200 || params.height > 200 {
            return Err(Error::InvalidArgument(format!(
                "expected a maze of 2 to 200 cells a side, found {} x {}",
                params.width, params.height
            )));
        }
        crate::world::grid::check_cell_walls(params.cell_size, params.wall_thickness)
            .map_err(|(_, message)| Error::InvalidArgument(message))?;
        let side = params.width.max(params.height) as f64 * params.cell_size;
        if side > crate::limits::MAX_COORDINATE {
            return Err(Error::InvalidArgument(format!(
                "expected a maze at most {} m a side (the bound of every coordinate), found {} \
                 cells of {:?} m: {side:?} m; use fewer or smaller cells",
                crate::limits::MAX_COORDINATE,
                params.width.max(params.height),
                params.cell_size
            )));
        }
        if !(0.0..=1.0).contains(&params.loops) {
            return Err(Error::InvalidArgument(format!(
                "expected loops in [0, 1], found {}",
                params.loops
            )));
        }
        if !(params.floor_reflectance > 0.0 && params.floor_reflectance <= 1.0) {
            return Err(Error::InvalidArgument(format!(
                "expected floor_reflectance in (0, 1], found {}",
                params.floor_reflectance
            )));
        }
        Ok(())
    }
}

/// A generated maze world.
pub fn generate(params: &MazeParams, seed: u64) -> Result<World> {
    params.check()?;
    let mut rng = Rng::new(seed);
    let mut m = carve(params, &mut rng);
    // A 2 x 2 maze is a ring of four cells at most: no cell can have three openings.
    let junction_possible = params.width.max(params.height) > 2;
    if params.junction && junction_possible {
        for _ in 1..MAX_DRAWS {
            if has_junction(&m) {
                break;
            }
            m = carve(params, &mut rng);
        }
    }
    let start = m.start.expect("carve sets the start");
    let dist = distances(&m, start);
    let goal_index = (0..dist.len())
        .max_by_key(|&i| (dist[i].unwrap_or(0), usize::MAX - i))
        .expect("a maze has cells");
    m.goal = Some((goal_index % m.cols, goal_index / m.cols));
    let cs = params.cell_size;
    let checkpoints = if params.checkpoints {
        place_checkpoints(&m, cs, [0.0, 0.0])
    } else {
        Vec::new()
    };
    // The robot starts facing its first opening.
    let start_dir = (0..4).find(|&d| m.open(start.0, start.1, d)).unwrap_or(0);
    let spec = WorldSpec {
        format: FormatTag(crate::world::values::WORLD_FORMAT_TAG.into()),
        version: FormatVersion(crate::world::values::WORLD_FORMAT_VERSION),
        name: format!("maze-{}x{}-seed{seed}", params.width, params.height),
        basic_time_step_ms: Positive(32.0),
        floor: Some(FloorSpec {
            reflectance: Reflectance(params.floor_reflectance),
            colour: None,
        }),
        start: Some(crate::world::spec::StartSpec {
            x: Finite((start.0 as f64 + 0.5) * cs),
            y: Finite((m.rows as f64 - start.1 as f64 - 0.5) * cs),
            yaw: Finite(start_dir as f64 * std::f64::consts::FRAC_PI_2),
        }),
        robots: Vec::new(),
        goal: None,
        grid: Some(GridSpec {
            cell_size: Positive(cs),
            wall_thickness: Positive(params.wall_thickness),
            origin: [Finite(0.0), Finite(0.0)],
            map: toml::Spanned::new(0..0, m.draw()),
        }),
        barcode: (!checkpoints.is_empty()).then(BarcodeSpec::default),
        walls: Vec::new(),
        segments: Vec::new(),
        paint: Vec::new(),
        bodies: Vec::new(),
        checkpoints,
    };
    World::from_spec(
        spec,
        &format!("generated:{}x{}:seed{seed}", params.width, params.height),
    )
}

/// Where a checkpoint's code lies relative to the approach cell it belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Spot {
    /// In the middle of a straight corridor cell or a dead end: the code is crossed along the
    /// corridor, and reading it backwards is the arrival at the door behind (if any).
    Middle,
    /// Across the edge between the approach cell and the door, half in each: the approach cell
    /// is a corner or itself a door, so its middle is no corridor the robot drives straight
    /// along. On the edge the robot has finished the corner and its side sensors already see the
    /// door's sides (not the corner's opening) when the code ends.
    Edge,
}

/// A checkpoint to be placed: the approach cell, the direction to the door it faces, where in
/// the cell, and whether the door (or the door behind a middle code) is on the way to the goal.
#[derive(Debug, Clone, Copy)]
struct Candidate {
    cell: (usize, usize),
    dir: usize,
    spot: Spot,
    on_way: bool,
}

/// One checkpoint for every approach to every door (a junction: a cell with 3 or 4 openings).
///
/// - Through a straight corridor cell or a dead end: a code in the middle of that cell, facing
///   the door. A straight cell between two doors gets one code, which serves both: read forwards
///   it is the arrival at one door, backwards the arrival at the other.
/// - Through a corner cell or from a neighbouring door: a code across the edge between the two
///   cells, facing the door (between two doors: one code for both ways).
///
/// The default book has 12 codes: enough for every approach of nearly all perfect 5 x 5 mazes
/// (they need 6 on average; of 300 drawn for tests, 3 run short by a code or two), not for
/// most mazes with loops, which have more doors. When a maze needs more codes than the book has, the approaches
/// of the doors on the shortest way from the start to the goal come first, then the others in
/// scan order; the rest get none. Ids and codes follow the scan order (row by row, then east,
/// north, west, south of each door).
fn place_checkpoints(m: &CellMaze, cs: f64, origin: [f64; 2]) -> Vec<CheckpointSpec> {
    let book = codebook::default_codes();
    let door = |c: usize, r: usize| openings(m, c, r) >= 3;
    let on_way = way_cells(m);
    let mut candidates: Vec<Candidate> = Vec::new();
    for r in 0..m.rows {
        for c in 0..m.cols {
            if !door(c, r) {
                continue;
            }
            for d in 0..4 {
                if !m.open(c, r, d) {
                    continue;
                }
                let (nc, nr) = neighbour(m, c, r, d).expect("open side has a neighbour");
                let back = (d + 2) % 4;
                // A straight corridor or a dead end: open towards the door and perhaps straight
                // on the far side, nowhere else.
                let middle = (0..4).all(|k| k == back || k == d || !m.open(nc, nr, k));
                let spot = if middle { Spot::Middle } else { Spot::Edge };
                let here = on_way[r * m.cols + c];
                let shared = candidates
                    .iter()
                    .position(|other| match (spot, other.spot) {
                        // The same straight cell, seen from the door at its other end.
                        (Spot::Middle, Spot::Middle) => other.cell == (nc, nr),
                        // The same edge between two doors, seen from the other door.
                        (Spot::Edge, Spot::Edge) => {
                            other.cell == (c, r) && neighbour(m, c, r, other.dir) == Some((nc, nr))
                        }
                        _ => false,
                    });
                if let Some(index) = shared {
                    candidates[index].on_way |= here;
                    continue;
                }
                candidates.push(Candidate {
                    cell: (nc, nr),
                    dir: back,
                    spot,
                    on_way: here,
                });
            }
        }
    }
    if candidates.len() > book.len() {
        let mut order: Vec<usize> = (0..candidates.len()).collect();
        order.sort_by_key(|&i| !candidates[i].on_way);
        order.truncate(book.len());
        order.sort_unstable();
        candidates = order.into_iter().map(|i| candidates[i]).collect();
    }
    candidates
        .iter()
        .zip(book)
        .enumerate()
        .map(|(index, (cand, code))| {
            let (nc, nr) = cand.cell;
            let yaw = cand.dir as f64 * std::f64::consts::FRAC_PI_2;
            let shift = match cand.spot {
                Spot::Middle => 0.0,
                Spot::Edge => cs / 2.0,
            };
            let center = [
                origin[0] + (nc as f64 + 0.5) * cs + shift * DX[cand.dir] as f64,
                origin[1] + (m.rows as f64 - nr as f64 - 0.5) * cs - shift * DY[cand.dir] as f64,
            ];
            CheckpointSpec {
                id: index as u32 + 1,
                code: BarcodeBits(code),
                center: [Finite(center[0]), Finite(center[1])],
                yaw: Finite(yaw),
                width: Positive(cs - 0.02),
            }
        })
        .collect()
}

/// The checkpoints [`generate`] would place on a world's `[grid]` maze: one on every way into
/// every junction, as on a generated maze (for a maze drawn by hand without `[[checkpoints]]`).
/// The start and goal cells are the `S` and `G` of the map, else those of the world's start pose
/// and goal. Empty when the world has no grid or its maze no junction.
pub fn junction_checkpoints(world: &World) -> Vec<CheckpointSpec> {
    let Some(placed) = world.maze() else {
        return Vec::new();
    };
    let (origin, cs) = (placed.origin, placed.cell_size);
    let mut m = placed.maze.clone();
    let (rows, cols) = (m.rows as f64, m.cols as f64);
    let cell_at = |p: [f64; 2]| {
        let c = ((p[0] - origin[0]) / cs).floor();
        let r = rows - 1.0 - ((p[1] - origin[1]) / cs).floor();
        let inside = c >= 0.0 && r >= 0.0 && c < cols && r < rows;
        inside.then_some((c as usize, r as usize))
    };
    let start = world.start();
    let start_cell = m.start.or_else(|| cell_at([start[0], start[1]]));
    let goal_cell = m
        .goal
        .or_else(|| world.goal().and_then(|g| cell_at(g.center)));
    (m.start, m.goal) = (start_cell, goal_cell);
    place_checkpoints(&m, cs, origin)
}

/// [`junction_checkpoints`] as the `[[checkpoints]]` tables of a world file, ready to paste (empty
/// when there are none), after the grey `[floor]` of generated mazes when the world has no
/// `[floor]` (on the default white floor a code's white bits would not show where it ends).
pub fn junction_checkpoints_toml(world: &World) -> Result<String> {
    #[derive(serde::Serialize)]
    struct Tables {
        #[serde(skip_serializing_if = "Option::is_none")]
        floor: Option<FloorSpec>,
        checkpoints: Vec<CheckpointSpec>,
    }
    let checkpoints = junction_checkpoints(world);
    if checkpoints.is_empty() {
        return Ok(String::new());
    }
    let floor = world.spec().floor.is_none().then(|| FloorSpec {
        reflectance: Reflectance(MazeParams::default().floor_reflectance),
        colour: None,
    });
    toml::to_string(&Tables { floor, checkpoints })
        .map_err(|e| Error::InvalidArgument(format!("cannot write the checkpoints: {e}")))
}

/// The cells on a shortest way from the start to the goal (true where on it).
fn way_cells(m: &CellMaze) -> Vec<bool> {
    let (Some(start), Some(goal)) = (m.start, m.goal) else {
        return vec![false; m.rows * m.cols];
    };
    let from_start = distances(m, start);
    let from_goal = distances(m, goal);
    let total = from_start[goal.1 * m.cols + goal.0];
    (0..m.rows * m.cols)
        .map(|i| match (from_start[i], from_goal[i], total) {
            (Some(a), Some(b), Some(t)) => a + b == t,
            _ => false,
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn issue_35_a_maze_larger_than_the_coordinates_is_refused_by_its_parameters() {
        let huge_cell = MazeParams {
            cell_size: 1e300,
            ..Default::default()
        };
        assert!(huge_cell.check().is_err());
        let too_wide = MazeParams {
            width: 200,
            height: 200,
            cell_size: 10.0,
            ..Default::default()
        };
        let refused = too_wide.check().unwrap_err().to_string();
        assert!(refused.contains("2000.0 m"), "{refused}");
        let widest = MazeParams {
            width: 200,
            height: 200,
            cell_size: 5.0,
            ..Default::default()
        };
        assert!(widest.check().is_ok());
    }

    /// The default maze of `seed` with a share `loops` of extra openings.
    fn with_loops(loops: f64, seed: u64) -> World {
        generate(
            &MazeParams {
                loops,
                ..Default::default()
            },
            seed,
        )
        .unwrap()
    }

    #[test]
    fn same_seed_same_maze_other_seed_differs() {
        let p = MazeParams::default();
        let a = generate(&p, 3).unwrap();
        assert_eq!(a, generate(&p, 3).unwrap());
        assert_ne!(
            a.to_toml().unwrap(),
            generate(&p, 4).unwrap().to_toml().unwrap()
        );
    }

    #[test]
    fn every_cell_is_reachable_and_perfect_mazes_are_trees() {
        for seed in 0..50 {
            for loops in [0.0, 0.3] {
                let p = MazeParams {
                    width: 7,
                    height: 4,
                    loops,
                    ..Default::default()
                };
                let mut rng = Rng::new(seed);
                let m = carve(&p, &mut rng);
                assert!(distances(&m, (0, 3)).iter().all(Option::is_some));
                let edges: usize = (0..m.rows)
                    .flat_map(|r| (0..m.cols).map(move |c| (c, r)))
                    .map(|(c, r)| usize::from(m.open(c, r, 0)) + usize::from(m.open(c, r, 3)))
                    .sum();
                if loops == 0.0 {
                    assert_eq!(edges, m.rows * m.cols - 1);
                }
            }
        }
    }

    /// The approach cell of a checkpoint (the cell just behind its middle, against its yaw) and
    /// the direction from there to the door it faces.
    fn approach(m: &CellMaze, cp: &crate::world::Checkpoint, cs: f64) -> ((usize, usize), usize) {
        let x = cp.center[0] - 0.05 * cp.axis[0];
        let y = cp.center[1] - 0.05 * cp.axis[1];
        let c = (x / cs).floor() as usize;
        let r = m.rows - 1 - (y / cs).floor() as usize;
        let dir = ((cp.yaw / std::f64::consts::FRAC_PI_2).round() as usize) % 4;
        ((c, r), dir)
    }

    /// The (cell, door) approaches a maze's checkpoints mark: the one each faces, and for a code
    /// in the middle of a straight cell also the door behind it (read backwards).
    fn marked(w: &World) -> Vec<((usize, usize), (usize, usize))> {
        let m = &w.maze().unwrap().maze;
        let mut out = Vec::new();
        for cp in w.checkpoints() {
            let ((c, r), dir) = approach(m, cp, 0.25);
            out.push(((c, r), neighbour(m, c, r, dir).unwrap()));
            let middle = [(c as f64 + 0.5) * 0.25, (m.rows - r) as f64 * 0.25 - 0.125];
            let in_middle =
                (cp.center[0] - middle[0]).abs() < 1e-9 && (cp.center[1] - middle[1]).abs() < 1e-9;
            let back = (dir + 2) % 4;
            if in_middle && m.open(c, r, back) {
                let (bc, br) = neighbour(m, c, r, back).unwrap();
                if openings(m, bc, br) >= 3 {
                    out.push(((c, r), (bc, br)));
                }
            }
        }
        out
    }

    /// Every (cell, door) approach of a maze.
    fn approaches(m: &CellMaze) -> Vec<((usize, usize), (usize, usize))> {
        let mut out = Vec::new();
        for r in 0..m.rows {
            for c in 0..m.cols {
                if openings(m, c, r) < 3 {
                    continue;
                }
                for d in (0..4).filter(|&d| m.open(c, r, d)) {
                    out.push((neighbour(m, c, r, d).unwrap(), (c, r)));
                }
            }
        }
        out
    }

    /// Every approach of `w`'s junctions is marked (or lies between two doors, where the other
    /// door's code serves it), unless the book ran short.
    fn assert_every_approach_marked(w: &World, label: &str) {
        let m = &w.maze().unwrap().maze;
        if w.checkpoints().len() >= codebook::default_codes().len() {
            return;
        }
        let marked = marked(w);
        for a in approaches(m) {
            let between_doors = openings(m, a.0 .0, a.0 .1) >= 3 && marked.contains(&(a.1, a.0));
            assert!(
                marked.contains(&a) || between_doors,
                "{label}: approach {a:?} unmarked"
            );
        }
    }

    #[test]
    fn a_generated_map_without_its_checkpoints_gets_them_back_wherever_it_lies() {
        let p = MazeParams {
            width: 4,
            height: 4,
            ..Default::default()
        };
        let generated = generate(&p, 3).unwrap();
        let mut spec = generated.spec().clone();
        spec.checkpoints.clear();
        let bare = World::from_spec(spec.clone(), "bare").unwrap();
        assert!(bare.checkpoints().is_empty());
        assert_eq!(junction_checkpoints(&bare), generated.spec().checkpoints);
        // The same map elsewhere, its start given by [start] alone (no S): the same codes, moved.
        let shift = [1.5, -2.0];
        let grid = spec.grid.as_mut().unwrap();
        grid.origin = [Finite(shift[0]), Finite(shift[1])];
        grid.map = toml::Spanned::new(0..0, grid.map.get_ref().replace('S', " "));
        let start = spec.start.as_mut().unwrap();
        (start.x, start.y) = (Finite(start.x.0 + shift[0]), Finite(start.y.0 + shift[1]));
        let moved = junction_checkpoints(&World::from_spec(spec, "moved").unwrap());
        assert_eq!(moved.len(), generated.checkpoints().len());
        for (m, g) in moved.iter().zip(&generated.spec().checkpoints) {
            assert_eq!((m.id, &m.code, m.yaw.0), (g.id, &g.code, g.yaw.0));
            for (k, by) in shift.iter().enumerate() {
                assert!((m.center[k].0 - g.center[k].0 - by).abs() < 1e-12);
            }
        }
        // A maze without a junction has nowhere for one.
        let ring = World::from_toml(
            "format = \"mazesim-world\"\nversion = 1\n[grid]\nmap = \"\"\"\n+--+--+\n|S    |\n+  +  +\n|   G |\n+--+--+\n\"\"\"\n",
            "ring",
        )
        .unwrap();
        assert!(junction_checkpoints(&ring).is_empty());
    }

    #[test]
    fn the_4_by_4_maze_of_seed_3_has_junctions_and_checkpoints() {
        // Its first draw is one corridor from the start to the goal, without a junction.
        let p = MazeParams {
            width: 4,
            height: 4,
            ..Default::default()
        };
        let first = carve(&p, &mut Rng::new(3));
        assert!(!has_junction(&first));
        let w = generate(&p, 3).unwrap();
        assert!(has_junction(&w.maze().unwrap().maze));
        assert!(!w.checkpoints().is_empty());
        assert_every_approach_marked(&w, "4 x 4 seed 3");
        // Asked to keep the first draw, it does.
        let kept = generate(
            &MazeParams {
                junction: false,
                ..p
            },
            3,
        )
        .unwrap();
        assert!(kept.checkpoints().is_empty());
        assert_eq!(kept.maze().unwrap().maze.horizontal, first.horizontal);
    }

    #[test]
    fn a_2_by_2_maze_has_no_junction_and_no_checkpoint() {
        let p = MazeParams {
            width: 2,
            height: 2,
            ..Default::default()
        };
        for seed in 0..20 {
            assert!(generate(&p, seed).unwrap().checkpoints().is_empty());
        }
    }

    proptest::proptest! {
        #![proptest_config(proptest::prelude::ProptestConfig::with_cases(200))]
        /// The documented promise, for every size and seed: a maze larger than 2 x 2 has a
        /// junction, and every way into every junction has a checkpoint while the codes last.
        #[test]
        fn every_maze_larger_than_2_by_2_has_checkpoints_at_its_junctions(
            width in 2usize..=12,
            height in 2usize..=12,
            seed in proptest::prelude::any::<u64>(),
            loops in proptest::prop_oneof![proptest::strategy::Just(0.0), 0.0f64..0.5],
        ) {
            proptest::prop_assume!(width.max(height) > 2);
            let p = MazeParams { width, height, loops, ..Default::default() };
            let w = generate(&p, seed).unwrap();
            let label = format!("{width} x {height} seed {seed} loops {loops}");
            proptest::prop_assert!(has_junction(&w.maze().unwrap().maze), "{}", label);
            proptest::prop_assert!(!w.checkpoints().is_empty(), "{}", label);
            assert_every_approach_marked(&w, &label);
        }
    }

    #[test]
    fn checkpoints_sit_before_junctions_with_valid_codes() {
        let mut total = 0;
        for seed in 0..30 {
            let w = with_loops(0.2, seed);
            let placed = w.maze().unwrap();
            let m = &placed.maze;
            let codes: Vec<String> = w
                .spec()
                .checkpoints
                .iter()
                .map(|c| c.code.0.clone())
                .collect();
            codebook::validate(&codes).unwrap();
            for cp in w.checkpoints() {
                total += 1;
                let ((c, r), dir) = approach(m, cp, 0.25);
                let (jc, jr) = neighbour(m, c, r, dir).unwrap();
                assert!(m.open(c, r, dir) && openings(m, jc, jr) >= 3, "seed {seed}");
            }
        }
        assert!(total > 100, "only {total} checkpoints in 30 mazes");
    }

    #[test]
    fn every_approach_to_every_junction_is_marked_when_the_book_suffices() {
        let mut corners = 0;
        for seed in 0..200 {
            for loops in [0.0, 0.2] {
                let w = with_loops(loops, seed);
                let m = &w.maze().unwrap().maze;
                assert_every_approach_marked(&w, &format!("seed {seed} loops {loops}"));
                // Codes on edges: the approach is a corner (or a door).
                corners += w
                    .checkpoints()
                    .iter()
                    .filter(|cp| {
                        let ((c, r), _) = approach(m, cp, 0.25);
                        openings(m, c, r) == 2 && !(m.open(c, r, 0) && m.open(c, r, 2))
                    })
                    .count();
            }
        }
        assert!(corners > 100, "only {corners} codes before corners");
    }

    #[test]
    fn a_straight_cell_between_two_junctions_gets_one_code() {
        // Seed 5002 with loops has a straight cell between two doors; it used to get two codes
        // at the same centre facing opposite ways.
        for (seed, loops) in (0..300).map(|s| (s, 0.3)).chain([(5002, 0.3)]) {
            let w = with_loops(loops, seed);
            let cps = w.checkpoints();
            for (i, a) in cps.iter().enumerate() {
                for b in &cps[..i] {
                    let apart = (a.center[0] - b.center[0]).hypot(a.center[1] - b.center[1]);
                    assert!(
                        apart >= a.length,
                        "seed {seed}: checkpoints {} and {} {apart} m apart",
                        a.id,
                        b.id
                    );
                }
            }
        }
        let w = with_loops(0.3, 5002);
        let m = &w.maze().unwrap().maze;
        let shared = w.checkpoints().iter().any(|cp| {
            let ((c, r), dir) = approach(m, cp, 0.25);
            let back = (dir + 2) % 4;
            openings(m, c, r) == 2
                && m.open(c, r, back)
                && neighbour(m, c, r, back).is_some_and(|(bc, br)| openings(m, bc, br) >= 3)
        });
        assert!(shared, "seed 5002 has no code shared by two doors");
    }

    #[test]
    fn when_codes_run_out_the_way_to_the_goal_comes_first() {
        let book = codebook::default_codes().len();
        let mut short = 0;
        for seed in 0..20 {
            let w = generate(
                &MazeParams {
                    width: 9,
                    height: 9,
                    ..Default::default()
                },
                seed,
            )
            .unwrap();
            let m = &w.maze().unwrap().maze;
            let marked = marked(&w);
            let way = way_cells(m);
            let all = approaches(m);
            let on_way: Vec<_> = all
                .iter()
                .filter(|a| way[a.1 .1 * m.cols + a.1 .0])
                .collect();
            assert!(w.checkpoints().len() <= book);
            if all.len() > book {
                assert_eq!(w.checkpoints().len(), book, "seed {seed}");
            }
            if on_way.len() <= book && all.len() > book {
                short += 1;
                for a in on_way {
                    let between_doors =
                        openings(m, a.0 .0, a.0 .1) >= 3 && marked.contains(&(a.1, a.0));
                    assert!(marked.contains(a) || between_doors, "seed {seed}: {a:?}");
                }
            }
        }
        assert!(short > 0, "no 9 x 9 maze ran out of codes");
    }
}
