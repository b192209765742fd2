//! Walls that are seen and not touched (`sensed_only = true`): Webots' infra-red rays meet "the
//! Solid nodes themselves", so a Solid without a `boundingObject` (a decorative wall, a marker
//! post, a goal object the robot drives through) is seen by the e-puck's infra-red proximity
//! sensors and its camera while nothing collides with it. Range sensors (Webots' `generic`,
//! `sonar` and `laser` types), the ground sensors, contacts and the physics pass them by.
//!
//! A world keeps them apart from its solid walls, boxed, so that a world without any (every
//! generated maze) holds one empty pointer for them.

use super::geometry::{Bounds, WallBox};
use super::walls::{RayHit, WallIndex};

/// The sensed-only walls of a world, in `[[walls]]` order, with their colours and index.
#[derive(Debug, Clone)]
pub struct SensedWalls {
    walls: Vec<WallBox>,
    colours: Vec<Option<[f64; 3]>>,
    index: WallIndex,
}

impl SensedWalls {
    /// Indexes `walls` (each with the colour a camera sees of it); `None` when there are none.
    pub fn new(walls: Vec<WallBox>, colours: Vec<Option<[f64; 3]>>) -> Option<Box<SensedWalls>> {
        if walls.is_empty() {
            return None;
        }
        let index = WallIndex::new(&walls);
        Some(Box::new(SensedWalls {
            walls,
            colours,
            index,
        }))
    }

    /// The walls, in `[[walls]]` order.
    pub fn walls(&self) -> &[WallBox] {
        &self.walls
    }

    /// The colour of each of `walls` as a camera sees it (`None`: the grey of its reflectance).
    pub fn colours(&self) -> &[Option<[f64; 3]>] {
        &self.colours
    }

    /// The nearest sensed-only wall along the ray from `origin` in the unit direction `dir`
    /// within `max_distance`.
    pub fn cast_ray(&self, origin: [f32; 2], dir: [f32; 2], max_distance: f32) -> Option<RayHit> {
        self.index.cast_ray(origin, dir, max_distance)
    }

    /// Their bounds.
    pub fn bounds(&self) -> Bounds {
        self.walls
            .iter()
            .fold(Bounds::EMPTY, |b, w| b.union(w.bounds()))
    }

    /// Bytes it holds, itself included (`crate::footprint`).
    pub fn heap_bytes(&self) -> usize {
        use crate::footprint::vec_bytes;
        std::mem::size_of::<SensedWalls>()
            + vec_bytes(&self.walls)
            + vec_bytes(&self.colours)
            + self.index.heap_bytes()
    }
}
