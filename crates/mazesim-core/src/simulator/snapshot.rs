//! Snapshots: a simulator's whole state as bytes, restored into a simulator of the same world,
//! robot profile, control step and noise setting, which then goes on exactly as the original
//! would have (for search-based planners, pickling and copies).
//!
//! Layout (integers little-endian):
//!
//! | bytes | what |
//! |---|---|
//! | 8 | magic `MZSNAPSH` |
//! | 4 | format version |
//! | 8 | world fingerprint ([`World::fingerprint`]) |
//! | 8 | robot profile fingerprint |
//! | 4 | physics steps per control step |
//! | 1 | noise on (1) or off (0) |
//! | 8 | payload length |
//! | 8 | FNV-1a checksum of every other byte of the snapshot, in order |
//! | 2 + n | world name (length, UTF-8), for error messages |
//! | 2 + n | robot profile name (length, UTF-8), for error messages |
//! | payload | the state, in postcard's encoding of serde data |
//!
//! The state holds the pose, rapier's world (bodies, colliders, broad and narrow phase with contact
//! manifolds and warm-start impulses, islands), the noise stream, time, counters, the barcode
//! tracker and crossings, the last readings and the ground sensors' caches.

use postcard::ser_flavors::Flavor;

use super::{Simulator, State};
use crate::error::{Error, Result};
use crate::fingerprint::{fnv1a, fnv1a_extend};

const MAGIC: &[u8; 8] = b"MZSNAPSH";

/// The version of the layout and of the state it holds; bumped whenever either changes.
pub const SNAPSHOT_VERSION: u32 = 2;

/// Bytes of the fixed part of the header (before the names).
const FIXED_HEADER: usize = 8 + 4 + 8 + 8 + 4 + 1 + 8 + 8;

