//! Static walls indexed for the sensors: ray casts and distance queries against only the walls
//! near the query, found through a uniform bin grid. Axis-aligned walls (every cell maze's) are
//! cast against with a slab test here; rotated ones through parry2d.

use std::sync::OnceLock;

use parry2d::math::{Pose, Vector};
use parry2d::query::{Ray, RayCast};
use parry2d::shape::Cuboid;

use super::binning::BinLists;
use super::geometry::{Bounds, WallBox};
use super::nearby::{Neighbourhoods, WIDE_REACH};

/// The walls of a world as parry2d shapes with a bin index.
#[derive(Debug, Clone)]
pub struct WallIndex {
    shapes: Vec<(Cuboid, Pose)>,
    /// Per wall: centre x, centre y, cos yaw, sin yaw, half x, half y (for distance queries).
    frames: Vec<[f32; 6]>,
    /// Per wall: its bounding box (min x, min y, max x, max y), to skip walls a ray cannot meet.
    boxes: Vec<[f32; 4]>,
    /// Per wall: the wall itself as an axis-aligned box (min x, min y, max x, max y) when it is
    /// one (yaw a multiple of 90 degrees, as in every cell maze), cast against with `SlabRay::hit`.
    aligned: Vec<Option<[f32; 4]>>,
    /// Every box of `aligned` has min <= max on both axes (as a wall of non-negative size does),
    /// as `SlabLanes` needs.
    aligned_ordered: bool,
    reflectance: Vec<f32>,
    /// The walls listed in every bin their bounds (grown by 0.1 mm) meet, in index order.
    bins: BinLists,
    /// Per coarser cell, the walls near it, for the sensors' once-per-step gathering.
    around: Neighbourhoods,
    /// The same for the wider squares of long-range sensors (the Sharp sensors' rays), made
    /// when first asked for.
    wide: OnceLock<Box<Neighbourhoods>>,
}

/// What a ray hit.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct RayHit {
    /// Distance along the ray in metres.
    pub distance: f32,
    /// Reflection factor of the wall hit.
    pub reflectance: f32,
}

impl WallIndex {
    /// Indexes `walls`.
    pub fn new(walls: &[WallBox]) -> Self {
        let shapes: Vec<(Cuboid, Pose)> = walls
            .iter()
            .map(|w| {
                (
                    Cuboid::new(Vector::new(w.half[0] as f32, w.half[1] as f32)),
                    Pose::new(
                        Vector::new(w.center[0] as f32, w.center[1] as f32),
                        w.yaw as f32,
                    ),
                )
            })
            .collect();
        let reflectance = walls.iter().map(|w| w.reflectance as f32).collect();
        let frames: Vec<[f32; 6]> = walls
            .iter()
            .map(|w| {
                let (s, c) = w.yaw.sin_cos();
                [
                    w.center[0] as f32,
                    w.center[1] as f32,
                    c as f32,
                    s as f32,
                    w.half[0] as f32,
                    w.half[1] as f32,
                ]
            })
            .collect();
        let boxes: Vec<[f32; 4]> = walls
            .iter()
            .map(|w| {
                let b = w.bounds().grown(1e-4);
                [
                    b.min[0] as f32,
                    b.min[1] as f32,
                    b.max[0] as f32,
                    b.max[1] as f32,
                ]
            })
            .collect();
        let aligned: Vec<Option<[f32; 4]>> = walls
            .iter()
            .map(|w| {
                let quarter = w.yaw / std::f64::consts::FRAC_PI_2;
                let k = quarter.round();
                ((quarter - k).abs() < 1e-9).then(|| {
                    let (hx, hy) = if (k as i64).rem_euclid(2) == 0 {
                        (w.half[0], w.half[1])
                    } else {
                        (w.half[1], w.half[0])
                    };
                    [
                        (w.center[0] - hx) as f32,
                        (w.center[1] - hy) as f32,
                        (w.center[0] + hx) as f32,
                        (w.center[1] + hy) as f32,
                    ]
                })
            })
            .collect();
        let aligned_ordered = aligned
            .iter()
            .flatten()
            .all(|&[x0, y0, x1, y1]| x0 <= x1 && y0 <= y1);
        let bounds = walls.iter().fold(Bounds::EMPTY, |b, w| b.union(w.bounds()));
        // Grown a little so that f32 rounding never drops a wall from a bin it touches.
        let grown = || walls.iter().map(|w| w.bounds().grown(1e-4));
        let (bins, around) = if bounds.is_empty() {
            (BinLists::none(), Neighbourhoods::default())
        } else {
            let around = Neighbourhoods::new(&boxes, bounds);
            (BinLists::over(bounds, grown, false), around)
        };
        Self {
            shapes,
            frames,
            boxes,
            aligned,
            aligned_ordered,
            reflectance,
            bins,
            around,
            wide: OnceLock::new(),
        }
    }

