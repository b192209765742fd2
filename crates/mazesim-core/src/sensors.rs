//! Sensor models: Webots' infra-red distance sensor and the downward ground sensor.
//!
//! Infra-red (Webots `DistanceSensor` of type "infra-red"): the ray meets a wall at distance `d`;
//! the wall's reflection factor `f` (1 white, 0.2 black) scales it, and the reading is
//! `LUT(d / f) * (1 + sigma(d / f) * N(0, 1))`, the table interpolated linearly and clamped, `sigma`
//! its relative-noise column. No hit within the ray reads the last row.
//! Ground sensors look down from `height`; the floor's reflectance is averaged over a square spot
//! of side `footprint` (so a reading over a bar edge lies between the two colours) and read as
//! `LUT(height / f)`.

use crate::rng::Rng;
use crate::robot::SensorModel;
use crate::world::{FloorPaint, RayHit, WallIndex};

/// Samples per side of the ground sensor's spot.
const SPOT_SAMPLES: usize = 3;

/// Applies the model's relative Gaussian noise to a table value.
#[inline]
fn noisy(value: f64, sigma: f64, rng: Option<&mut Rng>) -> f32 {
    let v = match rng {
        Some(r) if sigma > 0.0 => value * (1.0 + sigma * r.normal()),
        _ => value,
    };
    v.max(0.0) as f32
}

/// Reads an infra-red distance sensor whose ray starts at `origin` in the unit direction `dir`.
pub fn read_infrared(
    model: &SensorModel,
    walls: &WallIndex,
    origin: [f32; 2],
    dir: [f32; 2],
    rng: Option<&mut Rng>,
) -> f32 {
    let hit = walls.cast_ray(origin, dir, model.table.max_input() as f32);
    infrared_reading(model, hit, rng)
}

/// The infra-red reading for what the sensor's ray (of the table's range) met.
#[inline]
pub fn infrared_reading(model: &SensorModel, hit: Option<RayHit>, rng: Option<&mut Rng>) -> f32 {
    let x = match hit {
        Some(hit) => hit.distance as f64 / hit.reflectance as f64,
        None => model.table.max_input(),
    };
    let (value, sigma) = model.table.eval(x);
    noisy(value, sigma, rng)
}

/// What an infra-red sensor's table gives when its ray meets nothing (its last row), for
/// `infrared_reading_with`.
pub fn infrared_miss(model: &SensorModel) -> (f64, f64) {
    model.table.eval(model.table.max_input())
}

/// `infrared_reading`, with `miss = infrared_miss(model)` computed beforehand: a ray that met
/// nothing needs no table look-up.
#[inline]
pub fn infrared_reading_with(
    model: &SensorModel,
    hit: Option<RayHit>,
    miss: (f64, f64),
    rng: Option<&mut Rng>,
) -> f32 {
    let (value, sigma) = match hit {
        Some(hit) => model
            .table
            .eval(hit.distance as f64 / hit.reflectance as f64),
        None => miss,
    };
    noisy(value, sigma, rng)
}

/// Mean floor reflectance over the sensor's square spot centred at `at`, aligned with the robot's
/// unit forward vector `axis` (cos, sin of its heading).
pub fn spot_reflectance(
    model: &SensorModel,
    floor: &FloorPaint,
    at: [f64; 2],
    axis: [f64; 2],
) -> f64 {
    if model.footprint <= 0.0 {
        return floor.reflectance_at(at);
    }
    let candidates = floor.regions_near(at);
    if candidates.is_empty() {
        return floor.background();
    }
    debug_assert!(
        model.footprint * std::f64::consts::FRAC_1_SQRT_2 <= crate::world::floor::SPOT_MARGIN
    );
    let [c, s] = axis;
    let step = model.footprint / SPOT_SAMPLES as f64;
    let first = -(model.footprint - step) / 2.0;
    let mut sum = 0.0;
    for i in 0..SPOT_SAMPLES {
        let u = first + i as f64 * step;
        for j in 0..SPOT_SAMPLES {
            let v = first + j as f64 * step;
            sum +=
                floor.reflectance_among(candidates, [at[0] + c * u - s * v, at[1] + s * u + c * v]);
        }
    }
    sum / (SPOT_SAMPLES * SPOT_SAMPLES) as f64
}

