//! Snapshots of a world of several robots: every robot's simulator snapshot
//! (`crate::simulator` snapshot layout, robot 0's holding the shared rapier scene of a world with
//! movable bodies) and the robots' wheel commands, restored into a swarm of the same world,
//! profiles, control step and noise setting, which then goes on exactly as the original would.
//! A world of one robot's snapshot is that robot's simulator snapshot, byte for byte.
//!
//! Layout (integers little-endian):
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `MZSWARMS` |
//! | 4 | format version |
//! | 4 | number of robots `R` |
//! | 8 | FNV-1a checksum of every byte after it |
//! | 16 R | each robot's wheel command (left, right; float64, rad/s) |
//! | R times 8 + n | each robot's simulator snapshot (length, bytes) |
//!
//! Restoring re-checks everything as the API would (each robot's state by
//! `Simulator::restore`, the commands finite and within the motors' reach) and changes nothing
//! when any part is refused.

use super::{make_robots, Swarm};
use crate::error::{Error, Result};
use crate::fingerprint::fnv1a;
use crate::simulator::{Rig, Simulator};

const MAGIC: &[u8; 8] = b"MZSWARMS";

/// The version of the layout; bumped whenever it changes.
pub const SWARM_SNAPSHOT_VERSION: u32 = 1;

/// Bytes before the commands.
const HEADER: usize = 8 + 4 + 4 + 8;

fn refused(what: impl std::fmt::Display) -> Error {
    Error::Snapshot(format!(
        "expected a snapshot of a world of several robots, found {what}"
    ))
}

/// Takes `n` bytes from the front of `bytes`, or says what was missing.
fn take<'a>(bytes: &mut &'a [u8], n: usize, what: &str) -> Result<&'a [u8]> {
    if bytes.len() < n {
        return Err(refused(format!(
            "{} bytes where {what} needs {n} (truncated)",
            bytes.len()
        )));
    }
    let (head, tail) = bytes.split_at(n);
    *bytes = tail;
    Ok(head)
}

impl Swarm {
    /// The whole state as bytes, for [`Swarm::restore`] (see the module notes for the layout).
    pub fn snapshot(&self) -> Vec<u8> {
        if let [only] = &self.robots[..] {
            return only.snapshot();
        }
        snapshot_robots(&self.robots, &self.commands)
    }

    /// Puts the swarm in the state `snapshot` holds, taken by [`Swarm::snapshot`] of a swarm of
    /// the same world, robot profiles, control step and noise setting; it then goes on exactly
    /// as the one that took it. Anything else is refused with `Error::Snapshot` (or the error
    /// of the robot whose part is refused, naming it) and changes nothing.
    pub fn restore(&mut self, snapshot: &[u8]) -> Result<()> {
        if self.robots.len() == 1 {
            return self.robots[0].restore(snapshot);
        }
        let (robots, commands) = restored_robots(&self.robots, &self.names, snapshot)?;
        self.robots = robots;
        self.commands = commands;
        Ok(())
    }

    /// An independent copy in the same state.
    pub fn duplicate(&self) -> Result<Swarm> {
        if let [only] = &self.robots[..] {
            return Ok(Swarm {
                robots: vec![only.duplicate()?],
                names: self.names.clone(),
                commands: self.commands.clone(),
                profile: self.profile.clone(),
                overrides: self.overrides.clone(),
                made_of: self.made_of.clone(),
            });
        }
        let rigs: Vec<std::sync::Arc<Rig>> = self.robots.iter().map(|r| r.rig().clone()).collect();
        let world = self.robots[0].world().clone();
        let mut copy = Swarm::with_rigs(world, &rigs, self.robots[0].config())?;
        copy.profile = self.profile.clone();
        copy.overrides = self.overrides.clone();
        copy.made_of = self.made_of.clone();
        copy.restore(&self.snapshot())?;
        Ok(copy)
    }
}