    /// Pairs of walls listed in a common bin (a pair in two bins counts twice): an upper bound
    /// of the pairs of walls whose bounding boxes overlap.
    pub fn crowded_pairs(&self) -> u64 {
        let pairs = self.bins.lengths().map(|k| {
            let k = u64::from(k);
            k * k.saturating_sub(1) / 2
        });
        pairs.fold(0, u64::saturating_add)
    }

    /// The walls whose bounding boxes may meet the square of half side `reach` around `p`, each
    /// once and in index order, when a prepared list holds them all (`None`: use `for_each_near`).
    pub(super) fn walls_around(&self, p: [f32; 2], reach: f32) -> Option<&[u32]> {
        if let Some(list) = self.around.around(p, reach) {
            return Some(list);
        }
        if self.boxes.is_empty() || f64::from(reach) > WIDE_REACH {
            return None;
        }
        self.wide
            .get_or_init(|| {
                let bounds = self
                    .boxes
                    .iter()
                    .fold(Bounds::EMPTY, |b, &[x0, y0, x1, y1]| {
                        b.union(Bounds {
                            min: [x0.into(), y0.into()],
                            max: [x1.into(), y1.into()],
                        })
                    });
                Box::new(Neighbourhoods::wide(&self.boxes, bounds))
            })
            .around(p, reach)
    }

    /// Calls `f` with the index of every wall listed in a bin that meets `b` (a wall listed in
    /// several of those bins comes more than once; callers' tests are cheap and idempotent).
    pub(super) fn for_each_near(&self, b: Bounds, mut f: impl FnMut(usize)) {
        let g = self.bins.grid;
        if g.cols == 0 {
            return;
        }
        let far = b.max[0] < g.origin[0]
            || b.max[1] < g.origin[1]
            || b.min[0] > g.origin[0] + g.cols as f64 * g.side
            || b.min[1] > g.origin[1] + g.rows as f64 * g.side;
        if far {
            return;
        }
        let [c0, r0, c1, r1] = g.span(b);
        for row in r0..=r1 {
            for &i in self.bins.row_lists(row, c0, c1) {
                f(i as usize);
            }
        }
    }