/// Reads a ground sensor at floor point `at` on a robot whose unit forward vector is `axis`.
pub fn read_ground(
    model: &SensorModel,
    floor: &FloorPaint,
    at: [f64; 2],
    axis: [f64; 2],
    rng: Option<&mut Rng>,
) -> f32 {
    let f = spot_reflectance(model, floor, at, axis);
    let (value, sigma) = model.table.eval(model.height / f);
    noisy(value, sigma, rng)
}

/// A ground sensor's table value and relative sigma over bare floor, for `read_ground_with`.
pub fn ground_background(model: &SensorModel, floor: &FloorPaint) -> (f64, f64) {
    model.table.eval(model.height / floor.background())
}

/// `read_ground`, with `background = ground_background(model, floor)` computed beforehand: where
/// no paint is near, the reading needs no spot average and no table look-up.
#[inline]
pub fn read_ground_with(
    model: &SensorModel,
    floor: &FloorPaint,
    at: [f64; 2],
    axis: [f64; 2],
    background: (f64, f64),
    rng: Option<&mut Rng>,
) -> f32 {
    // With no region near `at`, every point of the spot reads the background.
    let (value, sigma) = if floor.regions_near(at).is_empty() {
        background
    } else {
        let f = spot_reflectance(model, floor, at, axis);
        model.table.eval(model.height / f)
    };
    noisy(value, sigma, rng)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::RobotProfile;
    use crate::world::{PaintRegion, PaintShape, WallBox};

    #[test]
    fn ground_sensor_reads_white_black_and_edges_between() {
        let e = RobotProfile::builtin("e-puck").unwrap();
        let model = &e.ground_sensors[0].model;
        let floor = FloorPaint::new(
            1.0,
            vec![PaintRegion {
                shape: PaintShape::Rect {
                    center: [1.0, 0.0],
                    half: [0.5, 0.5],
                    yaw: 0.0,
                },
                reflectance: 0.2,
            }],
        );
        let white = read_ground(model, &floor, [0.0, 0.0], [1.0, 0.0], None);
        let black = read_ground(model, &floor, [1.0, 0.0], [1.0, 0.0], None);
        let edge = read_ground(model, &floor, [0.5, 0.0], [1.0, 0.0], None);
        assert!((white - 855.625).abs() < 0.01, "{white}");
        assert!((black - 300.0).abs() < 1e-3, "{black}");
        assert!(edge > black + 10.0 && edge < white - 10.0, "{edge}");
        let background = ground_background(model, &floor);
        for k in 0..200 {
            let at = [k as f64 * 0.01 - 0.5, 0.3 - k as f64 * 0.003];
            let axis = [0.6, 0.8];
            assert_eq!(
                read_ground_with(model, &floor, at, axis, background, None),
                read_ground(model, &floor, at, axis, None),
                "at {at:?}"
            );
        }
    }

    #[test]
    fn infrared_reading_with_a_miss_computed_once_reads_the_same() {
        for name in ["e-puck", "seed", "alphabot2"] {
            let robot = RobotProfile::builtin(name).unwrap();
            let model = &robot.distance_sensors[0].model;
            let miss = infrared_miss(model);
            let range = model.table.max_input() as f32;
            let mut hits = vec![None];
            for k in 0..=100 {
                let distance = range * k as f32 / 100.0;
                for reflectance in [0.2, 0.5, 1.0] {
                    hits.push(Some(RayHit {
                        distance,
                        reflectance,
                    }));
                }
            }
            let (mut a, mut b) = (Rng::new(7), Rng::new(7));
            for hit in hits {
                let once = infrared_reading_with(model, hit, miss, None);
                assert_eq!(once.to_bits(), infrared_reading(model, hit, None).to_bits());
                let noisy_once = infrared_reading_with(model, hit, miss, Some(&mut a));
                let noisy = infrared_reading(model, hit, Some(&mut b));
                assert_eq!(noisy_once.to_bits(), noisy.to_bits(), "{name} {hit:?}");
            }
        }
    }

    #[test]
    fn infrared_free_space_reads_last_row() {
        let e = RobotProfile::builtin("e-puck").unwrap();
        let walls = WallIndex::new(&[WallBox {
            center: [5.0, 0.0],
            half: [0.1, 0.1],
            yaw: 0.0,
            reflectance: 1.0,
        }]);
        let v = read_infrared(
            &e.distance_sensors[0].model,
            &walls,
            [0.0, 0.0],
            [1.0, 0.0],
            None,
        );
        assert_eq!(v, 67.19);
    }
}
