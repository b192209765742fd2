//! The bounds of every input: coordinates, sizes, counts, angles, time steps, threads and batch
//! sizes. A world, simulator or batch outside them is refused when it is made, with an error that
//! names the field, the value and the allowed range, so that nothing later can overflow, allocate
//! without bound or lose the robot's motion to rounding. `docs/reliability.md` lists them.

use crate::error::{Error, Result};

/// Largest distance of any point of a world (wall, paint, checkpoint, start, goal) from the
/// origin along x or y, metres. Poses are `f32`: at 1 km one unit in the last place is 61 um, so a
/// physics step of 4 mm (the e-puck's top speed over 32 ms) is still resolved to 1.5 %.
pub const MAX_COORDINATE: f64 = 1_000.0;

/// Largest side of a maze cell, metres. A cell is a corridor a robot drives through: the
/// e-puck's mazes have 0.25 m cells, a car-sized robot's a few metres. A larger number is most
/// often a size in centimetres or millimetres written as metres (`cell_size = 25` for 25 cm
/// makes a 125 m maze of the seed maze), so it is refused with a message naming the unit.
pub const MAX_CELL_SIZE: f64 = 10.0;

/// Largest angle (a yaw) in radians, either sign; beyond it an `f32` angle is too coarse to turn by.
pub const MAX_ANGLE: f64 = 1_000.0;

/// Largest world file read (or world text parsed, and robot profile), bytes: 100,000 walls and
/// as much paint take a few tens of MB, and the parser's memory stays a small multiple of it.
pub const MAX_WORLD_FILE_BYTES: u64 = 64 << 20;

/// Largest `.wbt` file read, bytes (a world may inline meshes of its robots and objects).
pub const MAX_WBT_FILE_BYTES: u64 = 256 << 20;

/// Most walls of a world (boxes, segments and cell-maze walls together).
pub const MAX_WALLS: usize = 100_000;

/// Most floor paint regions of a world (each polyline segment and barcode bar counts as one).
pub const MAX_PAINT_REGIONS: usize = 100_000;

/// Most movable bodies of a world (each is a rapier body in every environment).
pub const MAX_BODIES: usize = 1_000;

/// Most robots of a world. Every control step each robot's contacts and sensor rays are checked
/// against every other robot (a cost that grows with the square of the count), and the swarms of
/// the e-puck literature and of Webots' sample worlds hold from 2 to a few dozen robots; 64 leaves
/// room for the largest of them.
pub const MAX_ROBOTS: usize = 64;

/// Most checkpoints of a world.
pub const MAX_CHECKPOINTS: usize = 10_000;

/// Least and largest basic time step (physics step), milliseconds.
pub const BASIC_TIME_STEP_MS: (f64, f64) = (0.1, 1_000.0);

/// Most physics steps in one control step: a control step never runs for long.
pub const MAX_PHYSICS_STEPS_PER_CONTROL_STEP: f64 = 10_000.0;

/// Largest top speed of a robot (its wheel radius times its motor limit times its faster motor's
/// gain), metres per second: 80 times the e-puck's, and a step of it stays resolved in `f32`.
pub const MAX_ROBOT_SPEED: f64 = 10.0;

/// Largest top turn rate of a robot (twice its top speed over its axle length), radians per
/// second: a control step never turns it by more than an `f32` angle can hold.
pub const MAX_TURN_RATE: f64 = 10_000.0;

/// Largest noise scale of a robot (each sensor model's relative noise is multiplied by it): a
/// hundred times the measured noise, far beyond any real sensor, and its readings stay finite
/// (a scale of 1e300 made every noisy reading infinite).
pub const MAX_NOISE_SCALE: f64 = 100.0;

/// Most tables (`[[walls]]`-style headers and `{ ... }` inline tables) of a world text: one per
/// wall, segment, paint region, checkpoint, movable body and robot at their limits, and one for
/// each of `[floor]`, `[start]`, `[goal]`, `[grid]` and `[barcode]`. A text of more cannot make a
/// world within the limits, and is refused by a count of its bytes before it is parsed (a
/// text of 300,000 inline walls took seconds to parse before the wall count refused it).
pub const MAX_WORLD_TABLES: usize =
    MAX_WALLS + MAX_PAINT_REGIONS + MAX_CHECKPOINTS + MAX_BODIES + MAX_ROBOTS + 5;

/// Most threads of a batch (0 means one per core).
pub const MAX_THREADS: usize = 256;

/// Most environments of a batch (memory is checked as well, see `batch::check_size`).
pub const MAX_ENVS: usize = 1 << 24;

/// `Ok` when `value` is finite and within `[-bound, bound]`; otherwise an error naming `what`.
pub fn check_bounded(what: &str, value: f64, bound: f64) -> Result<()> {
    if value.is_finite() && value.abs() <= bound {
        Ok(())
    } else {
        Err(Error::InvalidArgument(out_of_bounds(what, value, bound)))
    }
}

/// The message of a value outside `[-bound, bound]`.
pub fn out_of_bounds(what: &str, value: f64, bound: f64) -> String {
    format!("expected {what} to be a finite number in [-{bound}, {bound}], found {value:?}")
}

/// Checks a pose (x, y in metres, yaw in radians) against `MAX_COORDINATE` and `MAX_ANGLE`;
/// `what` names it ("start pose", "pose").
pub fn check_pose(what: &str, x: f64, y: f64, yaw: f64) -> Result<()> {
    check_bounded(&format!("the {what}'s x (metres)"), x, MAX_COORDINATE)?;
    check_bounded(&format!("the {what}'s y (metres)"), y, MAX_COORDINATE)?;
    check_bounded(&format!("the {what}'s yaw (radians)"), yaw, MAX_ANGLE)
}

/// Checks a count against its largest value; `what` names it ("walls").
pub fn check_count(what: &str, count: usize, most: usize) -> Result<()> {
    if count <= most {
        Ok(())
    } else {
        Err(Error::InvalidArgument(format!(
            "expected at most {most} {what}, found {count}"
        )))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn poses_beyond_the_bounds_are_refused_with_the_field_and_range() {
        assert!(check_pose("start pose", 999.0, -999.0, 6.0).is_ok());
        let Err(Error::InvalidArgument(m)) = check_pose("start pose", 1e39, 0.0, 0.0) else {
            panic!("refused")
        };
        assert!(m.contains("start pose's x"), "{m}");
        assert!(m.contains("[-1000, 1000]") && m.contains("1e39"), "{m}");
        assert!(check_pose("pose", 0.0, 0.0, 3.5e38).is_err());
        assert!(check_pose("pose", 0.0, f64::NAN, 0.0).is_err());
    }

    #[test]
    fn counts_above_the_most_are_refused() {
        assert!(check_count("walls", MAX_WALLS, MAX_WALLS).is_ok());
        assert!(check_count("walls", MAX_WALLS + 1, MAX_WALLS).is_err());
    }
}
