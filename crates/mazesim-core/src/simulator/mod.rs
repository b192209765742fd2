//! One robot in one world: physics, sensors, time and counters, stepped in control steps.

mod neighbours;
mod rig;
mod shared_scene;
#[macro_use]
mod snapshot;

pub use neighbours::{Neighbour, Others, ROBOT_CONTACT_GAP, ROBOT_REFLECTANCE};
pub use rig::{Rig, SharedChannels};
pub use shared_scene::{move_in_scene, place_in_scene, share_scene, SceneStep};

use std::sync::Arc;

use crate::crossing::{Crossing, CrossingTracker};
use crate::error::{Error, Result};
use crate::limits::{self, MAX_PHYSICS_STEPS_PER_CONTROL_STEP};
use crate::physics::Body;
use crate::rng::Rng;
use crate::robot::{slant_distance, RobotProfile};
use crate::sensors::{infrared_reading_with, range_reading, GroundReader};
use crate::world::{Goal, NearbyWalls, RayHit, SensedWalls, World};

/// A gap to a wall below this (metres) counts as touching it.
pub const CONTACT_GAP: f32 = 2e-4;

/// How far beyond the body the nearest wall is looked for (metres); farther counts as this far.
/// It exceeds the contact prediction distance plus a step's travel, so free flight is decided right.
const CLEARANCE_SEARCH: f32 = 0.03;

/// How deep the body may start in a wall, metres: a pose closer than this to overlapping is
/// accepted (rapier pushes the body out within a step), a deeper one is refused.
pub const START_OVERLAP: f64 = 1e-3;

/// Farthest (millimetres) a body is pushed out of the walls, tried a millimetre further out at a
/// time, as Webots' physics pushes out a body that overlaps a wall; one deeper in stays there.
pub const PUSH_OUT_LIMIT_MM: u32 = 50;
/// Directions tried at each distance of the push out, evenly spaced from +x.
pub const PUSH_OUT_DIRECTIONS: u32 = 16;

/// The nearest point to `[x, y]` that `clear` accepts, tried a millimetre further out at a time
/// up to `PUSH_OUT_LIMIT_MM`, in `PUSH_OUT_DIRECTIONS` directions at each distance: where a body
/// that lies in a wall is pushed out to (a start saved in a wall, a supervisor's move into one).
pub fn pushed_out([x, y]: [f64; 2], mut clear: impl FnMut([f64; 2]) -> bool) -> Option<[f64; 2]> {
    (1..=PUSH_OUT_LIMIT_MM).find_map(|mm| {
        let distance = f64::from(mm) * 1e-3;
        (0..PUSH_OUT_DIRECTIONS).find_map(|k| {
            let angle = 2.0 * std::f64::consts::PI * f64::from(k) / f64::from(PUSH_OUT_DIRECTIONS);
            let p = [x + distance * angle.cos(), y + distance * angle.sin()];
            clear(p).then_some(p)
        })
    })
}

/// How deep (metres) a body of `radius` centred at `[x, y]` lies in the world's walls: its radius
/// less the signed distance from its centre to the nearest wall (negative: clear of them), and
/// that distance.
pub fn wall_overlap(world: &World, radius: f64, [x, y]: [f64; 2]) -> (f64, f32) {
    let r = radius as f32;
    let gap = world
        .wall_index()
        .signed_distance([x as f32, y as f32], r + CLEARANCE_SEARCH);
    (r as f64 - gap as f64, gap)
}

/// Checks a pose `[x, y, yaw]` (named `what` in the error) against the limits and the walls: the
/// robot's body may not overlap a wall by more than `START_OVERLAP`.
fn check_free(world: &World, robot: &RobotProfile, what: &str, pose: [f64; 3]) -> Result<()> {
    let [x, y, yaw] = pose;
    limits::check_pose(what, x, y, yaw)?;
    let (overlap, gap) = wall_overlap(world, robot.body_radius, [x, y]);
    if overlap > START_OVERLAP {
        return Err(Error::InvalidArgument(format!(
            "expected a {what} where the robot (radius {} m) is clear of the walls, found \
             ({x}, {y}, {yaw}) {}",
            robot.body_radius,
            if gap < 0.0 {
                format!("with its centre {:.4} m inside a wall", -gap)
            } else {
                format!("overlapping a wall by {overlap:.4} m")
            }
        )));
    }
    Ok(())
}

