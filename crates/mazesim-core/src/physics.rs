//! The robot's body, seen from above (no gravity): a disc whose velocity the wheel speeds set each
//! physics step (differential drive).
//!
//! Among walls alone, its contacts are resolved by `crate::contact` against the world's shared
//! wall index. In a world with movable bodies, rapier2d simulates the robot as a dynamic ball
//! among fixed wall boxes and the bodies: its contact solver keeps the robot out of the walls and
//! pushes the bodies. The solver's length unit is scaled to the e-puck so its allowed penetration
//! and prediction distance are fractions of a millimetre, not of a metre.
//!
//! Floor friction of a movable body is Coulomb's kinetic friction, as Webots' ODE applies it
//! with a contact's `coulombFriction` `mu`: a body sliding on the floor slows at `mu * g`
//! whatever its speed, until it stops (a pushed body coasts `v^2 / (2 mu g)`: at the e-puck's
//! top speed, 0.129 m/s, and `mu` 0.5, 1.7 mm). Its turn slows by the torque of that friction
//! spread evenly over its footprint (`mu m g` times the footprint's mean distance from the
//! centre, over the moment of inertia): linear and angular friction are applied apart, over
//! each half of every physics step, and neither reverses a motion. Contacts between the robot, the
//! bodies and the walls have no friction.

use rapier2d::parry::query::Ray;
use rapier2d::prelude::*;

use crate::contact;
use crate::world::{BodyShape, MovableBody, RayHit, WallBox, WallIndex};

/// Gravity (m/s^2), which presses a movable body on the floor: Webots' `WorldInfo.gravity`
/// default.
pub const GRAVITY: f32 = 9.81;

/// Rapier's solver iterations: a push through a chain of bodies needs more than one.
const SOLVER_ITERATIONS_WITH_BODIES: usize = 4;

/// Scale of the scene for rapier's tolerances (allowed error, corrective velocity): 1 cm.
const LENGTH_UNIT: f32 = 0.01;

/// Contacts are predicted this far ahead (metres). It must exceed the distance the body can move in
/// one physics step (0.151 m/s * 32 ms = 4.8 mm at the e-puck2's top speed, 7.536 rad/s of 0.02 m
/// wheels) so that the solver sees a wall before the body reaches it; otherwise it only pushes the
/// body out after it has sunk in.
const PREDICTION_DISTANCE: f32 = 0.01;

/// Free flight gives way to the contact solve in any step that could end within this gap of a
/// wall (metres). The wall contact solve (`crate::contact`) moves a body that meets no wall
/// exactly as free flight does, so this margin only saves work: it does not change results.
const FREE_FLIGHT_MARGIN: f32 = 0.0005;

/// The physical state of one robot among its walls and the world's movable bodies.
///
/// Among walls alone the body holds only its pose: far from every wall it moves in free flight
/// (position += velocity * dt, angle += rate * dt), near one its contacts are resolved against the
/// world's shared wall index by `crate::contact`, without a rapier world per env. With movable
/// bodies, rapier simulates the robot, the bodies and the walls together every step.
pub struct Body {
    pose: [f32; 3],
    /// Sine and cosine of `pose[2]`.
    heading: [f32; 2],
    dt: f32,
    radius: f32,
    /// Rapier's scene, for a world with movable bodies (held by robot 0 of a world of several).
    scene: Option<Box<Scene>>,
    /// Whether the body is one of several robots' in one scene (`Body::shared`).
    shared: bool,
}

/// The robot, the walls and the movable bodies in rapier.
struct Scene {
    world: PhysicsWorld,
    /// The walls' colliders, in the order of the walls they were made of.
    walls: Vec<ColliderHandle>,
    /// The robots' bodies, in world order (one but in a world of several robots).
    robots: Vec<RigidBodyHandle>,
    /// The movable bodies with their reflectance, in world order.
    movables: Vec<(RigidBodyHandle, ColliderHandle, f32)>,
    /// Each movable body's floor friction (`FloorFriction`), in the order of `movables`.
    frictions: Vec<FloorFriction>,
}

