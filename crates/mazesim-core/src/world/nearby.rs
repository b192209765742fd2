//! The walls near a robot, gathered once per step from the bin grid and then queried by all its
//! sensor rays and by the clearance check, instead of walking the bins once per query.

use super::geometry::Bounds;
use super::walls::{Nearest, RayHit, SlabRay, WallIndex};

/// At most this many walls are kept; a region crowded with more is answered by the full index.
const CAPACITY: usize = 32;

/// Side of the cells of the neighbourhood lists (metres). A square of half side up to this (less
/// 1 mm for rounding) around a point of a cell lies within the 3 x 3 cells around that cell; the
/// e-puck's rays and clearance search reach 0.104 m.
const NEIGHBOURHOOD: f64 = 0.11;

/// At most this many cells: very large worlds get larger cells.
const MAX_CELLS: f64 = 65_536.0;

/// For each cell of a grid, the walls whose bounding boxes meet the 3 x 3 cells around it, in
/// index order: the candidates of any square query of half side below the cell side, with no
/// duplicates to weed out.
#[derive(Debug, Clone, Default)]
pub(super) struct Neighbourhoods {
    origin: [f64; 2],
    side: f64,
    cols: usize,
    rows: usize,
    start: Vec<u32>,
    walls: Vec<u32>,
}

impl Neighbourhoods {
    /// Lists for the walls of bounding `boxes` (min x, min y, max x, max y), all within `bounds`.
    pub(super) fn new(boxes: &[[f32; 4]], bounds: Bounds) -> Self {
        let w = bounds.max[0] - bounds.min[0];
        let h = bounds.max[1] - bounds.min[1];
        let side = NEIGHBOURHOOD.max((w * h / MAX_CELLS).sqrt());
        let cols = (w / side) as usize + 1;
        let rows = (h / side) as usize + 1;
        let origin = bounds.min;
        let mut cells: Vec<Vec<u32>> = vec![Vec::new(); cols * rows];
        // A point's square meets the box only if the point's cell lies at most one cell beyond
        // the cells the box spans; 1 mm more covers rounding (a wall too many costs a box test,
        // one missing would be wrong).
        let cell = |v: f64, o: f64| ((v - o) / side).floor() as i64;
        let margin = 1e-3;
        for (i, b) in boxes.iter().enumerate() {
            let [x0, y0, x1, y1] = b.map(|v| v as f64);
            let c0 = (cell(x0 - margin, origin[0]) - 1).max(0) as usize;
            let r0 = (cell(y0 - margin, origin[1]) - 1).max(0) as usize;
            let c1 = ((cell(x1 + margin, origin[0]) + 1).max(0) as usize).min(cols - 1);
            let r1 = ((cell(y1 + margin, origin[1]) + 1).max(0) as usize).min(rows - 1);
            for row in r0..=r1 {
                for col in c0..=c1 {
                    cells[row * cols + col].push(i as u32);
                }
            }
        }
        let mut start = Vec::with_capacity(cells.len() + 1);
        start.push(0u32);
        let mut walls = Vec::with_capacity(cells.iter().map(Vec::len).sum());
        for c in cells {
            walls.extend(c);
            start.push(walls.len() as u32);
        }
        Self {
            origin,
            side,
            cols,
            rows,
            start,
            walls,
        }
    }

    /// The list of the cell holding `p`, if the square of half side `reach` around `p` stays in
    /// its 3 x 3 block and `p` lies on the grid.
    pub(super) fn around(&self, p: [f32; 2], reach: f32) -> Option<&[u32]> {
        if self.cols == 0 || reach as f64 > self.side - 1e-3 {
            return None;
        }
        let fx = (p[0] as f64 - self.origin[0]) / self.side;
        let fy = (p[1] as f64 - self.origin[1]) / self.side;
        if !(fx >= 0.0 && fy >= 0.0) {
            return None;
        }
        let (col, row) = (fx as usize, fy as usize);
        if col >= self.cols || row >= self.rows {
            return None;
        }
        let c = row * self.cols + col;
        Some(&self.walls[self.start[c] as usize..self.start[c + 1] as usize])
    }
}