/// The wheel command of one control step, between `Simulator::command` and `finish_step`.
#[derive(Debug, Clone, Copy)]
pub struct Drive {
    /// Wheel speeds (rad/s) after the motors' gains.
    wheels: [f32; 2],
    /// Forward speed, m/s.
    linear: f32,
    /// Turn rate, rad/s.
    angular: f32,
    /// Whether the body touched a wall or a robot in a physics step so far.
    any_contact: bool,
}

/// How a simulator is set up.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimConfig {
    /// Seed of the noise stream.
    pub seed: u64,
    /// Sensor noise on or off.
    pub noise: bool,
    /// Control step in seconds; `None` = the world's basic time step. Must be a whole number of
    /// basic time steps.
    pub control_step: Option<f64>,
}

impl Default for SimConfig {
    fn default() -> Self {
        Self {
            seed: 0,
            noise: true,
            control_step: None,
        }
    }
}

simulator_fields! {
    /// A robot in a world.
    pub struct Simulator {
        world: Arc<World>,
        /// What a step reads of the robot, shared with the other simulators of its profile.
        rig: Arc<Rig>,
        config: SimConfig,
        physics_steps: u32,
        dt: f64,
        body: Body,
        /// Sine and cosine of the yaw.
        heading: [f32; 2],
        /// Touching another robot now (always false in a world of one robot).
        touching_robot: bool,
        /// The goal disc `set_goal` gave, instead of the world's.
        goal_override: Option<Goal>,
    }
    saved {
        rng: Rng,
        pose: [f32; 3],
        /// Per distance sensor: what its ray met at the last sensor reading.
        ray_hits: Vec<Option<RayHit>>,
        /// Per ground sensor: its reader of the world's floor.
        ground_readers: Vec<GroundReader>,
        time: f64,
        steps: u64,
        collisions: u64,
        colliding: bool,
        /// Touching a wall now.
        touching: bool,
        clearance: f32,
        distance_travelled: f64,
        wheel_speeds: [f32; 2],
        wheel_angles: [f64; 2],
        distance_readings: Vec<f32>,
        ground_readings: Vec<f32>,
        tracker: CrossingTracker,
        crossings: Vec<Crossing>,
        last_crossing: i32,
        /// Start pose used by `reset` instead of the world's, when set.
        start_override: Option<[f32; 3]>,
    }
}

impl Simulator {
    /// A simulator reset to the world's start pose.
    pub fn new(world: Arc<World>, robot: Arc<RobotProfile>, config: SimConfig) -> Result<Self> {
        Self::with_rig(world, Rig::new(robot), config)
    }

    /// A simulator of the robot of `rig` (shared with other simulators), reset to the world's
    /// start pose.
    pub fn with_rig(world: Arc<World>, rig: Arc<Rig>, config: SimConfig) -> Result<Self> {
        let start = world.start();
        Self::with_rig_at(world, rig, config, start)
    }

    /// A simulator of the robot of `rig` made at `start` (x, y, yaw), which must be clear of
    /// the walls for this robot: one of several robots is checked at its own start, not at the
    /// world's (the first robot's), where a larger robot may not fit. `reset` still goes to
    /// the world's start unless a start is set.
    pub fn with_rig_at(
        world: Arc<World>,
        rig: Arc<Rig>,
        config: SimConfig,
        start: [f64; 3],
    ) -> Result<Self> {
        let robot = rig.robot.clone();
        let dt = world.basic_time_step();
        let control = config.control_step.unwrap_or(dt);
        let ratio = control / dt;
        if !(control.is_finite() && control > 0.0)
            || (ratio - ratio.round()).abs() > 1e-6
            || ratio.round() < 1.0
        {
            return Err(Error::InvalidArgument(format!(
                "expected a control step that is a whole number of basic time steps ({} ms), found {} ms",
                dt * 1000.0,
                control * 1000.0
            )));
        }
        if ratio.round() > MAX_PHYSICS_STEPS_PER_CONTROL_STEP {
            return Err(Error::InvalidArgument(format!(
                "expected a control step of at most {MAX_PHYSICS_STEPS_PER_CONTROL_STEP} basic time \
                 steps ({} ms), found {} ms ({} steps)",
                MAX_PHYSICS_STEPS_PER_CONTROL_STEP * dt * 1000.0,
                control * 1000.0,
                ratio.round()
            )));
        }
        check_free(&world, &robot, "start pose", start)?;
        let pose = [start[0] as f32, start[1] as f32, start[2] as f32];
        let body = Body::new(
            world.solid_walls(),
            world.bodies(),
            robot.body_radius as f32,
            pose,
            dt as f32,
        );
        let mut sim = Simulator {
            tracker: CrossingTracker::new(),
            crossings: Vec::new(),
            last_crossing: 0,
            start_override: None,
            goal_override: None,
            distance_readings: vec![0.0; robot.distance_sensors.len()],
            ray_hits: vec![None; robot.distance_sensors.len()],
            ground_readers: robot
                .ground_sensors
                .iter()
                .map(|g| GroundReader::new(&g.model, world.floor()))
                .collect(),
            ground_readings: vec![0.0; robot.ground_sensors.len()],
            world,
            rig,
            config,
            physics_steps: ratio.round() as u32,
            dt,
            body,
            rng: Rng::new(config.seed),
            pose,
            heading: [0.0, 1.0],
            time: 0.0,
            steps: 0,
            collisions: 0,
            colliding: false,
            touching: false,
            touching_robot: false,
            clearance: 0.0,
            distance_travelled: 0.0,
            wheel_speeds: [0.0; 2],
            wheel_angles: [0.0; 2],
        };
        sim.reset(None);
        Ok(sim)
    }

