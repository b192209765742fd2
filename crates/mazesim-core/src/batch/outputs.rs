//! A batch's per-step outputs: the buffers the caller owns (numpy arrays from Python, or
//! `OutputBuffers` in Rust), cut into chunks of environments and into each environment's row.

use super::{Batch, CHUNK_ENVS};
use crate::simulator::Simulator;

/// Per-step outputs of a batch, one row per environment, in buffers the caller owns.
pub struct StepOutputs<'a> {
    /// `(n, observation_width)`: distance sensors then ground sensors.
    pub observations: &'a mut [f32],
    /// `(n, 3)`: x, y, yaw.
    pub poses: &'a mut [f32],
    /// `(n,)`: touched a wall during the step.
    pub colliding: &'a mut [bool],
    /// `(n,)`: barcode crossed in the step as a signed checkpoint id, 0 for none.
    pub crossings: &'a mut [i32],
}

/// Owned buffers of a batch's per-step outputs, zeroed, for callers in Rust (Python hands in
/// numpy arrays instead).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct OutputBuffers {
    /// `(rows, observation_width)`: distance sensors then ground sensors.
    pub observations: Vec<f32>,
    /// `(rows, 3)`: x, y, yaw.
    pub poses: Vec<f32>,
    /// `(rows,)`: touched a wall during the step.
    pub colliding: Vec<bool>,
    /// `(rows,)`: barcode crossed in the step as a signed checkpoint id, 0 for none.
    pub crossings: Vec<i32>,
}

impl OutputBuffers {
    /// Buffers of `rows` rows, observations `width` floats wide.
    pub fn new(rows: usize, width: usize) -> Self {
        Self {
            observations: vec![0.0; rows * width],
            poses: vec![0.0; rows * 3],
            colliding: vec![false; rows],
            crossings: vec![0; rows],
        }
    }

    /// Buffers of the shape of `batch`'s outputs: a row per simulator (per robot of every
    /// environment in a batch of several robots per environment).
    pub fn of(batch: &Batch) -> Self {
        Self::new(batch.envs.len(), batch.observation_width())
    }

    /// The buffers as the outputs of a call of the batch.
    pub fn outputs(&mut self) -> StepOutputs<'_> {
        StepOutputs {
            observations: &mut self.observations,
            poses: &mut self.poses,
            colliding: &mut self.colliding,
            crossings: &mut self.crossings,
        }
    }
}

impl<'a> StepOutputs<'a> {
    /// The same buffers, borrowed again for a shorter time.
    pub(crate) fn reborrow(&mut self) -> StepOutputs<'_> {
        StepOutputs {
            observations: self.observations,
            poses: self.poses,
            colliding: self.colliding,
            crossings: self.crossings,
        }
    }

    /// The buffers cut into the rows of successive chunks of `CHUNK_ENVS` environments
    /// (observations `width` wide).
    pub(crate) fn chunks(self, width: usize) -> impl Iterator<Item = StepOutputs<'a>> + Send {
        self.observations
            .chunks_mut(CHUNK_ENVS * width)
            .zip(self.poses.chunks_mut(CHUNK_ENVS * 3))
            .zip(self.colliding.chunks_mut(CHUNK_ENVS))
            .zip(self.crossings.chunks_mut(CHUNK_ENVS))
            .map(
                |(((observations, poses), colliding), crossings)| StepOutputs {
                    observations,
                    poses,
                    colliding,
                    crossings,
                },
            )
    }

    /// Each environment's row (observations `width` wide, the first `distance_width` of them
    /// distance readings).
    pub(crate) fn rows(self, width: usize, distance_width: usize) -> impl Iterator<Item = Row<'a>> {
        self.observations
            .chunks_mut(width)
            .zip(self.poses.chunks_mut(3))
            .zip(self.colliding.iter_mut())
            .zip(self.crossings.iter_mut())
            .map(move |(((observation, pose), colliding), crossing)| Row {
                observation,
                distance_width,
                pose,
                colliding,
                crossing,
            })
    }
}

/// One environment's rows of the outputs.
pub(crate) struct Row<'a> {
    pub(crate) observation: &'a mut [f32],
    pub(crate) distance_width: usize,
    pub(crate) pose: &'a mut [f32],
    pub(crate) colliding: &'a mut bool,
    pub(crate) crossing: &'a mut i32,
}

impl Row<'_> {
    pub(crate) fn write(self, env: &Simulator) {
        let (d, g) = self.observation.split_at_mut(self.distance_width);
        d.copy_from_slice(env.distance_sensors());
        g.copy_from_slice(env.ground_sensors());
        self.pose.copy_from_slice(&env.pose());
        *self.colliding = env.colliding();
        *self.crossing = env.last_crossing();
    }
}