/// The slowing of a movable body by the floor's Coulomb friction: its linear deceleration
/// (m/s^2) and its angular one (rad/s^2) while it slides and turns.
#[derive(Clone, Copy, Debug, PartialEq)]
struct FloorFriction {
    linear: f32,
    angular: f32,
    /// Whether a robot's wheels overcome this friction (`mu m g` within `ROBOT_GRIP`).
    yields_to_robots: bool,
}

/// The mass of a robot's body in the scene (kg): an e-puck's, about 0.16 kg.
const ROBOT_MASS: f32 = 0.16;

/// The force a robot's wheels push with before they slip (N): Coulomb friction 1 (Webots'
/// default contact) on the robot's weight.
const ROBOT_GRIP: f64 = ROBOT_MASS as f64 * GRAVITY as f64;

/// A movable body within this distance of a robot's body (m) touches it.
const TOUCHING: f32 = 1e-4;

impl FloorFriction {
    /// The friction of `m` on the floor: `mu g` along its motion, and about its centre the
    /// torque of `mu m g` spread evenly over its footprint over its moment of inertia (a disc's
    /// `4 mu g / (3 r)`).
    fn of(m: &MovableBody) -> Self {
        let linear = m.friction * f64::from(GRAVITY);
        // The footprint's mean distance from its centre, and its radius of gyration squared.
        let (mean_arm, gyration) = match m.shape {
            BodyShape::Circle { radius } => (2.0 * radius / 3.0, radius * radius / 2.0),
            BodyShape::Box { half: [a, b] } => {
                let d = a.hypot(b);
                let arm = (d
                    + a * a / (2.0 * b) * ((b + d) / a).ln()
                    + b * b / (2.0 * a) * ((a + d) / b).ln())
                    / 3.0;
                (arm, (a * a + b * b) / 3.0)
            }
        };
        FloorFriction {
            linear: linear as f32,
            angular: (linear * mean_arm / gyration) as f32,
            yields_to_robots: linear * m.mass <= ROBOT_GRIP,
        }
    }

    /// Slows `body` by this friction over `dt` seconds, to rest at most.
    fn slow(self, body: &mut RigidBody, dt: f32) {
        let v = body.linvel();
        let speed = v.length();
        let lost = self.linear * dt;
        if speed > 0.0 {
            let kept = if speed > lost {
                (speed - lost) / speed
            } else {
                0.0
            };
            body.set_linvel(v * kept, false);
        }
        let w = body.angvel();
        let turn_lost = self.angular * dt;
        if w != 0.0 {
            let kept = if w.abs() > turn_lost {
                w - turn_lost * w.signum()
            } else {
                0.0
            };
            body.set_angvel(kept, false);
        }
    }
}

fn wrap_angle(a: f32) -> f32 {
    let pi = std::f32::consts::PI;
    if a > pi {
        a - 2.0 * pi
    } else if a <= -pi {
        a + 2.0 * pi
    } else {
        a
    }
}

/// The fixed collider of a wall.
fn wall(w: &WallBox) -> ColliderBuilder {
    ColliderBuilder::cuboid(w.half[0] as f32, w.half[1] as f32)
        .position(Pose::new(
            Vector::new(w.center[0] as f32, w.center[1] as f32),
            w.yaw as f32,
        ))
        .friction(0.0)
        .restitution(0.0)
}

/// Inserts movable body `m` into `world` at its start, at rest: its body, its collider and its
/// reflectance.
fn movable(world: &mut PhysicsWorld, m: &MovableBody) -> (RigidBodyHandle, ColliderHandle, f32) {
    let [x, y, yaw] = m.start.map(|v| v as f32);
    let rigid = RigidBodyBuilder::dynamic()
        .translation(Vector::new(x, y))
        .rotation(yaw)
        .can_sleep(false)
        .build();
    let handle = world.bodies.insert(rigid);
    let shape = match m.shape {
        BodyShape::Box { half } => ColliderBuilder::cuboid(half[0] as f32, half[1] as f32),
        BodyShape::Circle { radius } => ColliderBuilder::ball(radius as f32),
    };
    let collider = shape
        .mass(m.mass as f32)
        .friction(0.0)
        .friction_combine_rule(CoefficientCombineRule::Min)
        .restitution(0.0);
    let collider = world
        .colliders
        .insert_with_parent(collider, handle, &mut world.bodies);
    (handle, collider, m.reflectance as f32)
}

