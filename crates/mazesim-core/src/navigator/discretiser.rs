//! The lower level's distance state: the six Sharp distances of the `seed` robot (front, back,
//! left, right, left-front, right-front), each turned back into centimetres by inverting the
//! sensor's table and then into a level by the report's Table 4.1, the six levels forming one
//! number `sum(level[i] * 4^i)`.

use crate::error::Result;
use crate::lut::LookupTable;
use crate::RobotProfile;

/// Distance sensors in the state: front, back, left, right, left-front, right-front.
pub const NUM_SENSORS: usize = 6;
/// Table 4.1: a distance is at level k when it is at least `LEVEL_EDGES_CM[k - 1]` cm and below
/// `LEVEL_EDGES_CM[k]` cm.
pub const LEVEL_EDGES_CM: [f64; 3] = [7.0, 13.0, 20.0];
/// Levels per sensor.
pub const NUM_LEVELS: usize = LEVEL_EDGES_CM.len() + 1;
/// States of the lower level, `4^6`.
pub const NUM_STATES: usize = 4096;

/// The level (0 to 3) of a distance in cm by Table 4.1; a distance that is not a number reads
/// as the farthest level, as a sorted search puts it.
pub fn level_of_cm(cm: f64) -> usize {
    if cm.is_nan() {
        return NUM_LEVELS - 1;
    }
    LEVEL_EDGES_CM.iter().filter(|&&edge| edge <= cm).count()
}

/// The state `sum(level[i] * 4^i)` of six levels in the report's order.
pub fn state_of_levels(levels: impl DoubleEndedIterator<Item = usize>) -> usize {
    levels
        .rev()
        .fold(0, |state, level| state * NUM_LEVELS + level)
}

/// Turns Sharp readings in volts into the lower level's state number.
#[derive(Debug, Clone, PartialEq)]
pub struct Discretiser {
    /// The Sharp GP2Y0A41SK0F table (metres to volts) of the `seed` robot.
    sharp: LookupTable,
    /// For each level k from 1 to 3, the least reading (volts) whose level is below k: a
    /// reading is at level k or farther exactly when it is below this. The inverted table falls
    /// as the volts rise, step by step of its arithmetic, so each level is a run of readings.
    below: [f32; NUM_LEVELS - 1],
}

impl Discretiser {
    /// The discretiser of the `seed` robot's Sharp sensors.
    pub fn new() -> Result<Self> {
        let seed = RobotProfile::builtin("seed")?;
        let sharp = seed.distance_sensors[0].model.table.clone();
        let level = |volts: f32| level_of_cm(sharp.invert(f64::from(volts)) * 100.0);
        let below = std::array::from_fn(|k| least_below(&level, k + 1));
        Ok(Self { sharp, below })
    }

    /// The level (0 to 3) of one reading in volts: volts to cm by inverting the Sharp table (the
    /// arithmetic of `mazesim.sharp_volts_to_cm`), then Table 4.1.
    pub fn level(&self, volts: f32) -> usize {
        if volts.is_nan() {
            return self.level_by_table(volts);
        }
        self.below.iter().filter(|&&edge| volts < edge).count()
    }

    /// `level` through the table itself.
    fn level_by_table(&self, volts: f32) -> usize {
        level_of_cm(self.cm(f64::from(volts)))
    }

    /// The distance in cm of one reading in volts, by inverting the Sharp table (clamped to
    /// 3-40 cm): the arithmetic of `mazesim.sharp_volts_to_cm`.
    pub fn cm(&self, volts: f64) -> f64 {
        self.sharp.invert(volts) * 100.0
    }

    /// The state `sum(level[i] * 4^i)` of the first six readings (volts, in the report's order).
    pub fn state(&self, volts: &[f32]) -> usize {
        state_of_levels(volts[..NUM_SENSORS].iter().map(|&v| self.level(v)))
    }
}

/// The least finite f32 reading whose `level` is below `k`, found by bisection over the
/// ordered finite f32 values (`level` falls as the reading rises).
fn least_below(level: &impl Fn(f32) -> usize, k: usize) -> f32 {
    // Finite f32 values in increasing order, as ordered integers (-0 and 0 as one).
    let key = |v: f32| {
        let bits = i64::from(v.to_bits() & 0x7fff_ffff);
        if v.is_sign_negative() {
            -bits
        } else {
            bits
        }
    };
    let value = |key: i64| {
        let v = f32::from_bits(key.unsigned_abs() as u32);
        if key < 0 {
            -v
        } else {
            v
        }
    };
    // `level(lo) >= k` and `level(hi) < k` throughout.
    let (mut lo, mut hi) = (key(f32::MIN), key(f32::MAX));
    while hi - lo > 1 {
        let mid = lo + (hi - lo) / 2;
        if level(value(mid)) < k {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    value(hi)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn levels_follow_table_4_1() {
        let d = Discretiser::new().unwrap();
        // 3.03 V and more read 3 cm, 0.31 V and less 40 cm; 1.76 V is 7 cm, 1.04 V 12 cm.
        assert_eq!(d.level(3.5), 0);
        assert_eq!(d.level(1.76), 1);
        assert_eq!(d.level(1.04), 1);
        assert_eq!(d.level(0.82), 2);
        assert_eq!(d.level(0.2), 3);
        assert_eq!(d.state(&[0.2, 3.5, 3.5, 3.5, 3.5, 3.5]), 3);
        assert_eq!(d.state(&[3.5, 3.5, 3.5, 3.5, 3.5, 0.2]), 3 * 4usize.pow(5));
    }

    #[test]
    fn levels_from_the_edges_in_volts_are_the_tables_for_every_reading() {
        // Every f32 reading from below the table's last output to above its first (all the
        // readings where the level can change), and a few far outside.
        let d = Discretiser::new().unwrap();
        let (lo, hi) = (0.3f32.to_bits(), 3.1f32.to_bits());
        for bits in lo..=hi {
            let v = f32::from_bits(bits);
            assert_eq!(d.level(v), d.level_by_table(v), "{v}");
        }
        for v in [
            f32::NEG_INFINITY,
            -1.0,
            -0.0,
            0.0,
            1e-30,
            4.0,
            1e30,
            f32::INFINITY,
            f32::NAN,
        ] {
            assert_eq!(d.level(v), d.level_by_table(v), "{v}");
        }
    }

    #[test]
    fn levels_of_distances_follow_table_4_1_and_not_a_number_is_far() {
        let levels: Vec<usize> = [3.0, 6.99, 7.0, 12.9, 13.0, 20.0, 40.0, f64::NAN]
            .map(level_of_cm)
            .to_vec();
        assert_eq!(levels, [0, 0, 1, 1, 2, 3, 3, 3]);
    }
}
