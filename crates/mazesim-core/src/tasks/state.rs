//! The state of [`Features`] as bytes (pickling, copies): the capacity, then per environment
//! its place, waypoints, open sides, visits, last cell and goal cell, all little-endian 8-byte
//! values.

use super::{EnvState, Features, Grid, Place, SIDES};
use crate::{Error, Result};

/// No cell (the last cell after a restart, no goal cell to plan towards).
const NONE: u64 = u64::MAX;

fn cell_code(cell: Option<usize>) -> u64 {
    cell.map_or(NONE, |c| c as u64)
}

/// Reads little-endian 8-byte values from a state, failing past its end.
struct Reader<'a> {
    bytes: &'a [u8],
}

impl Reader<'_> {
    fn word(&mut self) -> Result<[u8; 8]> {
        if self.bytes.len() < 8 {
            return Err(Error::InvalidArgument(
                "expected the state of TaskFeatures of this kind and size, found a shorter one"
                    .into(),
            ));
        }
        let (word, rest) = self.bytes.split_at(8);
        self.bytes = rest;
        Ok(word.try_into().unwrap_or([0; 8]))
    }

    fn real(&mut self) -> Result<f64> {
        Ok(f64::from_le_bytes(self.word()?))
    }

    fn count(&mut self) -> Result<u64> {
        Ok(u64::from_le_bytes(self.word()?))
    }

    fn cell(&mut self, cells: usize) -> Result<Option<usize>> {
        match self.count()? {
            NONE => Ok(None),
            c if (c as usize) < cells && c < NONE => Ok(Some(c as usize)),
            c => Err(Error::InvalidArgument(format!(
                "expected a cell below {cells} in the state, found {c}"
            ))),
        }
    }
}

impl Features {
    /// The state of every environment as bytes, for [`Features::restore`].
    pub fn state(&self) -> Vec<u8> {
        let mut out = Vec::new();
        let mut put = |value: u64| out.extend_from_slice(&value.to_le_bytes());
        put(self.capacity as u64);
        for env in &self.envs {
            let p = env.place;
            for v in [
                p.goal[0],
                p.goal[1],
                p.extent,
                p.corner[0],
                p.corner[1],
                p.cell_size,
            ] {
                put(v.to_bits());
            }
            put(p.origin[0].to_bits());
            put(p.origin[1].to_bits());
            put(p.grid.rows as u64);
            put(p.grid.cols as u64);
            env.waypoints
                .iter()
                .flatten()
                .for_each(|v| put(v.to_bits()));
            env.open.iter().flatten().for_each(|v| put(v.to_bits()));
            env.visits.iter().for_each(|v| put(v.to_bits()));
            put(cell_code(env.last));
            put(cell_code(env.goal_cell));
        }
        out
    }

    /// Puts every environment in the `state` of features of the same kind and number of
    /// environments ([`Features::state`]); a state of another shape changes nothing.
    pub fn restore(&mut self, state: &[u8]) -> Result<()> {
        let mut reader = Reader { bytes: state };
        let capacity = reader.count()? as usize;
        let per_env = 12 + capacity.saturating_mul(2 + SIDES + 1);
        let expected = per_env
            .checked_mul(self.envs.len())
            .and_then(|words| words.checked_add(1))
            .and_then(|words| words.checked_mul(8));
        if capacity == 0 || expected != Some(state.len()) {
            return Err(Error::InvalidArgument(format!(
                "expected the state of {} environments' TaskFeatures, found {} bytes",
                self.envs.len(),
                state.len()
            )));
        }
        let mut envs = Vec::with_capacity(self.envs.len());
        for _ in 0..self.envs.len() {
            let mut reals = [0.0; 8];
            for v in &mut reals {
                *v = reader.real()?;
            }
            let (rows, cols) = (reader.count()? as usize, reader.count()? as usize);
            let grid = Grid { rows, cols };
            if rows == 0 || cols == 0 || rows.checked_mul(cols).is_none_or(|c| c > capacity) {
                return Err(Error::InvalidArgument(format!(
                    "expected a grid of at most {capacity} cells in the state, found {rows} x \
                     {cols}"
                )));
            }
            let place = Place {
                goal: [reals[0], reals[1]],
                extent: reals[2],
                corner: [reals[3], reals[4]],
                cell_size: reals[5],
                origin: [reals[6], reals[7]],
                grid,
            };
            let mut waypoints = vec![[0.0; 2]; capacity];
            for point in &mut waypoints {
                *point = [reader.real()?, reader.real()?];
            }
            let mut open = vec![[0.0; SIDES]; capacity];
            for sides in &mut open {
                for side in sides.iter_mut() {
                    *side = reader.real()?;
                }
            }
            let mut visits = vec![0.0; capacity];
            for v in &mut visits {
                *v = reader.real()?;
            }
            let cells = grid.cells();
            let last = reader.cell(cells)?;
            let goal_cell = reader.cell(cells)?;
            envs.push(EnvState {
                place,
                waypoints,
                open,
                visits,
                last,
                goal_cell,
            });
        }
        self.capacity = capacity;
        self.envs = envs;
        Ok(())
    }
}
