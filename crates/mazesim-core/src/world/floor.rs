//! Floor paint: the reflectance of the floor at any point, for the ground sensors.
//!
//! Regions are drawn in order (a later region covers an earlier one). A coarse bin grid keeps a
//! look-up to the few regions near the point.

use super::geometry::{Bounds, PaintShape};

/// One painted region.
#[derive(Debug, Clone, PartialEq)]
pub struct PaintRegion {
    /// Where.
    pub shape: PaintShape,
    /// Reflection factor f in (0, 1].
    pub reflectance: f64,
}

/// Side of a look-up bin in metres.
const BIN: f64 = 0.05;

/// At most this many bins: a world spread over kilometres gets coarser bins, not a huge grid.
const MAX_BINS: f64 = 262_144.0;

/// Side of the bins for a grid over `bounds`: `BIN`, or larger for very large worlds.
fn bin_side(bounds: Bounds) -> f64 {
    let w = bounds.max[0] - bounds.min[0];
    let h = bounds.max[1] - bounds.min[1];
    BIN.max((w * h / MAX_BINS).sqrt())
        .max(w / 4096.0)
        .max(h / 4096.0)
}

/// Regions are listed in every bin they come within this distance of (metres), so that a bin's
/// list serves every point of a sensor spot centred in it (spots are a few millimetres wide).
pub const SPOT_MARGIN: f64 = 0.005;

/// The painted floor of a world.
#[derive(Debug, Clone, PartialEq)]
pub struct FloorPaint {
    background: f64,
    regions: Vec<PaintRegion>,
    /// Per region: `shape.turn()`, so that a look-up computes no sine or cosine.
    turns: Vec<[f64; 2]>,
    origin: [f64; 2],
    /// Side of a bin in metres.
    bin: f64,
    cols: usize,
    rows: usize,
    /// Start of each bin's region list in `bin_regions` (CSR layout), `cols * rows + 1` entries.
    bin_start: Vec<u32>,
    /// Region indices per bin, highest (topmost) first.
    bin_regions: Vec<u32>,
}

impl FloorPaint {
    /// Indexes `regions` over a floor of `background` reflectance.
    pub fn new(background: f64, regions: Vec<PaintRegion>) -> Self {
        let turns = regions.iter().map(|r| r.shape.turn()).collect();
        let bounds = regions
            .iter()
            .fold(Bounds::EMPTY, |b, r| b.union(r.shape.bounds()));
        if bounds.is_empty() {
            return Self {
                background,
                regions,
                turns,
                origin: [0.0, 0.0],
                bin: BIN,
                cols: 0,
                rows: 0,
                bin_start: vec![0],
                bin_regions: Vec::new(),
            };
        }
        let origin = bounds.min;
        let bin = bin_side(bounds);
        let cols = ((bounds.max[0] - origin[0]) / bin) as usize + 1;
        let rows = ((bounds.max[1] - origin[1]) / bin) as usize + 1;
        let mut bins: Vec<Vec<u32>> = vec![Vec::new(); cols * rows];
        for (i, r) in regions.iter().enumerate().rev() {
            let b = r.shape.bounds().grown(SPOT_MARGIN);
            let c0 = ((b.min[0] - origin[0]) / bin).max(0.0) as usize;
            let r0 = ((b.min[1] - origin[1]) / bin).max(0.0) as usize;
            let c1 = (((b.max[0] - origin[0]) / bin).max(0.0) as usize).min(cols - 1);
            let r1 = (((b.max[1] - origin[1]) / bin).max(0.0) as usize).min(rows - 1);
            for row in r0..=r1 {
                for col in c0..=c1 {
                    bins[row * cols + col].push(i as u32);
                }
            }
        }
        let mut bin_start = Vec::with_capacity(bins.len() + 1);
        let mut bin_regions = Vec::new();
        bin_start.push(0);
        for b in bins {
            bin_regions.extend(b);
            bin_start.push(bin_regions.len() as u32);
        }
        Self {
            background,
            regions,
            turns,
            origin,
            bin,
            cols,
            rows,
            bin_start,
            bin_regions,
        }
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
        let fx = (p[0] - self.origin[0]) / self.bin;
        let fy = (p[1] - self.origin[1]) / self.bin;
        if !(fx >= 0.0 && fy >= 0.0) {
            return &[];
        }
        let (col, row) = (fx as usize, fy as usize);
        if col >= self.cols || row >= self.rows {
            return &[];
        }
        let bin = row * self.cols + col;
        let (s, e) = (
            self.bin_start[bin] as usize,
            self.bin_start[bin + 1] as usize,
        );
        &self.bin_regions[s..e]
    }

    /// Reflectance at `p` among `candidates` (from `regions_near` of a point within
    /// `SPOT_MARGIN` of `p`).
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
}
