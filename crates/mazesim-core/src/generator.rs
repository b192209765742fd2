//! A seeded maze generator: W x H cells, perfect (one path between any two cells) or with extra
//! loops, with barcode checkpoints before the junctions and a goal in the cell farthest from the
//! start. Cheap enough to draw thousands of distinct mazes for training.

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
    /// Place barcode checkpoints before junctions.
    pub checkpoints: bool,
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

/// A generated maze world.
pub fn generate(params: &MazeParams, seed: u64) -> Result<World> {
    if params.width < 2 || params.height < 2 || params.width > 200 || params.height > 200 {
        return Err(Error::InvalidArgument(format!(
            "expected a maze of 2 to 200 cells a side, found {} x {}",
            params.width, params.height
        )));
    }
    if !(params.cell_size.is_finite() && params.wall_thickness.is_finite())
        || params.cell_size <= 0.0
        || params.wall_thickness <= 0.0
        || params.wall_thickness >= params.cell_size
    {
        return Err(Error::InvalidArgument(format!(
            "expected 0 < wall thickness < cell size, found {} and {}",
            params.wall_thickness, params.cell_size
        )));
    }
    let reflectance_ok = params.floor_reflectance > 0.0 && params.floor_reflectance <= 1.0;
    if !(0.0..=1.0).contains(&params.loops) || !reflectance_ok {
        return Err(Error::InvalidArgument(format!(
            "expected loops in [0, 1] and floor reflectance in (0, 1], found {} and {}",
            params.loops, params.floor_reflectance
        )));
    }
    let mut rng = Rng::new(seed);
    let mut m = carve(params, &mut rng);
    let start = m.start.expect("carve sets the start");
    let dist = distances(&m, start);
    let goal_index = (0..dist.len())
        .max_by_key(|&i| (dist[i].unwrap_or(0), usize::MAX - i))
        .expect("a maze has cells");
    m.goal = Some((goal_index % m.cols, goal_index / m.cols));
    let cs = params.cell_size;
    let checkpoints = if params.checkpoints {
        place_checkpoints(&m, cs)
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
        }),
        start: Some(crate::world::spec::StartSpec {
            x: Finite((start.0 as f64 + 0.5) * cs),
            y: Finite((m.rows as f64 - start.1 as f64 - 0.5) * cs),
            yaw: Finite(start_dir as f64 * std::f64::consts::FRAC_PI_2),
        }),
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
        checkpoints,
    };
    World::from_spec(
        spec,
        &format!("generated:{}x{}:seed{seed}", params.width, params.height),
    )
}

/// One checkpoint per approach to a junction (a cell with 3 or 4 openings) through a straight
/// corridor cell, up to the size of the code book, in a fixed scan order.
fn place_checkpoints(m: &CellMaze, cs: f64) -> Vec<CheckpointSpec> {
    let book = codebook::default_codes();
    let mut out = Vec::new();
    for r in 0..m.rows {
        for c in 0..m.cols {
            if openings(m, c, r) < 3 {
                continue;
            }
            for d in 0..4 {
                if !m.open(c, r, d) || out.len() >= book.len() {
                    continue;
                }
                let (nc, nr) = neighbour(m, c, r, d).expect("open side has a neighbour");
                let back = (d + 2) % 4;
                // A straight corridor: open towards the junction and on the far side only.
                let straight =
                    openings(m, nc, nr) == 2 && m.open(nc, nr, back) && m.open(nc, nr, d);
                if !straight {
                    continue;
                }
                let center = [
                    (nc as f64 + 0.5) * cs,
                    (m.rows as f64 - nr as f64 - 0.5) * cs,
                ];
                // Travelling from the corridor cell towards the junction is direction `back`.
                let yaw = back as f64 * std::f64::consts::FRAC_PI_2;
                out.push(CheckpointSpec {
                    id: out.len() as u32 + 1,
                    code: BarcodeBits(book[out.len()].clone()),
                    center: [Finite(center[0]), Finite(center[1])],
                    yaw: Finite(yaw),
                    width: Positive(cs - 0.02),
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

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

    #[test]
    fn checkpoints_sit_before_junctions_with_valid_codes() {
        let mut total = 0;
        for seed in 0..30 {
            let w = generate(
                &MazeParams {
                    loops: 0.2,
                    ..Default::default()
                },
                seed,
            )
            .unwrap();
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
                let c = (cp.center[0] / 0.25).floor() as usize;
                let r = m.rows - 1 - (cp.center[1] / 0.25).floor() as usize;
                let dir = ((cp.yaw / std::f64::consts::FRAC_PI_2).round() as usize) % 4;
                let (jc, jr) = neighbour(m, c, r, dir).unwrap();
                assert!(m.open(c, r, dir) && openings(m, jc, jr) >= 3, "seed {seed}");
            }
        }
        assert!(total > 30, "only {total} checkpoints in 30 mazes");
    }
}
