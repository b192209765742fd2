//! Floor paint: the reflectance of the floor at any point, for the ground sensors.
//!
//! Regions are drawn in order (a later region covers an earlier one). A coarse bin grid keeps a
//! look-up to the few regions near the point.
//!
//! Besides the point-wise look-up, two tests judge a whole area at once, for the ground sensors:
//! whether a disc (a sensor's spot) shows a single paint, and how far around a point the bins
//! hold no region (the floor is bare). Both keep a slack far above the rounding of any coordinate
//! of the floor from every edge they rely on, so that each point of the area reads exactly as the
//! point-wise look-up reads it.

use super::binning::BinLists;
use super::geometry::{Bounds, DiscSide, PaintShape};

/// One painted region.
#[derive(Debug, Clone, PartialEq)]
pub struct PaintRegion {
    /// Where.
    pub shape: PaintShape,
    /// Reflection factor f in (0, 1].
    pub reflectance: f64,
}

/// Regions are listed in every bin they come within this distance of (metres), so that a bin's
/// list serves every point of a sensor spot centred in it (spots are a few millimetres wide).
pub const SPOT_MARGIN: f64 = 0.005;

/// Up to this many bins each way are joined to a point's own by `FloorPaint::bare_box`.
const BARE_BOX_REACH: usize = 8;

/// Metres of slack for every metre of the largest coordinate of a floor: some 4,500 times the
/// relative rounding of an f64, where the tests' arithmetic loses a few roundings at most.
const SLACK_PER_METRE: f64 = 1e-12;

/// The least slack in metres, however small the floor's coordinates.
const LEAST_SLACK: f64 = 1e-9;

/// What a disc of floor shows, as the regions' edges tell.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum DiscPaint<'a> {
    /// Every point of the disc has this reflectance (a region's, or the background).
    Uniform(f64),
    /// An edge may pass through the disc: its points are painted by these candidates (topmost
    /// first) or are bare.
    Mixed(&'a [u32]),
}

/// The painted floor of a world.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorPaint {
    background: f64,
    regions: Vec<PaintRegion>,
    /// Per region: `shape.turn()`, so that a look-up computes no sine or cosine.
    turns: Vec<[f64; 2]>,
    /// The regions listed in every bin their bounds (grown by `SPOT_MARGIN`) meet, topmost first.
    bins: BinLists,
    /// Metres by which the area tests stay clear of the edges they rely on: far above the
    /// rounding of any coordinate of the grid or of a region.
    slack: f64,
}

impl FloorPaint {
    /// Indexes `regions` over a floor of `background` reflectance.
    pub fn new(background: f64, regions: Vec<PaintRegion>) -> Self {
        let turns = regions.iter().map(|r| r.shape.turn()).collect();
        let bounds = regions
            .iter()
            .fold(Bounds::EMPTY, |b, r| b.union(r.shape.bounds()));
        let (bins, slack) = if bounds.is_empty() {
            (BinLists::none(), LEAST_SLACK)
        } else {
            // The grid covers every point within the margin of some paint.
            let covered = bounds.grown(SPOT_MARGIN);
            let grown = || regions.iter().map(|r| r.shape.bounds().grown(SPOT_MARGIN));
            // Topmost first.
            let bins = BinLists::over(covered, grown, true);
            let g = bins.grid;
            // The grid reaches a bin beyond the bounds, and every region lies within them.
            let far = [
                covered.min,
                bounds.max,
                [
                    g.origin[0] + (g.cols as f64 + 1.0) * g.side,
                    g.origin[1] + (g.rows as f64 + 1.0) * g.side,
                ],
            ]
            .iter()
            .flatten()
            .fold(0.0_f64, |m, v| m.max(v.abs()));
            (bins, LEAST_SLACK + far * SLACK_PER_METRE)
        };
        Self {
            background,
            regions,
            turns,
            bins,
            slack,
        }
    }

