//! The plan of the `"plan"` observation: the next waypoint of every cell of a maze on a shortest
//! path to the goal through the maze as its robot knows it (the sides of the cells it visited as
//! they are, every other side assumed open, the grid's edge walled), by one breadth-first search.

/// Cell sides in direction order: east, north, west, south (the Python model's order).
pub const SIDES: usize = 4;

/// The (column, row) step across each side, rows counted from the north.
const STEP: [(isize, isize); SIDES] = [(1, 0), (0, -1), (-1, 0), (0, 1)];

/// A grid of `rows` x `cols` cells, row-major from the north-west.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Grid {
    /// Cell rows.
    pub rows: usize,
    /// Cell columns.
    pub cols: usize,
}

impl Grid {
    /// The cell across `side` of `cell`, or None off the grid.
    pub fn across(&self, cell: usize, side: usize) -> Option<usize> {
        let (row, col) = ((cell / self.cols) as isize, (cell % self.cols) as isize);
        let (step_col, step_row) = STEP[side];
        let (row, col) = (row + step_row, col + step_col);
        let inside =
            row >= 0 && col >= 0 && (row as usize) < self.rows && (col as usize) < self.cols;
        inside.then(|| row as usize * self.cols + col as usize)
    }

    /// Number of cells.
    pub fn cells(&self) -> usize {
        self.rows * self.cols
    }
}

/// The open sides a robot that visited the cells `visited` assumes: a side of a visited cell, or
/// of a cell next to one across that side, is as it is (`open`); any other side is open; a side
/// on the grid's edge is walled.
pub fn assumed_open(grid: Grid, open: &[[bool; SIDES]], visited: &[bool]) -> Vec<[bool; SIDES]> {
    (0..grid.cells())
        .map(|cell| {
            let mut sides = [false; SIDES];
            for (side, assumed) in sides.iter_mut().enumerate() {
                let Some(there) = grid.across(cell, side) else {
                    continue;
                };
                let seen = visited[cell] || visited[there];
                *assumed = open[cell][side] || !seen;
            }
            sides
        })
        .collect()
}

/// Breadth-first steps from `source` along `open` sides (the grid's edge walled); None where
/// unreachable. Neighbours are taken in direction order.
pub fn steps_from(grid: Grid, open: &[[bool; SIDES]], source: usize) -> Vec<Option<usize>> {
    let mut steps = vec![None; grid.cells()];
    steps[source] = Some(0);
    let mut queue = vec![source];
    let mut next = 0;
    while let Some(&here) = queue.get(next) {
        next += 1;
        let step = steps[here].unwrap_or(0) + 1;
        for (side, &opened) in open[here].iter().enumerate() {
            if !opened {
                continue;
            }
            if let Some(there) = grid.across(here, side) {
                if steps[there].is_none() {
                    steps[there] = Some(step);
                    queue.push(there);
                }
            }
        }
    }
    steps
}

/// The next cell of every cell on a shortest path to `target` along `open` sides: across the
/// first open side in direction order whose neighbour is one step nearer; None in the target and
/// in the cells that cannot reach it.
pub fn next_cells(grid: Grid, open: &[[bool; SIDES]], target: usize) -> Vec<Option<usize>> {
    let steps = steps_from(grid, open, target);
    (0..grid.cells())
        .map(|cell| {
            let here = steps[cell].filter(|&s| s > 0)?;
            (0..SIDES)
                .filter(|&side| open[cell][side])
                .filter_map(|side| grid.across(cell, side))
                .find(|&there| steps[there] == Some(here - 1))
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_corridor_leads_to_its_end() {
        // Three cells in a row, all joined: the way from the west end goes east.
        let grid = Grid { rows: 1, cols: 3 };
        let open = vec![
            [true, false, false, false],
            [true, false, true, false],
            [false, false, true, false],
        ];
        assert_eq!(next_cells(grid, &open, 2), vec![Some(1), Some(2), None]);
        assert_eq!(steps_from(grid, &open, 0), vec![Some(0), Some(1), Some(2)]);
    }

    #[test]
    fn unseen_sides_are_assumed_open_and_the_edge_walled() {
        let grid = Grid { rows: 2, cols: 2 };
        let closed = vec![[false; SIDES]; 4];
        let nothing = assumed_open(grid, &closed, &[false; 4]);
        // North-west cell: east and south open (inside), north and west on the edge.
        assert_eq!(nothing[0], [true, false, false, true]);
        let seen = assumed_open(grid, &closed, &[true, false, false, false]);
        // Its own sides and the sides its neighbours share with it are known walls now.
        assert_eq!(seen[0], [false; SIDES]);
        assert_eq!(seen[1], [false, false, false, true]);
        assert_eq!(seen[3], [false, true, true, false]);
    }
}
