//! Task observations: the navigation features of the learnable gymnasium tasks, computed per
//! step for N environments (the goal in the robot's frame, the explored map round the robot, the
//! next waypoint of the true shortest path or of a path planned through the maze as the robot
//! knows it, the pose, the previous action). Python's `mazesim.envs.navigation` documents each
//! value; this module computes them with the same float64 operations in the same order, so the
//! observations are those the numpy code gave, bit for bit, and every environment's values
//! depend on its own state alone (whatever the batch it sits in).

mod goal;
mod plan;
mod setup;
mod state;

pub use goal::{GoalMode, GoalTable, TARGETS};

pub use plan::{assumed_open, next_cells, steps_from, Grid, SIDES};
pub use setup::{cell_targets, grid_of, largest_connected_cells, open_sides};

use crate::{Error, Result};

/// Visits of a cell the explored map tells apart (more read as this many).
const VISITS_SEEN: f64 = 3.0;

/// Most cells kept over all environments (environments times the largest grid): about 60 bytes
/// each, so a quarter of a GB at most.
pub const MAX_FEATURE_CELLS: usize = 1 << 22;

fn check_cells(num_envs: usize, cells: usize) -> Result<()> {
    match num_envs.checked_mul(cells) {
        Some(total) if total <= MAX_FEATURE_CELLS => Ok(()),
        _ => Err(Error::InvalidArgument(format!(
            "expected at most {MAX_FEATURE_CELLS} cells over all environments, found {num_envs} \
             environments of {cells} cells"
        ))),
    }
}

/// Which features an observation holds, after the scaled sensor readings and the goal.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct FeatureKinds {
    /// The next waypoint of the shortest path through the true maze (`"guided"`).
    pub guided: bool,
    /// The next waypoint of the path planned through the maze as the robot knows it (`"plan"`).
    pub plan: bool,
    /// The explored map round the robot's cell (`"explore"`, `"plan"`).
    pub explore: bool,
    /// The robot's position in the world's bounds and its heading's cosine and sine.
    pub pose: bool,
}

/// Where one environment is: its world's geometry and the goal (see [`Features::set_env`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Place {
    /// The goal point (x, y).
    pub goal: [f64; 2],
    /// The world's larger side (the goal's unit).
    pub extent: f64,
    /// The world's south-west corner (the pose's origin).
    pub corner: [f64; 2],
    /// The side of a cell (the waypoint's unit).
    pub cell_size: f64,
    /// The grid's south-west corner.
    pub origin: [f64; 2],
    /// The cell grid (1 x 1 without a maze).
    pub grid: Grid,
}

/// What one environment knows: its place, its waypoints, the explored map and the plan.
#[derive(Debug, Clone)]
struct EnvState {
    place: Place,
    /// Per cell (up to the capacity): the next waypoint (x, y).
    waypoints: Vec<[f64; 2]>,
    /// Per cell: the true open sides (1.0 open, 0.0 walled).
    open: Vec<[f64; SIDES]>,
    /// Per cell: the visits this episode.
    visits: Vec<f64>,
    /// The cell the robot was last seen in; None after a restart.
    last: Option<usize>,
    /// The goal cell to plan towards, when the environment has a cell maze to plan in.
    goal_cell: Option<usize>,
}

/// The navigation features of N environments.
#[derive(Debug, Clone)]
pub struct Features {
    kinds: FeatureKinds,
    /// The largest value of each sensor's table (readings are divided by it).
    scale: Vec<f64>,
    low: Vec<f32>,
    high: Vec<f32>,
    /// Cells kept per environment: the most any environment's grid (or waypoints) needed.
    capacity: usize,
    envs: Vec<EnvState>,
    /// Each environment's distance table to its goal (not part of [`Features::state`]: it is
    /// set again from the world and the goal).
    goals: Vec<GoalTable>,
}

