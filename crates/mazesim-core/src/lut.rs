//! Lookup tables as Webots' distance sensors define them: rows of (input, output, relative noise),
//! interpolated linearly and clamped at both ends.

use crate::error::{Error, Result};

/// Cells of the guide that points `eval` at the right row without a scan from the top.
const GUIDE_CELLS: usize = 64;

/// A piecewise-linear table with a relative noise column.
#[derive(Debug, Clone, PartialEq)]
pub struct LookupTable {
    inputs: Vec<f64>,
    outputs: Vec<f64>,
    noise: Vec<f64>,
    /// `GUIDE_CELLS` equal cells over the inputs: `1 / cell width`.
    guide_scale: f64,
    /// Per cell, the first row whose input is at or above the cell's start (at least 1): where
    /// `eval`'s search for the row above `x` may begin.
    guide: [u8; GUIDE_CELLS],
    /// The outputs fall or rise strictly from row to row, so that `invert` finds its row by
    /// bisection.
    strictly_monotonic: bool,
}

impl LookupTable {
    /// Builds a table from `(input, output, relative_sigma)` rows with strictly increasing inputs.
    pub fn new(rows: &[[f64; 3]]) -> Result<Self> {
        if rows.len() < 2 {
            return Err(Error::InvalidArgument(format!(
                "a lookup table needs at least 2 rows, found {}",
                rows.len()
            )));
        }
        for (i, w) in rows.windows(2).enumerate() {
            if w[1][0] <= w[0][0] {
                return Err(Error::InvalidArgument(format!(
                    "lookup table inputs must increase strictly; row {} ({}) is not above row {} ({})",
                    i + 1,
                    w[1][0],
                    i,
                    w[0][0]
                )));
            }
        }
        if rows.iter().flatten().any(|v| !v.is_finite()) || rows.iter().any(|r| r[2] < 0.0) {
            return Err(Error::InvalidArgument(
                "lookup table values must be finite and noise non-negative".into(),
            ));
        }
        if rows.len() > u8::MAX as usize {
            return Err(Error::InvalidArgument(format!(
                "a lookup table has at most {} rows, found {}",
                u8::MAX,
                rows.len()
            )));
        }
        let inputs: Vec<f64> = rows.iter().map(|r| r[0]).collect();
        let outputs: Vec<f64> = rows.iter().map(|r| r[1]).collect();
        let (first, last) = (inputs[0], inputs[rows.len() - 1]);
        let guide_scale = GUIDE_CELLS as f64 / (last - first);
        let mut guide = [1u8; GUIDE_CELLS];
        for (cell, g) in guide.iter_mut().enumerate() {
            // A row below the cell's start (as `eval` computes cells) is never the one sought
            // there; rounding only makes this start earlier, never later.
            let start = first + (cell as f64 - 0.5).max(0.0) / guide_scale;
            let row = inputs
                .iter()
                .position(|&x| x >= start)
                .unwrap_or(rows.len() - 1);
            *g = row.clamp(1, rows.len() - 1) as u8;
        }
        Ok(Self {
            inputs,
            strictly_monotonic: strictly_monotonic(&outputs),
            outputs,
            noise: rows.iter().map(|r| r[2]).collect(),
            guide_scale,
            guide,
        })
    }

    /// Output and relative sigma at `x`, interpolated linearly, clamped outside the table.
    #[inline]
    pub fn eval(&self, x: f64) -> (f64, f64) {
        let n = self.inputs.len();
        if x.is_nan() || x <= self.inputs[0] {
            return (self.outputs[0], self.noise[0]);
        }
        if x >= self.inputs[n - 1] {
            return (self.outputs[n - 1], self.noise[n - 1]);
        }
        // The first row whose input is at or above x: the guide gives a row at or before it, a
        // short scan finds it.
        let cell = ((x - self.inputs[0]) * self.guide_scale) as usize;
        let mut i = self.guide[cell.min(GUIDE_CELLS - 1)] as usize;
        while self.inputs[i] < x {
            i += 1;
        }
        let (x0, x1) = (self.inputs[i - 1], self.inputs[i]);
        let t = (x - x0) / (x1 - x0);
        let lerp = |a: &[f64]| a[i - 1] + t * (a[i] - a[i - 1]);
        (lerp(&self.outputs), lerp(&self.noise))
    }