impl Scene {
    /// Rapier's world of `walls`, the balls of `robots` (radius and pose of each) and the movable
    /// `bodies`, made in that order.
    fn new(walls: &[WallBox], bodies: &[MovableBody], robots: &[(f32, [f32; 3])], dt: f32) -> Self {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        world.integration_parameters.dt = dt;
        world.integration_parameters.length_unit = LENGTH_UNIT;
        world.integration_parameters.num_solver_iterations = SOLVER_ITERATIONS_WITH_BODIES;
        world.integration_parameters.normalized_prediction_distance =
            PREDICTION_DISTANCE / LENGTH_UNIT;
        let walls = walls
            .iter()
            .map(|w| world.colliders.insert(wall(w)))
            .collect();
        let robots = robots
            .iter()
            .map(|&(radius, pose)| {
                let body = RigidBodyBuilder::dynamic()
                    .translation(Vector::new(pose[0], pose[1]))
                    .rotation(pose[2])
                    .can_sleep(false)
                    .build();
                let robot = world.bodies.insert(body);
                // e-puck mass is about 0.16 kg; only the ratio to walls (infinite) matters here.
                let ball = ColliderBuilder::ball(radius)
                    .mass(ROBOT_MASS)
                    .friction(0.0)
                    .friction_combine_rule(CoefficientCombineRule::Min)
                    .restitution(0.0);
                world
                    .colliders
                    .insert_with_parent(ball, robot, &mut world.bodies);
                robot
            })
            .collect();
        let movables = bodies.iter().map(|m| movable(&mut world, m)).collect();
        let frictions = bodies.iter().map(FloorFriction::of).collect();
        Scene {
            world,
            walls,
            robots,
            movables,
            frictions,
        }
    }

    /// One physics step: the floor's friction slows every movable body over half the step,
    /// rapier steps (moving each at that mid-step velocity, as a constant deceleration moves
    /// it), and the friction slows them over the other half.
    fn step(&mut self) {
        self.slow_movables();
        self.world.step();
        self.slow_movables();
    }

    /// Slows every movable body by its floor friction over half a physics step, but for one a
    /// robot pushes whose friction its wheels overcome: its pusher's motors hold their speed,
    /// so the body goes at the pusher's speed, as in Webots (a heavier body is slowed as a free
    /// one, and slows its pusher).
    fn slow_movables(&mut self) {
        let half = 0.5 * self.world.integration_parameters.dt;
        for (&(handle, collider, _), friction) in self.movables.iter().zip(&self.frictions) {
            if friction.yields_to_robots && self.touches_a_robot(collider) {
                continue;
            }
            friction.slow(&mut self.world.bodies[handle], half);
        }
    }

    /// Whether `collider` touches a robot's body (as the last step's contacts found it).
    fn touches_a_robot(&self, collider: ColliderHandle) -> bool {
        let world = &self.world;
        world.narrow_phase.contact_pairs_with(collider).any(|pair| {
            let other = if pair.collider1 == collider {
                pair.collider2
            } else {
                pair.collider1
            };
            let robot = (world.colliders.get(other))
                .and_then(|c| c.parent())
                .is_some_and(|body| self.robots.contains(&body));
            robot
                && pair
                    .find_deepest_contact()
                    .is_some_and(|(_, contact)| contact.dist <= TOUCHING)
        })
    }