    /// Bytes of its buffers on the heap (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        use crate::footprint::vec_bytes;
        vec_bytes(&self.shapes)
            + vec_bytes(&self.frames)
            + vec_bytes(&self.boxes)
            + vec_bytes(&self.aligned)
            + vec_bytes(&self.reflectance)
            + self.bins.heap_bytes()
            + self.around.heap_bytes()
            + self.wide.get().map_or(0, |wide| {
                std::mem::size_of::<Neighbourhoods>() + wide.heap_bytes()
            })
    }

    /// Number of walls.
    pub fn len(&self) -> usize {
        self.shapes.len()
    }

    /// True when the world has no walls.
    pub fn is_empty(&self) -> bool {
        self.shapes.is_empty()
    }

    /// The nearest wall along the ray from `origin` in the unit direction `dir`, up to `max_distance`
    /// (of walls met at the same distance, the one of lowest index).
    pub fn cast_ray(&self, origin: [f32; 2], dir: [f32; 2], max_distance: f32) -> Option<RayHit> {
        let end = [
            origin[0] + dir[0] * max_distance,
            origin[1] + dir[1] * max_distance,
        ];
        let b = Bounds {
            min: [origin[0].min(end[0]) as f64, origin[1].min(end[1]) as f64],
            max: [origin[0].max(end[0]) as f64, origin[1].max(end[1]) as f64],
        };
        let slab = SlabRay::new(origin, dir);
        let mut best = Nearest::new(max_distance);
        let (lo, hi) = (
            [origin[0].min(end[0]), origin[1].min(end[1])],
            [origin[0].max(end[0]), origin[1].max(end[1])],
        );
        self.for_each_near(b, |i| {
            let [x0, y0, x1, y1] = self.boxes[i];
            if x0 > hi[0] || y0 > hi[1] || x1 < lo[0] || y1 < lo[1] {
                return;
            }
            let toi = match &self.aligned[i] {
                Some(aabb) => slab.hit(aabb, best.limit()),
                None => self.cast_rotated(i, origin, dir, best.limit()),
            };
            if let Some(t) = toi {
                best.offer(t, i as u32, self.reflectance[i]);
            }
        });
        best.hit()
    }

    /// Ray cast against wall `i` (any yaw) through parry2d.
    pub(super) fn cast_rotated(
        &self,
        i: usize,
        origin: [f32; 2],
        dir: [f32; 2],
        limit: f32,
    ) -> Option<f32> {
        let ray = Ray::new(
            Vector::new(origin[0], origin[1]),
            Vector::new(dir[0], dir[1]),
        );
        let (shape, pose) = &self.shapes[i];
        shape.cast_ray(pose, &ray, limit, true)
    }

    /// Wall `i`'s axis-aligned box, when it is one.
    pub(super) fn aligned_box(&self, i: usize) -> Option<[f32; 4]> {
        self.aligned[i]
    }

    /// Whether every axis-aligned wall's box has min <= max on both axes.
    pub(super) fn aligned_ordered(&self) -> bool {
        self.aligned_ordered
    }

    /// Wall `i`'s bounding box (min x, min y, max x, max y), grown by 0.1 mm.
    pub(super) fn bounding_box(&self, i: usize) -> [f32; 4] {
        self.boxes[i]
    }

    /// Wall `i`'s reflection factor.
    pub(super) fn reflectance(&self, i: usize) -> f32 {
        self.reflectance[i]
    }

    /// Signed distance from `p` to wall `i`'s surface (negative inside).
    #[inline]
    pub(super) fn wall_distance(&self, i: usize, p: [f32; 2]) -> f32 {
        let [cx, cy, c, s, hx, hy] = self.frames[i];
        let (dx, dy) = (p[0] - cx, p[1] - cy);
        let qx = (c * dx + s * dy).abs() - hx;
        let qy = (-s * dx + c * dy).abs() - hy;
        let outside = (qx.max(0.0).powi(2) + qy.max(0.0).powi(2)).sqrt();
        outside + qx.max(qy).min(0.0)
    }

    /// Signed distance from `p` to wall `i`'s surface (negative inside) with the unit normal of the
    /// surface nearest `p`, pointing out of the wall: the direction in which the wall pushes a disc
    /// centred at `p`.
    #[inline]
    pub(crate) fn wall_contact(&self, i: usize, p: [f32; 2]) -> (f32, [f32; 2]) {
        let [cx, cy, c, s, hx, hy] = self.frames[i];
        let (dx, dy) = (p[0] - cx, p[1] - cy);
        // `p` in the wall's frame, and its offset beyond each pair of faces.
        let (lx, ly) = (c * dx + s * dy, -s * dx + c * dy);
        let (qx, qy) = (lx.abs() - hx, ly.abs() - hy);
        let (sx, sy) = (1f32.copysign(lx), 1f32.copysign(ly));
        let (distance, [nx, ny]) = if qx > 0.0 || qy > 0.0 {
            let (ox, oy) = (qx.max(0.0), qy.max(0.0));
            let d = (ox * ox + oy * oy).sqrt();
            (d, [sx * ox / d, sy * oy / d])
        } else if qx > qy {
            (qx, [sx, 0.0])
        } else {
            (qy, [0.0, sy])
        };
        (distance, [c * nx - s * ny, s * nx + c * ny])
    }

    /// Calls `f` with every wall whose bounding box may meet the square of half side `reach`
    /// around `p` (a wall may come more than once).
    pub(crate) fn for_each_around(&self, p: [f32; 2], reach: f32, mut f: impl FnMut(usize)) {
        match self.walls_around(p, reach) {
            Some(list) => list.iter().for_each(|&i| f(i as usize)),
            None => {
                let b = Bounds {
                    min: [(p[0] - reach) as f64, (p[1] - reach) as f64],
                    max: [(p[0] + reach) as f64, (p[1] + reach) as f64],
                };
                self.for_each_near(b, f);
            }
        }
    }

    /// Signed distance from `p` to the nearest wall surface within `search` metres
    /// (negative inside a wall); `search` when no wall is that close.
    pub fn signed_distance(&self, p: [f32; 2], search: f32) -> f32 {
        let b = Bounds {
            min: [(p[0] - search) as f64, (p[1] - search) as f64],
            max: [(p[0] + search) as f64, (p[1] + search) as f64],
        };
        let mut best = search;
        self.for_each_near(b, |i| {
            let signed = self.wall_distance(i, p);
            if signed < best {
                best = signed;
            }
        });
        best
    }
}

