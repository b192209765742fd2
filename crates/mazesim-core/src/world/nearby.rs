//! The walls near a robot, gathered once per step from the bin grid and then queried by all its
//! sensor rays and by the clearance check, instead of walking the bins once per query.

use super::binning::{self, BinLists, Grid};
use super::geometry::Bounds;
use super::walls::{next_up, Nearest, RayHit, SlabBox, SlabLanes, SlabRay, WallIndex, LANES};

/// At most this many walls are kept; a region crowded with more is answered by the full index.
const CAPACITY: usize = 32;

/// Side of the cells of the neighbourhood lists (metres). A square of half side up to this (less
/// 1 mm for rounding) around a point of a cell lies within the 3 x 3 cells around that cell; the
/// e-puck's rays and clearance search reach 0.104 m.
const NEIGHBOURHOOD: f64 = 0.11;

/// At most this many cells: very large worlds get larger cells.
const MAX_CELLS: f64 = 65_536.0;

/// Half side (metres) of the squares the wide neighbourhood lists answer: a Sharp
/// GP2Y0A41SK0F's 0.40 m ray from a body's rim, with room for a perturbed mounting.
pub(super) const WIDE_REACH: f64 = 0.5;

/// Cells a wall is listed beyond those it spans in the wide lists: cells of `WIDE_REACH / 8`,
/// so that a list holds little more than the walls of the widest square it answers.
const WIDE_BEYOND: usize = 8;

/// For each cell of a grid, the walls whose bounding boxes meet the block of cells around it
/// (`beyond` cells on every side), in index order: the candidates of any square query of half
/// side below `beyond` cell sides, with no duplicates to weed out.
#[derive(Debug, Clone, Default)]
pub(super) struct Neighbourhoods {
    lists: BinLists,
    /// The largest half side of a query the lists answer, metres.
    covers: f64,
}

impl Neighbourhoods {
    /// Lists of the 3 x 3 cells around each cell for the walls of bounding `boxes` (min x, min
    /// y, max x, max y), all within `bounds`: the e-puck's rays and clearance search.
    pub(super) fn new(boxes: &[[f32; 4]], bounds: Bounds) -> Self {
        Self::with_block(boxes, bounds, NEIGHBOURHOOD, 1)
    }

    /// Lists that answer squares of half side up to [`WIDE_REACH`] (less 1 mm), such as the
    /// Sharp sensors' rays, for the same walls.
    pub(super) fn wide(boxes: &[[f32; 4]], bounds: Bounds) -> Self {
        Self::with_block(boxes, bounds, WIDE_REACH / WIDE_BEYOND as f64, WIDE_BEYOND)
    }

    /// Lists of cells of `side` (or larger for very large worlds), each wall listed `beyond`
    /// cells beyond those it spans.
    fn with_block(boxes: &[[f32; 4]], bounds: Bounds, side: f64, beyond: usize) -> Self {
        let w = bounds.max[0] - bounds.min[0];
        let h = bounds.max[1] - bounds.min[1];
        let origin = bounds.min;
        let grid = |side: f64| ((w / side) as usize + 1, (h / side) as usize + 1);
        // A wall is listed `beyond` cells beyond those it spans on every side, and 1 mm more.
        let margin = 1e-3;
        let side =
            binning::fitting_side(side.max((w * h / MAX_CELLS).sqrt()), boxes.len(), |side| {
                let listed = boxes.iter().map(|b| {
                    let [x0, y0, x1, y1] = b.map(|v| v as f64);
                    let b = Bounds {
                        min: [x0, y0],
                        max: [x1, y1],
                    };
                    b.grown(beyond as f64 * side + margin)
                });
                binning::entries(listed, origin, side, grid(side))
            });
        let (cols, rows) = grid(side);
        // A point's square meets the box only if the point's cell lies at most `beyond` cells
        // beyond the cells the box spans; 1 mm more covers rounding (a wall too many costs a box
        // test, one missing would be wrong).
        let cell = |v: f64, o: f64| ((v - o) / side).floor() as i64;
        let k = beyond as i64;
        let spans = |_| {
            (0u32..).zip(boxes).map(move |(i, b)| {
                let [x0, y0, x1, y1] = b.map(|v| v as f64);
                let c0 = (cell(x0 - margin, origin[0]) - k).max(0) as usize;
                let r0 = (cell(y0 - margin, origin[1]) - k).max(0) as usize;
                let c1 = ((cell(x1 + margin, origin[0]) + k).max(0) as usize).min(cols - 1);
                let r1 = ((cell(y1 + margin, origin[1]) + k).max(0) as usize).min(rows - 1);
                (i, [c0, r0, c1, r1])
            })
        };
        Self {
            lists: BinLists::new(Grid::new(origin, side, (cols, rows)), spans),
            covers: beyond as f64 * side - 1e-3,
        }
    }