    /// Takes `walls` in place of the walls the scene was made among (some of them moved).
    fn replace_walls(&mut self, walls: &[WallBox]) {
        let world = &mut self.world;
        for handle in self.walls.drain(..) {
            world.colliders.remove(
                handle,
                &mut world.islands,
                &mut world.bodies,
                &mut world.soft_bodies,
                true,
            );
        }
        self.walls = walls
            .iter()
            .map(|w| world.colliders.insert(wall(w)))
            .collect();
    }

    /// Takes `bodies` in place of the movable bodies: body `i` is the running body `kept[i]`
    /// where it is given (its pose and motion go on), else a new one at its start, at rest; the
    /// running bodies that none keeps are taken out.
    fn replace_movables(&mut self, bodies: &[MovableBody], kept: &[Option<usize>]) {
        let running = std::mem::take(&mut self.movables);
        let world = &mut self.world;
        for (i, &(handle, _, _)) in running.iter().enumerate() {
            if !kept.contains(&Some(i)) {
                world.bodies.remove(
                    handle,
                    &mut world.islands,
                    &mut world.colliders,
                    &mut world.impulse_joints,
                    &mut world.multibody_joints,
                    &mut world.soft_bodies,
                    true,
                );
            }
        }
        self.movables = (bodies.iter().zip(kept))
            .map(|(m, k)| match k {
                Some(i) => running[*i],
                None => movable(world, m),
            })
            .collect();
        self.frictions = bodies.iter().map(FloorFriction::of).collect();
    }

    /// The pose of robot `index`'s body.
    fn robot_pose(&self, index: usize) -> [f32; 3] {
        let b = &self.world.bodies[self.robots[index]];
        let t = b.translation();
        [t.x, t.y, b.rotation().angle()]
    }

    /// Takes `world`, read back from a snapshot, after checking it was made like this one.
    fn load(&mut self, world: PhysicsWorld) -> Result<(), String> {
        let counts = |w: &PhysicsWorld| (w.bodies.len(), w.colliders.len());
        if counts(&world) != counts(&self.world) {
            return Err(format!(
                "expected a physics state of {} bodies and {} colliders, found {} and {}",
                self.world.bodies.len(),
                self.world.colliders.len(),
                world.bodies.len(),
                world.colliders.len()
            ));
        }
        let handles_known = self.robots.iter().all(|&r| world.bodies.get(r).is_some())
            && self.movables.iter().all(|&(body, collider, _)| {
                world.bodies.get(body).is_some() && world.colliders.get(collider).is_some()
            });
        if !handles_known {
            return Err(
                "expected every robot's and every movable body's handles, found a \
                        physics state without them"
                    .to_string(),
            );
        }
        // The same limits as a world file's bodies: a state edited far away is refused.
        for (_, body) in world.bodies.iter() {
            let t = body.translation();
            let angle = body.rotation().angle();
            crate::limits::check_pose("physics body", t.x.into(), t.y.into(), angle.into())
                .map_err(|e| e.to_string())?;
        }
        self.world.islands = world.islands;
        self.world.broad_phase = world.broad_phase;
        self.world.narrow_phase = world.narrow_phase;
        self.world.bodies = world.bodies;
        self.world.colliders = world.colliders;
        self.world.impulse_joints = world.impulse_joints;
        self.world.multibody_joints = world.multibody_joints;
        self.world.soft_bodies = world.soft_bodies;
        self.world.integration_parameters = world.integration_parameters;
        self.world.gravity = world.gravity;
        Ok(())
    }
}

impl Body {
    /// A body of `radius` at `pose` (x, y, yaw) among `walls` and the movable `bodies` at their
    /// start poses, stepped by `dt` seconds. Without movable bodies nothing of `walls` is kept:
    /// `step` takes the world's wall index.
    pub fn new(
        walls: &[WallBox],
        bodies: &[MovableBody],
        radius: f32,
        pose: [f32; 3],
        dt: f32,
    ) -> Body {
        let robot = [(radius, pose)];
        let scene = (!bodies.is_empty()).then(|| Box::new(Scene::new(walls, bodies, &robot, dt)));
        let mut body = Body {
            pose,
            heading: [0.0, 1.0],
            dt,
            radius,
            scene,
            shared: false,
        };
        let start = body.scene.as_ref().map_or(pose, |s| s.robot_pose(0));
        body.set_pose(start);
        body
    }