    /// Back to the start pose with zeroed time and counters; a new seed if given.
    pub fn reset(&mut self, seed: Option<u64>) {
        if let Some(s) = seed {
            self.config.seed = s;
        }
        let s = self.world.start();
        let start = self
            .start_override
            .unwrap_or([s[0] as f32, s[1] as f32, s[2] as f32]);
        self.place(start);
        self.rng = Rng::new(self.config.seed);
        self.time = 0.0;
        self.steps = 0;
        self.collisions = 0;
        self.distance_travelled = 0.0;
        self.wheel_speeds = [0.0; 2];
        self.wheel_angles = [0.0; 2];
        self.crossings.clear();
        self.last_crossing = 0;
        self.sense();
    }

    /// Sets the pose every later `reset` starts from (instead of the world's start).
    /// The pose must lie within the limits (`crate::limits`) and leave the body clear of every wall.
    pub fn set_start(&mut self, x: f64, y: f64, yaw: f64) -> Result<()> {
        self.check_start(x, y, yaw)?;
        self.start_override = Some([x as f32, y as f32, yaw as f32]);
        Ok(())
    }

    /// The goal disc the episodes end at: the one `set_goal` gave, else the world's.
    pub fn goal(&self) -> Option<Goal> {
        self.goal_override.or(self.world.goal())
    }

    /// Sets the goal disc of this simulator, centre (x, y) and radius in metres, instead of the
    /// world's, until the simulator is made again. The centre must lie within the limits
    /// (`crate::limits`), the radius be finite and positive.
    pub fn set_goal(&mut self, x: f64, y: f64, radius: f64) -> Result<()> {
        check_goal(x, y, radius)?;
        self.goal_override = Some(Goal {
            center: [x, y],
            radius,
        });
        Ok(())
    }

    /// Whether `set_start(x, y, yaw)` would accept the pose (it changes nothing).
    pub fn check_start(&self, x: f64, y: f64, yaw: f64) -> Result<()> {
        check_free(&self.world, &self.rig.robot, "start pose", [x, y, yaw])
    }

    /// Moves the robot to a pose (x, y, yaw), at rest; sensors are read there. Time and counters go on.
    /// The pose must lie within the limits (`crate::limits`) and leave the body clear of every wall.
    /// The world's movable bodies stay where they are (with their motion).
    pub fn set_pose(&mut self, x: f64, y: f64, yaw: f64) -> Result<()> {
        check_free(&self.world, &self.rig.robot, "pose", [x, y, yaw])?;
        // Among movable bodies, the robot's ball moves in its scene (in a shared scene, the
        // swarm moves it there); the bodies are not made again.
        self.body.place_robot(0, [x as f32, y as f32, yaw as f32]);
        self.placed();
        self.sense();
        Ok(())
    }

    /// Puts the robot at `pose` at rest among the world's walls and its movable bodies made
    /// again at their starts (one of several robots in one scene: the swarm moves its ball).
    fn place(&mut self, pose: [f32; 3]) {
        if self.body.is_shared() {
            self.body.place_robot(0, pose);
        } else {
            self.body = Body::new(
                self.world.solid_walls(),
                self.world.bodies(),
                self.rig.drivetrain.body_radius,
                pose,
                self.dt as f32,
            );
        }
        self.placed();
    }

