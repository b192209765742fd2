//! The report's Alg. 1, avoid-collision, as `mazesim.controllers.AvoidCollision` computes it:
//! the same comparisons and the same float64 arithmetic, rounded to float32 at the end as its
//! `batch` method rounds them.

use crate::error::{Error, Result};

/// ps5, ps6, ps7: the e-puck's front-left sensors.
const LEFT_SENSORS: [usize; 3] = [5, 6, 7];
/// ps0, ps1, ps2: the e-puck's front-right sensors.
const RIGHT_SENSORS: [usize; 3] = [0, 1, 2];

/// Drive forward at half speed; turn right (left wheel at full speed, right wheel stopped) when a
/// front-left sensor reads above the threshold, else turn left when a front-right one does.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AvoidCollision {
    /// Raw proximity reading above which a sensor sees an obstacle (80 in the report).
    pub threshold: f64,
    /// The wheel speed in rad/s the rule scales (6.28 on the e-puck).
    pub max_speed: f64,
}

/// The e-puck's motor limit, rad/s (not 2 pi: the value Webots' PROTO gives).
#[allow(clippy::approx_constant)]
pub const EPUCK_MAX_SPEED: f64 = 6.28;

impl Default for AvoidCollision {
    fn default() -> Self {
        Self {
            threshold: 80.0,
            max_speed: EPUCK_MAX_SPEED,
        }
    }
}

impl AvoidCollision {
    /// The rule with `threshold` and `max_speed`, both finite.
    pub fn new(threshold: f64, max_speed: f64) -> Result<Self> {
        if !threshold.is_finite() || !max_speed.is_finite() {
            return Err(Error::InvalidArgument(format!(
                "expected a finite threshold and max_speed for avoid-collision, found {threshold} \
                 and {max_speed}"
            )));
        }
        Ok(Self {
            threshold,
            max_speed,
        })
    }

    /// Wheel speeds (left, right) in rad/s from the eight readings ps0..ps7.
    pub fn wheel_speeds(&self, ps: &[f32]) -> [f32; 2] {
        let sees = |sensors: [usize; 3]| sensors.iter().any(|&i| ps[i] as f64 > self.threshold);
        // +1: turn right (left wheel faster), -1: turn left, 0: straight on.
        let turn = if sees(LEFT_SENSORS) {
            1.0
        } else if sees(RIGHT_SENSORS) {
            -1.0
        } else {
            0.0
        };
        let half = 0.5 * self.max_speed;
        [(half + turn * half) as f32, (half - turn * half) as f32]
    }
}

#[cfg(test)]
#[allow(clippy::approx_constant)] // 6.28 rad/s is the e-puck motor limit, not tau.
mod tests {
    use super::*;

    #[test]
    fn turns_away_from_the_side_that_sees_and_left_wins() {
        let rule = AvoidCollision::default();
        let mut ps = [0.0f32; 8];
        assert_eq!(rule.wheel_speeds(&ps), [3.14, 3.14]);
        ps[1] = 81.0;
        assert_eq!(rule.wheel_speeds(&ps), [0.0, 6.28]);
        ps[6] = 200.0;
        assert_eq!(rule.wheel_speeds(&ps), [6.28, 0.0]);
        assert!(AvoidCollision::new(f64::NAN, 1.0).is_err());
    }
}
