//! What a batch is assembled from, checked before anything is allocated: its size against the
//! memory the process may use, one seed per environment, worlds of equal content shared, and the
//! sensing rigs of its robot profiles.

use std::sync::Arc;

use crate::error::{Error, Result};
use crate::limits::{check_count, MAX_ENVS};
use crate::robot::RobotProfile;
use crate::simulator::{Rig, SharedChannels};
use crate::world::World;

/// Bytes an environment needs besides its walls (simulator, buffers), a generous estimate.
const ENV_BYTES: u128 = 8 * 1024;

/// Bytes each solid wall adds to a world (its index entries), or to an env of a world with
/// movable bodies (its rapier collider and broad-phase entry), a generous estimate.
const WALL_BYTES: u128 = 1024;

/// `worlds` with every world of the same content as an earlier one replaced by that one, so that
/// envs of equal worlds share one copy of its walls, paint and indexes.
pub fn share_equal_worlds(worlds: Vec<Arc<World>>) -> Vec<Arc<World>> {
    let mut seen: std::collections::HashMap<u64, Vec<Arc<World>>> =
        std::collections::HashMap::new();
    worlds
        .into_iter()
        .map(|world| {
            let same = seen.entry(world.fingerprint()).or_default();
            match same
                .iter()
                .find(|w| Arc::ptr_eq(w, &world) || ***w == *world)
            {
                Some(first) => first.clone(),
                None => {
                    same.push(world.clone());
                    world
                }
            }
        })
        .collect()
}

/// Refuses a batch of `envs` environments without one seed each.
pub(crate) fn check_seeds(envs: usize, seeds: &[u64]) -> Result<()> {
    if seeds.len() != envs {
        return Err(Error::InvalidArgument(format!(
            "expected one seed per environment ({envs}), found {}",
            seeds.len()
        )));
    }
    Ok(())
}

/// Refuses a batch of `envs` environments holding `walls` solid walls in all (summed over the
/// environments) before anything is allocated: beyond `MAX_ENVS`, or when its estimated memory
/// exceeds what the process may still allocate (the address-space limit and the memory the system
/// has available, where the system tells).
pub fn check_size(envs: usize, walls: u128) -> Result<()> {
    check_count("environments (num_envs)", envs, MAX_ENVS)?;
    if envs == 0 {
        return Err(Error::InvalidArgument(
            "expected at least one environment, found 0".into(),
        ));
    }
    let needed = ENV_BYTES * envs as u128 + WALL_BYTES * walls;
    if let Some(free) = crate::memory::allocatable_bytes() {
        if needed > free as u128 {
            return Err(Error::InvalidArgument(format!(
                "expected a batch that fits in memory: num_envs = {envs} needs about {:.2} GB, \
                 but this process can allocate about {:.2} GB more",
                needed as f64 / 1e9,
                free as f64 / 1e9
            )));
        }
    }
    Ok(())
}

/// The sensing rigs of a batch of `n` envs: one per env of `robots` (or one for all when
/// `robots` holds one profile), equal profiles sharing one rig and the rigs sharing their equal
/// channel lists (profiles perturbed from copies of one profile read one copy of their sensor
/// models, which every step of every robot then finds in cache). Every profile must have sensors
/// to observe, and as many of each kind as the first.
pub(crate) fn rigs_of(robots: &[Arc<RobotProfile>], n: usize) -> Result<Vec<Arc<Rig>>> {
    if robots.len() != 1 && robots.len() != n {
        return Err(Error::InvalidArgument(format!(
            "expected one robot profile, or one per environment ({n}), found {}",
            robots.len()
        )));
    }
    let first = &robots[0];
    if first.distance_sensors.is_empty() && first.ground_sensors.is_empty() {
        return Err(Error::InvalidArgument(format!(
            "robot profile {:?} has no sensors to observe",
            first.name
        )));
    }
    let widths = |r: &RobotProfile| (r.distance_sensors.len(), r.ground_sensors.len());
    let mut made: Vec<Arc<Rig>> = Vec::new();
    let mut channels = SharedChannels::default();
    let mut rigs = Vec::with_capacity(robots.len());
    for (i, robot) in robots.iter().enumerate() {
        if widths(robot) != widths(first) {
            return Err(Error::InvalidArgument(format!(
                "expected every environment's robot profile to have the sensors of the first \
                 ({:?}: {} distance, {} ground), found {:?} in environment {i} with {} and {}",
                first.name,
                first.distance_sensors.len(),
                first.ground_sensors.len(),
                robot.name,
                robot.distance_sensors.len(),
                robot.ground_sensors.len()
            )));
        }
        let same = made
            .iter()
            .find(|r| Arc::ptr_eq(r.robot(), robot) || **r.robot() == **robot);
        let rig = match same {
            Some(rig) => rig.clone(),
            None => {
                let rig = Rig::sharing(robot.clone(), &mut channels);
                made.push(rig.clone());
                rig
            }
        };
        rigs.push(rig);
    }
    Ok(rigs)
}