/// Walls of a `WallIndex` whose bounding boxes meet a region, axis-aligned ones as boxes.
///
/// Queries, given the same index, give exactly what the same query on the index gives as long as
/// they stay inside the region (a ray's whole length, a distance's whole search square): every
/// wall they could meet is here. A simulator keeps one and gathers into it each step, so that
/// nothing is allocated, cleared or copied per step.
#[derive(Debug, Clone)]
pub struct NearbyWalls {
    /// Set when the region held more walls than `CAPACITY`: every query goes to `index`.
    overflow: bool,
    /// Walls kept, as indices into `index`.
    walls: [u32; CAPACITY],
    count: usize,
    /// Axis-aligned walls: min x, min y, max x, max y, reflectance and index, in `aligned` slots.
    aligned_boxes: [[f32; 4]; CAPACITY],
    aligned_reflectance: [f32; CAPACITY],
    aligned_wall: [u32; CAPACITY],
    aligned: usize,
    /// Rotated walls, as indices into `index`.
    rotated: [u32; CAPACITY],
    rotated_count: usize,
}

impl Default for NearbyWalls {
    fn default() -> Self {
        Self {
            overflow: false,
            walls: [0; CAPACITY],
            count: 0,
            aligned_boxes: [[0.0; 4]; CAPACITY],
            aligned_reflectance: [0.0; CAPACITY],
            aligned_wall: [0; CAPACITY],
            aligned: 0,
            rotated: [0; CAPACITY],
            rotated_count: 0,
        }
    }
}

impl NearbyWalls {
    /// Replaces the contents with the walls of `index` whose bounding boxes meet the square of
    /// half side `reach` around `center`.
    pub fn gather(&mut self, index: &WallIndex, center: [f32; 2], reach: f32) {
        self.overflow = false;
        self.count = 0;
        self.aligned = 0;
        self.rotated_count = 0;
        let lo = [center[0] - reach, center[1] - reach];
        let hi = [center[0] + reach, center[1] + reach];
        let meets = |i: usize| {
            let [x0, y0, x1, y1] = index.bounding_box(i);
            !(x0 > hi[0] || y0 > hi[1] || x1 < lo[0] || y1 < lo[1])
        };
        if let Some(list) = index.walls_around(center, reach) {
            for &i in list {
                if meets(i as usize) {
                    self.keep(index, i as usize);
                }
            }
            return;
        }
        let region = Bounds {
            min: [lo[0] as f64, lo[1] as f64],
            max: [hi[0] as f64, hi[1] as f64],
        };
        index.for_each_near(region, |i| {
            // A wall spanning several bins is listed in each of them.
            if meets(i) && !self.walls[..self.count].contains(&(i as u32)) {
                self.keep(index, i);
            }
        });
    }

    /// Adds wall `i` of `index` (or notes the overflow).
    #[inline]
    fn keep(&mut self, index: &WallIndex, i: usize) {
        let near = self;
        {
            if near.overflow {
                return;
            }
            if near.count == CAPACITY {
                near.overflow = true;
                return;
            }
            near.walls[near.count] = i as u32;
            near.count += 1;
            match index.aligned_box(i) {
                Some(b) => {
                    near.aligned_boxes[near.aligned] = b;
                    near.aligned_reflectance[near.aligned] = index.reflectance(i);
                    near.aligned_wall[near.aligned] = i as u32;
                    near.aligned += 1;
                }
                None => {
                    near.rotated[near.rotated_count] = i as u32;
                    near.rotated_count += 1;
                }
            }
        }
    }

