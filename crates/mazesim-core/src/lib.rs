//! mazesim-core: a fast, deterministic 2D simulation of a small differential-drive robot (the
//! e-puck and kin) in mazes. Worlds are TOML files ([`world`]), robots are profiles of data
//! ([`robot`]), bodies and contacts are rapier2d ([`physics`]), sensors are parry2d ray casts and
//! floor look-ups following Webots' models ([`sensors`]). No Python here: the bindings live in the
//! `mazesim-py` crate.
//!
//! ```
//! use std::sync::Arc;
//! use mazesim_core::{RobotProfile, SimConfig, Simulator, World};
//!
//! let world = Arc::new(World::builtin("arena").unwrap());
//! let robot = Arc::new(RobotProfile::builtin("e-puck").unwrap());
//! let mut sim = Simulator::new(world, robot, SimConfig::default()).unwrap();
//! sim.step(3.0, 3.0).unwrap();
//! assert_eq!(sim.distance_sensors().len(), 8);
//! ```
#![warn(missing_docs)]

pub mod batch;
pub mod codebook;
pub mod contact;
pub mod control;
pub mod crossing;
pub mod error;
pub mod fingerprint;
pub mod footprint;
pub mod generator;
pub mod io;
pub mod limits;
pub mod lower_training;
pub mod lut;
pub mod memory;
pub mod physics;
pub mod qlearning;
pub mod rng;
pub mod robot;
pub mod rollout;
pub mod sensors;
pub mod simulator;
pub mod wbt;
pub mod world;

pub use batch::{Batch, StepOutputs};
pub use control::Controller;
pub use error::{Error, Location, Result};
pub use robot::{robot_profile_names, Perturbation, RobotProfile};
pub use rollout::{RunCounters, RunOptions, RunTrace};
pub use simulator::{SimConfig, Simulator};
pub use world::{builtin_world_names, World};

/// Converts a Sharp GP2Y0A41SK0F reading in volts to centimetres by inverting its table
/// (clamped to 3-40 cm). A reading that is not a finite number is an `InvalidArgument` error.
pub fn sharp_volts_to_cm(volts: f64) -> Result<f64> {
    if !volts.is_finite() {
        return Err(Error::InvalidArgument(format!(
            "expected a finite Sharp sensor reading in volts, found {volts}"
        )));
    }
    let seed = RobotProfile::builtin("seed")?;
    Ok(seed.distance_sensors[0].model.table.invert(volts) * 100.0)
}
