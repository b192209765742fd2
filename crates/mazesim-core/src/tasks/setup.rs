//! The per-episode set-up of a maze task: the goal-distance table's interpolation targets of
//! every cell, and the cells a random start and goal are drawn from. Python's
//! `mazesim.maze.PathDistanceTable` and `mazesim.envs.navigation.start_and_goal_cells` document
//! them; the float64 operations here are those of the Python model in the same order, so the
//! tables are the same bit for bit (a new random maze every episode makes them every reset).

use super::goal::TARGETS;
use super::plan::{steps_from, Grid, SIDES};
use crate::world::CellMaze;

/// Ties between sides in a dead end's back-wall test go north, east, south, west: each side's
/// rank (sides in direction order east, north, west, south).
const TIE_RANK: [usize; SIDES] = [1, 0, 3, 2];

/// The grid of a cell maze.
pub fn grid_of(maze: &CellMaze) -> Grid {
    Grid {
        rows: maze.rows,
        cols: maze.cols,
    }
}

/// Whether each side of each cell is open, cells row-major from the north-west, sides in
/// direction order; a side on the grid's edge is walled.
pub fn open_sides(maze: &CellMaze) -> Vec<[bool; SIDES]> {
    (0..maze.rows)
        .flat_map(|row| {
            (0..maze.cols).map(move |col| std::array::from_fn(|side| maze.open(col, row, side)))
        })
        .collect()
}

/// The interpolation targets of every cell towards the goal cell `goal` (row-major index): per
/// side, the path distance at the side's midpoint (NaN where the side is closed or leads
/// nowhere; a dead end's back wall gets its cell's distance plus half a cell), then 0 at the goal
/// cell's goal point (NaN elsewhere). A cell that cannot reach the goal has every side at one
/// cell more than the farthest reachable cell.
pub fn cell_targets(
    grid: Grid,
    open: &[[bool; SIDES]],
    cell_size: f64,
    goal: usize,
) -> Vec<[f64; TARGETS]> {
    let steps = steps_from(grid, open, goal);
    let farthest = steps.iter().flatten().copied().max().unwrap_or(0);
    let unreachable = (farthest + 1) as f64 * cell_size;
    (0..grid.cells())
        .map(|cell| {
            let mut values = [f64::NAN; TARGETS];
            let Some(step) = steps[cell] else {
                values[..SIDES].fill(unreachable);
                return values;
            };
            let here = step as f64 * cell_size;
            for (side, value) in values[..SIDES].iter_mut().enumerate() {
                let there = grid.across(cell, side).filter(|_| open[cell][side]);
                if let Some(next) = there.and_then(|there| steps[there]) {
                    *value = 0.5 * (here + next as f64 * cell_size);
                }
            }
            if cell == goal {
                values[SIDES] = 0.0;
                return values;
            }
            let known = (0..SIDES).filter(|&side| !values[side].is_nan());
            let nearest = known.clone().min_by(|&a, &b| {
                values[a]
                    .total_cmp(&values[b])
                    .then(TIE_RANK[a].cmp(&TIE_RANK[b]))
            });
            if let Some(nearest) = nearest {
                if known.into_iter().all(|side| values[side] <= here) {
                    let back = (nearest + 2) % SIDES;
                    if values[back].is_nan() {
                        values[back] = here + 0.5 * cell_size;
                    }
                }
            }
            values
        })
        .collect()
}

/// The cells (row-major indices, in order) of the largest set of cells joined by open sides: the
/// first such set from the north-west if two are as large.
pub fn largest_connected_cells(grid: Grid, open: &[[bool; SIDES]]) -> Vec<usize> {
    let mut seen = vec![false; grid.cells()];
    let mut best = Vec::new();
    for cell in 0..grid.cells() {
        if seen[cell] {
            continue;
        }
        let steps = steps_from(grid, open, cell);
        let reach: Vec<usize> = (0..grid.cells()).filter(|&c| steps[c].is_some()).collect();
        for &c in &reach {
            seen[c] = true;
        }
        if reach.len() > best.len() {
            best = reach;
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Three cells west to east, the middle one walled from the east one.
    fn split() -> CellMaze {
        CellMaze::parse("+--+--+--+\n|     |  |\n+--+--+--+").unwrap()
    }

    #[test]
    fn a_walled_off_cell_is_left_out_of_the_largest_joined_cells() {
        let maze = split();
        assert_eq!(
            largest_connected_cells(grid_of(&maze), &open_sides(&maze)),
            vec![0, 1]
        );
    }

    #[test]
    fn targets_meet_halfway_between_cells_and_a_dead_end_gets_its_back_wall() {
        let maze = split();
        let targets = cell_targets(grid_of(&maze), &open_sides(&maze), 0.25, 0);
        // The goal cell: its east side halfway to the next cell, the goal point at 0.
        assert_eq!(targets[0][0], 0.125);
        assert_eq!(targets[0][4], 0.0);
        // The middle cell is a dead end one cell away: west side 0.125, back (east) wall 0.375.
        assert_eq!(targets[1][2], 0.125);
        assert_eq!(targets[1][0], 0.375);
        assert!(targets[1][1].is_nan() && targets[1][3].is_nan() && targets[1][4].is_nan());
        // The east cell cannot reach the goal: every side one cell beyond the farthest.
        assert_eq!(&targets[2][..4], &[0.5; 4]);
    }
}