    /// Back at the start pose among the walls of `world` (this robot's world as it was made,
    /// before `take_world`), the movable bodies at their starts, all at rest (see
    /// `Swarm::reset_scene`), the noise stream started again from the seed of the last `reset`
    /// and the sensors read there as `reset` reads them; time and counters go on. The wheels'
    /// angles drop what they turned past their encoders' last tick, so that the encoders count
    /// the turns from here as Webots' position sensors count them from a reset joint: a reading
    /// less the reading here is the turn since, quantised, never a tick off.
    pub(crate) fn restart_among(&mut self, world: &Arc<World>) {
        self.wheel_angles = self.encoders();
        self.forget_moves(world);
        let start = self.start_pose().map(|v| v as f32);
        self.place(start);
        self.rng = Rng::new(self.config.seed);
        self.sense();
    }

    /// Takes `world` back, this robot's world as it was made, when `take_world` gave it another
    /// (the walls are met there once the body is placed again, at the next reset).
    pub(crate) fn forget_moves(&mut self, world: &Arc<World>) {
        if !Arc::ptr_eq(&self.world, world) {
            self.world = world.clone();
        }
    }

    /// Sets the velocity (vx, vy in m/s, turn rate in rad/s) of movable body `index` of the
    /// scene this simulator holds; returns whether it holds that body.
    pub(crate) fn set_body_velocity(&mut self, index: usize, velocity: [f32; 3]) -> bool {
        self.body.set_movable_velocity(index, velocity)
    }

    /// What follows a move of the body: the pose, heading, wall contact and barcode tracker.
    fn placed(&mut self) {
        self.pose = self.body.pose();
        self.heading = self.body.heading();
        self.update_contact();
        self.touching_robot = false;
        self.colliding = self.touching;
        if let Some(at) = self.barcode_sensor_position() {
            self.tracker.place(self.world.checkpoints(), at);
        }
    }

    /// World position of the barcode-reading ground sensor.
    fn barcode_sensor_position(&self) -> Option<[f64; 2]> {
        let (_, [px, py]) = self.rig.barcode_sensor?;
        let [x, y, _] = self.pose.map(|v| v as f64);
        let [s, c] = self.heading.map(|v| v as f64);
        Some([x + c * px - s * py, y + s * px + c * py])
    }

    fn update_contact(&mut self) {
        let r = self.rig.drivetrain.body_radius;
        let gap = self
            .world
            .wall_index()
            .signed_distance([self.pose[0], self.pose[1]], r + CLEARANCE_SEARCH);
        self.clearance = gap - r;
        self.touching = self.clearance < CONTACT_GAP;
    }

    /// Clamps a wheel speed to the motor limit; NaN or infinite speeds are an error.
    fn clamp_speed(&self, which: &str, w: f64) -> Result<f32> {
        if !w.is_finite() {
            return Err(Error::InvalidAction(format!(
                "expected a finite {which} wheel speed in rad/s, found {w}"
            )));
        }
        let m = self.rig.drivetrain.max_wheel_speed;
        Ok(w.clamp(-m, m) as f32)
    }

    /// Advances one control step with wheel speeds in rad/s. Speeds beyond the motor limit are
    /// clamped to it (as Webots does); NaN or infinite speeds raise `InvalidAction`. Each wheel
    /// then turns at its motor's gain (the profile's `motor_gains`) times its clamped speed, and
    /// while the body touches a wall it moves only `1 - slip_on_contact` of the wheels' motion.
    pub fn step(&mut self, left: f64, right: f64) -> Result<()> {
        // A robot alone steps as one of several does, with no other robot to meet.
        let mut drive = self.command(left, right)?;
        for k in 1..=self.physics_steps {
            let before = self.physics_move(&drive, Others::NONE);
            self.physics_settle(&mut drive, k, before, Others::NONE, None);
        }
        self.finish_step(&drive);
        Ok(())
    }

    /// Physics steps per control step.
    pub fn physics_steps(&self) -> u32 {
        self.physics_steps
    }

    /// Takes the wheel speeds of a control step (see `step`) and starts it.
    pub fn command(&mut self, left: f64, right: f64) -> Result<Drive> {
        let wl = self.clamp_speed("left", left)?;
        let wr = self.clamp_speed("right", right)?;
        self.wheel_speeds = [wl, wr];
        // The wheels turn at the motors' gains times the command.
        let drivetrain = &self.rig.drivetrain;
        let [gl, gr] = drivetrain.motor_gains;
        let (wl, wr) = ((wl as f64 * gl) as f32, (wr as f64 * gr) as f32);
        let r = drivetrain.wheel_radius;
        self.last_crossing = 0;
        Ok(Drive {
            wheels: [wl, wr],
            linear: r * (wl + wr) / 2.0,
            angular: r * (wr - wl) / drivetrain.axle_length,
            any_contact: false,
        })
    }