/// Refuses clamp bounds `low`..`high` (paired by index) of which a pair is not ordered: a
/// `low` above its `high`, or either NaN, would clamp every value to one end, unseen.
///
/// # Errors
/// [`Error::InvalidArgument`] naming `what`, the first such pair and its index.
pub fn check_ordered(low: &[f32], high: &[f32], what: &str) -> Result<()> {
    match low
        .iter()
        .zip(high)
        .position(|(l, h)| l.partial_cmp(h).is_none_or(std::cmp::Ordering::is_gt))
    {
        Some(i) => Err(Error::InvalidArgument(format!(
            "expected {what} with low <= high (neither NaN), found low[{i}] = {}, high[{i}] = {}",
            low[i], high[i]
        ))),
        None => Ok(()),
    }
}

impl Features {
    /// Features of `num_envs` environments whose sensors' largest values are `scale`, clamped to
    /// `low`..`high` (one bound per value of an observation, [`Features::width`] of each).
    pub fn new(
        num_envs: usize,
        kinds: FeatureKinds,
        scale: Vec<f64>,
        low: Vec<f32>,
        high: Vec<f32>,
    ) -> Result<Self> {
        check_cells(num_envs, 1)?;
        let width = Self::width_of(kinds, scale.len());
        if low.len() != width || high.len() != width {
            return Err(Error::InvalidArgument(format!(
                "expected low and high of {width} values (the observation's width), found {} \
                 and {}",
                low.len(),
                high.len()
            )));
        }
        // Every observation is a reading over its scale, clamped to [low, high]: bounds that are
        // finite and ordered, and scales finite and positive, keep every value finite.
        if let Some((i, s)) = scale
            .iter()
            .enumerate()
            .find(|(_, s)| !(s.is_finite() && **s > 0.0))
        {
            return Err(Error::InvalidArgument(format!(
                "expected every sensor scale to be a finite positive number, found {s} at {i}"
            )));
        }
        if let Some(i) = (0..width).find(|&i| !(low[i].is_finite() && high[i].is_finite())) {
            return Err(Error::InvalidArgument(format!(
                "expected finite feature bounds, found low[{i}] = {}, high[{i}] = {}",
                low[i], high[i]
            )));
        }
        check_ordered(&low, &high, "feature bounds")?;
        let place = Place {
            goal: [0.0; 2],
            extent: 1.0,
            corner: [0.0; 2],
            cell_size: 1.0,
            origin: [0.0; 2],
            grid: Grid { rows: 1, cols: 1 },
        };
        let env = EnvState {
            place,
            waypoints: vec![[0.0; 2]],
            open: vec![[0.0; SIDES]],
            visits: vec![0.0],
            last: None,
            goal_cell: None,
        };
        Ok(Self {
            kinds,
            scale,
            low,
            high,
            capacity: 1,
            envs: vec![env; num_envs],
            goals: vec![GoalTable::default(); num_envs],
        })
    }

    /// Values of one observation of `kinds` after `sensors` readings.
    pub fn width_of(kinds: FeatureKinds, sensors: usize) -> usize {
        let waypoint = if kinds.guided || kinds.plan { 2 } else { 0 };
        let explore = if kinds.explore { 9 } else { 0 };
        let pose = if kinds.pose { 4 } else { 0 };
        sensors + 2 + waypoint + explore + pose + 2
    }

    /// Values of one observation.
    pub fn width(&self) -> usize {
        Self::width_of(self.kinds, self.scale.len())
    }

    /// Number of environments.
    pub fn num_envs(&self) -> usize {
        self.envs.len()
    }

