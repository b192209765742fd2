//! The navigator of the report's chapter 4, in one place: the lower level's distance state
//! ([`discretiser`]), the four sub-tasks with the odometry their phases and ends read ([`door`]),
//! the tabular controller that acts from their stacked Q-tables ([`tabular`]), what Corridors
//! and Corners does over its table's action (a turn on the spot kept, and the blind rule where no
//! sensor sees a wall: [`heading_hold`]), the left-right mirror image every transition is learned
//! from twice ([`symmetry`]), the Q update ([`qlearning`]), another robot's readings in the seed
//! robot's volts ([`seed_volts`]), the step of N robots below the higher level ([`step`]) and the
//! lower level's training round ([`training`]).
//!
//! The higher level's choices (which sub-task a checkpoint starts) come in as data; the random
//! draws of training rounds, their order and the checkpoints of a run stay with the caller.

pub mod discretiser;
pub mod door;
pub mod heading_hold;
pub mod qlearning;
pub mod seed_volts;
pub mod step;
pub mod symmetry;
pub mod tabular;
pub mod training;

pub use discretiser::{Discretiser, LEVEL_EDGES_CM, NUM_LEVELS, NUM_SENSORS, NUM_STATES};
pub use step::Navigator;
pub use tabular::{TabularPolicy, NUM_ACTIONS, WHEEL_SPEED_FRACTIONS};