/// Declares the simulator once: `Simulator` with its fields and those of `saved` (the state
/// outside the body, in the payload's order), and of those the snapshot's `State` (the seed first,
/// the goal set by `set_goal` last), what a snapshot takes of a simulator and what a restore puts
/// back.
macro_rules! simulator_fields {
    (
        $(#[$doc:meta])*
        pub struct Simulator {
            $($(#[$kept_doc:meta])* $kept:ident: $kept_t:ty,)*
        }
        saved {
            $($(#[$field_doc:meta])* $field:ident: $t:ty,)*
        }
    ) => {
        $(#[$doc])*
        pub struct Simulator {
            $($(#[$kept_doc])* $kept: $kept_t,)*
            $($(#[$field_doc])* $field: $t,)*
        }

        /// The state outside the body, as serde data.
        #[derive(serde::Serialize, serde::Deserialize)]
        struct State {
            seed: u64,
            $($field: $t,)*
            goal_override: Option<[f64; 3]>,
        }

        impl Simulator {
            /// The state outside the body now.
            fn saved_state(&self) -> State {
                State {
                    seed: self.config.seed,
                    $($field: Clone::clone(&self.$field),)*
                    goal_override: self
                        .goal_override
                        .map(|g| [g.center[0], g.center[1], g.radius]),
                }
            }

            /// Puts back the state outside the body.
            fn put_state(&mut self, state: State) {
                self.config.seed = state.seed;
                $(self.$field = state.$field;)*
                self.goal_override = state.goal_override.map(|[x, y, radius]| Goal {
                    center: [x, y],
                    radius,
                });
            }
        }
    };
}

/// What the header says, read back.
struct Header<'a> {
    version: u32,
    world: u64,
    robot: u64,
    physics_steps: u32,
    noise: u8,
    length: u64,
    checksum: u64,
    world_name: &'a str,
    robot_name: &'a str,
}

fn corrupt(what: impl std::fmt::Display) -> Error {
    Error::Snapshot(format!(
        "expected a simulator snapshot, found corrupt bytes: {what}"
    ))
}

/// Reads the header at the start of `bytes`; returns it and the rest.
fn read_header(bytes: &[u8]) -> Result<(Header<'_>, &[u8])> {
    if bytes.len() < MAGIC.len() || &bytes[..MAGIC.len()] != MAGIC {
        let start = &bytes[..bytes.len().min(MAGIC.len())];
        return Err(Error::Snapshot(format!(
            "expected a simulator snapshot (bytes starting with {:?}), found {} bytes starting \
             with {:?}",
            String::from_utf8_lossy(MAGIC),
            bytes.len(),
            String::from_utf8_lossy(start)
        )));
    }
    if bytes.len() < FIXED_HEADER {
        return Err(Error::Snapshot(format!(
            "expected a simulator snapshot of at least {FIXED_HEADER} bytes, found {} bytes \
             (truncated)",
            bytes.len()
        )));
    }
    let mut at = MAGIC.len();
    let mut take = |n: usize| {
        let part = &bytes[at..at + n];
        at += n;
        part
    };
    let u32_at = |b: &[u8]| u32::from_le_bytes(b.try_into().expect("4 bytes"));
    let u64_at = |b: &[u8]| u64::from_le_bytes(b.try_into().expect("8 bytes"));
    let version = u32_at(take(4));
    let world = u64_at(take(8));
    let robot = u64_at(take(8));
    let physics_steps = u32_at(take(4));
    let noise = take(1)[0];
    let length = u64_at(take(8));
    let checksum = u64_at(take(8));
    let mut rest = &bytes[at..];
    let mut name = |what: &str| -> Result<&str> {
        let truncated = || {
            Error::Snapshot(format!(
                "expected the {what} name in the snapshot's header, found the bytes end \
                 (truncated)"
            ))
        };
        let (len, tail) = rest.split_first_chunk::<2>().ok_or_else(truncated)?;
        let len = u16::from_le_bytes(*len) as usize;
        let text = tail.get(..len).ok_or_else(truncated)?;
        rest = &tail[len..];
        std::str::from_utf8(text).map_err(corrupt)
    };
    let world_name = name("world")?;
    let robot_name = name("robot profile")?;
    let header = Header {
        version,
        world,
        robot,
        physics_steps,
        noise,
        length,
        checksum,
        world_name,
        robot_name,
    };
    Ok((header, rest))
}

/// The checksum of a snapshot: every byte but those of the checksum itself.
fn checksum(bytes: &[u8]) -> u64 {
    let before = FIXED_HEADER - 8;
    fnv1a_extend(fnv1a(&bytes[..before]), &bytes[FIXED_HEADER..])
}

/// Appends `text` with its length as two bytes (cut to 65,535 bytes at a character boundary).
fn push_name(out: &mut Vec<u8>, text: &str) {
    let mut end = text.len().min(u16::MAX as usize);
    while !text.is_char_boundary(end) {
        end -= 1;
    }
    out.extend_from_slice(&(end as u16).to_le_bytes());
    out.extend_from_slice(&text.as_bytes()[..end]);
}

impl Simulator {
    /// The whole state as bytes, for [`Simulator::restore`] (see the module notes for the layout).
    pub fn snapshot(&self) -> Vec<u8> {
        let state = self.saved_state();
        let payload = postcard::to_allocvec(&state).expect("the state is serde data");
        let mut body = postcard::Serializer {
            output: postcard::ser_flavors::ExtendFlavor::new(payload),
        };
        self.body
            .save(&mut body)
            .expect("the physics state is serde data");
        let payload = body.output.finalize().expect("a vector takes every byte");
        let mut out = Vec::with_capacity(FIXED_HEADER + 64 + payload.len());
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&SNAPSHOT_VERSION.to_le_bytes());
        out.extend_from_slice(&self.world.fingerprint().to_le_bytes());
        out.extend_from_slice(&self.rig.fingerprint.to_le_bytes());
        out.extend_from_slice(&self.physics_steps.to_le_bytes());
        out.push(u8::from(self.config.noise));
        out.extend_from_slice(&(payload.len() as u64).to_le_bytes());
        out.extend_from_slice(&[0; 8]);
        push_name(&mut out, self.world.name());
        push_name(&mut out, &self.rig.robot.name);
        out.extend_from_slice(&payload);
        let sum = checksum(&out);
        out[FIXED_HEADER - 8..FIXED_HEADER].copy_from_slice(&sum.to_le_bytes());
        out
    }

    /// Puts this simulator in the state `snapshot` holds, taken by [`Simulator::snapshot`] of a
    /// simulator of the same world, robot profile, control step and noise setting; it then goes
    /// on exactly as the one that took the snapshot. Bytes that are not such a snapshot (another
    /// world or robot, another format version, truncated or corrupt) are refused with
    /// `Error::Snapshot` and change nothing.
    pub fn restore(&mut self, snapshot: &[u8]) -> Result<()> {
        let (header, payload) = read_header(snapshot)?;
        if header.version != SNAPSHOT_VERSION {
            return Err(Error::Snapshot(format!(
                "expected a snapshot of format version {SNAPSHOT_VERSION}, found version {}",
                header.version
            )));
        }
        if header.world != self.world.fingerprint() {
            return Err(Error::Snapshot(format!(
                "expected a snapshot taken in world {:?} (fingerprint {:016x}), found one taken \
                 in world {:?} (fingerprint {:016x})",
                self.world.name(),
                self.world.fingerprint(),
                header.world_name,
                header.world
            )));
        }
        if header.robot != self.rig.fingerprint {
            return Err(Error::Snapshot(format!(
                "expected a snapshot of robot profile {:?} (fingerprint {:016x}), found one of \
                 robot profile {:?} (fingerprint {:016x})",
                self.rig.robot.name, self.rig.fingerprint, header.robot_name, header.robot
            )));
        }
        let noise = u8::from(self.config.noise);
        if header.physics_steps != self.physics_steps || header.noise != noise {
            let describe = |steps: u32, noise: bool| {
                format!(
                    "a {} ms control step with noise {}",
                    steps as f64 * self.dt * 1000.0,
                    if noise { "on" } else { "off" }
                )
            };
            return Err(Error::Snapshot(format!(
                "expected a snapshot of a simulator with {}, found one with {}",
                describe(self.physics_steps, self.config.noise),
                describe(header.physics_steps, header.noise != 0)
            )));
        }
        if payload.len() as u64 != header.length {
            return Err(Error::Snapshot(format!(
                "expected {} bytes of state after the snapshot's header, found {}{}",
                header.length,
                payload.len(),
                if (payload.len() as u64) < header.length {
                    " (truncated)"
                } else {
                    ""
                }
            )));
        }
        if checksum(snapshot) != header.checksum {
            return Err(corrupt("its checksum does not match its contents"));
        }
        let (state, body_bytes): (State, &[u8]) =
            postcard::take_from_bytes(payload).map_err(corrupt)?;
        self.check_state(&state)?;
        let mut body_reader = postcard::Deserializer::from_bytes(body_bytes);
        self.body.load(&mut body_reader).map_err(corrupt)?;
        self.heading = self.body.heading();
        self.put_state(state);
        Ok(())
    }

    /// Refuses a decoded state that does not fit this simulator (sizes, indices, finite pose).
    fn check_state(&self, state: &State) -> Result<()> {
        let sizes = [
            ("ray hits", state.ray_hits.len(), self.ray_hits.len()),
            (
                "ground sensor readers",
                state.ground_readers.len(),
                self.ground_readers.len(),
            ),
            (
                "distance readings",
                state.distance_readings.len(),
                self.distance_readings.len(),
            ),
            (
                "ground readings",
                state.ground_readings.len(),
                self.ground_readings.len(),
            ),
        ];
        for (what, found, expected) in sizes {
            if found != expected {
                return Err(corrupt(format!(
                    "expected {expected} {what}, found {found}"
                )));
            }
        }
        if !state.tracker.fits(self.world.checkpoints().len()) {
            return Err(corrupt(format!(
                "its barcode tracker refers to codes beyond the world's {}",
                self.world.checkpoints().len()
            )));
        }
        // The same limits as the API's: a snapshot edited with its checksum recomputed is
        // refused as `set_start` would refuse its values.
        let pose = |what: &str, p: &[f32; 3]| {
            let [x, y, yaw] = p.map(f64::from);
            crate::limits::check_pose(what, x, y, yaw).map_err(|e| corrupt(e.to_string()))
        };
        pose("robot pose", &state.pose)?;
        if let Some(start) = &state.start_override {
            pose("start pose", start)?;
        }
        let top = self.max_wheel_speed() * crate::robot::perturb::MAX_FACTOR;
        let checks: [(&str, f64, f64, f64); 6] = [
            ("time (s)", state.time, 0.0, f64::MAX),
            (
                "distance travelled (m)",
                state.distance_travelled,
                0.0,
                f64::MAX,
            ),
            ("left wheel speed", state.wheel_speeds[0].into(), -top, top),
            ("right wheel speed", state.wheel_speeds[1].into(), -top, top),
            (
                "left wheel angle",
                state.wheel_angles[0],
                f64::MIN,
                f64::MAX,
            ),
            (
                "right wheel angle",
                state.wheel_angles[1],
                f64::MIN,
                f64::MAX,
            ),
        ];
        for (what, value, low, high) in checks {
            if !(value.is_finite() && (low..=high).contains(&value)) {
                return Err(corrupt(format!(
                    "expected its {what} to be a finite number in [{low:e}, {high:e}], found {value}"
                )));
            }
        }
        let readings = state.distance_readings.iter().chain(&state.ground_readings);
        if let Some(bad) = readings.copied().find(|v| !v.is_finite()) {
            return Err(corrupt(format!(
                "expected finite sensor readings, found {bad}"
            )));
        }
        if let Some([x, y, radius]) = state.goal_override {
            super::check_goal(x, y, radius).map_err(|e| corrupt(e.to_string()))?;
        }
        Ok(())
    }

    /// A simulator in the same state as this one, which goes on exactly as this one would.
    pub fn duplicate(&self) -> Result<Simulator> {
        // Made at its own start: a robot of several may not fit at the world's.
        let start = (self.start_override).map_or(self.world.start(), |s| s.map(f64::from));
        let (world, rig) = (self.world.clone(), self.rig.clone());
        let mut copy = Simulator::with_rig_at(world, rig, self.config(), start)?;
        copy.restore(&self.snapshot())?;
        Ok(copy)
    }
}
