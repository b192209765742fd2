//! Sizing the bin grids of the world's indexes (walls, neighbourhoods, floor paint) so that their
//! memory stays proportional to the world's size: a grid whose lists would hold more entries than
//! its budget gets bins twice as large, until they fit. Worlds of ordinary walls and paint never
//! reach the budget, so their grids are as before; a thousand walls a kilometre long get coarse
//! bins instead of gigabytes of lists.

use super::geometry::Bounds;

/// Side of a look-up bin in metres: a few e-puck diameters; a barcode's bars share a bin or two,
/// and a 5 x 5 maze's grid stays under 200 bins (under a kilobyte of offsets).
pub(super) const BIN: f64 = 0.1;

/// At most this many bins: a world spread over kilometres gets coarser bins, not a huge grid.
const MAX_BINS: f64 = 262_144.0;

/// Side of the bins for a grid over `bounds` (walls, floor paint): [`BIN`], or larger for very
/// large worlds.
fn bin_side(bounds: Bounds) -> f64 {
    let w = bounds.max[0] - bounds.min[0];
    let h = bounds.max[1] - bounds.min[1];
    BIN.max((w * h / MAX_BINS).sqrt())
        .max(w / 4096.0)
        .max(h / 4096.0)
}

/// The look-up grid over `bounds` (bins from `bounds.min`) of `items` items listed in every bin
/// their box from `listed()` meets: bins of [`bin_side`], doubled until the lists fit the budget
/// of [`fitting_side`].
fn grid_over<I: Iterator<Item = Bounds>>(
    bounds: Bounds,
    items: usize,
    listed: impl Fn() -> I,
) -> Grid {
    let origin = bounds.min;
    let grid = |bin: f64| {
        let cols = ((bounds.max[0] - origin[0]) / bin) as usize + 1;
        let rows = ((bounds.max[1] - origin[1]) / bin) as usize + 1;
        (cols, rows)
    };
    let side = fitting_side(bin_side(bounds), items, |bin| {
        entries(listed(), origin, bin, grid(bin))
    });
    Grid::new(origin, side, grid(side))
}

/// Entries any grid may hold, at least: 4 Mi `u32` indices, 16 MiB.
const LEAST_BUDGET: u64 = 1 << 22;

/// Entries a grid may hold per item it indexes: an item listed in more bins than this on average
/// makes the bins grow. Every item meets at most 3 x 3 bins once bins are as large as the item
/// and its margins, so the growth ends.
const ENTRIES_PER_ITEM: u64 = 16;

/// The side, `side` or a power-of-two multiple of it, at which `entries(side)` (the list entries a
/// grid of bins of that side would hold for `items` items) fits the budget.
pub(super) fn fitting_side(side: f64, items: usize, entries: impl Fn(f64) -> u64) -> f64 {
    let budget = LEAST_BUDGET.max(ENTRIES_PER_ITEM.saturating_mul(items as u64));
    let mut side = side;
    while entries(side) > budget {
        side *= 2.0;
    }
    side
}

/// List entries of a grid of `cols` x `rows` bins of `side` from `origin` where each of `boxes`
/// is listed in every bin it meets.
pub(super) fn entries(
    boxes: impl Iterator<Item = Bounds>,
    origin: [f64; 2],
    side: f64,
    (cols, rows): (usize, usize),
) -> u64 {
    let grid = Grid::new(origin, side, (cols, rows));
    boxes
        .map(|b| {
            let [c0, r0, c1, r1] = grid.span(b);
            (c1 - c0 + 1) as u64 * (r1 - r0 + 1) as u64
        })
        .fold(0, u64::saturating_add)
}

/// A uniform grid of `cols` x `rows` square bins of `side` metres from `origin`.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(super) struct Grid {
    /// The south-west corner of bin (0, 0).
    pub(super) origin: [f64; 2],
    pub(super) side: f64,
    pub(super) cols: usize,
    pub(super) rows: usize,
}

impl Grid {
    /// `cols` x `rows` bins of `side` from `origin`.
    pub(super) fn new(origin: [f64; 2], side: f64, (cols, rows): (usize, usize)) -> Self {
        Self {
            origin,
            side,
            cols,
            rows,
        }
    }

    /// The closed ranges of the columns and rows of the bins `b` meets, `[c0, r0, c1, r1]`,
    /// clamped to the grid.
    #[inline]
    pub(super) fn span(self, b: Bounds) -> [usize; 4] {
        // Truncation of a non-negative number is its floor (and avoids a libm call).
        let clamp = |v: f64, n: usize| (v.max(0.0) as usize).min(n - 1);
        let (o, side) = (self.origin, self.side);
        [
            clamp((b.min[0] - o[0]) / side, self.cols),
            clamp((b.min[1] - o[1]) / side, self.rows),
            clamp((b.max[0] - o[0]) / side, self.cols),
            clamp((b.max[1] - o[1]) / side, self.rows),
        ]
    }

