//! What every simulator of one robot profile shares: the sensor rays in the robot frame, each
//! distance sensor's reading when its ray meets nothing, how far the sensing reaches, which ground
//! sensor reads barcodes, and the profile's fingerprint. A batch makes it once for all its envs.

use std::cell::RefCell;
use std::sync::Arc;

use crate::fingerprint::fnv1a;
use crate::robot::RobotProfile;
use crate::sensors::infrared_miss;
use crate::world::{NearbyWalls, RayFan};

use super::CLEARANCE_SEARCH;

thread_local! {
    /// The walls near the robot being sensed on this thread: gathered afresh by every reading, so
    /// one per thread serves every simulator (and keeps 0.8 kB out of each).
    pub(super) static NEARBY: RefCell<NearbyWalls> = RefCell::new(NearbyWalls::default());
}

/// The sensing set-up of a robot profile, shared by its simulators.
#[derive(Debug)]
pub struct Rig {
    /// The profile it was made for.
    pub(super) robot: Arc<RobotProfile>,
    /// The distance sensors' rays in the robot frame (position, unit direction, length across the
    /// floor: a tilted ray's length times the cosine of its elevation).
    pub(super) rays: RayFan,
    /// The same rays as plain numbers `[px, py, dx, dy, length]`, cast against movable bodies.
    pub(super) sensor_rays: Vec<[f32; 5]>,
    /// Per distance sensor: its table value and relative sigma when its ray meets nothing.
    pub(super) infrared_miss: Vec<(f64, f64)>,
    /// How far from the robot's centre a sensor ray or the clearance search can reach, metres.
    pub(super) reach: f32,
    /// Index of the ground sensor that reads barcodes: the one nearest the centre line.
    pub(super) barcode_sensor: Option<usize>,
    /// A hash of the profile's content, that snapshots carry.
    pub(super) fingerprint: u64,
}

/// How far from a robot's centre its sensor rays and the clearance search reach, metres, with a
/// margin of 1 mm for rounding: the square of this half side around the robot holds them all.
fn sensing_reach(robot: &RobotProfile) -> f32 {
    let rays = robot.distance_sensors.iter().map(|d| {
        let [px, py] = d.position;
        (px * px + py * py).sqrt() + d.model.table.max_input()
    });
    let search = robot.body_radius + CLEARANCE_SEARCH as f64;
    rays.fold(search, f64::max) as f32 + 1e-3
}

impl Rig {
    /// The set-up of `robot`.
    pub fn new(robot: Arc<RobotProfile>) -> Arc<Rig> {
        let sensor_rays: Vec<[f32; 5]> = robot
            .distance_sensors
            .iter()
            .map(|d| {
                let [px, py] = d.position;
                let [dx, dy] = d.direction;
                // A tilted ray reaches across the floor cos(elevation) of its length.
                let mut range = d.model.table.max_input();
                if d.elevation != 0.0 {
                    range *= d.elevation.cos();
                }
                [px, py, dx, dy, range].map(|v| v as f32)
            })
            .collect();
        let barcode_sensor = (0..robot.ground_sensors.len()).min_by(|&a, &b| {
            let ya = robot.ground_sensors[a].position[1].abs();
            let yb = robot.ground_sensors[b].position[1].abs();
            ya.total_cmp(&yb)
        });
        Arc::new(Rig {
            rays: RayFan::new(&sensor_rays),
            sensor_rays,
            infrared_miss: robot
                .distance_sensors
                .iter()
                .map(|d| infrared_miss(&d.model))
                .collect(),
            reach: sensing_reach(&robot),
            barcode_sensor,
            fingerprint: fnv1a(format!("{robot:?}").as_bytes()),
            robot,
        })
    }

    /// Bytes of the rig and its buffers on the heap (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        use crate::footprint::vec_bytes;
        std::mem::size_of_val(self)
            + self.rays.heap_bytes()
            + vec_bytes(&self.sensor_rays)
            + vec_bytes(&self.infrared_miss)
    }

    /// The robot profile.
    pub fn robot(&self) -> &Arc<RobotProfile> {
        &self.robot
    }
}
