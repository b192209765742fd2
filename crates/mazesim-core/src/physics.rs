//! The robot's body in rapier2d: a dynamic ball among fixed wall boxes, seen from above (no gravity).
//!
//! Each physics step the wheel speeds set the body's velocity (differential drive), and rapier's
//! contact solver keeps it out of the walls. The solver's length unit is scaled to the e-puck so
//! its allowed penetration and prediction distance are fractions of a millimetre, not of a metre.

use rapier2d::prelude::*;

use crate::world::WallBox;

/// Scale of the scene for rapier's tolerances (allowed error, corrective velocity): 1 cm.
const LENGTH_UNIT: f32 = 0.01;

/// Contacts are predicted this far ahead (metres). It must exceed the distance the body can move in
/// one physics step (0.129 m/s * 32 ms = 4.1 mm at the e-puck's top speed) so that the solver sees a
/// wall before the body reaches it; otherwise it only pushes the body out after it has sunk in.
const PREDICTION_DISTANCE: f32 = 0.01;

/// The physical state of one robot among its walls.
pub struct Body {
    world: PhysicsWorld,
    robot: RigidBodyHandle,
}

impl Body {
    /// A body of `radius` at `pose` (x, y, yaw) among `walls`, stepped by `dt` seconds.
    pub fn new(walls: &[WallBox], radius: f32, pose: [f32; 3], dt: f32) -> Body {
        let mut world = PhysicsWorld::new();
        world.gravity = Vector::ZERO;
        world.integration_parameters.dt = dt;
        world.integration_parameters.length_unit = LENGTH_UNIT;
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
            .ccd_enabled(true)
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
        Body { world, robot }
    }

    /// Advances one physics step with the body driven at `linear` m/s forward and `angular` rad/s.
    pub fn step(&mut self, linear: f32, angular: f32) {
        let body = &mut self.world.bodies[self.robot];
        let yaw = body.rotation().angle();
        let (s, c) = yaw.sin_cos();
        body.set_linvel(Vector::new(c * linear, s * linear), true);
        body.set_angvel(angular, true);
        self.world.step();
    }

    /// Current pose (x, y, yaw in (-pi, pi]).
    pub fn pose(&self) -> [f32; 3] {
        let b = &self.world.bodies[self.robot];
        let t = b.translation();
        [t.x, t.y, b.rotation().angle()]
    }
}
