//! A world's extent, angles, counts and time step checked against [`crate::limits`] while it is
//! compiled, before any index is built: a refused world is a format error at the offending table,
//! naming the field, the value and the allowed range.

use super::geometry::Bounds;
use super::locate;
use crate::error::{Error, Result};
use crate::limits::{
    BASIC_TIME_STEP_MS, MAX_ANGLE, MAX_BODIES, MAX_CHECKPOINTS, MAX_COORDINATE, MAX_PAINT_REGIONS,
    MAX_WALLS,
};

/// Pairs of walls sharing a bin of the wall index that any world may have.
const MAX_CROWDED_PAIRS: u64 = 1 << 20;

/// Pairs of walls sharing a bin allowed per wall beyond `MAX_CROWDED_PAIRS`.
const CROWDED_PAIRS_PER_WALL: u64 = 64;

/// Where in the file a checked thing was written.
#[derive(Debug, Clone, Copy)]
pub(super) enum Place<'a> {
    /// The `n`-th `[[name]]` table.
    Array(&'a str, usize),
    /// The `[name]` table.
    Table(&'a str),
    /// A top-level key.
    Key(&'a str),
}

/// Checks the parts of one world file.
pub(super) struct ExtentCheck<'a> {
    pub source: &'a str,
    pub text: &'a str,
}

/// Byte offset of the start of the first line of `text` that starts with `prefix` (0 if none).
pub(super) fn line_offset(text: &str, prefix: &str, nth: usize) -> usize {
    let mut seen = 0;
    let mut offset = 0;
    for line in text.split_inclusive('\n') {
        let trimmed = line.trim_start();
        if trimmed.starts_with(prefix) {
            if seen == nth {
                return offset + (line.len() - trimmed.len());
            }
            seen += 1;
        }
        offset += line.len();
    }
    0
}

impl ExtentCheck<'_> {
    /// The format error of `field` at `place`, saying `message`.
    pub fn refused(&self, place: Place<'_>, field: &str, message: String) -> Error {
        self.refuse(place, field, message)
    }

    fn refuse(&self, place: Place<'_>, field: &str, message: String) -> Error {
        let offset = match place {
            Place::Array(name, n) => line_offset(self.text, &format!("[[{name}]]"), n),
            Place::Table(name) => line_offset(self.text, &format!("[{name}]"), 0),
            Place::Key(name) => line_offset(self.text, name, 0),
        };
        locate::format_error(self.source, self.text, offset, Some(field), message)
    }

    /// Every point of `bounds` lies within `MAX_COORDINATE` of the origin on both axes.
    pub fn within(&self, place: Place<'_>, field: &str, bounds: Bounds) -> Result<()> {
        let corners = [bounds.min[0], bounds.min[1], bounds.max[0], bounds.max[1]];
        if corners
            .iter()
            .all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE)
        {
            return Ok(());
        }
        Err(self.refuse(
            place,
            field,
            format!(
                "expected every point within [-{m}, {m}] m on x and y (poses are f32: farther out \
                 the robot's motion is lost to rounding), found x in [{:?}, {:?}], y in [{:?}, {:?}]",
                bounds.min[0],
                bounds.max[0],
                bounds.min[1],
                bounds.max[1],
                m = MAX_COORDINATE
            ),
        ))
    }

    /// A point lies within `MAX_COORDINATE` of the origin.
    pub fn point(&self, place: Place<'_>, field: &str, p: [f64; 2]) -> Result<()> {
        self.within(place, field, Bounds { min: p, max: p })
    }

    /// An angle lies within `MAX_ANGLE` radians of zero.
    pub fn angle(&self, place: Place<'_>, field: &str, yaw: f64) -> Result<()> {
        if yaw.is_finite() && yaw.abs() <= MAX_ANGLE {
            return Ok(());
        }
        Err(self.refuse(
            place,
            field,
            format!("expected an angle in [-{MAX_ANGLE}, {MAX_ANGLE}] radians, found {yaw:?}"),
        ))
    }

    /// The counts of walls, paint regions and checkpoints.
    pub fn counts(&self, walls: usize, regions: usize, checkpoints: usize) -> Result<()> {
        let checks = [
            (
                "walls",
                "walls (boxes, segments and maze walls)",
                walls,
                MAX_WALLS,
            ),
            (
                "paint",
                "paint regions (polyline segments and barcode bars included)",
                regions,
                MAX_PAINT_REGIONS,
            ),
            ("checkpoints", "checkpoints", checkpoints, MAX_CHECKPOINTS),
        ];
        for (field, what, count, most) in checks {
            if count > most {
                return Err(self.refuse(
                    Place::Array(field, most),
                    field,
                    format!("expected at most {most} {what}, found {count}"),
                ));
            }
        }
        Ok(())
    }

    /// The count of movable bodies.
    pub fn body_count(&self, bodies: usize) -> Result<()> {
        if bodies <= MAX_BODIES {
            return Ok(());
        }
        Err(self.refuse(
            Place::Array("bodies", MAX_BODIES),
            "bodies",
            format!("expected at most {MAX_BODIES} movable bodies, found {bodies}"),
        ))
    }

    /// `pairs` (pairs of walls listed in a common bin of the wall index, an upper bound of the
    /// pairs of overlapping walls the physics engine tracks) stays within a budget proportional
    /// to the `walls`.
    pub fn crowding(&self, pairs: u64, walls: usize) -> Result<()> {
        let most = MAX_CROWDED_PAIRS.max(CROWDED_PAIRS_PER_WALL * walls as u64);
        if pairs <= most {
            return Ok(());
        }
        Err(self.refuse(
            Place::Array("walls", 0),
            "walls",
            format!(
                "expected walls spread out enough that at most {most} pairs of them share a bin \
                 of the wall index (overlapping walls cost the physics engine memory per pair), \
                 found {pairs} pairs; walls written twice count once"
            ),
        ))
    }

    /// The basic time step in milliseconds.
    pub fn time_step(&self, ms: f64) -> Result<()> {
        let (least, most) = BASIC_TIME_STEP_MS;
        if (least..=most).contains(&ms) {
            return Ok(());
        }
        Err(self.refuse(
            Place::Key("basic_time_step_ms"),
            "basic_time_step_ms",
            format!("expected a basic time step in [{least}, {most}] ms, found {ms}"),
        ))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn places_are_found_by_their_header_line() {
        let text = "a = 1\n[[walls]]\nx = 1\n  [[walls]]\n[start]\n";
        assert_eq!(line_offset(text, "[[walls]]", 1), 24);
        assert_eq!(line_offset(text, "[start]", 0), 34);
        assert_eq!(line_offset(text, "[goal]", 0), 0);
    }
}
