//! Another robot's distance readings in the navigator's terms, the seed robot's six Sharp volts,
//! from tables handed in as data (`mazesim.transfer.readings.SeedReadings` makes them): each of
//! the six directions takes the nearest distance its sensors show (a reading becomes a distance
//! through its sensor's inverted table; a distance in the last part of the sensor's range counts
//! as "no wall seen", `far`), and that distance becomes seed volts through the Sharp table.
//!
//! The interpolation is numpy's `interp` (the same search, products and sums in f64), so a round
//! of a fleet reads, bit for bit, the volts that `SeedReadings.volts` gives.

use crate::error::{Error, Result};
use crate::navigator::NUM_SENSORS;

/// A piecewise-linear map `x -> y` through the points `(xs[k], ys[k])`, `xs` increasing; clamped
/// to the first and last `y` outside them.
#[derive(Debug, Clone, PartialEq)]
pub struct Interpolation {
    xs: Vec<f64>,
    ys: Vec<f64>,
}

impl Interpolation {
    /// The map through `xs` (at least two, finite, non-decreasing) and `ys` (as many, finite);
    /// `what` names it in errors.
    pub fn new(xs: Vec<f64>, ys: Vec<f64>, what: &str) -> Result<Self> {
        if xs.len() < 2 || xs.len() != ys.len() {
            return Err(Error::InvalidArgument(format!(
                "expected {what} to hold as many points as values, two at least, found {} and {}",
                xs.len(),
                ys.len()
            )));
        }
        if let Some(v) = xs.iter().chain(&ys).find(|v| !v.is_finite()) {
            return Err(Error::InvalidArgument(format!(
                "expected finite points and values in {what}, found {v}"
            )));
        }
        if let Some(k) = (1..xs.len()).find(|&k| xs[k] < xs[k - 1]) {
            return Err(Error::InvalidArgument(format!(
                "expected the points of {what} in increasing order, found {} after {}",
                xs[k],
                xs[k - 1]
            )));
        }
        Ok(Self { xs, ys })
    }

    /// The value at `x`, as `numpy.interp(x, xs, ys)` computes it.
    pub fn at(&self, x: f64) -> f64 {
        let (xs, ys) = (&self.xs, &self.ys);
        if x.is_nan() {
            return x;
        }
        // The last point at or below x.
        let below = xs.partition_point(|&p| p <= x);
        if below == 0 {
            return ys[0];
        }
        let j = below - 1;
        if j == xs.len() - 1 || xs[j] == x {
            return ys[j];
        }
        let slope = (ys[j + 1] - ys[j]) / (xs[j + 1] - xs[j]);
        let value = slope * (x - xs[j]) + ys[j];
        if !value.is_nan() {
            return value;
        }
        let other = slope * (x - xs[j + 1]) + ys[j + 1];
        if other.is_nan() && ys[j] == ys[j + 1] {
            ys[j]
        } else {
            other
        }
    }
}

/// One distance sensor's reading turned into metres, and how far it sees a wall.
#[derive(Debug, Clone, PartialEq)]
pub struct SensorDistance {
    /// Reading to metres (the sensor's lookup table, inverted).
    pub distance: Interpolation,
    /// A distance at or beyond this counts as no wall seen.
    pub seen_up_to: f64,
}

/// How a robot's distance readings become the seed robot's six volts (see the module).
#[derive(Debug, Clone, PartialEq)]
pub struct SeedVolts {
    /// For each of the six directions (the report's order), the sensors it takes.
    directions: [Vec<usize>; NUM_SENSORS],
    /// Each distance sensor of the robot.
    sensors: Vec<SensorDistance>,
    /// The distance of a direction that sees no wall (metres).
    far: f64,
    /// Metres to seed volts (the Sharp table).
    volts: Interpolation,
}

