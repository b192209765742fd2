//! What every simulator of one robot profile shares: everything a control step reads of the
//! robot, held compact so that a step never follows the profile itself. The drivetrain's
//! constants and the sensors' imperfections are plain numbers; the sensor rays in the robot frame
//! are cast together; each sensor is a channel (its model, its reading when its ray meets
//! nothing, where a ground sensor sits), and the channel lists are shared by the rigs of a batch
//! where they are equal (a perturbation moves rays and scales readings, not models); which ground
//! sensor reads barcodes, how far the sensing reaches, and the profile's fingerprint. A batch
//! makes one rig for all envs of equal profiles.

use std::cell::RefCell;
use std::sync::Arc;

use crate::fingerprint::fnv1a;
use crate::robot::{RobotProfile, SensorKind, SensorModel};
use crate::sensors::{infrared_miss, SensorImperfections};
use crate::world::{NearbyWalls, RayFan};

use super::CLEARANCE_SEARCH;

thread_local! {
    /// The walls near the robot being sensed on this thread: gathered afresh by every reading, so
    /// one per thread serves every simulator (and keeps 0.8 kB out of each).
    pub(super) static NEARBY: RefCell<NearbyWalls> = RefCell::new(NearbyWalls::default());
}

/// The body, wheels and motors of a profile as a control step reads them (the profile's values,
/// converted to `f32` where the step computes in `f32`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Drivetrain {
    /// Motor limit, rad/s: commands are clamped to it.
    pub(super) max_wheel_speed: f64,
    /// Each wheel's speed over its command.
    pub(super) motor_gains: [f64; 2],
    /// Share of the wheels' motion lost while the body touches a wall.
    pub(super) slip_on_contact: f64,
    pub(super) wheel_radius: f32,
    pub(super) axle_length: f32,
    pub(super) body_radius: f32,
}

impl Drivetrain {
    fn of(robot: &RobotProfile) -> Self {
        Self {
            max_wheel_speed: robot.max_wheel_speed,
            motor_gains: robot.motor_gains,
            slip_on_contact: robot.slip_on_contact,
            wheel_radius: robot.wheel_radius as f32,
            axle_length: robot.axle_length as f32,
            body_radius: robot.body_radius as f32,
        }
    }
}

/// One infra-red distance sensor as a reading uses it (its ray is in the rig's fan).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct InfraredChannel {
    /// The sensor's model (its table), shared.
    pub(super) model: Arc<SensorModel>,
    /// Its table value and relative sigma when its ray meets nothing (`infrared_miss`).
    pub(super) miss: (f64, f64),
    /// How far its ray rises above the floor's plane, radians (`DistanceSensor::elevation`).
    pub(super) elevation: f64,
    /// Whether the reflection factor of what its ray meets divides the distance (an
    /// `Infrared` model), or the distance is read as it is (a `Range` model).
    pub(super) reflective: bool,
}

/// One ground sensor as a reading uses it.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct GroundChannel {
    /// Position in the robot frame, metres.
    pub(super) position: [f64; 2],
    /// The sensor's model, shared.
    pub(super) model: Arc<SensorModel>,
}

/// The channel lists of the rigs made so far, which a new rig takes instead of its own copy
/// where equal (`Rig::sharing`).
#[derive(Debug, Default)]
pub struct SharedChannels {
    infrared: Vec<Arc<[InfraredChannel]>>,
    ground: Vec<Arc<[GroundChannel]>>,
}

/// `channels`, or an equal list among `made` (to which it is added when new).
fn shared<T: PartialEq>(made: &mut Vec<Arc<[T]>>, channels: Vec<T>) -> Arc<[T]> {
    if let Some(same) = made.iter().find(|m| ***m == *channels) {
        return same.clone();
    }
    let list: Arc<[T]> = channels.into();
    made.push(list.clone());
    list
}

