//! mazesim-core: a fast, deterministic 2D simulation of a small differential-drive robot (the
//! e-puck and kin) in mazes. Worlds are TOML files ([`world`]), robots are profiles of data
//! ([`robot`]), bodies and contacts are rapier2d ([`physics`]), sensors are parry2d ray casts and
//! floor look-ups following Webots' models ([`sensors`]). No Python here: the bindings live in the
//! `mazesim-py` crate.
//!
//! ```
//! use std::sync::Arc;
//! use mazesim_core::prelude::*;
//!
//! let world = Arc::new(World::builtin("arena").unwrap());
//! let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
//! let mut sim = Simulator::new(world, robot, SimConfig::default()).unwrap();
//! sim.step(3.0, 3.0).unwrap();
//! assert_eq!(sim.distance_sensors().len(), 8);
//! ```
//!
//! Modules are grouped by subsystem below, from the ground up; `Batch` has one `impl` per concern
//! (stepping in [`batch`], the multi-step call in [`rollout`], the robot axis of worlds of several
//! robots in [`swarm`]; the navigator's training round, [`navigator::training`], drives batches
//! from outside them), and [`prelude`] brings the types most programs start from.
#![warn(missing_docs)]

// World and geometry: the format and walls, seeded mazes, barcode code books.
pub mod codebook;
pub mod generator;
pub mod world;

// Robot and sensors: profiles, lookup tables, infra-red and ground models, crossings.
mod crossing;
mod lut;
pub mod robot;
pub mod sensors;

// Physics: the body (rapier2d when bodies move) and its contacts with static walls.
mod contact;
pub mod physics;

// Engine: one simulator, the batch, the multi-step call and its built-in controllers.
pub mod batch;
pub mod control;
pub mod rollout;
pub mod simulator;
pub mod swarm;

// Navigator: the report's hierarchical navigator, from the distance state and the sub-tasks to
// the tabular controller, the Q update and the lower level's training round.
pub mod navigator;

// Task observations of the gymnasium tasks.
pub mod tasks;

// Webots import.
pub mod wbt;

// Utilities: errors, file kinds, fingerprints, memory accounting, file access, limits, random
// streams.
mod error;
pub mod file_kind;
pub mod fingerprint;
mod footprint;
mod io;
pub mod limits;
mod memory;
pub mod rng;
pub mod temporary_files;

pub use batch::{Batch, OutputBuffers, StepOutputs};
pub use control::Controller;
pub use crossing::{Crossing, CrossingTracker};
pub use error::{readable_numbers, Error, Location, Result};
pub use lut::LookupTable;
pub use robot::{robot_profile_names, Perturbation, RobotProfile};
pub use rollout::{RunCounters, RunOptions, RunTrace};
pub use simulator::{SimConfig, Simulator};
pub use swarm::Swarm;
pub use world::{builtin_world_names, World};

/// The types most programs start from: `use mazesim_core::prelude::*;`.
pub mod prelude {
    pub use crate::{Batch, Error, Result, RobotProfile, SimConfig, Simulator, StepOutputs, World};
}

/// Converts a Sharp GP2Y0A41SK0F reading in volts to centimetres by inverting its table
/// (clamped to 3-40 cm). A reading that is not a finite number, or is below 0 V (the sensor's
/// output never is, nor is a simulated reading), is an `InvalidArgument` error.
pub fn sharp_volts_to_cm(volts: f64) -> Result<f64> {
    if !(volts.is_finite() && volts >= 0.0) {
        return Err(Error::InvalidArgument(format!(
            "expected a Sharp GP2Y0A41SK0F reading of 0 V or more (its output never goes below \
             0 V), found {volts} V"
        )));
    }
    let seed = RobotProfile::builtin("seed")?;
    Ok(seed.distance_sensors[0].model.table.invert(volts) * 100.0)
}