/// A ray prepared for slab tests against axis-aligned boxes: its origin, the reciprocals of its
/// direction and, per axis, which side of a box it enters by (the classic slab method: the ray is
/// inside the box between the largest entry and the smallest exit parameter over the two axes).
#[derive(Debug, Clone, Copy)]
pub(super) struct SlabRay {
    origin: [f32; 2],
    inv: [f32; 2],
    /// Per axis, whether the ray enters a box by its lower side (it runs towards +x, +y).
    rising: [bool; 2],
}

/// The smaller of two numbers known not to be NaN (a plain comparison, cheaper than `f32::min`).
#[inline]
fn lesser(a: f32, b: f32) -> f32 {
    if a < b {
        a
    } else {
        b
    }
}

/// The larger of two numbers known not to be NaN.
#[inline]
fn greater(a: f32, b: f32) -> f32 {
    if a > b {
        a
    } else {
        b
    }
}

/// The reciprocal of a ray's direction component `d`, as slab tests use it. A component of
/// (almost) zero becomes a tiny one of the same sign: the slab parameters then stay finite (no
/// 0 * infinity, no NaN) and mean "never crosses this slab".
#[inline]
pub(super) fn slab_inverse(d: f32) -> f32 {
    // The magnitude raised to 1e-20 if below (NaN stays) and the sign put back: `d` itself
    // unless it is that small.
    1.0 / greater(1e-20, d.abs()).copysign(d)
}

impl SlabRay {
    /// The ray from `origin` along `dir`.
    #[inline]
    pub(super) fn new(origin: [f32; 2], dir: [f32; 2]) -> Self {
        let inv = dir.map(slab_inverse);
        let rising = [inv[0] > 0.0, inv[1] > 0.0];
        Self {
            origin,
            inv,
            rising,
        }
    }

    /// Distance along the ray to the box `[min x, min y, max x, max y]` if it is met within
    /// `limit`; 0 when the origin lies inside (a solid box, as parry's `solid = true`).
    #[inline]
    pub(super) fn hit(&self, b: &[f32; 4], limit: f32) -> Option<f32> {
        // (side - origin) * inv is monotonic in the side, so the side entered by gives the smaller
        // parameter exactly as a min of both would.
        let [x0, y0, x1, y1] = *b;
        let (in_x, out_x) = if self.rising[0] { (x0, x1) } else { (x1, x0) };
        let (in_y, out_y) = if self.rising[1] { (y0, y1) } else { (y1, y0) };
        let enter_x = (in_x - self.origin[0]) * self.inv[0];
        let leave_x = (out_x - self.origin[0]) * self.inv[0];
        let enter_y = (in_y - self.origin[1]) * self.inv[1];
        let leave_y = (out_y - self.origin[1]) * self.inv[1];
        let near = greater(greater(enter_x, enter_y), 0.0);
        let far = lesser(leave_x, leave_y);
        (near <= far && near <= limit).then_some(near)
    }
}