/// The snapshot bytes of the robots of one world of several robots with their wheel commands
/// (see the module notes for the layout).
pub(crate) fn snapshot_robots(robots: &[Simulator], commands: &[[f64; 2]]) -> Vec<u8> {
    let mut body = Vec::new();
    for [left, right] in commands {
        body.extend_from_slice(&left.to_le_bytes());
        body.extend_from_slice(&right.to_le_bytes());
    }
    for robot in robots {
        let part = robot.snapshot();
        body.extend_from_slice(&(part.len() as u64).to_le_bytes());
        body.extend_from_slice(&part);
    }
    let mut out = Vec::with_capacity(HEADER + body.len());
    out.extend_from_slice(MAGIC);
    out.extend_from_slice(&SWARM_SNAPSHOT_VERSION.to_le_bytes());
    out.extend_from_slice(&(robots.len() as u32).to_le_bytes());
    out.extend_from_slice(&fnv1a(&body).to_le_bytes());
    out.extend_from_slice(&body);
    out
}

/// New simulators of the robots `robots` (of one world of several robots, named `names`) in the
/// state `snapshot` holds, with the wheel commands it holds; `robots` are left as they are.
/// Refused as [`Swarm::restore`] refuses.
pub(crate) fn restored_robots(
    robots: &[Simulator],
    names: &[String],
    snapshot: &[u8],
) -> Result<(Vec<Simulator>, Vec<[f64; 2]>)> {
    let mut rest = snapshot;
    let magic = take(&mut rest, MAGIC.len(), "the magic")?;
    if magic != MAGIC {
        return Err(refused(format!(
            "bytes starting with {:?} (not {:?})",
            String::from_utf8_lossy(magic),
            String::from_utf8_lossy(MAGIC)
        )));
    }
    let u32_of = |b: &[u8]| u32::from_le_bytes(b.try_into().expect("4 bytes"));
    let u64_of = |b: &[u8]| u64::from_le_bytes(b.try_into().expect("8 bytes"));
    let version = u32_of(take(&mut rest, 4, "the version")?);
    if version != SWARM_SNAPSHOT_VERSION {
        return Err(refused(format!(
            "format version {version} (this build reads version {SWARM_SNAPSHOT_VERSION})"
        )));
    }
    let count = u32_of(take(&mut rest, 4, "the robot count")?) as usize;
    let n = robots.len();
    if count != n {
        return Err(refused(format!(
            "one of {count} robots (this world has {n})"
        )));
    }
    let checksum = u64_of(take(&mut rest, 8, "the checksum")?);
    if fnv1a(rest) != checksum {
        return Err(refused("corrupt bytes: the checksum does not match"));
    }
    let mut commands = Vec::with_capacity(n);
    for (i, robot) in robots.iter().enumerate() {
        let pair = take(&mut rest, 16, "the wheel commands")?;
        let [left, right] =
            [&pair[..8], &pair[8..]].map(|b| f64::from_le_bytes(b.try_into().expect("8 bytes")));
        let top = robot.robot().max_wheel_speed * crate::robot::perturb::MAX_FACTOR;
        if !(left.abs() <= top && right.abs() <= top) {
            return Err(refused(format!(
                "robot {i}'s wheel command ({left}, {right}) beyond the finite range \
                 [-{top}, {top}] rad/s"
            )));
        }
        commands.push([left, right]);
    }
    // Restored into a fresh swarm, taken only when every part is accepted.
    let rigs: Vec<std::sync::Arc<Rig>> = robots.iter().map(|r| r.rig().clone()).collect();
    let world = robots[0].world().clone();
    let mut fresh = make_robots(&world, &rigs, robots[0].config())?;
    for (i, robot) in fresh.iter_mut().enumerate() {
        let length = u64_of(take(&mut rest, 8, "a robot's snapshot length")?);
        let part = usize::try_from(length)
            .ok()
            .filter(|&l| l <= rest.len())
            .ok_or_else(|| {
                refused(format!(
                    "robot {i}'s part of {length} bytes where {} are left (truncated)",
                    rest.len()
                ))
            })?;
        let part = take(&mut rest, part, "a robot's snapshot")?;
        robot.restore(part).map_err(|e| match e {
            Error::Snapshot(m) => Error::Snapshot(format!("robot {i} ({:?}): {m}", names[i])),
            other => other,
        })?;
    }
    if !rest.is_empty() {
        return Err(refused(format!(
            "{} bytes after the last robot",
            rest.len()
        )));
    }
    Ok((fresh, commands))
}