    /// Moves the body one physics step of `drive`, held back by the `others` robots at their
    /// poses before the step; returns the pose before it.
    #[inline]
    pub fn physics_move(&mut self, drive: &Drive, others: Others<'_>) -> [f32; 3] {
        let before = self.pose;
        let (linear, angular, held) = self.driven(drive, others);
        let walls = self.world.wall_index();
        match held {
            None => self.body.step(linear, angular, self.clearance, walls),
            Some(v) => {
                let speed = (v[0] * v[0] + v[1] * v[1]).sqrt();
                self.body.drive(v, speed, angular, self.clearance, walls);
            }
        }
        self.pose = self.body.pose();
        self.heading = self.body.heading();
        before
    }

    /// The motion `drive` asks of the body in a physics step: forward speed and turn rate (less
    /// the wheels' slip on a wall), and the velocity vector the `others` robots leave it when
    /// they hold it back (`None` when they do not).
    #[inline]
    fn driven(&self, drive: &Drive, others: Others<'_>) -> (f32, f32, Option<[f32; 2]>) {
        let slip = self.rig.drivetrain.slip_on_contact;
        // In contact with a wall, the wheels slip: the body moves `kept` of their motion.
        let (linear, angular) = if slip > 0.0 && self.touching {
            let kept = (1.0 - slip) as f32;
            (drive.linear * kept, drive.angular * kept)
        } else {
            (drive.linear, drive.angular)
        };
        let [s, c] = self.heading;
        let held = if others.is_empty() {
            None
        } else {
            let centre = [self.pose[0], self.pose[1]];
            let radius = self.rig.drivetrain.body_radius;
            let wanted = [c * linear, s * linear];
            others.yield_velocity(centre, radius, wanted, self.dt as f32)
        };
        (linear, angular, held)
    }

    /// Ends physics step `k` of the control step (its last: every sensor is read) once every
    /// robot has moved: contacts with the walls and the `others` robots, bumps, distance, wheel
    /// angles and barcode crossings. `scene` is the robot holding the rapier scene this one's
    /// rays meet the movable bodies in, when not this one (`shared`).
    #[inline]
    pub fn physics_settle(
        &mut self,
        drive: &mut Drive,
        k: u32,
        before: [f32; 3],
        others: Others<'_>,
        scene: Option<&Simulator>,
    ) {
        let dx = (self.pose[0] - before[0]) as f64;
        let dy = (self.pose[1] - before[1]) as f64;
        self.distance_travelled += (dx * dx + dy * dy).sqrt();
        self.wheel_angles[0] += drive.wheels[0] as f64 * self.dt;
        self.wheel_angles[1] += drive.wheels[1] as f64 * self.dt;
        let was_touching = self.touching || self.touching_robot;
        if k < self.physics_steps {
            self.update_contact();
        } else {
            // The last physics step: contact and every sensor together.
            self.sense_among_robots(others, scene);
        }
        self.touching_robot = !others.is_empty() && {
            let radius = self.rig.drivetrain.body_radius;
            others.gap([self.pose[0], self.pose[1]], radius) < ROBOT_CONTACT_GAP
        };
        let touching = self.touching || self.touching_robot;
        if touching && !was_touching {
            self.collisions += 1;
        }
        drive.any_contact |= touching;
        if let Some(at) = self.barcode_sensor_position() {
            if let Some(c) = self
                .tracker
                .update(self.world.checkpoints(), at, self.steps + 1)
            {
                self.last_crossing = c.signed_id();
                self.crossings.push(c);
            }
        }
    }

    /// Ends the control step that `command` started.
    #[inline]
    pub fn finish_step(&mut self, drive: &Drive) {
        self.colliding = drive.any_contact;
        self.steps += 1;
        self.time = self.steps as f64 * self.physics_steps as f64 * self.dt;
    }

    /// Updates the clearance (as `update_contact`) and reads every sensor at the current pose. The
    /// walls near the robot are gathered once, over a square holding every sensor ray and the
    /// clearance search square, and all those queries run against them.
    fn sense(&mut self) {
        rig::NEARBY.with_borrow_mut(|near| self.sense_among(near, Others::NONE, None));
    }