/// An axis-aligned wall as a box, for slab tests.
#[derive(Debug, Clone, Copy, Default)]
pub(super) struct SlabBox {
    /// Min x, min y, max x, max y.
    pub(super) bounds: [f32; 4],
    /// The wall's reflection factor.
    pub(super) reflectance: f32,
    /// The wall's index.
    pub(super) wall: u32,
}

/// Rays cast together against axis-aligned boxes: a group of this many lanes (two SSE vectors of
/// f32).
pub(super) const LANES: usize = 8;

/// `LANES` rays prepared for slab tests together, as structure of arrays: lane `l` holds what a
/// `SlabRay` holds for one ray, and all lanes meet each box side by side in a loop of fixed width
/// that the compiler turns into vector instructions.
#[derive(Debug, Clone, Copy)]
pub(super) struct SlabLanes {
    /// Origin x and y per lane.
    origin: [[f32; LANES]; 2],
    /// Reciprocal direction x and y per lane (`slab_inverse`).
    inv: [[f32; LANES]; 2],
}

impl SlabLanes {
    /// The rays from `origin` (x, y per lane) along `dir` (x, y per lane).
    #[inline]
    pub(super) fn new(origin: [[f32; LANES]; 2], dir: [[f32; LANES]; 2]) -> Self {
        let mut inv = [[0.0; LANES]; 2];
        for l in 0..LANES {
            inv[0][l] = slab_inverse(dir[0][l]);
            inv[1][l] = slab_inverse(dir[1][l]);
        }
        Self { origin, inv }
    }

    /// Per lane, the nearest of `boxes` (each with min <= max on both axes, in increasing wall
    /// index) met nearer than `bound` (the least f32 above the lane's range) as its distance and
    /// the box's reflectance; `bound` and 0 where none is.
    ///
    /// Bit for bit what `SlabRay::hit` and `Nearest::offer` make of the same boxes:
    /// - a side's parameter `(side - origin) * inv` is monotonic in the side, so with min <= max
    ///   the lesser of a box's two parameters on an axis is the one of the side `SlabRay` picks
    ///   as entered by (ties have equal bits), and the greater the one it leaves by;
    /// - `near < bound` is `near <= limit` (`near` is never NaN);
    /// - only a strictly nearer hit replaces the best, so of hits at equal distances the first,
    ///   of lowest wall index, stays, and a hit at exactly the range counts.
    #[inline]
    pub(super) fn nearest(
        &self,
        boxes: &[SlabBox],
        bound: [f32; LANES],
    ) -> ([f32; LANES], [f32; LANES]) {
        let [ox, oy] = self.origin;
        let [ix, iy] = self.inv;
        let mut best = bound;
        let mut best_reflectance = [0.0; LANES];
        for b in boxes {
            let [x0, y0, x1, y1] = b.bounds;
            let r = b.reflectance;
            for l in 0..LANES {
                let (ax, bx) = ((x0 - ox[l]) * ix[l], (x1 - ox[l]) * ix[l]);
                let (ay, by) = ((y0 - oy[l]) * iy[l], (y1 - oy[l]) * iy[l]);
                let near = greater(greater(lesser(ax, bx), lesser(ay, by)), 0.0);
                let far = lesser(greater(ax, bx), greater(ay, by));
                // Selects, not branches: a miss as an infinite distance, never below `best`
                // (at most `next_up(f32::MAX)`, infinity itself).
                let t = if near <= far { near } else { f32::INFINITY };
                best_reflectance[l] = if t < best[l] { r } else { best_reflectance[l] };
                best[l] = lesser(t, best[l]);
            }
        }
        (best, best_reflectance)
    }
}

/// The least f32 above the finite `x`: a distance `t` has `t <= x` exactly when `t < next_up(x)`.
pub(super) fn next_up(x: f32) -> f32 {
    debug_assert!(x.is_finite());
    if x == 0.0 {
        f32::from_bits(1)
    } else if x > 0.0 {
        f32::from_bits(x.to_bits() + 1)
    } else {
        f32::from_bits(x.to_bits() - 1)
    }
}

/// The nearest hit so far along a ray.
#[derive(Debug, Clone, Copy)]
pub(super) struct Nearest {
    distance: f32,
    reflectance: f32,
    /// Index of the wall hit; `u32::MAX` before any hit.
    wall: u32,
}