    /// The bodies of several robots (radius and pose of each) among `walls` and the movable
    /// `bodies` at their start poses, all in one rapier scene that the first body holds: robots
    /// push the bodies, the bodies push robots, and everything meets the walls. The others follow
    /// the poses [`Body::step_shared`] gives them.
    pub fn shared(
        walls: &[WallBox],
        bodies: &[MovableBody],
        robots: &[(f32, [f32; 3])],
        dt: f32,
    ) -> Vec<Body> {
        let scene = Scene::new(walls, bodies, robots, dt);
        let mut made: Vec<Body> = (robots.iter().enumerate())
            .map(|(i, &(radius, _))| {
                let mut body = Body {
                    pose: [0.0; 3],
                    heading: [0.0, 1.0],
                    dt,
                    radius,
                    scene: None,
                    shared: true,
                };
                body.set_pose(scene.robot_pose(i));
                body
            })
            .collect();
        if let Some(first) = made.first_mut() {
            first.scene = Some(Box::new(scene));
        }
        made
    }

    /// Whether the body is one of several robots' in one scene.
    pub fn is_shared(&self) -> bool {
        self.shared
    }

    /// One physics step of the scene this body holds (see [`Body::shared`]): robot `i` driven at
    /// `drives[i]` (velocity vector in m/s, turn rate in rad/s); `poses` receives every robot's
    /// pose after the step, and this body takes robot 0's.
    pub fn step_shared(&mut self, drives: &[([f32; 2], f32)], poses: &mut Vec<[f32; 3]>) {
        poses.clear();
        let Some(scene) = self.scene.as_mut() else {
            return;
        };
        for (&handle, &(v, angular)) in scene.robots.iter().zip(drives) {
            let body = &mut scene.world.bodies[handle];
            body.set_linvel(Vector::new(v[0], v[1]), true);
            body.set_angvel(angular, true);
        }
        scene.step();
        poses.extend((0..scene.robots.len()).map(|i| scene.robot_pose(i)));
        let first = poses[0];
        self.set_pose(first);
    }

    /// Puts robot `index` of the scene this body holds at `pose`, at rest (a robot moved by
    /// hand); the movable bodies stay where they are. Without a scene the body takes the pose.
    pub fn place_robot(&mut self, index: usize, pose: [f32; 3]) {
        if let Some(scene) = self.scene.as_mut() {
            if let Some(&handle) = scene.robots.get(index) {
                let body = &mut scene.world.bodies[handle];
                body.set_translation(Vector::new(pose[0], pose[1]), true);
                body.set_rotation(Rotation::new(pose[2]), true);
                body.set_linvel(Vector::ZERO, true);
                body.set_angvel(0.0, true);
            }
        }
        if index == 0 || self.scene.is_none() {
            self.set_pose(pose);
        }
    }

    /// Takes `pose` as this body's own (a body that follows a shared scene).
    pub fn follow(&mut self, pose: [f32; 3]) {
        self.set_pose(pose);
    }

    /// Advances one physics step with the body driven at `linear` m/s forward and `angular` rad/s;
    /// `clearance` is the current gap between the body and the nearest of `walls` (the world's
    /// wall index, the same walls the body was made among).
    pub fn step(&mut self, linear: f32, angular: f32, clearance: f32, walls: &WallIndex) {
        let [s, c] = self.heading;
        self.drive(
            [c * linear, s * linear],
            linear.abs(),
            angular,
            clearance,
            walls,
        );
    }

