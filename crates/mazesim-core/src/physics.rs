//! The robot's body in rapier2d: a dynamic ball among fixed wall boxes and the world's movable
//! bodies, seen from above (no gravity).
//!
//! Each physics step the wheel speeds set the body's velocity (differential drive), and rapier's
//! contact solver keeps it out of the walls and pushes the movable bodies. The solver's length unit
//! is scaled to the e-puck so its allowed penetration and prediction distance are fractions of a
//! millimetre, not of a metre.
//!
//! Floor friction of a movable body: seen from above there is no gravity to press a body on the
//! floor, so the floor's friction is a damping of its linear and angular velocity at a rate of
//! `friction * FLOOR_DAMPING_PER_FRICTION` per second. A body sliding at 1 m/s slows at `mu * g`,
//! as Coulomb friction would slow it; slower bodies slow less, and a pushed body coasts a short way
//! (at the e-puck's top speed and friction 0.5, about 2.6 cm) before it stops. Contacts between the
//! robot, the bodies and the walls have no friction.

use rapier2d::parry::query::Ray;
use rapier2d::prelude::*;

use crate::world::{BodyShape, MovableBody, RayHit, WallBox};

/// Damping rate (1/s) of a movable body per unit of floor friction coefficient: g, 9.81 m/s^2,
/// over a reference speed of 1 m/s.
pub const FLOOR_DAMPING_PER_FRICTION: f32 = 9.81;

/// Solver iterations when movable bodies are present: a push through a chain of bodies needs more
/// than the single iteration that a ball against static walls needs.
const SOLVER_ITERATIONS_WITH_BODIES: usize = 4;

/// Scale of the scene for rapier's tolerances (allowed error, corrective velocity): 1 cm.
const LENGTH_UNIT: f32 = 0.01;

/// Contacts are predicted this far ahead (metres). It must exceed the distance the body can move in
/// one physics step (0.151 m/s * 32 ms = 4.8 mm at the e-puck2's top speed, 7.536 rad/s of 0.02 m
/// wheels) so that the solver sees a wall before the body reaches it; otherwise it only pushes the
/// body out after it has sunk in.
const PREDICTION_DISTANCE: f32 = 0.01;

/// Rapier takes over from free flight in any step that could end within this gap of a wall
/// (metres). Free flight never reaches a wall: the gap is measured before the step and the body,
/// a disc, cannot close more of it than it travels, so rapier's solver still meets every wall from
/// at least this far out, well inside its prediction distance. Free flight and rapier move a free
/// body alike but not to the last bit (rapier keeps the heading as a unit complex number), so this
/// margin is part of the results: the shipped navigator was trained with this one. (A margin of
/// one prediction distance, 1 cm, ran every step near a wall through rapier and cost a fifth more
/// per env-step.)
const FREE_FLIGHT_MARGIN: f32 = 0.0005;

/// The physical state of one robot among its walls.
///
/// Far from every wall the body moves in free flight, integrated here as rapier integrates a body
/// with a set velocity and no contact, up to rounding (position += velocity * dt, angle += rate *
/// dt); the contact pipeline runs only in the steps where the body could reach a wall. This is what
/// makes a step cheap in a maze's corridors, and it changes nothing physical: rapier's solver still
/// handles every approach to a wall. It takes over while the body is at least `FREE_FLIGHT_MARGIN`
/// from the wall, and its contact prediction reaches further than the body travels in a step.
pub struct Body {
    world: PhysicsWorld,
    robot: RigidBodyHandle,
    pose: [f32; 3],
    /// Sine and cosine of `pose[2]`.
    heading: [f32; 2],
    dt: f32,
    /// The rapier body lags behind `pose` after free-flight steps.
    stale: bool,
    /// The movable bodies with their reflectance, in world order. With any of them every step
    /// runs through rapier (no free flight).
    movables: Vec<(RigidBodyHandle, ColliderHandle, f32)>,
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

impl Body {
    /// A body of `radius` at `pose` (x, y, yaw) among `walls` and the movable `bodies` at their
    /// start poses, stepped by `dt` seconds.
    pub fn new(
        walls: &[WallBox],
        bodies: &[MovableBody],
        radius: f32,
        pose: [f32; 3],
        dt: f32,
    ) -> Body {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        world.integration_parameters.dt = dt;
        world.integration_parameters.length_unit = LENGTH_UNIT;
        // One ball against static boxes needs no more: the contact tests hold, a contact step
        // costs about a fifth less than with rapier's default of 4.
        world.integration_parameters.num_solver_iterations = 1;
        world.integration_parameters.normalized_prediction_distance =
            PREDICTION_DISTANCE / LENGTH_UNIT;
        for w in walls {
            let collider = ColliderBuilder::cuboid(w.half[0] as f32, w.half[1] as f32)
                .position(Pose::new(
                    Vector::new(w.center[0] as f32, w.center[1] as f32),
                    w.yaw as f32,
                ))
                .friction(0.0)
                .restitution(0.0);
            world.colliders.insert(collider);
        }
        let body = RigidBodyBuilder::dynamic()
            .translation(Vector::new(pose[0], pose[1]))
            .rotation(pose[2])
            .can_sleep(false)
            .build();
        let robot = world.bodies.insert(body);
        // e-puck mass is about 0.16 kg; only the ratio to walls (infinite) matters here.
        let ball = ColliderBuilder::ball(radius)
            .mass(0.16)
            .friction(0.0)
            .friction_combine_rule(CoefficientCombineRule::Min)
            .restitution(0.0);
        world
            .colliders
            .insert_with_parent(ball, robot, &mut world.bodies);
        if !bodies.is_empty() {
            world.integration_parameters.num_solver_iterations = SOLVER_ITERATIONS_WITH_BODIES;
        }
        let movables = bodies
            .iter()
            .map(|m| {
                let damping = m.friction as f32 * FLOOR_DAMPING_PER_FRICTION;
                let [x, y, yaw] = m.start.map(|v| v as f32);
                let rigid = RigidBodyBuilder::dynamic()
                    .translation(Vector::new(x, y))
                    .rotation(yaw)
                    .linear_damping(damping)
                    .angular_damping(damping)
                    .can_sleep(false)
                    .build();
                let handle = world.bodies.insert(rigid);
                let shape = match m.shape {
                    BodyShape::Box { half } => {
                        ColliderBuilder::cuboid(half[0] as f32, half[1] as f32)
                    }
                    BodyShape::Circle { radius } => ColliderBuilder::ball(radius as f32),
                };
                let collider = shape
                    .mass(m.mass as f32)
                    .friction(0.0)
                    .friction_combine_rule(CoefficientCombineRule::Min)
                    .restitution(0.0);
                let collider =
                    world
                        .colliders
                        .insert_with_parent(collider, handle, &mut world.bodies);
                (handle, collider, m.reflectance as f32)
            })
            .collect();
        let mut body = Body {
            world,
            robot,
            pose,
            heading: [0.0, 1.0],
            dt,
            stale: false,
            movables,
        };
        body.set_pose(body.rapier_pose());
        body
    }