impl Nearest {
    /// No hit yet; hits beyond `max_distance` do not count.
    #[inline]
    pub(super) fn new(max_distance: f32) -> Self {
        Self {
            distance: max_distance,
            reflectance: 0.0,
            wall: u32::MAX,
        }
    }

    /// The farthest a hit may be and still count.
    #[inline]
    pub(super) fn limit(&self) -> f32 {
        self.distance
    }

    /// Keeps a hit at `distance` (within `limit`) on wall `wall` if it is nearer than the best so
    /// far; of equal distances the lowest wall index wins, whatever the order walls are offered in.
    #[inline]
    pub(super) fn offer(&mut self, distance: f32, wall: u32, reflectance: f32) {
        if distance < self.distance || (distance == self.distance && wall < self.wall) {
            self.distance = distance;
            self.reflectance = reflectance;
            self.wall = wall;
        }
    }

    /// The hit, if any.
    #[inline]
    pub(super) fn hit(&self) -> Option<RayHit> {
        (self.wall != u32::MAX).then_some(RayHit {
            distance: self.distance,
            reflectance: self.reflectance,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn index() -> WallIndex {
        WallIndex::new(&[
            WallBox {
                center: [1.0, 0.0],
                half: [0.005, 0.5],
                yaw: 0.0,
                reflectance: 0.5,
            },
            WallBox {
                center: [2.0, 0.0],
                half: [0.005, 0.5],
                yaw: 0.0,
                reflectance: 1.0,
            },
        ])
    }

    #[test]
    fn ray_hits_nearest_wall() {
        let w = index();
        let hit = w.cast_ray([0.0, 0.0], [1.0, 0.0], 3.0).unwrap();
        assert!((hit.distance - 0.995).abs() < 1e-5);
        assert_eq!(hit.reflectance, 0.5);
        assert!(w.cast_ray([0.0, 0.0], [1.0, 0.0], 0.5).is_none());
        assert!(w.cast_ray([0.0, 0.0], [-1.0, 0.0], 3.0).is_none());
        let hit = w.cast_ray([1.5, 0.0], [1.0, 0.0], 3.0).unwrap();
        assert_eq!(hit.reflectance, 1.0);
    }

    #[test]
    fn slab_inverse_and_next_up_are_exact() {
        // The reciprocal as first written: the component itself unless below 1e-20 in magnitude.
        let first = |d: f32| {
            let d = if d.abs() < 1e-20 {
                1e-20f32.copysign(d)
            } else {
                d
            };
            1.0 / d
        };
        let tiny = 1e-20f32;
        let specials = [
            0.0,
            -0.0,
            tiny,
            -tiny,
            f32::from_bits(tiny.to_bits() - 1),
            f32::from_bits(tiny.to_bits() + 1),
            f32::from_bits(1),
            -f32::from_bits(1),
            f32::MIN_POSITIVE,
            1.0,
            -1.0,
            0.3,
            f32::MAX,
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
        ];
        for d in specials {
            assert_eq!(slab_inverse(d).to_bits(), first(d).to_bits(), "{d:e}");
        }
        let least = f32::from_bits(1);
        assert_eq!(next_up(0.0).to_bits(), least.to_bits());
        assert_eq!(next_up(-0.0).to_bits(), least.to_bits());
        assert_eq!(next_up(-least).to_bits(), (-0.0f32).to_bits());
        assert_eq!(next_up(least), f32::from_bits(2));
        assert_eq!(next_up(1.0), 1.0 + f32::EPSILON);
        assert_eq!(next_up(-1.0), -1.0 + f32::EPSILON / 2.0);
        assert_eq!(next_up(0.07), f32::from_bits(0.07f32.to_bits() + 1));
        assert_eq!(next_up(f32::MAX), f32::INFINITY);
    }

    #[test]
    fn signed_distance_is_negative_inside() {
        let w = index();
        assert!((w.signed_distance([0.9, 0.0], 0.5) - 0.095).abs() < 1e-5);
        assert!(w.signed_distance([1.0, 0.0], 0.5) < 0.0);
        assert_eq!(w.signed_distance([-3.0, 0.0], 0.2), 0.2);
    }
}