    /// `sense`, the infra-red rays meeting the `others` robots as well as the walls, and the
    /// movable bodies of `scene`'s rapier scene when given (else of this robot's own).
    fn sense_among_robots(&mut self, others: Others<'_>, scene: Option<&Simulator>) {
        rig::NEARBY.with_borrow_mut(|near| self.sense_among(near, others, scene));
    }

    /// `sense_among_robots` with `near` to gather the walls into.
    fn sense_among(
        &mut self,
        near: &mut NearbyWalls,
        others: Others<'_>,
        scene: Option<&Simulator>,
    ) {
        let [x, y, _] = self.pose;
        let [s, c] = self.heading;
        let world = &*self.world;
        let rig = &*self.rig;
        let r = rig.drivetrain.body_radius;
        let index = world.wall_index();
        near.gather(index, [x, y], rig.reach);
        self.clearance = near.signed_distance(index, [x, y], r + CLEARANCE_SEARCH) - r;
        self.touching = self.clearance < CONTACT_GAP;
        let noise = self.config.noise;
        let imperfect = &rig.imperfections;
        near.cast_fan(index, &rig.rays, [x, y], [s, c], &mut self.ray_hits);
        let movables = scene.map_or(&self.body, |holder| &holder.body);
        if movables.has_movables() {
            for (hit, &[px, py, dx, dy, length]) in self.ray_hits.iter_mut().zip(&rig.sensor_rays) {
                let origin = [x + c * px - s * py, y + s * px + c * py];
                let dir = [c * dx - s * dy, s * dx + c * dy];
                let limit = hit.map_or(length, |h| h.distance);
                if let Some(body_hit) = movables.cast_ray_movables(origin, dir, limit) {
                    *hit = Some(body_hit);
                }
            }
        }
        if !others.is_empty() {
            cast_among_robots(&mut self.ray_hits, &rig.sensor_rays, [x, y], [s, c], others);
        }
        if let Some(sensed) = world.sensed_walls() {
            cast_among_sensed(&mut self.ray_hits, rig, [x, y], [s, c], sensed);
        }
        let readings = self.distance_readings.iter_mut();
        for ((reading, channel), &hit) in readings.zip(&*rig.infrared).zip(&self.ray_hits) {
            let hit = hit.map(|h| RayHit {
                distance: slant_distance(channel.elevation, h.distance),
                ..h
            });
            let rng = noise.then_some(&mut self.rng);
            *reading = if channel.reflective {
                infrared_reading_with(&channel.model, hit, channel.miss, imperfect, rng)
            } else {
                let distance = hit.map(|h| h.distance);
                range_reading(
                    &channel.model,
                    distance,
                    channel.miss,
                    imperfect.noise_scale,
                    rng,
                )
            };
        }
        let (sd, cd) = (s as f64, c as f64);
        let ground = rig.ground.iter().zip(&mut self.ground_readers);
        for ((channel, reader), reading) in ground.zip(&mut self.ground_readings) {
            let [px, py] = channel.position;
            let at = [x as f64 + cd * px - sd * py, y as f64 + sd * px + cd * py];
            let rng = noise.then_some(&mut self.rng);
            *reading = reader.read(&channel.model, world.floor(), at, [cd, sd], imperfect, rng);
        }
    }

    /// Reads every sensor again at the current pose with the `others` robots where they stand
    /// (and the movable bodies of `scene`'s rapier scene, when not this robot's own), and whether
    /// the body touches one of them.
    pub fn sense_robots(&mut self, others: Others<'_>, scene: Option<&Simulator>) {
        self.sense_among_robots(others, scene);
        let radius = self.rig.drivetrain.body_radius;
        let gap = others.gap([self.pose[0], self.pose[1]], radius);
        self.touching_robot = gap < ROBOT_CONTACT_GAP;
        self.colliding |= self.touching_robot;
    }

    /// How far from the robot's centre its sensor rays and contacts reach in a step, metres:
    /// another robot farther than this plus its radius neither touches it nor meets its rays.
    pub fn reach(&self) -> f32 {
        self.rig.reach + crate::contact::CONTACT_MARGIN
    }

    /// Whether the body touches another robot now.
    pub fn touching_robot(&self) -> bool {
        self.touching_robot
    }

    /// The pose `reset` starts from (`set_start`'s, else the world's start).
    pub fn start_pose(&self) -> [f64; 3] {
        self.start_override
            .map_or(self.world.start(), |p| p.map(f64::from))
    }

    /// Reads the memory the next step reads first (the walls near the robot), so that a batch can
    /// bring it into cache for several environments at once; changes nothing.
    pub fn warm(&self) {
        let [x, y, _] = self.pose;
        NearbyWalls::warm(self.world.wall_index(), [x, y], self.rig.reach);
    }