    /// `step` with the body's velocity given as a vector (m/s) of length `speed`, turning at
    /// `angular` rad/s: how a robot that other robots hold back moves.
    #[inline]
    pub fn drive(
        &mut self,
        velocity: [f32; 2],
        speed: f32,
        angular: f32,
        clearance: f32,
        walls: &WallIndex,
    ) {
        let [x, y, yaw] = self.pose;
        let turned = wrap_angle(yaw + angular * self.dt);
        if let Some(scene) = self.scene.as_mut() {
            let body = &mut scene.world.bodies[scene.robots[0]];
            body.set_linvel(Vector::new(velocity[0], velocity[1]), true);
            body.set_angvel(angular, true);
            scene.step();
            let pose = scene.robot_pose(0);
            self.set_pose(pose);
        } else if clearance - speed * self.dt > FREE_FLIGHT_MARGIN {
            self.set_pose([x + velocity[0] * self.dt, y + velocity[1] * self.dt, turned]);
        } else {
            let [nx, ny] = contact::slide(walls, [x, y], self.radius, velocity, self.dt);
            self.set_pose([nx, ny, turned]);
        }
    }

    fn set_pose(&mut self, pose: [f32; 3]) {
        let (s, c) = pose[2].sin_cos();
        self.pose = pose;
        self.heading = [s, c];
    }

    /// Current pose (x, y, yaw in (-pi, pi]).
    pub fn pose(&self) -> [f32; 3] {
        self.pose
    }

    /// Takes `walls` in place of the walls the scene this body holds was made among (some of
    /// them moved); nothing to do without one (the walls are then the world's wall index).
    pub fn replace_walls(&mut self, walls: &[WallBox]) {
        if let Some(scene) = self.scene.as_mut() {
            scene.replace_walls(walls);
        }
    }

    /// Takes `bodies` as the movable bodies of the scene this body holds (see the scene's
    /// `replace_movables`: `kept` names the running body each one is, if any). A body of its
    /// own without a scene gets one, among `walls`, when `bodies` is not empty: from then on
    /// rapier moves it, as in a world made with movable bodies. A body that follows a shared
    /// scene has nothing to do.
    pub fn replace_movables(
        &mut self,
        walls: &[WallBox],
        bodies: &[MovableBody],
        kept: &[Option<usize>],
    ) {
        match self.scene.as_mut() {
            Some(scene) => scene.replace_movables(bodies, kept),
            None if !self.shared && !bodies.is_empty() => {
                let robot = [(self.radius, self.pose)];
                self.scene = Some(Box::new(Scene::new(walls, bodies, &robot, self.dt)));
            }
            None => {}
        }
    }

    /// Puts movable body `index` of the scene this body holds at `pose` (x, y, yaw), at rest;
    /// returns whether there is such a body.
    pub fn place_movable(&mut self, index: usize, pose: [f32; 3]) -> bool {
        let Some(body) = self.movable_mut(index) else {
            return false;
        };
        body.set_translation(Vector::new(pose[0], pose[1]), true);
        body.set_rotation(Rotation::new(pose[2]), true);
        body.set_linvel(Vector::ZERO, true);
        body.set_angvel(0.0, true);
        true
    }

    /// Sets the velocity (vx, vy in m/s, turn rate in rad/s) of movable body `index` of the
    /// scene this body holds; returns whether there is such a body.
    pub fn set_movable_velocity(&mut self, index: usize, velocity: [f32; 3]) -> bool {
        let Some(body) = self.movable_mut(index) else {
            return false;
        };
        body.set_linvel(Vector::new(velocity[0], velocity[1]), true);
        body.set_angvel(velocity[2], true);
        true
    }

    /// Movable body `index` of the scene this body holds, if there is one.
    fn movable_mut(&mut self, index: usize) -> Option<&mut RigidBody> {
        let scene = self.scene.as_mut()?;
        let &(handle, _, _) = scene.movables.get(index)?;
        Some(&mut scene.world.bodies[handle])
    }

    /// Current velocities (vx, vy in m/s, turn rate in rad/s) of the movable bodies, in world
    /// order.
    pub fn movable_velocities(&self) -> Vec<[f32; 3]> {
        let Some(scene) = self.scene.as_deref() else {
            return Vec::new();
        };
        (scene.movables.iter())
            .map(|&(handle, _, _)| {
                let b = &scene.world.bodies[handle];
                let v = b.linvel();
                [v.x, v.y, b.angvel()]
            })
            .collect()
    }

