//! Sensor models: Webots' infra-red distance sensor and the downward ground sensor.
//!
//! A distance sensor of a `Range` model (Webots' `generic`, `sonar` and `laser` types) reads
//! `LUT(d)`, the distance its ray runs, whatever colour it meets ([`range_reading`]).
//!
//! Infra-red (Webots `DistanceSensor` of type "infra-red"): the ray meets a wall at distance `d`;
//! the wall's reflection factor `f` (1 white, 0.2 black) scales it, and the reading is
//! `LUT(d / f) * (1 + sigma(d / f) * N(0, 1))`, the table interpolated linearly and clamped, `sigma`
//! its relative-noise column. No hit within the ray reads the last row.
//! Ground sensors look down from `height`; the floor's reflectance is averaged over a square spot
//! of side `footprint` (so a reading over a bar edge lies between the two colours) and read as
//! `LUT(height / f)`.
//!
//! A robot's profile may describe how its sensors differ from their models
//! ([`SensorImperfections`]):
//! - `noise_scale` multiplies every relative sigma (0: noiseless, and no random number drawn, as
//!   with the noise off).
//! - `wall_reflectance` multiplies the reflection factor of whatever an infra-red ray meets, so
//!   the reading is `LUT(d / (f * wall_reflectance))`. This is Webots' own infra-red model of a
//!   darker surface (its `f = 0.2 + 0.8 * red * (1 - 0.5 * roughness)` falls from 1 for a white
//!   wall to 0.2 for a black one): a wall of reflectance `r` reads at distance `d` what a white
//!   wall reads at `d / r`, so darker walls read farther, and a reading that falls to the far
//!   value sooner. (Real triangulating sensors such as the Sharp GP2Y0A41SK0F depend less on
//!   colour than this model says; the model errs on the side of a larger perturbation.)
//! - `ground_gain` multiplies every ground sensor reading (before noise): the gain drift of a
//!   reflective floor sensor, which Alg. 7's fixed threshold of 700 sees as the threshold moved
//!   to `700 / ground_gain`.

use crate::rng::Rng;
use crate::robot::{RobotProfile, SensorModel};
use crate::world::floor::DiscPaint;
use crate::world::{Bounds, FloorPaint, RayHit};

/// Samples per side of the ground sensor's spot.
const SPOT_SAMPLES: usize = 3;

/// How one robot's sensors differ from their models (see the module notes).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SensorImperfections {
    /// Multiplies every relative sigma.
    pub noise_scale: f64,
    /// Multiplies the reflection factor of what an infra-red ray meets.
    pub wall_reflectance: f64,
    /// Multiplies every ground reading.
    pub ground_gain: f64,
}

impl SensorImperfections {
    /// Sensors exactly as their models.
    pub const NONE: SensorImperfections = SensorImperfections {
        noise_scale: 1.0,
        wall_reflectance: 1.0,
        ground_gain: 1.0,
    };

    /// Those of `robot`'s profile.
    pub fn of(robot: &RobotProfile) -> Self {
        Self {
            noise_scale: robot.noise_scale,
            wall_reflectance: robot.wall_reflectance,
            ground_gain: robot.ground_gain,
        }
    }
}

/// Applies the model's relative Gaussian noise to a table value.
#[inline]
fn noisy(value: f64, sigma: f64, rng: Option<&mut Rng>) -> f32 {
    let v = match rng {
        Some(r) if sigma > 0.0 => value * (1.0 + sigma * r.normal()),
        _ => value,
    };
    v.max(0.0) as f32
}

/// What an infra-red sensor's table gives when its ray meets nothing (its last row), for
/// `infrared_reading_with`.
pub fn infrared_miss(model: &SensorModel) -> (f64, f64) {
    model.table.eval(model.table.max_input())
}

/// The reading of an infra-red sensor with imperfections `imperfect` for what its ray (of the
/// table's range) met, with `miss = infrared_miss(model)` computed beforehand: a ray that met
/// nothing needs no table look-up.
#[inline]
pub fn infrared_reading_with(
    model: &SensorModel,
    hit: Option<RayHit>,
    miss: (f64, f64),
    imperfect: &SensorImperfections,
    rng: Option<&mut Rng>,
) -> f32 {
    let (value, sigma) = match hit {
        Some(hit) => {
            let reflectance = hit.reflectance as f64 * imperfect.wall_reflectance;
            model.table.eval(hit.distance as f64 / reflectance)
        }
        None => miss,
    };
    noisy(value, sigma * imperfect.noise_scale, rng)
}