    /// The nearest wall along the ray from `origin` in the unit direction `dir`, up to
    /// `max_distance`, as `index.cast_ray` finds it (`index` the one gathered from; the ray must
    /// lie inside the region).
    pub fn cast_ray(
        &self,
        index: &WallIndex,
        origin: [f32; 2],
        dir: [f32; 2],
        max_distance: f32,
    ) -> Option<RayHit> {
        if self.overflow {
            return index.cast_ray(origin, dir, max_distance);
        }
        let slab = SlabRay::new(origin, dir);
        let mut best = Nearest::new(max_distance);
        for k in 0..self.aligned {
            if let Some(t) = slab.hit(&self.aligned_boxes[k], best.limit()) {
                best.offer(t, self.aligned_wall[k], self.aligned_reflectance[k]);
            }
        }
        for &i in &self.rotated[..self.rotated_count] {
            let i = i as usize;
            if let Some(t) = index.cast_rotated(i, origin, dir, best.limit()) {
                best.offer(t, i as u32, index.reflectance(i));
            }
        }
        best.hit()
    }

    /// Signed distance from `p` to the nearest wall surface within `search` metres, as
    /// `index.signed_distance` gives it (the square of side `2 search` around `p` must lie inside
    /// the region).
    pub fn signed_distance(&self, index: &WallIndex, p: [f32; 2], search: f32) -> f32 {
        if self.overflow {
            return index.signed_distance(p, search);
        }
        let mut best = search;
        for &i in &self.walls[..self.count] {
            let signed = index.wall_distance(i as usize, p);
            if signed < best {
                best = signed;
            }
        }
        best
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::WallBox;

    /// A few axis-aligned and rotated walls around the origin.
    fn index() -> WallIndex {
        let mut walls = Vec::new();
        for k in 0..6 {
            let a = k as f64 * 0.9;
            walls.push(WallBox {
                center: [0.3 * a.cos(), 0.3 * a.sin()],
                half: [0.005, 0.1],
                yaw: if k % 2 == 0 { 0.0 } else { a },
                reflectance: 0.2 + 0.1 * k as f64,
            });
        }
        walls.push(WallBox {
            center: [0.0, -0.2],
            half: [0.4, 0.005],
            yaw: std::f64::consts::FRAC_PI_2 * 2.0,
            reflectance: 1.0,
        });
        WallIndex::new(&walls)
    }

    #[test]
    fn gathered_walls_answer_as_the_index() {
        let w = index();
        let mut near = NearbyWalls::default();
        near.gather(&w, [0.0, 0.0], 0.5);
        for k in 0..360 {
            let a = (k as f32).to_radians();
            let dir = [a.cos(), a.sin()];
            for origin in [[0.0, 0.0], [0.05, -0.02], [0.3, 0.0], [-0.1, 0.12]] {
                assert_eq!(
                    near.cast_ray(&w, origin, dir, 0.35),
                    w.cast_ray(origin, dir, 0.35),
                    "ray {k} from {origin:?}"
                );
            }
        }
        for p in [[0.0, 0.0], [0.29, 0.02], [0.1, -0.19], [-0.2, 0.2]] {
            assert_eq!(near.signed_distance(&w, p, 0.1), w.signed_distance(p, 0.1));
        }
    }

    #[test]
    fn neighbourhood_lists_give_the_walls_the_bins_give() {
        // Small squares (answered from the neighbourhood lists) all over the walls.
        let w = index();
        for k in 0..400 {
            let center = [(k % 20) as f32 * 0.04 - 0.4, (k / 20) as f32 * 0.04 - 0.4];
            if center[0].abs() <= 0.2 && center[1].abs() <= 0.2 {
                assert!(w.walls_around(center, 0.104).is_some());
            }
            let mut near = NearbyWalls::default();
            near.gather(&w, center, 0.104);
            for a in 0..16 {
                let a = a as f32 * 0.4;
                let origin = [center[0] + 0.03 * a.cos(), center[1] + 0.03 * a.sin()];
                let dir = [a.cos(), a.sin()];
                assert_eq!(
                    near.cast_ray(&w, origin, dir, 0.07),
                    w.cast_ray(origin, dir, 0.07)
                );
            }
            assert_eq!(
                near.signed_distance(&w, center, 0.067),
                w.signed_distance(center, 0.067)
            );
        }
    }
}