    /// The table's `(input, output, relative_sigma)` rows, as `new` took them.
    pub fn rows(&self) -> impl Iterator<Item = [f64; 3]> + '_ {
        let columns = self.inputs.iter().zip(&self.outputs).zip(&self.noise);
        columns.map(|((&x, &y), &sigma)| [x, y, sigma])
    }

    /// The smallest input (the nearest distance the table describes).
    pub fn min_input(&self) -> f64 {
        self.inputs[0]
    }

    /// The largest input (the sensor's range).
    pub fn max_input(&self) -> f64 {
        self.inputs[self.inputs.len() - 1]
    }

    /// The largest output of the table (before noise).
    pub fn max_output(&self) -> f64 {
        self.outputs
            .iter()
            .copied()
            .fold(f64::NEG_INFINITY, f64::max)
    }

    /// Inverts the table on its monotonic part: the input whose output is `y`, clamped.
    /// Used to turn a Sharp reading in volts back into a distance.
    pub fn invert(&self, y: f64) -> f64 {
        let n = self.outputs.len();
        let decreasing = self.outputs[n - 1] < self.outputs[0];
        let (first, last) = (self.outputs[0], self.outputs[n - 1]);
        let before_first = if decreasing { y >= first } else { y <= first };
        let after_last = if decreasing { y <= last } else { y >= last };
        if before_first {
            return self.inputs[0];
        }
        if after_last {
            return self.inputs[n - 1];
        }
        if self.strictly_monotonic && !y.is_nan() {
            // The row the scan below finds: the first whose output is at or past `y`, the one
            // before it short of `y` (the first row is, as `before_first` is false).
            let rest = &self.outputs[1..];
            let i = 1 + if decreasing {
                rest.partition_point(|&o| o > y)
            } else {
                rest.partition_point(|&o| o < y)
            };
            let (y0, y1) = (self.outputs[i - 1], self.outputs[i]);
            let t = (y - y0) / (y1 - y0);
            return self.inputs[i - 1] + t * (self.inputs[i] - self.inputs[i - 1]);
        }
        self.invert_by_scan(y, decreasing)
    }

    /// `invert` of a `y` within the outputs' ends, by a scan for the first row whose segment
    /// holds it (and is not flat).
    fn invert_by_scan(&self, y: f64, decreasing: bool) -> f64 {
        let n = self.outputs.len();
        for i in 1..n {
            let (y0, y1) = (self.outputs[i - 1], self.outputs[i]);
            let inside = if decreasing {
                y <= y0 && y >= y1
            } else {
                y >= y0 && y <= y1
            };
            if inside && y1 != y0 {
                let t = (y - y0) / (y1 - y0);
                return self.inputs[i - 1] + t * (self.inputs[i] - self.inputs[i - 1]);
            }
        }
        self.inputs[n - 1]
    }
}