    /// The bin (`row * cols + col`) holding `p`, or `None` off the grid.
    #[inline]
    pub(super) fn bin_at(self, p: [f64; 2]) -> Option<usize> {
        let fx = (p[0] - self.origin[0]) / self.side;
        let fy = (p[1] - self.origin[1]) / self.side;
        if !(fx >= 0.0 && fy >= 0.0) {
            return None;
        }
        // Truncations of non-negative numbers: floors (through i64, cheaper than to usize; a
        // saturated one is off the grid either way).
        let (col, row) = (fx as i64 as usize, fy as i64 as usize);
        (col < self.cols && row < self.rows).then_some(row * self.cols + col)
    }
}

/// Item indices listed per bin of a [`Grid`], in CSR layout: the lists of the bins of a row
/// follow one another, so one slice covers a run of bins of a row.
#[derive(Debug, Clone, Default, PartialEq)]
pub(super) struct BinLists {
    pub(super) grid: Grid,
    /// Start of each bin's list in `items`, `cols * rows + 1` entries (none in a default one).
    start: Vec<u32>,
    items: Vec<u32>,
}

impl BinLists {
    /// No bins, of side [`BIN`].
    pub(super) fn none() -> Self {
        Self {
            grid: Grid::new([0.0, 0.0], BIN, (0, 0)),
            start: vec![0],
            items: Vec::new(),
        }
    }

    /// Each bin of `grid` listing the items of `spans(grid)` that span it, in the order given: an
    /// item's index and the [`Grid::span`] of its bins, within the grid.
    pub(super) fn new<I: Iterator<Item = (u32, [usize; 4])>>(
        grid: Grid,
        spans: impl Fn(Grid) -> I,
    ) -> Self {
        let (cols, bins) = (grid.cols, grid.cols * grid.rows);
        let bins_of = |[c0, r0, c1, r1]: [usize; 4]| {
            (r0..=r1).flat_map(move |row| (c0..=c1).map(move |col| row * cols + col))
        };
        // Count the items of each bin, then fill the lists.
        let mut start = vec![0u32; bins + 1];
        for (_, span) in spans(grid) {
            for b in bins_of(span) {
                start[b + 1] += 1;
            }
        }
        for b in 0..bins {
            start[b + 1] += start[b];
        }
        let mut filled = start[..bins].to_vec();
        let mut items = vec![0u32; start[bins] as usize];
        for (i, span) in spans(grid) {
            for b in bins_of(span) {
                items[filled[b] as usize] = i;
                filled[b] += 1;
            }
        }
        Self { grid, start, items }
    }

    /// The items of `boxes()`, each listed in every bin its box meets (last first with
    /// `last_first`), over the grid of [`grid_over`] on `bounds`, which holds every box.
    pub(super) fn over<I>(bounds: Bounds, boxes: impl Fn() -> I, last_first: bool) -> Self
    where
        I: DoubleEndedIterator<Item = Bounds> + ExactSizeIterator,
    {
        let grid = grid_over(bounds, boxes().len(), &boxes);
        let spans = |g: Grid| (0..boxes().len() as u32).zip(boxes().map(move |b| g.span(b)));
        if last_first {
            Self::new(grid, |g| spans(g).rev())
        } else {
            Self::new(grid, spans)
        }
    }

    /// The list of bin `bin` (`row * cols + col`).
    #[inline]
    pub(super) fn list(&self, bin: usize) -> &[u32] {
        &self.items[self.start[bin] as usize..self.start[bin + 1] as usize]
    }

    /// The lists of bins `c0..=c1` of `row`, one after the other.
    #[inline]
    pub(super) fn row_lists(&self, row: usize, c0: usize, c1: usize) -> &[u32] {
        let first = row * self.grid.cols;
        &self.items[self.start[first + c0] as usize..self.start[first + c1 + 1] as usize]
    }

    /// The length of each bin's list.
    pub(super) fn lengths(&self) -> impl Iterator<Item = u32> + '_ {
        self.start.windows(2).map(|w| w[1] - w[0])
    }

    /// Bytes of its buffers on the heap (`crate::footprint`).
    pub(super) fn heap_bytes(&self) -> usize {
        crate::footprint::vec_bytes(&self.start) + crate::footprint::vec_bytes(&self.items)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_grid_over_its_budget_gets_larger_bins_until_it_fits() {
        // 1,000 items each covering a 1 km square: bins of 0.1 m would list each in 10^8 bins.
        let entries = |side: f64| {
            let per_axis = (1000.0 / side).ceil() as u64;
            1000 * per_axis * per_axis
        };
        let side = fitting_side(0.1, 1000, entries);
        assert!(entries(side) <= LEAST_BUDGET);
        assert!(side > 0.1 && side < 1000.0);
        // An ordinary grid keeps its side.
        assert_eq!(fitting_side(0.1, 100, |_| 400), 0.1);
    }

    #[test]
    fn spans_are_clamped_to_the_grid() {
        let grid = Grid::new([0.0, 0.0], 0.1, (10, 10));
        let wide = Bounds {
            min: [0.05, -5.0],
            max: [0.25, 50.0],
        };
        assert_eq!(grid.span(wide), [0, 0, 2, 9]);
        let b = Bounds {
            min: [0.05, -1.0],
            max: [0.25, 0.05],
        };
        assert_eq!(entries([b, b].into_iter(), [0.0, 0.0], 0.1, (10, 10)), 6);
    }
}