/// The sensing set-up of a robot profile, shared by its simulators.
#[derive(Debug)]
pub struct Rig {
    /// Body, wheels and motors.
    pub(super) drivetrain: Drivetrain,
    /// How the sensors differ from their models.
    pub(super) imperfections: SensorImperfections,
    /// How far from the robot's centre a sensor ray or the clearance search can reach, metres.
    pub(super) reach: f32,
    /// The ground sensor that reads barcodes (the one nearest the centre line): its index and
    /// position in the robot frame.
    pub(super) barcode_sensor: Option<(usize, [f64; 2])>,
    /// The distance sensors' rays in the robot frame (position, unit direction, length across the
    /// floor: a tilted ray's length times the cosine of its elevation).
    pub(super) rays: RayFan,
    /// Per distance sensor, in device order.
    pub(super) infrared: Arc<[InfraredChannel]>,
    /// Per ground sensor, in device order.
    pub(super) ground: Arc<[GroundChannel]>,
    /// The rays as plain numbers `[px, py, dx, dy, length]`, cast against movable bodies and
    /// other robots.
    pub(super) sensor_rays: Vec<[f32; 5]>,
    /// A hash of the profile's content, that snapshots carry.
    pub(super) fingerprint: u64,
    /// The profile it was made for (read when a simulator is made or checked, not by a step).
    pub(super) robot: Arc<RobotProfile>,
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
        Self::sharing(robot, &mut SharedChannels::default())
    }

    /// The set-up of `robot`, its channel lists those of `made` where equal (and added to it
    /// where new).
    pub fn sharing(robot: Arc<RobotProfile>, made: &mut SharedChannels) -> Arc<Rig> {
        // The fingerprint's text first: it is dropped before the parts a step reads are
        // allocated, which then lie together.
        let fingerprint = fnv1a(format!("{robot:?}").as_bytes());
        let infrared = (robot.distance_sensors.iter())
            .map(|d| InfraredChannel {
                model: d.model.clone(),
                miss: infrared_miss(&d.model),
                elevation: d.elevation,
                reflective: d.model.kind == SensorKind::Infrared,
            })
            .collect();
        let ground = (robot.ground_sensors.iter())
            .map(|g| GroundChannel {
                position: g.position,
                model: g.model.clone(),
            })
            .collect();
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
            drivetrain: Drivetrain::of(&robot),
            imperfections: SensorImperfections::of(&robot),
            reach: sensing_reach(&robot),
            barcode_sensor: barcode_sensor.map(|i| (i, robot.ground_sensors[i].position)),
            rays: RayFan::new(&sensor_rays),
            infrared: shared(&mut made.infrared, infrared),
            ground: shared(&mut made.ground, ground),
            sensor_rays,
            fingerprint,
            robot,
        })
    }

    /// Bytes of the rig and its buffers on the heap, its channel lists aside (other rigs may
    /// share them: `channel_bytes`) (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        use crate::footprint::vec_bytes;
        std::mem::size_of_val(self) + self.rays.heap_bytes() + vec_bytes(&self.sensor_rays)
    }

    /// Bytes of the channel lists on the heap that `counted` (their addresses) does not hold
    /// yet; adds them to it.
    pub(crate) fn channel_bytes(&self, counted: &mut std::collections::HashSet<usize>) -> usize {
        let infrared = counted.insert(self.infrared.as_ptr() as usize);
        let ground = counted.insert(self.ground.as_ptr() as usize);
        usize::from(infrared) * std::mem::size_of_val(&*self.infrared)
            + usize::from(ground) * std::mem::size_of_val(&*self.ground)
    }

    /// The robot profile.
    pub fn robot(&self) -> &Arc<RobotProfile> {
        &self.robot
    }

    /// Whether this rig and `other` share their channel lists (one copy of each in memory).
    pub fn shares_channels_with(&self, other: &Rig) -> bool {
        Arc::ptr_eq(&self.infrared, &other.infrared) && Arc::ptr_eq(&self.ground, &other.ground)
    }
}
