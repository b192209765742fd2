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
/// their box from `listed()` meets: the bins' side ([`bin_side`], doubled until the lists fit the
/// budget of [`fitting_side`]) and the grid's columns and rows.
pub(super) fn grid_over<I: Iterator<Item = Bounds>>(
    bounds: Bounds,
    items: usize,
    listed: impl Fn() -> I,
) -> (f64, usize, usize) {
    let origin = bounds.min;
    let grid = |bin: f64| {
        let cols = ((bounds.max[0] - origin[0]) / bin) as usize + 1;
        let rows = ((bounds.max[1] - origin[1]) / bin) as usize + 1;
        (cols, rows)
    };
    let bin = fitting_side(bin_side(bounds), items, |bin| {
        entries(listed(), origin, bin, grid(bin))
    });
    let (cols, rows) = grid(bin);
    (bin, cols, rows)
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

/// Bins spanned from `lo` to `hi` (`lo <= hi`), with bins of `side` starting at `origin` and
/// `count` bins in all: the closed index range, clamped to the grid.
fn span(lo: f64, hi: f64, origin: f64, side: f64, count: usize) -> u64 {
    let clamp = |v: f64| ((v - origin) / side).max(0.0).min((count - 1) as f64) as u64;
    clamp(hi) - clamp(lo) + 1
}

/// List entries of a grid of `cols` x `rows` bins of `side` from `origin` where each of `boxes`
/// is listed in every bin it meets.
pub(super) fn entries(
    boxes: impl Iterator<Item = Bounds>,
    origin: [f64; 2],
    side: f64,
    (cols, rows): (usize, usize),
) -> u64 {
    boxes
        .map(|b| {
            span(b.min[0], b.max[0], origin[0], side, cols)
                * span(b.min[1], b.max[1], origin[1], side, rows)
        })
        .fold(0, u64::saturating_add)
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
        assert_eq!(span(0.05, 0.25, 0.0, 0.1, 10), 3);
        assert_eq!(span(-5.0, 50.0, 0.0, 0.1, 10), 10);
        let b = Bounds {
            min: [0.05, -1.0],
            max: [0.25, 0.05],
        };
        assert_eq!(entries([b, b].into_iter(), [0.0, 0.0], 0.1, (10, 10)), 6);
    }
}