    /// Barcode crossings since reset, in order.
    pub fn crossings(&self) -> &[Crossing] {
        &self.crossings
    }

    /// The crossing completed in the last control step as a signed checkpoint id (+id along the
    /// checkpoint's yaw, -id against it), 0 for none.
    pub fn last_crossing(&self) -> i32 {
        self.last_crossing
    }

    /// Index of the ground sensor whose crossings are tracked (nearest the robot's centre line).
    pub fn barcode_sensor(&self) -> Option<usize> {
        self.rig.barcode_sensor.map(|(index, _)| index)
    }

    /// Current poses (x, y, yaw) of the world's movable bodies, in world order.
    pub fn body_poses(&self) -> Vec<[f32; 3]> {
        self.body.movable_poses().collect()
    }

    /// Current velocities (vx, vy in m/s, turn rate in rad/s) of the world's movable bodies, in
    /// world order (empty but in the simulator that holds the bodies' scene).
    pub fn body_velocities(&self) -> Vec<[f32; 3]> {
        self.body.movable_velocities()
    }

    /// Puts movable body `index` at `pose`, at rest, in the scene this simulator holds; returns
    /// whether it holds that body.
    pub(crate) fn place_body(&mut self, index: usize, pose: [f32; 3]) -> bool {
        self.body.place_movable(index, pose)
    }

    /// Takes `world`, this one with some walls moved (`World::with_walls_moved`): the physics
    /// meets them and the next step's sensors see them where they are now.
    pub(crate) fn take_world(&mut self, world: Arc<World>) {
        self.world = world;
        self.body.replace_walls(self.world.solid_walls());
        self.read_floor_anew();
        self.update_contact();
    }

    /// New ground readers for the world's floor, which may be painted otherwise now: a reader
    /// keeps the bare floor it last saw, which a moved or imported mark may cover.
    fn read_floor_anew(&mut self) {
        let floor = self.world.floor();
        for (reader, channel) in self.ground_readers.iter_mut().zip(self.rig.ground.iter()) {
            *reader = GroundReader::new(&channel.model, floor);
        }
    }

    /// Takes `world`, the running world with nodes a supervisor imported or removed: its walls
    /// as `take_world` takes them, and its movable bodies, body `i` being the running body
    /// `kept[i]` where given (see `Body::replace_movables`).
    pub(crate) fn take_changed_world(&mut self, world: Arc<World>, kept: &[Option<usize>]) {
        self.world = world;
        let walls = self.world.solid_walls();
        self.body.replace_walls(walls);
        self.body.replace_movables(walls, self.world.bodies(), kept);
        self.read_floor_anew();
        self.update_contact();
    }

    /// Distance sensor readings in device order (raw counts or volts, per the profile).
    pub fn distance_sensors(&self) -> &[f32] {
        &self.distance_readings
    }

    /// Ground sensor readings in device order.
    pub fn ground_sensors(&self) -> &[f32] {
        &self.ground_readings
    }

    /// Pose (x, y, yaw).
    pub fn pose(&self) -> [f32; 3] {
        self.pose
    }

    /// Simulated seconds since reset.
    pub fn time(&self) -> f64 {
        self.time
    }

    /// Control steps since reset.
    pub fn steps(&self) -> u64 {
        self.steps
    }

    /// Bumps since reset: times the body came into contact with a wall.
    pub fn collisions(&self) -> u64 {
        self.collisions
    }

    /// Whether the body touched a wall during the last control step.
    pub fn colliding(&self) -> bool {
        self.colliding
    }

    /// Signed gap between the body and the nearest wall (negative: penetration), metres.
    pub fn wall_clearance(&self) -> f32 {
        self.clearance
    }

    /// Path length driven since reset, metres.
    pub fn distance_travelled(&self) -> f64 {
        self.distance_travelled
    }

    /// Wheel speeds commanded in the last step (after clamping), rad/s; the wheels turned at the
    /// motors' gains times these.
    pub fn wheel_speeds(&self) -> [f32; 2] {
        self.wheel_speeds
    }

    /// The wheels' rotation (radians) as it is, unquantised: what `encoders` reads before its
    /// rounding to the profile's resolution (motor gains included, slip not taken off), for
    /// callers that round it to a resolution of their own (a Webots PositionSensor's).
    pub fn wheel_turns(&self) -> [f64; 2] {
        self.wheel_angles
    }