/// Whether `values` fall strictly or rise strictly from each to the next.
fn strictly_monotonic(values: &[f64]) -> bool {
    let steps = || values.windows(2);
    steps().all(|w| w[1] < w[0]) || steps().all(|w| w[1] > w[0])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn table() -> LookupTable {
        LookupTable::new(&[[0.0, 100.0, 0.1], [1.0, 50.0, 0.2], [2.0, 0.0, 0.3]]).unwrap()
    }

    #[test]
    fn interpolates_and_clamps() {
        let t = table();
        assert_eq!(t.eval(-1.0), (100.0, 0.1));
        assert_eq!(t.eval(0.5), (75.0, 0.15000000000000002));
        assert_eq!(t.eval(1.5).0, 25.0);
        assert_eq!(t.eval(5.0), (0.0, 0.3));
        assert_eq!(t.eval(f64::NAN).0, 100.0);
    }

    #[test]
    fn input_range_and_inverse() {
        let t = LookupTable::new(&[[0.5, 100.0, 0.1], [1.0, 50.0, 0.2], [2.0, 0.0, 0.3]]).unwrap();
        assert_eq!((t.min_input(), t.max_input()), (0.5, 2.0));
        assert_eq!(t.invert(75.0), 0.75);
        assert_eq!(t.invert(500.0), 0.5); // clamped to the nearest distance
        assert_eq!(t.invert(-1.0), 2.0); // and to the farthest
    }

    /// `eval` as defined: the first row at or above `x` by a scan from the top.
    fn eval_by_scan(t: &LookupTable, x: f64) -> (f64, f64) {
        let n = t.inputs.len();
        if x.is_nan() || x <= t.inputs[0] {
            return (t.outputs[0], t.noise[0]);
        }
        if x >= t.inputs[n - 1] {
            return (t.outputs[n - 1], t.noise[n - 1]);
        }
        let i = (1..n).find(|&i| t.inputs[i] >= x).unwrap();
        let s = (x - t.inputs[i - 1]) / (t.inputs[i] - t.inputs[i - 1]);
        let lerp = |a: &[f64]| a[i - 1] + s * (a[i] - a[i - 1]);
        (lerp(&t.outputs), lerp(&t.noise))
    }

    #[test]
    fn guided_search_finds_the_row_a_scan_finds() {
        // Uneven rows (as the e-puck's), rows closer than a guide cell, and exact breakpoints.
        let tables = [
            vec![0.0, 0.005, 0.01, 0.015, 0.02, 0.03, 0.04, 0.05, 0.06, 0.07],
            vec![-1.0, -0.999, -0.9989, 0.3, 0.30001, 2.0],
            vec![0.1, 0.2],
        ];
        for inputs in tables {
            let rows: Vec<[f64; 3]> = inputs
                .iter()
                .enumerate()
                .map(|(k, &x)| [x, 100.0 / (k as f64 + 1.0), 0.01 * k as f64])
                .collect();
            let t = LookupTable::new(&rows).unwrap();
            let (a, b) = (inputs[0] - 0.01, inputs[inputs.len() - 1] + 0.01);
            let mut xs: Vec<f64> = (0..=20_000)
                .map(|k| a + (b - a) * k as f64 / 20_000.0)
                .collect();
            for &x in &inputs {
                // The input and its two neighbouring floats.
                let (up, down) = if x == 0.0 {
                    (f64::from_bits(1), -f64::from_bits(1))
                } else {
                    (
                        f64::from_bits(x.to_bits() + 1),
                        f64::from_bits(x.to_bits() - 1),
                    )
                };
                xs.extend([x, up, down]);
            }
            for x in xs {
                assert_eq!(t.eval(x), eval_by_scan(&t, x), "x = {x}");
            }
        }
    }

    #[test]
    fn inverts_monotonic_tables() {
        let t = table();
        for x in [0.0, 0.25, 1.0, 1.75, 2.0] {
            let y = t.eval(x).0;
            assert!((t.invert(y) - x).abs() < 1e-12);
        }
        assert_eq!(t.invert(1000.0), 0.0);
        assert_eq!(t.invert(-5.0), 2.0);
    }

    #[test]
    fn bisection_inverts_as_the_scan_does() {
        // Falling (the Sharp sensor's volts), rising, and not monotonic (a scan's case alone).
        let tables = [
            vec![
                3.03, 2.78, 2.72, 2.33, 2.01, 1.76, 1.55, 1.4, 1.25, 1.04, 0.92, 0.31,
            ],
            vec![0.0, 0.1, 0.10001, 5.0, 7.5],
            vec![1.0, 3.0, 2.0, 2.0, 0.5],
        ];
        for (k, outputs) in tables.iter().enumerate() {
            let rows: Vec<[f64; 3]> = outputs
                .iter()
                .enumerate()
                .map(|(j, &y)| [0.03 + 0.01 * j as f64, y, 0.0])
                .collect();
            let t = LookupTable::new(&rows).unwrap();
            assert_eq!(t.strictly_monotonic, k < 2);
            let (lo, hi) = (-0.5, 8.0);
            let mut ys: Vec<f64> = (0..=20_000)
                .map(|j| lo + (hi - lo) * j as f64 / 20_000.0)
                .collect();
            for &y in outputs {
                ys.extend([y, f64::from_bits(y.to_bits() + 1), y.next_down()]);
            }
            // Volts as a robot reads them: f32 values.
            ys.extend((0..=20_000).map(|j| (j as f32 * 1.6e-4) as f64));
            for y in ys {
                let (first, last) = (outputs[0], outputs[outputs.len() - 1]);
                let inside = y > first.min(last) && y < first.max(last);
                let expected = if inside {
                    t.invert_by_scan(y, last < first)
                } else {
                    t.invert(y)
                };
                assert_eq!(t.invert(y).to_bits(), expected.to_bits(), "y = {y}");
            }
            assert_eq!(t.invert(f64::NAN), t.max_input());
        }
    }

    #[test]
    fn rejects_bad_tables() {
        assert!(LookupTable::new(&[[0.0, 1.0, 0.0]]).is_err());
        assert!(LookupTable::new(&[[0.0, 1.0, 0.0], [0.0, 2.0, 0.0]]).is_err());
        assert!(LookupTable::new(&[[0.0, 1.0, -0.1], [1.0, 2.0, 0.0]]).is_err());
        let long: Vec<[f64; 3]> = (0..256).map(|k| [k as f64, 1.0, 0.0]).collect();
        let err = LookupTable::new(&long).unwrap_err().to_string();
        assert!(
            err.contains("at most 255 rows") && err.contains("256"),
            "{err}"
        );
        assert!(LookupTable::new(&long[..255]).is_ok());
    }
}