    /// Current poses (x, y, yaw) of the movable bodies, in world order.
    pub fn movable_poses(&self) -> impl Iterator<Item = [f32; 3]> + '_ {
        let scene = self.scene.as_deref();
        let movables = scene.map_or(&[][..], |s| &s.movables[..]);
        movables.iter().filter_map(move |&(handle, _, _)| {
            let b = &scene?.world.bodies[handle];
            let t = b.translation();
            Some([t.x, t.y, b.rotation().angle()])
        })
    }

    /// The nearest movable body a ray from `origin` along the unit `dir` meets within
    /// `max_distance`, at the bodies' current poses.
    pub fn cast_ray_movables(
        &self,
        origin: [f32; 2],
        dir: [f32; 2],
        max_distance: f32,
    ) -> Option<RayHit> {
        let ray = Ray::new(
            Vector::new(origin[0], origin[1]),
            Vector::new(dir[0], dir[1]),
        );
        let mut nearest: Option<RayHit> = None;
        let scene = self.scene.as_deref()?;
        for &(_, collider, reflectance) in &scene.movables {
            let c = &scene.world.colliders[collider];
            let limit = nearest.map_or(max_distance, |h| h.distance);
            if let Some(distance) = c.shape().cast_ray(c.position(), &ray, limit, true) {
                if distance < limit {
                    nearest = Some(RayHit {
                        distance,
                        reflectance,
                    });
                }
            }
        }
        nearest
    }

    /// Writes the body's whole physical state with `serializer`: its pose and, with movable
    /// bodies, rapier's bodies, colliders, broad and narrow phases with their contact manifolds
    /// and warm-start impulses, and islands. Rapier's pipelines hold only workspace and are left
    /// out.
    pub fn save<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::Serialize;
        let world = self.scene.as_ref().map(|s| &s.world);
        (self.pose, world).serialize(serializer)
    }

    /// Reads back what `save` wrote for a body built like this one (same walls, bodies and
    /// radius); a state of another make is refused with what was expected and what was found.
    pub fn load<'de, D: serde::Deserializer<'de>>(
        &mut self,
        deserializer: D,
    ) -> Result<(), String> {
        use serde::Deserialize;
        let (pose, world): ([f32; 3], Option<PhysicsWorld>) =
            Deserialize::deserialize(deserializer).map_err(|e| e.to_string())?;
        let [x, y, yaw] = pose.map(f64::from);
        crate::limits::check_pose("robot", x, y, yaw).map_err(|e| e.to_string())?;
        match (self.scene.as_mut(), world) {
            (Some(scene), Some(world)) => scene.load(world)?,
            (None, None) => {}
            (mine, _) => {
                return Err(format!(
                    "expected a physics state {} movable bodies, found one {}",
                    if mine.is_some() { "with" } else { "without" },
                    if mine.is_some() { "without" } else { "with" }
                ))
            }
        }
        self.set_pose(pose);
        Ok(())
    }

    /// Bytes of rapier's scene, estimated from the sizes of its sets' entries (0 without one).
    pub fn heap_bytes(&self) -> usize {
        use std::mem::size_of;
        self.scene.as_ref().map_or(0, |s| {
            size_of::<Scene>()
                + s.world.bodies.len() * size_of::<RigidBody>()
                + s.world.colliders.len() * (size_of::<Collider>() + size_of::<Cuboid>())
                + s.movables.capacity() * size_of::<(RigidBodyHandle, ColliderHandle, f32)>()
                + s.robots.capacity() * size_of::<RigidBodyHandle>()
                + s.walls.capacity() * size_of::<ColliderHandle>()
        })
    }

    /// Whether the world has movable bodies.
    pub fn has_movables(&self) -> bool {
        self.scene.is_some()
    }

    /// Sine and cosine of the current yaw (computed once per step, for every user of the pose).
    pub fn heading(&self) -> [f32; 2] {
        self.heading
    }
}