    /// Whether a step of `linear` m/s could bring the body within `FREE_FLIGHT_MARGIN` of a wall,
    /// given its current `clearance` (gap to the nearest wall).
    fn near_wall(&self, linear: f32, clearance: f32) -> bool {
        !self.movables.is_empty() || clearance - linear.abs() * self.dt <= FREE_FLIGHT_MARGIN
    }

    /// Advances one physics step with the body driven at `linear` m/s forward and `angular` rad/s;
    /// `clearance` is the current gap between the body and the nearest wall.
    pub fn step(&mut self, linear: f32, angular: f32, clearance: f32) {
        let [x, y, yaw] = self.pose;
        let [s, c] = self.heading;
        if !self.near_wall(linear, clearance) {
            self.set_pose([
                x + c * linear * self.dt,
                y + s * linear * self.dt,
                wrap_angle(yaw + angular * self.dt),
            ]);
            self.stale = true;
            return;
        }
        let body = &mut self.world.bodies[self.robot];
        if self.stale {
            body.set_position(Pose::new(Vector::new(x, y), yaw), true);
            self.stale = false;
        }
        body.set_linvel(Vector::new(c * linear, s * linear), true);
        body.set_angvel(angular, true);
        self.world.step();
        self.set_pose(self.rapier_pose());
    }

    fn set_pose(&mut self, pose: [f32; 3]) {
        let (s, c) = pose[2].sin_cos();
        self.pose = pose;
        self.heading = [s, c];
    }

    fn rapier_pose(&self) -> [f32; 3] {
        let b = &self.world.bodies[self.robot];
        let t = b.translation();
        [t.x, t.y, b.rotation().angle()]
    }

    /// Current pose (x, y, yaw in (-pi, pi]).
    pub fn pose(&self) -> [f32; 3] {
        self.pose
    }

    /// Current poses (x, y, yaw) of the movable bodies, in world order.
    pub fn movable_poses(&self) -> impl Iterator<Item = [f32; 3]> + '_ {
        self.movables.iter().map(|&(handle, _, _)| {
            let b = &self.world.bodies[handle];
            let t = b.translation();
            [t.x, t.y, b.rotation().angle()]
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
        for &(_, collider, reflectance) in &self.movables {
            let c = &self.world.colliders[collider];
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

    /// Writes the body's whole physical state with `serializer`: rapier's bodies, colliders,
    /// broad and narrow phases with their contact manifolds and warm-start impulses, islands, and
    /// the pose kept outside rapier. Rapier's pipelines hold only workspace and are left out.
    pub fn save<S: serde::Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        use serde::Serialize;
        (&self.world, self.pose, self.stale).serialize(serializer)
    }

    /// Reads back what `save` wrote for a body built like this one (same walls, bodies and
    /// radius); a state of another make is refused with what was expected and what was found.
    pub fn load<'de, D: serde::Deserializer<'de>>(
        &mut self,
        deserializer: D,
    ) -> Result<(), String> {
        use serde::Deserialize;
        let (world, pose, stale): (PhysicsWorld, [f32; 3], bool) =
            Deserialize::deserialize(deserializer).map_err(|e| e.to_string())?;
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
        let handles_known = world.bodies.get(self.robot).is_some()
            && self.movables.iter().all(|&(body, collider, _)| {
                world.bodies.get(body).is_some() && world.colliders.get(collider).is_some()
            });
        if !handles_known || !pose.iter().all(|v| v.is_finite()) {
            return Err(
                "expected the robot's and every movable body's handles and a finite pose, \
                 found a physics state without them"
                    .to_string(),
            );
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
        self.set_pose(pose);
        self.stale = stale;
        Ok(())
    }

    /// Whether the world has movable bodies.
    pub fn has_movables(&self) -> bool {
        !self.movables.is_empty()
    }

    /// Sine and cosine of the current yaw (computed once per step, for every user of the pose).
    pub fn heading(&self) -> [f32; 2] {
        self.heading
    }
}