    /// Puts environment `env` into a world: its `place`, the next `waypoints` of its cells
    /// (row-major; one, the goal, without a maze), the true open `sides` of its cells (when the
    /// features hold the explored map; all walled without a maze) and the goal cell to plan
    /// towards (None: no plan, the waypoints stay). Restarts the environment's episode.
    pub fn set_env(
        &mut self,
        env: usize,
        place: Place,
        waypoints: &[[f64; 2]],
        sides: Option<&[[f64; SIDES]]>,
        goal_cell: Option<usize>,
    ) -> Result<()> {
        self.check_env(env)?;
        let cells = place.grid.cells();
        if place.grid.rows == 0 || place.grid.cols == 0 || waypoints.is_empty() {
            return Err(Error::InvalidArgument(format!(
                "expected a grid of at least one cell and at least one waypoint, found {} x {} \
                 cells and {} waypoints",
                place.grid.rows,
                place.grid.cols,
                waypoints.len()
            )));
        }
        if let Some(sides) = sides {
            if sides.len() != cells {
                return Err(Error::InvalidArgument(format!(
                    "expected the open sides of {cells} cells, found {}",
                    sides.len()
                )));
            }
        }
        if goal_cell.is_some_and(|cell| cell >= cells) {
            return Err(Error::InvalidArgument(format!(
                "expected a goal cell below {cells}, found {goal_cell:?}"
            )));
        }
        let needed = waypoints.len().max(cells);
        if needed > self.capacity {
            check_cells(self.envs.len(), needed)?;
            self.capacity = needed;
            for state in &mut self.envs {
                state.waypoints.resize(needed, [0.0; 2]);
                state.open.resize(needed, [0.0; SIDES]);
                state.visits.resize(needed, 0.0);
            }
        }
        let state = &mut self.envs[env];
        state.place = place;
        state.waypoints[..waypoints.len()].copy_from_slice(waypoints);
        if let Some(sides) = sides {
            state.open[..cells].copy_from_slice(sides);
        }
        state.goal_cell = goal_cell;
        self.restart(env)
    }

    /// Sets the distance table of environment `env`'s goal.
    pub fn set_goal(&mut self, env: usize, table: GoalTable) -> Result<()> {
        self.check_env(env)?;
        self.goals[env] = table;
        Ok(())
    }

    /// The distance in metres from (x, y) to environment `env`'s goal along its maze (its
    /// [`GoalTable`]), and whether (x, y) lies in the goal disc.
    pub fn goal_distance(&self, env: usize, x: f64, y: f64) -> Result<(f64, bool)> {
        self.check_env(env)?;
        Ok(self.goals[env].evaluate(x, y))
    }

    /// Forgets the explored map's visits of environment `env` (a new episode); the plan is made
    /// again at the next observation, from the robot's first cell.
    pub fn restart(&mut self, env: usize) -> Result<()> {
        self.check_env(env)?;
        let state = &mut self.envs[env];
        state.visits.iter_mut().for_each(|v| *v = 0.0);
        state.last = None;
        Ok(())
    }

    fn check_env(&self, env: usize) -> Result<()> {
        if env >= self.envs.len() {
            return Err(Error::InvalidArgument(format!(
                "expected an environment index below {}, found {env}",
                self.envs.len()
            )));
        }
        Ok(())
    }

    /// Writes the observation of environment `env` into `out` ([`Features::width`] values) from
    /// its raw `readings`, its float32 `pose` (x, y, yaw) and the `previous` action as wheel
    /// speed fractions. Counts the visit of a cell the robot entered since its last observation
    /// and plans again on entering a cell for the first time.
    pub fn observe(
        &mut self,
        env: usize,
        readings: &[f32],
        pose: [f32; 3],
        previous: [f32; 2],
        out: &mut [f32],
    ) -> Result<()> {
        self.check_env(env)?;
        if readings.len() != self.scale.len() || out.len() != self.width() {
            return Err(Error::InvalidArgument(format!(
                "expected {} readings and room for {} values, found {} and {}",
                self.scale.len(),
                self.width(),
                readings.len(),
                out.len()
            )));
        }
        let kinds = self.kinds;
        let capacity = self.capacity;
        let state = &mut self.envs[env];
        let place = state.place;
        let (x, y, yaw) = (f64::from(pose[0]), f64::from(pose[1]), f64::from(pose[2]));
        let (cos, sin) = (yaw.cos(), yaw.sin());
        let cell = cell_of(&place, x, y);
        if kinds.explore && state.last != Some(cell) {
            let first = state.visits[cell] == 0.0;
            state.visits[cell] += 1.0;
            if kinds.plan && first {
                replan(state);
            }
        }
        if kinds.explore {
            state.last = Some(cell);
        }
        let mut values = Vec::with_capacity(out.len());
        values.extend(
            readings
                .iter()
                .zip(&self.scale)
                .map(|(r, s)| f64::from(*r) / s),
        );
        let mut relative = |target: [f64; 2], unit: f64| {
            let (dx, dy) = (target[0] - x, target[1] - y);
            values.push((cos * dx + sin * dy) / unit);
            values.push((cos * dy - sin * dx) / unit);
        };
        relative(place.goal, place.extent);
        if kinds.guided || kinds.plan {
            relative(state.waypoints[cell], place.cell_size);
        }
        if kinds.explore {
            explored(state, cell, yaw, capacity, &mut values);
        }
        if kinds.pose {
            values.push((x - place.corner[0]) / place.extent);
            values.push((y - place.corner[1]) / place.extent);
            values.push(cos);
            values.push(sin);
        }
        values.extend(previous.iter().map(|p| f64::from(*p)));
        for (((slot, value), low), high) in
            out.iter_mut().zip(values).zip(&self.low).zip(&self.high)
        {
            *slot = clamp(value as f32, *low, *high);
        }
        Ok(())
    }
}

