//! The range of every number a robot profile holds, in one table ([`PROFILE_RANGES`]), and the
//! one check that holds a profile to it: each number of the profile, as its file writes it, is
//! looked up by its field's name and refused outside its range, naming the field. A number whose
//! field has no row is refused too, so a new field cannot be added without its range.

use toml::Value;

use super::{ProfileFile, MAX_ELEVATION};
use crate::limits::{MAX_ANGLE, MAX_COORDINATE, MAX_NOISE_SCALE};

/// One field's range: its name in the profile file, the smallest and largest values (each
/// bound included unless `open` says otherwise), and its unit for messages.
pub struct FieldRange {
    /// The field's key (`heading`, `body_radius`); a lookup table's column is `table[N]`.
    pub field: &'static str,
    /// Smallest value.
    pub min: f64,
    /// Largest value.
    pub max: f64,
    /// Whether the smallest and largest values are themselves refused.
    pub open: (bool, bool),
    /// Unit, for messages.
    pub unit: &'static str,
}

const fn range(
    field: &'static str,
    min: f64,
    max: f64,
    open: (bool, bool),
    unit: &'static str,
) -> FieldRange {
    FieldRange {
        field,
        min,
        max,
        open,
        unit,
    }
}

const ABOVE_ZERO: (bool, bool) = (true, false);
const CLOSED: (bool, bool) = (false, false);

/// Every number of a profile file and its range. Lengths are those of a small wheeled robot
/// (a body at most 1 m across its radius, sensors on it); angles are bounded as a world's are.
pub const PROFILE_RANGES: &[FieldRange] = &[
    range("body_radius", 0.0, 1.0, ABOVE_ZERO, "m"),
    range("wheel_radius", 0.0, 1.0, ABOVE_ZERO, "m"),
    range("axle_length", 0.0, 2.0, ABOVE_ZERO, "m"),
    range("max_wheel_speed", 0.0, 1_000.0, ABOVE_ZERO, "rad/s"),
    range(
        "encoder_resolution",
        0.0,
        std::f64::consts::TAU,
        ABOVE_ZERO,
        "rad",
    ),
    range("motor_gains", 0.0, 100.0, ABOVE_ZERO, ""),
    range("noise_scale", 0.0, MAX_NOISE_SCALE, CLOSED, ""),
    range("wall_reflectance", 0.0, 1.0, ABOVE_ZERO, ""),
    range("ground_gain", 0.0, 1_000.0, ABOVE_ZERO, ""),
    range("slip_on_contact", 0.0, 1.0, (false, true), ""),
    range("height", 0.0, 1.0, ABOVE_ZERO, "m"),
    range("footprint", 0.0, 1.0, ABOVE_ZERO, "m"),
    range("position", -1.0, 1.0, CLOSED, "m"),
    range("heading", -MAX_ANGLE, MAX_ANGLE, CLOSED, "rad"),
    range("elevation", 0.0, MAX_ELEVATION, CLOSED, "rad"),
    range("table[0]", 0.0, MAX_COORDINATE, CLOSED, "m"),
    range("table[1]", -1e9, 1e9, CLOSED, ""),
    range("table[2]", 0.0, 100.0, CLOSED, ""),
];

/// The first number of `file` outside its range (or without one): its field path and what was
/// expected and found.
pub(super) fn check(file: &ProfileFile) -> std::result::Result<(), (String, String)> {
    let Ok(value) = Value::try_from(file) else {
        return Ok(()); // a profile TOML cannot hold is refused when it is written
    };
    walk(&value, "", "", None)
}

fn walk(
    value: &Value,
    path: &str,
    key: &str,
    column: Option<usize>,
) -> Result<(), (String, String)> {
    match value {
        Value::Table(table) => table.iter().try_for_each(|(k, v)| {
            let inner = if path.is_empty() {
                k.clone()
            } else {
                format!("{path}.{k}")
            };
            walk(v, &inner, k, None)
        }),
        Value::Array(items) => items.iter().enumerate().try_for_each(|(i, v)| {
            let inner = format!("{path}[{i}]");
            // The numbers of a table's row are its columns; any other array's share its range.
            let column = matches!(v, Value::Integer(_) | Value::Float(_)).then_some(i);
            walk(v, &inner, key, column.filter(|_| key == "table"))
        }),
        Value::Float(_) | Value::Integer(_) => {
            let number = value
                .as_float()
                .unwrap_or_else(|| value.as_integer().unwrap_or(0) as f64);
            let name = match column {
                Some(c) => format!("{key}[{c}]"),
                None => key.to_string(),
            };
            let Some(r) = PROFILE_RANGES.iter().find(|r| r.field == name) else {
                return Err((
                    path.to_string(),
                    format!("expected no number here, found {number:?}"),
                ));
            };
            let above = if r.open.0 {
                number > r.min
            } else {
                number >= r.min
            };
            let below = if r.open.1 {
                number < r.max
            } else {
                number <= r.max
            };
            if above && below {
                return Ok(());
            }
            let (left, right) = (
                if r.open.0 { '(' } else { '[' },
                if r.open.1 { ')' } else { ']' },
            );
            let unit = if r.unit.is_empty() {
                String::new()
            } else {
                format!(" {}", r.unit)
            };
            Err((
                path.to_string(),
                format!(
                    "expected a number in {left}{}, {}{right}{unit}, found {number:?} (every number \
                     of a robot profile has its range: see the robot profile format)",
                    r.min, r.max
                ),
            ))
        }
        _ => Ok(()),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::robot::{robot_profile_names, RobotProfile};

    #[test]
    fn every_built_in_profile_is_within_its_ranges() {
        for name in robot_profile_names() {
            let profile = RobotProfile::builtin(&name).unwrap();
            assert_eq!(check(&profile.file()), Ok(()), "{name}");
        }
    }

    #[test]
    fn an_absurd_number_in_any_field_of_a_profile_is_refused_naming_it() {
        let text = RobotProfile::builtin("alphabot2")
            .unwrap()
            .to_toml()
            .unwrap();
        let cases = [
            ("heading = ", "heading"),
            ("body_radius = ", "body_radius"),
            ("max_wheel_speed = ", "max_wheel_speed"),
            ("ground_gain = ", "ground_gain"),
            ("height = ", "height"),
            ("position = [", "position"),
            ("table = [[", "table"),
            ("encoder_resolution = ", "encoder_resolution"),
        ];
        for (prefix, field) in cases {
            let at = text
                .find(prefix)
                .unwrap_or_else(|| panic!("{prefix} in\n{text}"))
                + prefix.len();
            let end = at + text[at..].find([',', '\n', ']']).unwrap();
            let absurd = format!("{}1e300{}", &text[..at], &text[end..]);
            let err = RobotProfile::from_toml(&absurd, "p.toml")
                .unwrap_err()
                .to_string();
            assert!(
                err.contains(field) && err.contains("expected a number in"),
                "{field}: {err}"
            );
        }
    }
}