    /// Bytes of its buffers on the heap.
    pub(super) fn heap_bytes(&self) -> usize {
        self.lists.heap_bytes()
    }

    /// The list of the cell holding `p`, if the square of half side `reach` around `p` stays in
    /// its block and `p` lies on the grid.
    pub(super) fn around(&self, p: [f32; 2], reach: f32) -> Option<&[u32]> {
        let grid = self.lists.grid;
        if grid.cols == 0 || reach as f64 > self.covers {
            return None;
        }
        let cell = grid.bin_at([p[0] as f64, p[1] as f64])?;
        Some(self.lists.list(cell))
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
    /// Axis-aligned walls as boxes, in `aligned` slots in increasing wall index.
    boxes: [SlabBox; CAPACITY],
    aligned: usize,
    /// Rotated walls, as indices into `index`.
    rotated: [u32; CAPACITY],
    rotated_count: usize,
    /// Every wall kept is an axis-aligned box with min <= max, and none overflowed: `cast_fan`
    /// may cast all rays of a group together with `SlabLanes`.
    slabs_only: bool,
}

impl Default for NearbyWalls {
    fn default() -> Self {
        Self {
            overflow: false,
            walls: [0; CAPACITY],
            count: 0,
            boxes: [SlabBox::default(); CAPACITY],
            aligned: 0,
            rotated: [0; CAPACITY],
            rotated_count: 0,
            slabs_only: false,
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
            // In index order: so are the axis-aligned walls kept.
            for &i in list {
                if meets(i as usize) {
                    self.keep(index, i as usize);
                }
            }
        } else {
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
            self.sort_aligned();
        }
        self.slabs_only = !self.overflow && self.rotated_count == 0 && index.aligned_ordered();
    }

    /// Reads what `gather` around `center` will read first (the neighbourhood list and the walls'
    /// bounding boxes), so that a batch can bring several environments' walls into cache at once.
    pub fn warm(index: &WallIndex, center: [f32; 2], reach: f32) {
        if let Some(list) = index.walls_around(center, reach) {
            let mut sum = 0.0f32;
            for &i in list {
                sum += index.bounding_box(i as usize)[0];
            }
            std::hint::black_box(sum);
        }
    }

    /// Puts the axis-aligned walls in increasing wall index (they came in bin order).
    fn sort_aligned(&mut self) {
        self.boxes[..self.aligned].sort_unstable_by_key(|b| b.wall);
    }