/// numpy's `maximum` then `minimum`: NaN stays NaN.
fn clamp(value: f32, low: f32, high: f32) -> f32 {
    let value = if value < low { low } else { value };
    if value > high {
        high
    } else {
        value
    }
}

/// The cell (row-major from the north-west) the point (x, y) is in, clipped to the grid.
fn cell_of(place: &Place, x: f64, y: f64) -> usize {
    let Grid { rows, cols } = place.grid;
    let col = ((x - place.origin[0]) / place.cell_size).floor();
    let up = ((y - place.origin[1]) / place.cell_size).floor();
    let col = col.clamp(0.0, (cols - 1) as f64) as usize;
    let up = up.clamp(0.0, (rows - 1) as f64) as usize;
    (rows - 1 - up) * cols + col
}

/// Plans again the waypoints of `state` through its maze as its robot knows it now.
fn replan(state: &mut EnvState) {
    let Some(goal_cell) = state.goal_cell else {
        return;
    };
    let place = state.place;
    let grid = place.grid;
    let cells = grid.cells();
    let open: Vec<[bool; SIDES]> = state.open[..cells]
        .iter()
        .map(|sides| sides.map(|s| s > 0.0))
        .collect();
    let visited: Vec<bool> = state.visits[..cells].iter().map(|v| *v > 0.0).collect();
    let assumed = assumed_open(grid, &open, &visited);
    for (cell, next) in next_cells(grid, &assumed, goal_cell)
        .into_iter()
        .enumerate()
    {
        state.waypoints[cell] = match next {
            Some(next) => {
                let (row, col) = (next / grid.cols, next % grid.cols);
                [
                    place.origin[0] + (col as f64 + 0.5) * place.cell_size,
                    place.origin[1] + ((grid.rows - row) as f64 - 0.5) * place.cell_size,
                ]
            }
            None => place.goal,
        };
    }
}

/// Appends the explored map round the robot's `cell`: the sides of the cell ahead, left, behind
/// and right of the robot (the side its heading is nearest first), open or not; the visits of
/// the cells across them (0 across a wall) and of its own cell, each up to 3 and scaled to 1.
fn explored(state: &EnvState, cell: usize, yaw: f64, capacity: usize, values: &mut Vec<f64>) {
    let facing = (yaw / (0.5 * std::f64::consts::PI)).round_ties_even();
    // As numpy's cast of a float to intp, then a modulo with the divisor's sign.
    let facing = (facing as i64).rem_euclid(SIDES as i64) as usize;
    let cols = state.place.grid.cols as i64;
    let sides: [usize; SIDES] = std::array::from_fn(|k| (facing + k) % SIDES);
    let opened = sides.map(|side| state.open[cell][side]);
    let seen = sides.map(|side| {
        let step = [1, -1, -1, 1][side] * if side % 2 == 0 { 1 } else { cols };
        let across = (cell as i64 + step).clamp(0, capacity as i64 - 1) as usize;
        state.visits[across].min(VISITS_SEEN) / VISITS_SEEN
    });
    values.extend(opened);
    values.extend(opened.iter().zip(seen).map(|(o, s)| o * s));
    values.push(state.visits[cell].min(VISITS_SEEN) / VISITS_SEEN);
}

#[cfg(test)]
mod tests;