    /// Bytes of its buffers on the heap (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        use crate::footprint::vec_bytes;
        vec_bytes(&self.regions) + vec_bytes(&self.turns) + self.bins.heap_bytes()
    }

    /// Background reflectance.
    pub fn background(&self) -> f64 {
        self.background
    }

    /// Regions in drawing order.
    pub fn regions(&self) -> &[PaintRegion] {
        &self.regions
    }

    /// The regions that may paint points within `SPOT_MARGIN` of `p`, topmost first.
    pub fn regions_near(&self, p: [f64; 2]) -> &[u32] {
        match self.bins.grid.bin_at(p) {
            Some(bin) => self.bins.list(bin),
            None => &[],
        }
    }

    /// Reflectance at `p` among `candidates` (from `regions_near` of a point within
    /// `SPOT_MARGIN` of `p`).
    #[inline]
    pub fn reflectance_among(&self, candidates: &[u32], p: [f64; 2]) -> f64 {
        for &i in candidates {
            let r = &self.regions[i as usize];
            if r.shape.contains_turned(p, self.turns[i as usize]) {
                return r.reflectance;
            }
        }
        self.background
    }

    /// Reflectance factor of the floor at `p`.
    pub fn reflectance_at(&self, p: [f64; 2]) -> f64 {
        self.reflectance_among(self.regions_near(p), p)
    }

    /// What the disc of `radius` around `at` shows among `candidates` (from `regions_near` of a
    /// point within `SPOT_MARGIN - radius` of `at`): `Uniform` when every point of it reads the
    /// same with `reflectance_among`, otherwise the candidates from the topmost region whose edge
    /// may cross it (those above it paint no point of the disc).
    pub fn disc_paint<'a>(
        &self,
        candidates: &'a [u32],
        at: [f64; 2],
        radius: f64,
    ) -> DiscPaint<'a> {
        let radius = radius + self.slack;
        for (k, &i) in candidates.iter().enumerate() {
            let r = &self.regions[i as usize];
            match r.shape.disc_side(at, radius, self.turns[i as usize]) {
                DiscSide::Inside => return DiscPaint::Uniform(r.reflectance),
                DiscSide::Outside => {}
                DiscSide::Across => return DiscPaint::Mixed(&candidates[k..]),
            }
        }
        DiscPaint::Uniform(self.background)
    }

    /// A box around `p` in which `regions_near` finds no region at any point, or the empty box
    /// when it finds some at `p`. The box joins empty bins around `p`'s, up to `BARE_BOX_REACH`
    /// each way, opens onto the bare floor beyond the grid and keeps the slack from other bins.
    pub fn bare_box(&self, p: [f64; 2]) -> Bounds {
        const WHOLE: Bounds = Bounds {
            min: [f64::NEG_INFINITY; 2],
            max: [f64::INFINITY; 2],
        };
        let g = self.bins.grid;
        if g.cols == 0 {
            return WHOLE;
        }
        if !self.regions_near(p).is_empty() || p[0].is_nan() || p[1].is_nan() {
            return Bounds::EMPTY;
        }
        let f = [(p[0] - g.origin[0]) / g.side, (p[1] - g.origin[1]) / g.side];
        let n = [g.cols, g.rows];
        // Beyond the grid: the half plane on that side of it.
        for axis in 0..2 {
            let mut half = WHOLE;
            if f[axis] < 0.0 {
                half.max[axis] = g.origin[axis] - self.slack;
                return half;
            }
            if f[axis] >= n[axis] as f64 {
                half.min[axis] = g.origin[axis] + n[axis] as f64 * g.side + self.slack;
                return half;
            }
        }
        let (col, row) = (f[0] as usize, f[1] as usize);
        let empty = |c: usize, r: usize| self.bins.list(r * g.cols + c).is_empty();
        // Along the row first, then whole rows of that width down and up.
        let (mut c0, mut c1) = (col, col);
        while c0 > 0 && col - c0 < BARE_BOX_REACH && empty(c0 - 1, row) {
            c0 -= 1;
        }
        while c1 + 1 < g.cols && c1 - col < BARE_BOX_REACH && empty(c1 + 1, row) {
            c1 += 1;
        }
        let (mut r0, mut r1) = (row, row);
        while r0 > 0 && row - r0 < BARE_BOX_REACH && (c0..=c1).all(|c| empty(c, r0 - 1)) {
            r0 -= 1;
        }
        while r1 + 1 < g.rows && r1 - row < BARE_BOX_REACH && (c0..=c1).all(|c| empty(c, r1 + 1)) {
            r1 += 1;
        }
        let mut bare = WHOLE;
        for (axis, first, last) in [(0, c0, c1), (1, r0, r1)] {
            // A side on the grid's edge stays open.
            if first > 0 {
                bare.min[axis] = g.origin[axis] + first as f64 * g.side + self.slack;
            }
            if last + 1 < n[axis] {
                bare.max[axis] = g.origin[axis] + (last + 1) as f64 * g.side - self.slack;
            }
        }
        bare
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn later_regions_cover_earlier_ones() {
        let big = PaintRegion {
            shape: PaintShape::Rect {
                center: [0.0, 0.0],
                half: [1.0, 1.0],
                yaw: 0.0,
            },
            reflectance: 0.5,
        };
        let dot = PaintRegion {
            shape: PaintShape::Circle {
                center: [0.3, 0.3],
                radius: 0.1,
            },
            reflectance: 0.2,
        };
        let floor = FloorPaint::new(1.0, vec![big, dot]);
        assert_eq!(floor.reflectance_at([0.3, 0.3]), 0.2);
        assert_eq!(floor.reflectance_at([-0.5, 0.0]), 0.5);
        assert_eq!(floor.reflectance_at([3.0, 0.0]), 1.0);
        assert_eq!(floor.reflectance_at([-3.0, -3.0]), 1.0);
    }

    /// Scattered codes of bars, a few discs and strokes, over about a metre and a half.
    fn scattered_floor() -> FloorPaint {
        let mut regions = Vec::new();
        for k in 0..7 {
            let yaw = [0.0, std::f64::consts::FRAC_PI_2, 0.4][k % 3];
            let (s, c) = f64::sin_cos(yaw);
            let centre = [0.23 * k as f64 - 0.1, 0.61 * ((k * 5) % 7) as f64 / 4.0];
            for bar in 0..5 {
                let along = (bar as f64 - 2.0) * 0.017;
                regions.push(PaintRegion {
                    shape: PaintShape::Rect {
                        center: [centre[0] + c * along, centre[1] + s * along],
                        half: [0.0085, 0.115],
                        yaw,
                    },
                    reflectance: 0.2,
                });
            }
        }
        regions.push(PaintRegion {
            shape: PaintShape::Circle {
                center: [0.9, 0.3],
                radius: 0.04,
            },
            reflectance: 0.5,
        });
        regions.push(PaintRegion {
            shape: PaintShape::Capsule {
                a: [0.2, 1.2],
                b: [1.1, 0.9],
                radius: 0.01,
            },
            reflectance: 0.5,
        });
        FloorPaint::new(1.0, regions)
    }

    #[test]
    fn bins_list_every_region_whose_grown_bounds_meet_them_topmost_first() {
        let floor = scattered_floor();
        let g = floor.bins.grid;
        for row in 0..g.rows {
            for col in 0..g.cols {
                let x0 = g.origin[0] + col as f64 * g.side;
                let y0 = g.origin[1] + row as f64 * g.side;
                let expected: Vec<u32> = (0..floor.regions.len() as u32)
                    .rev()
                    .filter(|&i| {
                        let b = floor.regions[i as usize].shape.bounds().grown(SPOT_MARGIN);
                        let c0 = ((b.min[0] - g.origin[0]) / g.side).max(0.0) as usize;
                        let c1 = ((b.max[0] - g.origin[0]) / g.side).max(0.0) as usize;
                        let r0 = ((b.min[1] - g.origin[1]) / g.side).max(0.0) as usize;
                        let r1 = ((b.max[1] - g.origin[1]) / g.side).max(0.0) as usize;
                        (c0..=c1).contains(&col) && (r0..=r1).contains(&row)
                    })
                    .collect();
                let middle = [x0 + g.side / 2.0, y0 + g.side / 2.0];
                assert_eq!(
                    floor.regions_near(middle),
                    &expected[..],
                    "bin {col}, {row}"
                );
            }
        }
    }

    #[test]
    fn regions_are_found_from_within_the_margin_beyond_all_paint() {
        // One square of paint: points a little outside each of its sides and corners are within
        // the margin of it, below and left of the paint's own bounds as well as above and right.
        let floor = FloorPaint::new(
            1.0,
            vec![PaintRegion {
                shape: PaintShape::Rect {
                    center: [0.3, 0.2],
                    half: [0.01, 0.01],
                    yaw: 0.0,
                },
                reflectance: 0.2,
            }],
        );
        let gap = 0.8 * SPOT_MARGIN;
        let sides = (-1..=1).flat_map(|dx| (-1..=1).map(move |dy| (dx, dy)));
        for (dx, dy) in sides.filter(|&side| side != (0, 0)) {
            let p = [
                0.3 + dx as f64 * (0.01 + gap / 2.0_f64.sqrt()),
                0.2 + dy as f64 * (0.01 + gap / 2.0_f64.sqrt()),
            ];
            assert_eq!(floor.regions_near(p), &[0], "{p:?}");
            assert!(floor.bare_box(p).is_empty(), "{p:?}");
        }
    }

    #[test]
    fn bare_boxes_hold_no_point_with_regions_near() {
        let floor = scattered_floor();
        let mut rng = crate::rng::Rng::new(0x9e37_79b9_7f4a_7c15);
        let mut uniform = move || rng.uniform();
        let (mut boxes, mut open) = (0, 0);
        for _ in 0..20_000 {
            let p = [uniform() * 2.4 - 0.6, uniform() * 2.4 - 0.6];
            let bare = floor.bare_box(p);
            if !floor.regions_near(p).is_empty() {
                assert!(bare.is_empty());
                continue;
            }
            assert!(bare.contains(p), "{p:?} {bare:?}");
            boxes += 1;
            open += bare.min.iter().chain(&bare.max).any(|v| v.is_infinite()) as usize;
            // Open sides are tried a metre out; the others at their very edge too.
            let lo = bare.min.map(|v| v.max(-2.0));
            let hi = bare.max.map(|v| v.min(3.0));
            for k in 0..40 {
                let t = [uniform(), uniform()];
                let mut q = [
                    lo[0] + t[0] * (hi[0] - lo[0]),
                    lo[1] + t[1] * (hi[1] - lo[1]),
                ];
                if k % 4 == 1 {
                    q[0] = if t[1] < 0.5 { lo[0] } else { hi[0] };
                }
                if k % 4 == 2 {
                    q[1] = if t[0] < 0.5 { lo[1] } else { hi[1] };
                }
                assert!(bare.contains(q), "{q:?} {bare:?}");
                assert!(floor.regions_near(q).is_empty(), "{q:?} in {bare:?}");
            }
        }
        assert!(boxes > 5_000 && open > 1_000, "{boxes} {open}");
        // A bare floor is bare everywhere.
        let plain = FloorPaint::new(1.0, Vec::new());
        assert!(plain.bare_box([3.0, -1e9]).contains([-1e300, 1e300]));
    }
}