impl SeedVolts {
    /// The map; every direction takes one sensor at least, each an index into `sensors`.
    pub fn new(
        directions: [Vec<usize>; NUM_SENSORS],
        sensors: Vec<SensorDistance>,
        far: f64,
        volts: Interpolation,
    ) -> Result<Self> {
        for (place, taken) in directions.iter().enumerate() {
            if taken.is_empty() {
                return Err(Error::InvalidArgument(format!(
                    "expected direction {place} to take one sensor at least, found none"
                )));
            }
            if let Some(s) = taken.iter().find(|&&s| s >= sensors.len()) {
                return Err(Error::InvalidArgument(format!(
                    "expected the sensors of direction {place} in [0, {}), found {s}",
                    sensors.len()
                )));
            }
        }
        if !far.is_finite() || sensors.iter().any(|s| !s.seen_up_to.is_finite()) {
            return Err(Error::InvalidArgument(
                "expected a finite far distance and finite sensor ranges".into(),
            ));
        }
        Ok(Self {
            directions,
            sensors,
            far,
            volts,
        })
    }

    /// How many distance sensors the robot has.
    pub fn sensor_count(&self) -> usize {
        self.sensors.len()
    }

    /// The six seed volts of one robot's distance `readings` (one per sensor).
    pub fn volts(&self, readings: &[f32]) -> [f32; NUM_SENSORS] {
        let mut out = [0f32; NUM_SENSORS];
        for (volts, taken) in out.iter_mut().zip(&self.directions) {
            // The nearest distance the direction's sensors show (NaN wins, as numpy's min).
            let mut nearest = f64::INFINITY;
            for &s in taken {
                let sensor = &self.sensors[s];
                let distance = sensor.distance.at(f64::from(readings[s]));
                let seen = if distance >= sensor.seen_up_to {
                    self.far
                } else {
                    distance
                };
                if seen.is_nan() || seen < nearest {
                    nearest = seen;
                }
                if nearest.is_nan() {
                    break;
                }
            }
            *volts = self.volts.at(nearest) as f32;
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn line() -> Interpolation {
        Interpolation::new(vec![0.0, 1.0, 3.0], vec![10.0, 20.0, 0.0], "a line").unwrap()
    }

    #[test]
    fn interpolation_clamps_and_hits_its_points() {
        let map = line();
        assert_eq!(map.at(-1.0), 10.0);
        assert_eq!(map.at(0.0), 10.0);
        assert_eq!(map.at(0.5), 15.0);
        assert_eq!(map.at(1.0), 20.0);
        assert_eq!(map.at(2.0), 10.0);
        assert_eq!(map.at(3.0), 0.0);
        assert_eq!(map.at(7.0), 0.0);
        assert!(map.at(f64::NAN).is_nan());
    }

    #[test]
    fn a_bad_table_is_refused_naming_it() {
        let err = Interpolation::new(vec![1.0, 0.0], vec![0.0, 0.0], "t").unwrap_err();
        assert!(err.to_string().contains("increasing order"), "{err}");
        let err = Interpolation::new(vec![1.0], vec![0.0], "t").unwrap_err();
        assert!(err.to_string().contains("two at least"), "{err}");
    }

    #[test]
    fn each_direction_takes_its_nearest_sensor_and_far_beyond_range() {
        let metres = Interpolation::new(vec![0.0, 1.0], vec![0.0, 1.0], "m").unwrap();
        let sensor = SensorDistance {
            distance: metres.clone(),
            seen_up_to: 0.5,
        };
        let volts = Interpolation::new(vec![0.0, 1.0], vec![3.0, 1.0], "v").unwrap();
        let directions = [vec![0, 1], vec![1], vec![2], vec![2], vec![2], vec![2]];
        let map = SeedVolts::new(directions, vec![sensor; 3], 1.0, volts).unwrap();
        let out = map.volts(&[0.25, 0.125, 0.75]);
        assert_eq!(out[0], 2.75); // the nearer of 0.25 and 0.125 m
        assert_eq!(out[1], 2.75);
        assert_eq!(out[2], 1.0); // 0.75 m is past the sensor's range: far
        let bad = SeedVolts::new(
            [vec![3], vec![0], vec![0], vec![0], vec![0], vec![0]],
            vec![],
            1.0,
            metres,
        );
        assert!(bad.unwrap_err().to_string().contains("direction 0"));
    }
}
