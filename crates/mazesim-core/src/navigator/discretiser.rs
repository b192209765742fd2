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

/// Turns Sharp readings in volts into the lower level's state number.
#[derive(Debug, Clone, PartialEq)]
pub struct Discretiser {
    /// The Sharp GP2Y0A41SK0F table (metres to volts) of the `seed` robot.
    sharp: LookupTable,
}

impl Discretiser {
    /// The discretiser of the `seed` robot's Sharp sensors.
    pub fn new() -> Result<Self> {
        let seed = RobotProfile::builtin("seed")?;
        Ok(Self {
            sharp: seed.distance_sensors[0].model.table.clone(),
        })
    }

    /// The level (0 to 3) of one reading in volts: volts to cm by inverting the Sharp table (the
    /// arithmetic of `mazesim.sharp_volts_to_cm`), then Table 4.1.
    pub fn level(&self, volts: f32) -> usize {
        let cm = self.sharp.invert(volts as f64) * 100.0;
        LEVEL_EDGES_CM.iter().filter(|&&edge| edge <= cm).count()
    }

    /// The state `sum(level[i] * 4^i)` of the first six readings (volts, in the report's order).
    pub fn state(&self, volts: &[f32]) -> usize {
        volts[..NUM_SENSORS]
            .iter()
            .rev()
            .fold(0, |state, &v| state * NUM_LEVELS + self.level(v))
    }
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
}