    /// Adds wall `i` of `index` (or notes the overflow).
    #[inline]
    fn keep(&mut self, index: &WallIndex, i: usize) {
        // Once full, the count stays at `CAPACITY`: every later wall lands here too.
        let count = self.count;
        if count >= CAPACITY {
            self.overflow = true;
            return;
        }
        self.walls[count] = i as u32;
        self.count = count + 1;
        match index.aligned_box(i) {
            Some(bounds) => {
                self.boxes[self.aligned] = SlabBox {
                    bounds,
                    reflectance: index.reflectance(i),
                    wall: i as u32,
                };
                self.aligned += 1;
            }
            None => {
                self.rotated[self.rotated_count] = i as u32;
                self.rotated_count += 1;
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
        for b in &self.boxes[..self.aligned] {
            if let Some(t) = slab.hit(&b.bounds, best.limit()) {
                best.offer(t, b.wall, b.reflectance);
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

    /// The nearest wall along each ray of `fan` for the frame at `at` with heading `heading` (sine
    /// and cosine of its yaw), into `hits` in the fan's order (`hits` holds one per ray): for a
    /// ray of position `p`, direction `d` and length `r` in the frame, `cast_ray` from
    /// `[x + c p0 - s p1, y + s p0 + c p1]` along `[c d0 - s d1, s d0 + c d1]` up to `r`, bit for
    /// bit. The rays must lie inside the region.
    ///
    /// When every wall kept is an axis-aligned box, each group of the fan meets all the boxes
    /// in one pass (`SlabLanes`); otherwise its rays are cast one by one.
    pub fn cast_fan(
        &self,
        index: &WallIndex,
        fan: &RayFan,
        at: [f32; 2],
        heading: [f32; 2],
        hits: &mut [Option<RayHit>],
    ) {
        assert_eq!(hits.len(), fan.len, "one hit slot per ray of the fan");
        if !(self.slabs_only && fan.finite) {
            self.cast_fan_one_by_one(index, fan, at, heading, hits);
            return;
        }
        let boxes = &self.boxes[..self.aligned];
        if boxes.is_empty() {
            // Nothing near (as often between corridor walls): no ray meets anything.
            hits.fill(None);
            return;
        }
        for (group, hits) in fan.groups.iter().zip(hits.chunks_mut(LANES)) {
            let (origin, dir) = group.place(at, heading);
            let bound = group.bound;
            let (distance, reflectance) = SlabLanes::new(origin, dir).nearest(boxes, bound);
            for (l, hit) in hits.iter_mut().enumerate() {
                *hit = (distance[l] < bound[l]).then_some(RayHit {
                    distance: distance[l],
                    reflectance: reflectance[l],
                });
            }
        }
    }

    /// `cast_fan` by `cast_ray` for each ray.
    #[inline(never)]
    fn cast_fan_one_by_one(
        &self,
        index: &WallIndex,
        fan: &RayFan,
        at: [f32; 2],
        heading: [f32; 2],
        hits: &mut [Option<RayHit>],
    ) {
        for (group, hits) in fan.groups.iter().zip(hits.chunks_mut(LANES)) {
            let (origin, dir) = group.place(at, heading);
            for (l, hit) in hits.iter_mut().enumerate() {
                let (o, d) = ([origin[0][l], origin[1][l]], [dir[0][l], dir[1][l]]);
                *hit = self.cast_ray(index, o, d, group.range[l]);
            }
        }
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

/// Rays fixed to a moving frame, such as a robot's distance sensors, kept in groups of `LANES`
/// (the last one padded) to be cast together by `NearbyWalls::cast_fan`.
#[derive(Debug, Clone)]
pub struct RayFan {
    groups: Vec<FanGroup>,
    /// Number of rays (the rest of the last group is padding).
    len: usize,
    /// Every ray's length is finite, so that `bound` is defined.
    finite: bool,
}

/// `LANES` rays of a fan as structure of arrays.
#[derive(Debug, Clone, Copy)]
struct FanGroup {
    /// Position x and y in the frame per lane.
    position: [[f32; LANES]; 2],
    /// Unit direction x and y in the frame per lane.
    direction: [[f32; LANES]; 2],
    /// Length per lane.
    range: [f32; LANES],
    /// Per lane, the least f32 above the length (`next_up`): a hit counts when nearer than this.
    /// Padding lanes: negative infinity, no hit.
    bound: [f32; LANES],
}

impl FanGroup {
    /// The rays' origins and directions (x, y per lane) for the frame at `at` with heading
    /// `heading` (sine and cosine of its yaw).
    #[inline(always)]
    fn place(&self, at: [f32; 2], heading: [f32; 2]) -> ([[f32; LANES]; 2], [[f32; LANES]; 2]) {
        let [x, y] = at;
        let [s, c] = heading;
        let [px, py] = &self.position;
        let [dx, dy] = &self.direction;
        let mut origin = [[0.0; LANES]; 2];
        let mut dir = [[0.0; LANES]; 2];
        for l in 0..LANES {
            origin[0][l] = x + c * px[l] - s * py[l];
            origin[1][l] = y + s * px[l] + c * py[l];
            dir[0][l] = c * dx[l] - s * dy[l];
            dir[1][l] = s * dx[l] + c * dy[l];
        }
        (origin, dir)
    }
}

impl RayFan {
    /// The rays `[position x, position y, direction x, direction y, length]` in the frame
    /// (unit directions).
    pub fn new(rays: &[[f32; 5]]) -> Self {
        let groups = rays
            .chunks(LANES)
            .map(|chunk| {
                let mut g = FanGroup {
                    position: [[0.0; LANES]; 2],
                    direction: [[1.0; LANES], [0.0; LANES]],
                    range: [0.0; LANES],
                    bound: [f32::NEG_INFINITY; LANES],
                };
                for (l, &[px, py, dx, dy, range]) in chunk.iter().enumerate() {
                    g.position[0][l] = px;
                    g.position[1][l] = py;
                    g.direction[0][l] = dx;
                    g.direction[1][l] = dy;
                    g.range[l] = range;
                    if range.is_finite() {
                        g.bound[l] = next_up(range);
                    }
                }
                g
            })
            .collect();
        Self {
            groups,
            len: rays.len(),
            finite: rays.iter().all(|r| r[4].is_finite()),
        }
    }

    /// Bytes of its buffers on the heap (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        crate::footprint::vec_bytes(&self.groups)
    }

    /// Number of rays.
    pub fn len(&self) -> usize {
        self.len
    }

    /// True when the fan has no rays.
    pub fn is_empty(&self) -> bool {
        self.len == 0
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

    /// Axis-aligned walls only, with exact binary coordinates: walls 0 and 1 are the same box
    /// (every hit on it a tie), wall 6 shares their face x = 0.1875 and reaches farther down (ties
    /// for rays through it, and it comes first in bin order), wall 2 continues wall 0 upwards,
    /// wall 3 is turned a quarter, wall 4 half a turn.
    fn aligned_index() -> WallIndex {
        let wall = |center: [f64; 2], half: [f64; 2], yaw: f64, reflectance: f64| WallBox {
            center,
            half,
            yaw,
            reflectance,
        };
        let quarter = std::f64::consts::FRAC_PI_2;
        WallIndex::new(&[
            wall([0.25, 0.0], [0.0625, 0.125], 0.0, 0.5),
            wall([0.25, 0.0], [0.0625, 0.125], 0.0, 0.9),
            wall([0.25, 0.25], [0.0625, 0.125], 0.0, 0.7),
            wall([-0.25, 0.125], [0.125, 0.03125], quarter, 0.3),
            wall([0.0, -0.3125], [0.375, 0.0078125], 2.0 * quarter, 1.0),
            wall([-0.0625, -0.125], [0.03125, 0.03125], 0.0, 0.2),
            wall([0.21875, -0.15625], [0.03125, 0.21875], 0.0, 0.1),
        ])
    }

    /// Casts `rays` (position, direction, length in the frame) with `cast_fan` and checks each
    /// against `index.cast_ray` from the documented world origin and direction, bit for bit;
    /// returns the hits.
    fn check_fan(
        index: &WallIndex,
        near: &NearbyWalls,
        rays: &[[f32; 5]],
        at: [f32; 2],
        heading: [f32; 2],
    ) -> Vec<Option<RayHit>> {
        let fan = RayFan::new(rays);
        assert_eq!(fan.len(), rays.len());
        let mut hits = vec![None; rays.len()];
        near.cast_fan(index, &fan, at, heading, &mut hits);
        let ([x, y], [s, c]) = (at, heading);
        for (&[px, py, dx, dy, range], hit) in rays.iter().zip(&hits) {
            let origin = [x + c * px - s * py, y + s * px + c * py];
            let dir = [c * dx - s * dy, s * dx + c * dy];
            let expected = index.cast_ray(origin, dir, range);
            let bits =
                |h: Option<RayHit>| h.map(|h| (h.distance.to_bits(), h.reflectance.to_bits()));
            assert_eq!(
                bits(*hit),
                bits(expected),
                "ray from {origin:?} along {dir:?} up to {range}"
            );
        }
        hits
    }

    /// Directions with zero components of both signs, diagonals and a sweep of angles.
    fn directions() -> Vec<[f32; 2]> {
        let h = std::f32::consts::FRAC_1_SQRT_2;
        let mut dirs = vec![
            [1.0, 0.0],
            [-1.0, 0.0],
            [0.0, 1.0],
            [0.0, -1.0],
            [1.0, -0.0],
            [-1.0, -0.0],
            [-0.0, 1.0],
            [-0.0, -1.0],
            [h, h],
            [-h, h],
            [h, -h],
            [-h, -h],
        ];
        dirs.extend((0..72).map(|k| {
            let a = (k as f32 * 5.0 + 0.5).to_radians();
            [a.cos(), a.sin()]
        }));
        dirs
    }

    #[test]
    fn fan_cast_together_answers_as_the_index_bit_for_bit() {
        let w = aligned_index();
        let mut near = NearbyWalls::default();
        // Larger than a neighbourhood: gathered from the bins, then put in index order.
        near.gather(&w, [0.0, 0.0], 0.9);
        assert!(near.slabs_only && near.aligned == 7);
        assert!(near.walls[..near.count].windows(2).any(|p| p[0] > p[1]));
        // Origins on a grid (some inside walls, some on their faces and edges) and on corners.
        let mut origins: Vec<[f32; 2]> = (0..15 * 15)
            .map(|k| [(k % 15) as f32 * 0.05 - 0.35, (k / 15) as f32 * 0.05 - 0.35])
            .collect();
        origins.extend([
            [0.0, 0.0],
            [0.0, 0.125],
            [0.1875, 0.0],
            [0.3125, 0.125],
            [0.1875, -0.125],
            [-0.0625, -0.125],
            [-0.09375, -0.15625],
        ]);
        // Lengths: none, exactly the distance from the origin to wall 0's face, and more.
        let ranges = [0.0, 0.1875, 0.2, 0.35];
        let mut rays = Vec::new();
        for o in &origins {
            for (k, d) in directions().iter().enumerate() {
                rays.push([o[0], o[1], d[0], d[1], ranges[k % ranges.len()]]);
                rays.push([o[0], o[1], d[0], d[1], 0.35]);
            }
        }
        // Rays aimed at the walls' corners: entry and exit within rounding of each other.
        let corners: Vec<[f32; 2]> = near.boxes[..near.aligned]
            .iter()
            .flat_map(|b| {
                let [x0, y0, x1, y1] = b.bounds;
                [[x0, y0], [x0, y1], [x1, y0], [x1, y1]]
            })
            .collect();
        for o in origins.iter().step_by(3) {
            for c in &corners {
                let (dx, dy) = (c[0] - o[0], c[1] - o[1]);
                let n = (dx * dx + dy * dy).sqrt();
                if n > 0.0 {
                    rays.push([o[0], o[1], dx / n, dy / n, 0.5]);
                }
            }
        }
        // Identity poses (world rays are the frame's; with a sine of +0 or -0 a zero component
        // keeps one sign or the other), then turned ones; 13 rays a fan: a full group and a
        // padded one.
        let mut hits = 0;
        for chunk in rays.chunks(13) {
            for heading in [[0.0, 1.0], [-0.0, 1.0]] {
                let found = check_fan(&w, &near, chunk, [0.0, 0.0], heading);
                hits += found.iter().flatten().count();
            }
        }
        for (k, chunk) in rays.chunks(13).enumerate().step_by(7) {
            let a = k as f32 * 0.37;
            let (s, c) = a.sin_cos();
            let at = [0.01 * s, -0.02 * c];
            let short: Vec<[f32; 5]> = chunk
                .iter()
                .map(|r| [r[0], r[1], r[2], r[3], 0.3])
                .collect();
            check_fan(&w, &near, &short, at, [s, c]);
        }
        assert!(hits > 1000, "{hits} hits");
        // Ties: walls 0, 1 and 6 are met at once, and wall 0 comes first.
        let along = |o: [f32; 2], range| {
            check_fan(
                &w,
                &near,
                &[[o[0], o[1], 1.0, 0.0, range]],
                [0.0, 0.0],
                [0.0, 1.0],
            )[0]
        };
        assert_eq!(
            along([0.0, 0.0], 0.1875),
            Some(RayHit {
                distance: 0.1875,
                reflectance: 0.5
            })
        );
        // From inside: at once.
        assert_eq!(along([0.25, 0.0], 0.35).unwrap().distance, 0.0);
    }

    #[test]
    fn fan_cast_in_a_neighbourhood_answers_as_the_index() {
        let w = aligned_index();
        let rays: Vec<[f32; 5]> = directions()
            .iter()
            .map(|d| [0.02 * d[1], -0.02 * d[0], d[0], d[1], 0.07])
            .collect();
        let mut hits = 0;
        for k in 0..400 {
            let center = [(k % 20) as f32 * 0.04 - 0.4, (k / 20) as f32 * 0.04 - 0.4];
            let mut near = NearbyWalls::default();
            near.gather(&w, center, 0.104);
            let a = k as f32 * 0.1;
            let found = check_fan(&w, &near, &rays, center, [a.sin(), a.cos()]);
            hits += found.iter().flatten().count();
        }
        assert!(hits > 1000, "{hits} hits");
    }

    #[test]
    fn fan_cast_one_by_one_answers_as_the_index() {
        // Rotated walls among them.
        let w = index();
        let mut near = NearbyWalls::default();
        near.gather(&w, [0.0, 0.0], 0.5);
        assert!(!near.slabs_only);
        let rays: Vec<[f32; 5]> = directions()
            .iter()
            .map(|d| [0.03 * d[0], 0.03 * d[1], d[0], d[1], 0.3])
            .collect();
        for k in 0..20 {
            let a = k as f32 * 0.3;
            check_fan(&w, &near, &rays, [0.01 * k as f32, 0.0], [a.sin(), a.cos()]);
        }
        // Too many walls: the full index answers.
        let crowd: Vec<WallBox> = (0..40)
            .map(|k| WallBox {
                center: [(k % 8) as f64 * 0.05 - 0.2, (k / 8) as f64 * 0.05 - 0.1],
                half: [0.01, 0.01],
                yaw: 0.0,
                reflectance: 0.5,
            })
            .collect();
        let w = WallIndex::new(&crowd);
        near.gather(&w, [0.0, 0.0], 0.3);
        assert!(near.overflow && !near.slabs_only);
        let found = check_fan(&w, &near, &rays, [0.0, 0.0], [0.0, 1.0]);
        assert!(found.iter().flatten().count() > 10);
        // A wall of negative size (min above max): not for the lanes, cast one by one.
        let odd = WallIndex::new(&[WallBox {
            center: [0.1, 0.0],
            half: [-0.02, 0.05],
            yaw: 0.0,
            reflectance: 0.5,
        }]);
        near.gather(&odd, [0.0, 0.0], 0.3);
        assert!(!near.slabs_only);
        check_fan(&odd, &near, &rays, [0.0, 0.0], [0.0, 1.0]);
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

    #[test]
    fn wide_lists_give_the_sharp_sensors_the_walls_the_bins_give() {
        // Squares of the seed robot's reach (0.40 m Sharp rays from its rim) over a maze.
        let world = crate::generator::generate(&Default::default(), 7).unwrap();
        let w = world.wall_index();
        let reach = 0.45;
        for k in 0..400 {
            let center = [(k % 20) as f32 * 0.07 - 0.1, (k / 20) as f32 * 0.07 - 0.1];
            let mut near = NearbyWalls::default();
            near.gather(w, center, reach);
            // What the bins give, each wall once, in index order.
            let lo = [center[0] - reach, center[1] - reach];
            let hi = [center[0] + reach, center[1] + reach];
            let mut expected = Vec::new();
            let region = Bounds {
                min: [lo[0] as f64, lo[1] as f64],
                max: [hi[0] as f64, hi[1] as f64],
            };
            w.for_each_near(region, |i| {
                let [x0, y0, x1, y1] = w.bounding_box(i);
                let meets = !(x0 > hi[0] || y0 > hi[1] || x1 < lo[0] || y1 < lo[1]);
                if meets && !expected.contains(&(i as u32)) {
                    expected.push(i as u32);
                }
            });
            expected.sort_unstable();
            let on_grid = (0.0..=1.25).contains(&center[0]) && (0.0..=1.25).contains(&center[1]);
            if on_grid {
                assert!(w.walls_around(center, reach).is_some(), "{center:?}");
            }
            assert!(!near.overflow);
            let mut kept = near.walls[..near.count].to_vec();
            kept.sort_unstable();
            assert_eq!(kept, expected, "{center:?}");
            for a in 0..16 {
                let a = a as f32 * 0.4;
                let origin = [center[0] + 0.037 * a.cos(), center[1] + 0.037 * a.sin()];
                let dir = [a.cos(), a.sin()];
                assert_eq!(
                    near.cast_ray(w, origin, dir, 0.4),
                    w.cast_ray(origin, dir, 0.4)
                );
            }
        }
    }
}