/// The reading of a sensor whose table reads the distance its ray runs as it is (a `Range`
/// model: Webots' `generic`, `sonar` and `laser` types), whatever colour the ray meets:
/// `distance` is where it met something (None: nothing), `miss` is `infrared_miss(model)`, and
/// `noise_scale` multiplies the table's sigma (a profile's `wall_reflectance` does not apply).
#[inline]
pub fn range_reading(
    model: &SensorModel,
    distance: Option<f32>,
    miss: (f64, f64),
    noise_scale: f64,
    rng: Option<&mut Rng>,
) -> f32 {
    let (value, sigma) = distance.map_or(miss, |d| model.table.eval(d as f64));
    noisy(value, sigma * noise_scale, rng)
}

/// Mean floor reflectance over the square spot (`footprint > 0`) of a sensor centred at `at`,
/// aligned with the robot's unit forward vector `axis` (cos, sin of its heading), given
/// `candidates = floor.regions_near(at)`.
///
/// The mean is that of the floor at `SPOT_SAMPLES` x `SPOT_SAMPLES` points of the spot. When no
/// edge of paint passes near the spot, all of them read the same, and that one value is summed
/// as many times instead of looking every point up.
pub fn spot_reflectance_among(
    model: &SensorModel,
    floor: &FloorPaint,
    candidates: &[u32],
    at: [f64; 2],
    axis: [f64; 2],
) -> f64 {
    if candidates.is_empty() {
        return floor.background();
    }
    debug_assert!(
        model.footprint * std::f64::consts::FRAC_1_SQRT_2 <= crate::world::floor::SPOT_MARGIN
    );
    let [c, s] = axis;
    let step = model.footprint / SPOT_SAMPLES as f64;
    let first = -(model.footprint - step) / 2.0;
    // Every sample lies within this distance of `at`: the corners of the grid of samples, turned
    // and scaled by `axis` (of length 1 give or take rounding).
    let reach = first.abs() * std::f64::consts::SQRT_2 * (c * c + s * s).sqrt();
    let candidates = match floor.disc_paint(candidates, at, reach) {
        DiscPaint::Uniform(f) => return uniform_spot(f),
        DiscPaint::Mixed(candidates) => candidates,
    };
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

/// The spot mean when every sample reads `f`: summed sample by sample like a mixed spot, which
/// need not give back `f` itself to the last bit.
#[inline]
fn uniform_spot(f: f64) -> f64 {
    let mut sum = 0.0;
    for _ in 0..SPOT_SAMPLES * SPOT_SAMPLES {
        sum += f;
    }
    sum / (SPOT_SAMPLES * SPOT_SAMPLES) as f64
}

/// The table value and relative sigma of a ground sensor over floor point `at`, given
/// `candidates = floor.regions_near(at)` and `background = ground_background(model, floor)`.
#[inline]
fn ground_value(
    model: &SensorModel,
    floor: &FloorPaint,
    candidates: &[u32],
    at: [f64; 2],
    axis: [f64; 2],
    background: (f64, f64),
) -> (f64, f64) {
    // With no region near `at`, every point of the spot reads the background.
    if candidates.is_empty() {
        return background;
    }
    let f = if model.footprint <= 0.0 {
        floor.reflectance_among(candidates, at)
    } else {
        spot_reflectance_among(model, floor, candidates, at, axis)
    };
    model.table.eval(model.height / f)
}

/// A ground sensor's table value and relative sigma over bare floor, for `GroundReader`.
pub fn ground_background(model: &SensorModel, floor: &FloorPaint) -> (f64, f64) {
    model.table.eval(model.height / floor.background())
}

/// One ground sensor reading the floor of one world again and again: it keeps its table value over bare floor and the last box of bare floor it was in (from
/// `FloorPaint::bare_box`), so that while it stays in that box a reading needs no look-up.
#[derive(Debug, Clone, PartialEq, serde::Serialize, serde::Deserialize)]
pub struct GroundReader {
    /// `ground_background` of the sensor and floor.
    background: (f64, f64),
    /// Floor where no region is near any point.
    bare: Bounds,
}

impl GroundReader {
    /// A reader of `floor` for a sensor of `model`.
    pub fn new(model: &SensorModel, floor: &FloorPaint) -> Self {
        Self {
            background: ground_background(model, floor),
            bare: Bounds::EMPTY,
        }
    }

    /// Reads the sensor, of imperfections `imperfect`, at floor point `at` on a robot whose unit
    /// forward vector is `axis`; `floor` must be the one the reader was made for.
    #[inline]
    pub fn read(
        &mut self,
        model: &SensorModel,
        floor: &FloorPaint,
        at: [f64; 2],
        axis: [f64; 2],
        imperfect: &SensorImperfections,
        rng: Option<&mut Rng>,
    ) -> f32 {
        let (value, sigma) = if self.bare.contains(at) {
            self.background
        } else {
            let candidates = floor.regions_near(at);
            if candidates.is_empty() {
                self.bare = floor.bare_box(at);
            }
            ground_value(model, floor, candidates, at, axis, self.background)
        };
        let gain = imperfect.ground_gain;
        noisy(value * gain, sigma * imperfect.noise_scale, rng)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::RobotProfile;
    use crate::world::{PaintRegion, PaintShape, WallBox, WallIndex};

    // The readings by their definitions, one sensor at a time: what the step's readers must give
    // to the bit.

    /// Reads an infra-red distance sensor whose ray starts at `origin` in the unit direction `dir`.
    fn read_infrared(
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
    fn infrared_reading(model: &SensorModel, hit: Option<RayHit>, rng: Option<&mut Rng>) -> f32 {
        let x = match hit {
            Some(hit) => hit.distance as f64 / hit.reflectance as f64,
            None => model.table.max_input(),
        };
        let (value, sigma) = model.table.eval(x);
        noisy(value, sigma, rng)
    }

    /// Mean floor reflectance over the sensor's square spot centred at `at`, aligned with the
    /// robot's unit forward vector `axis` (cos, sin of its heading).
    fn spot_reflectance(
        model: &SensorModel,
        floor: &FloorPaint,
        at: [f64; 2],
        axis: [f64; 2],
    ) -> f64 {
        if model.footprint <= 0.0 {
            return floor.reflectance_at(at);
        }
        spot_reflectance_among(model, floor, floor.regions_near(at), at, axis)
    }

    /// Reads a ground sensor at floor point `at` on a robot whose unit forward vector is `axis`.
    fn read_ground(
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
    }

    /// The spot mean by its definition: every sample looked up among the regions near the
    /// centre, summed and divided.
    fn reference_spot(
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
        let [c, s] = axis;
        let step = model.footprint / SPOT_SAMPLES as f64;
        let first = -(model.footprint - step) / 2.0;
        let mut sum = 0.0;
        for i in 0..SPOT_SAMPLES {
            let u = first + i as f64 * step;
            for j in 0..SPOT_SAMPLES {
                let v = first + j as f64 * step;
                let p = [at[0] + c * u - s * v, at[1] + s * u + c * v];
                sum += floor.reflectance_among(candidates, p);
            }
        }
        sum / (SPOT_SAMPLES * SPOT_SAMPLES) as f64
    }

    /// Barcode bars side by side (square to the axes and turned), discs and strokes over one
    /// another, in reflectances whose nine-fold sums do not divide back exactly.
    fn busy_floor() -> FloorPaint {
        let mut regions = Vec::new();
        for (k, yaw) in [0.0, std::f64::consts::FRAC_PI_2, 0.3]
            .into_iter()
            .enumerate()
        {
            let (s, c) = yaw.sin_cos();
            let centre = [0.5 * k as f64, 0.2 * k as f64];
            for bar in 0..6 {
                let along = (bar as f64 - 2.5) * 0.017;
                regions.push(PaintRegion {
                    shape: PaintShape::Rect {
                        center: [centre[0] + c * along, centre[1] + s * along],
                        half: [0.0085, 0.115],
                        yaw,
                    },
                    reflectance: [0.1, 0.7, 0.3][bar % 3],
                });
            }
        }
        regions.push(PaintRegion {
            shape: PaintShape::Circle {
                center: [0.5, 0.25],
                radius: 0.03,
            },
            reflectance: 0.3,
        });
        regions.push(PaintRegion {
            shape: PaintShape::Circle {
                center: [1.2, -0.1],
                radius: 0.002,
            },
            reflectance: 0.1,
        });
        regions.push(PaintRegion {
            shape: PaintShape::Capsule {
                a: [-0.1, -0.1],
                b: [0.4, 0.05],
                radius: 0.01,
            },
            reflectance: 0.7,
        });
        FloorPaint::new(0.9, regions)
    }

    #[test]
    fn quick_spot_is_the_nine_sample_mean_to_the_bit() {
        assert_ne!(
            uniform_spot(0.1),
            0.1,
            "the test needs sums that do not divide back"
        );
        let e = RobotProfile::builtin("e-puck").unwrap();
        let mut widest = (*e.ground_sensors[0].model).clone();
        widest.footprint = 0.007;
        let models = [&*e.ground_sensors[0].model, &widest];
        let floor = busy_floor();
        let mut rng = Rng::new(7);
        let (mut mixed, mut painted) = (0, 0);
        for n in 0..400_000 {
            let model = models[n % 2];
            // Near an edge of some region: a corner of its bounds, moved along and across.
            let region = &floor.regions()[n % floor.regions().len()];
            let b = region.shape.bounds();
            let corner = [
                if rng.uniform() < 0.5 {
                    b.min[0]
                } else {
                    b.max[0]
                },
                if rng.uniform() < 0.5 {
                    b.min[1]
                } else {
                    b.max[1]
                },
            ];
            let spread = [0.004, 0.03, 0.3][n % 3];
            let at = [
                corner[0] + rng.uniform_range(-spread, spread),
                corner[1] + rng.uniform_range(-spread, spread),
            ];
            let heading = rng.uniform_range(-4.0, 4.0);
            let axis = if n % 4 == 0 {
                // As the simulator has it: from an f32 heading.
                let (s, c) = (heading as f32).sin_cos();
                [c as f64, s as f64]
            } else {
                [heading.cos(), heading.sin()]
            };
            let quick = spot_reflectance(model, &floor, at, axis);
            let expected = reference_spot(model, &floor, at, axis);
            assert_eq!(quick, expected, "at {at:?} axis {axis:?}");
            let candidates = floor.regions_near(at);
            if !candidates.is_empty() {
                let reach = model.footprint / 3.0 * std::f64::consts::SQRT_2;
                match floor.disc_paint(candidates, at, reach) {
                    crate::world::floor::DiscPaint::Mixed(_) => mixed += 1,
                    crate::world::floor::DiscPaint::Uniform(f) => painted += (f != 0.9) as usize,
                }
            }
        }
        // Both ways were taken, many times.
        assert!(mixed > 20_000 && painted > 20_000, "{mixed} {painted}");
    }

    /// Points on the edge of a shape, each with its outward unit normal.
    fn edge_points(shape: &PaintShape) -> Vec<([f64; 2], [f64; 2])> {
        let turned = |centre: [f64; 2], (s, c): (f64, f64), p: [f64; 2]| {
            [
                centre[0] + c * p[0] - s * p[1],
                centre[1] + s * p[0] + c * p[1],
            ]
        };
        let along = [-0.9, -0.31, 0.0, 0.57, 1.0];
        let mut points = Vec::new();
        match *shape {
            PaintShape::Rect { center, half, yaw } => {
                let turn = yaw.sin_cos();
                for t in along {
                    for (p, n) in [
                        ([half[0], t * half[1]], [1.0, 0.0]),
                        ([-half[0], t * half[1]], [-1.0, 0.0]),
                        ([t * half[0], half[1]], [0.0, 1.0]),
                        ([t * half[0], -half[1]], [0.0, -1.0]),
                    ] {
                        points.push((turned(center, turn, p), turned([0.0; 2], turn, n)));
                    }
                }
            }
            PaintShape::Circle { center, radius } => {
                for k in 0..24 {
                    let (s, c) = (k as f64 * 0.2618 + 0.1).sin_cos();
                    points.push(([center[0] + radius * c, center[1] + radius * s], [c, s]));
                }
            }
            PaintShape::Capsule { a, b, radius } => {
                let d = [b[0] - a[0], b[1] - a[1]];
                let len = (d[0] * d[0] + d[1] * d[1]).sqrt();
                let n = [-d[1] / len, d[0] / len];
                for t in along.map(|t| (t + 1.0) / 2.0) {
                    let m = [a[0] + t * d[0], a[1] + t * d[1]];
                    for side in [1.0, -1.0] {
                        let n = [side * n[0], side * n[1]];
                        points.push(([m[0] + radius * n[0], m[1] + radius * n[1]], n));
                    }
                }
                for (end, away) in [(b, 1.0), (a, -1.0)] {
                    let u = [away * d[0] / len, away * d[1] / len];
                    points.push(([end[0] + radius * u[0], end[1] + radius * u[1]], u));
                }
            }
        }
        points
    }

    #[test]
    fn quick_spot_on_edges_to_the_last_bit() {
        // Spots whose corner sample falls on an edge (inside the shape or outside it), give or
        // take a few rounding steps: there the quick tests must give way to the samples.
        let e = RobotProfile::builtin("e-puck").unwrap();
        let model = &*e.ground_sensors[0].model;
        let floor = busy_floor();
        let third = model.footprint / 3.0;
        let reach = third * std::f64::consts::SQRT_2;
        let mut checked = 0;
        for region in floor.regions() {
            for (edge, n) in edge_points(&region.shape) {
                // The first corner sample lies at -reach along the diagonal of this heading,
                // the last at +reach.
                let heading = n[1].atan2(n[0]) - std::f64::consts::FRAC_PI_4;
                let axis = [heading.cos(), heading.sin()];
                for k in -30..=30 {
                    for away in [reach, -reach, third, -third] {
                        let d = away + k as f64 * 2e-13;
                        let at = [edge[0] + d * n[0], edge[1] + d * n[1]];
                        assert_eq!(
                            spot_reflectance(model, &floor, at, axis),
                            reference_spot(model, &floor, at, axis),
                            "at {at:?} axis {axis:?}"
                        );
                        checked += 1;
                    }
                }
            }
        }
        assert!(checked > 50_000, "{checked}");
    }

    #[test]
    fn a_ground_reader_reads_as_read_ground() {
        let e = RobotProfile::builtin("e-puck").unwrap();
        let model = &*e.ground_sensors[0].model;
        let floor = busy_floor();
        let mut reader = GroundReader::new(model, &floor);
        let (mut noise_a, mut noise_b) = (Rng::new(3), Rng::new(3));
        let mut walk = Rng::new(11);
        let (mut at, mut heading) = ([-0.6, -0.4], 0.0_f64);
        for k in 0..200_000 {
            heading += walk.uniform_range(-0.3, 0.3);
            at = [at[0] + 0.004 * heading.cos(), at[1] + 0.004 * heading.sin()];
            if !(-0.8..=1.8).contains(&at[0]) || !(-0.6..=0.9).contains(&at[1]) {
                heading += std::f64::consts::PI;
            }
            let axis = [heading.cos(), heading.sin()];
            let (a, b) = if k % 2 == 0 {
                (Some(&mut noise_a), Some(&mut noise_b))
            } else {
                (None, None)
            };
            assert_eq!(
                reader.read(model, &floor, at, axis, &SensorImperfections::NONE, a),
                read_ground(model, &floor, at, axis, b),
                "at {at:?}"
            );
        }
        assert_eq!(noise_a, noise_b);
    }

    #[test]
    fn a_range_sensor_reads_the_distance_whatever_colour_it_meets() {
        let robot = RobotProfile::builtin("e-puck").unwrap();
        let model = &robot.distance_sensors[0].model;
        let miss = infrared_miss(model);
        let darker = SensorImperfections {
            wall_reflectance: 0.5,
            ..SensorImperfections::NONE
        };
        for reflectance in [0.2, 0.38, 1.0] {
            let hit = Some(RayHit {
                distance: 0.02,
                reflectance,
            });
            let read = range_reading(model, Some(0.02), miss, darker.noise_scale, None);
            assert_eq!(read, model.table.eval(0.02_f32 as f64).0 as f32);
            let infrared = infrared_reading_with(model, hit, miss, &darker, None);
            assert!(infrared < read, "{reflectance}: {infrared} vs {read}");
        }
        let none = range_reading(model, None, miss, 1.0, None);
        assert_eq!(none, miss.0 as f32);
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
                let none = &SensorImperfections::NONE;
                let once = infrared_reading_with(model, hit, miss, none, None);
                assert_eq!(once.to_bits(), infrared_reading(model, hit, None).to_bits());
                let noisy_once = infrared_reading_with(model, hit, miss, none, Some(&mut a));
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
