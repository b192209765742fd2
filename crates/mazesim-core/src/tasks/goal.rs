//! The shortest-path distance to the goal of one environment (Python's `mazesim.maze`
//! `GoalDistance` of one environment): in a cell maze, the inverse-distance weighting of the
//! targets of the robot's cell (its sides' and the goal's distances along the cells), else the
//! straight line, or 0 without a goal. The same float64 operations in the same order as the
//! Python floats of `GoalDistance.evaluate_one`, so the rewards are what they were, bit for bit.

use crate::{Error, Result};

/// Targets of a cell: its east, north, west and south sides, then the goal point.
pub const TARGETS: usize = 5;
/// Smallest distance used in an inverse-distance weight (metres).
const NEAREST: f64 = 1e-9;
/// Indices of the sides in a cell's targets.
const EAST: usize = 0;
const NORTH: usize = 1;
const WEST: usize = 2;
const SOUTH: usize = 3;

/// How the distance to the goal is measured.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum GoalMode {
    /// No goal: the distance is 0 and never reached.
    Nowhere,
    /// The straight line to the goal (a world without a cell maze).
    Straight,
    /// Along the cells of a cell maze.
    Maze,
}

/// The distance table of one environment's world and goal.
#[derive(Debug, Clone, PartialEq)]
pub struct GoalTable {
    mode: GoalMode,
    goal: [f64; 2],
    goal_r2: f64,
    size: f64,
    origin: [f64; 2],
    last_row: usize,
    last_col: usize,
    cols: usize,
    /// Per cell (row-major from the north-west) and target: (value, presence 0 or 1).
    cells: Vec<[(f64, f64); TARGETS]>,
}

impl Default for GoalTable {
    fn default() -> Self {
        Self {
            mode: GoalMode::Nowhere,
            goal: [0.0; 2],
            goal_r2: -1.0,
            size: 1.0,
            origin: [0.0; 2],
            last_row: 0,
            last_col: 0,
            cols: 1,
            cells: vec![[(0.0, 0.0); TARGETS]],
        }
    }
}

impl GoalTable {
    /// The table of a goal disc (x, y, radius) in a grid of `rows` x `cols` cells of side
    /// `size` whose south-west corner is `origin`, with the `targets` of each cell (NaN where a
    /// side is no target); one cell without a maze.
    pub fn new(
        mode: GoalMode,
        goal: [f64; 3],
        size: f64,
        origin: [f64; 2],
        rows: usize,
        cols: usize,
        targets: &[[f64; TARGETS]],
    ) -> Result<Self> {
        if rows == 0 || cols == 0 || rows.checked_mul(cols) != Some(targets.len()) {
            return Err(Error::InvalidArgument(format!(
                "expected the targets of {rows} x {cols} cells (at least one), found {}",
                targets.len()
            )));
        }
        let cells = targets
            .iter()
            .map(|row| row.map(|v| if v.is_nan() { (0.0, 0.0) } else { (v, 1.0) }))
            .collect();
        let goal_r2 = if mode == GoalMode::Nowhere {
            -1.0
        } else {
            goal[2] * goal[2]
        };
        Ok(Self {
            mode,
            goal: [goal[0], goal[1]],
            goal_r2,
            size,
            origin,
            last_row: rows - 1,
            last_col: cols - 1,
            cols,
            cells,
        })
    }

    /// The distance in metres to the goal from (x, y), and whether (x, y) is in the goal disc.
    pub fn evaluate(&self, x: f64, y: f64) -> (f64, bool) {
        let gx = x - self.goal[0];
        let gy = y - self.goal[1];
        let to_goal2 = gx * gx + gy * gy;
        let reached = to_goal2 <= self.goal_r2;
        match self.mode {
            GoalMode::Maze => (self.along(x, y, to_goal2.sqrt()), reached),
            GoalMode::Straight => (to_goal2.sqrt(), reached),
            GoalMode::Nowhere => (0.0, reached),
        }
    }

    fn along(&self, x: f64, y: f64, to_goal: f64) -> f64 {
        let size = self.size;
        let index = |value: f64, last: usize| -> usize {
            let floor = value.floor();
            if floor.is_nan() || floor <= 0.0 {
                0
            } else if floor >= last as f64 {
                last
            } else {
                floor as usize
            }
        };
        let col = index((x - self.origin[0]) / size, self.last_col);
        let up = index((y - self.origin[1]) / size, self.last_row);
        let half = 0.5 * size;
        let u = x - (self.origin[0] + (col as f64 + 0.5) * size);
        let v = y - (self.origin[1] + (up as f64 + 0.5) * size);
        let cell = &self.cells[(self.last_row - up) * self.cols + col];
        let (north, east, south, west, goal) = (
            cell[NORTH],
            cell[EAST],
            cell[SOUTH],
            cell[WEST],
            cell[TARGETS - 1],
        );
        // Python's max(a, b): a unless b is larger.
        let most = |a: f64, b: f64| if b > a { b } else { a };
        let w0 = north.1 / most(half - v, NEAREST);
        let w1 = east.1 / most(half - u, NEAREST);
        let w2 = south.1 / most(half + v, NEAREST);
        let w3 = west.1 / most(half + u, NEAREST);
        let w4 = goal.1 / most(to_goal, NEAREST);
        let weighted = w0 * north.0 + w1 * east.0 + w2 * south.0 + w3 * west.0 + w4 * goal.0;
        weighted / (w0 + w1 + w2 + w3 + w4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_straight_line_and_the_goal_disc() {
        let table = GoalTable::new(
            GoalMode::Straight,
            [3.0, 4.0, 1.0],
            1.0,
            [0.0; 2],
            1,
            1,
            &[[f64::NAN; TARGETS]],
        )
        .unwrap();
        assert_eq!(table.evaluate(0.0, 0.0), (5.0, false));
        assert_eq!(table.evaluate(3.0, 4.5), (0.5, true));
        assert_eq!(GoalTable::default().evaluate(1.0, 1.0), (0.0, false));
    }

    #[test]
    fn in_the_goal_cell_the_distance_is_the_goal_points() {
        // One cell: only the goal point is a target (its value 0).
        let targets = [[f64::NAN, f64::NAN, f64::NAN, f64::NAN, 0.0]];
        let table = GoalTable::new(
            GoalMode::Maze,
            [0.5, 0.5, 0.1],
            1.0,
            [0.0; 2],
            1,
            1,
            &targets,
        )
        .unwrap();
        assert_eq!(table.evaluate(0.2, 0.5).0, 0.0);
        assert!(GoalTable::new(GoalMode::Maze, [0.0; 3], 1.0, [0.0; 2], 2, 1, &targets).is_err());
    }
}