    /// Wheel position sensors (radians): the wheels' true rotation (motor gains included, slip
    /// not taken off), quantised to the profile's encoder resolution.
    pub fn encoders(&self) -> [f64; 2] {
        let q = self.rig.robot.encoder_resolution;
        self.wheel_angles
            .map(|a| if q > 0.0 { (a / q).round() * q } else { a })
    }

    /// The configuration (with the seed of the last reset).
    pub fn config(&self) -> SimConfig {
        SimConfig {
            control_step: Some(self.control_step()),
            ..self.config
        }
    }

    /// Control step in seconds.
    pub fn control_step(&self) -> f64 {
        self.physics_steps as f64 * self.dt
    }

    /// The world.
    pub fn world(&self) -> &Arc<World> {
        &self.world
    }

    /// The robot profile.
    pub fn robot(&self) -> &Arc<RobotProfile> {
        &self.rig.robot
    }

    /// The robot's motor limit, rad/s (the profile's `max_wheel_speed`).
    #[inline]
    pub fn max_wheel_speed(&self) -> f64 {
        self.rig.drivetrain.max_wheel_speed
    }

    /// Bytes this simulator holds of its own: its size and its buffers on the heap, rapier's scene
    /// in a world with movable bodies estimated from its bodies and colliders; the world and the
    /// rig, which simulators share, are not counted (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        use crate::footprint::vec_bytes;
        std::mem::size_of_val(self)
            + vec_bytes(&self.ray_hits)
            + vec_bytes(&self.ground_readers)
            + vec_bytes(&self.distance_readings)
            + vec_bytes(&self.ground_readings)
            + vec_bytes(&self.crossings)
            + self.tracker.heap_bytes()
            + self.body.heap_bytes()
    }

    /// The robot's sensing set-up (shared with the other simulators of a batch).
    pub fn rig(&self) -> &Arc<Rig> {
        &self.rig
    }
}

/// Lets the rays `sensor_rays` (in the frame of a robot at `at` heading `[sin, cos]`) meet the
/// `others` robots nearer than what they met before (`hits`). Kept out of line: a robot alone
/// never calls it.
#[inline(never)]
fn cast_among_robots(
    hits: &mut [Option<RayHit>],
    sensor_rays: &[[f32; 5]],
    at: [f32; 2],
    heading: [f32; 2],
    others: Others<'_>,
) {
    let ([x, y], [s, c]) = (at, heading);
    for (hit, &[px, py, dx, dy, length]) in hits.iter_mut().zip(sensor_rays) {
        let origin = [x + c * px - s * py, y + s * px + c * py];
        let dir = [c * dx - s * dy, s * dx + c * dy];
        let limit = hit.map_or(length, |h| h.distance);
        if let Some(robot_hit) = others.cast_ray(origin, dir, limit) {
            *hit = Some(robot_hit);
        }
    }
}

/// Lets the infra-red rays of `rig` (a robot at `at` heading `[sin, cos]`) meet the world's
/// `sensed` walls nearer than what they met before (`hits`); the rays of range sensors pass them
/// by. Kept out of line: a world without sensed-only walls never calls it.
#[inline(never)]
fn cast_among_sensed(
    hits: &mut [Option<RayHit>],
    rig: &Rig,
    at: [f32; 2],
    heading: [f32; 2],
    sensed: &SensedWalls,
) {
    let ([x, y], [s, c]) = (at, heading);
    let rays = hits.iter_mut().zip(&rig.sensor_rays).zip(&*rig.infrared);
    for ((hit, &[px, py, dx, dy, length]), channel) in rays {
        if !channel.reflective {
            continue;
        }
        let origin = [x + c * px - s * py, y + s * px + c * py];
        let dir = [c * dx - s * dy, s * dx + c * dy];
        let limit = hit.map_or(length, |h| h.distance);
        if let Some(seen) = sensed.cast_ray(origin, dir, limit) {
            *hit = Some(seen);
        }
    }
}

/// Checks a goal disc: a centre within `MAX_COORDINATE`, a finite positive radius.
pub(crate) fn check_goal(x: f64, y: f64, radius: f64) -> Result<()> {
    use limits::{check_bounded, MAX_COORDINATE};
    check_bounded("the goal's x (metres)", x, MAX_COORDINATE)?;
    check_bounded("the goal's y (metres)", y, MAX_COORDINATE)?;
    if radius.is_finite() && radius > 0.0 && radius <= MAX_COORDINATE {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "expected the goal's radius to be a positive number of metres up to {MAX_COORDINATE}, \
             found {radius:?}"
        )))
    }
}
