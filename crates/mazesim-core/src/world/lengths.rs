//! Arrays of a TOML file held to the length their field has.
//!
//! The TOML reader fills a fixed-length field, such as a point `[x, y]` or a colour
//! `[r, g, b]`, from the first numbers of the array it is given and drops the rest without a
//! word: `center = [0.5, 0.2, 0.1]` would be read as `[0.5, 0.2]`. Rather than a check at each
//! of the many fields of that kind, a file is compared, once read, with the same description
//! written back: an array that comes back shorter held items its field has no place for.

use serde::Serialize;
use toml::Value;

use super::extent;
use super::locate;
use crate::error::Result;

/// Refuses `text` (read from `source` into `read`) when one of its arrays holds more items than
/// `read` keeps of it, naming the field, the count it takes and the count found.
pub fn check<T: Serialize>(read: &T, text: &str, source: &str) -> Result<()> {
    // Both conversions succeed for a text that was just read into `read`; if one did not,
    // there would be nothing to compare, and the reading itself stands.
    let (Ok(given), Ok(written)) = (text.parse::<toml::Table>(), Value::try_from(read)) else {
        return Ok(());
    };
    let Some(longer) = first_longer(&Value::Table(given), &written, String::new()) else {
        return Ok(());
    };
    let items = if longer.numbers { "numbers" } else { "items" };
    let message = format!(
        "expected {} {items}, found {} (remove the extra ones)",
        longer.kept, longer.found
    );
    let offset = offset_of(text, &longer.path);
    Err(locate::format_error(
        source,
        text,
        offset,
        Some(&longer.path),
        message,
    ))
}

/// An array of the file longer than what was read of it.
struct Longer {
    path: String,
    found: usize,
    kept: usize,
    numbers: bool,
}

/// The first array of `given` longer than the array at the same place in `written` (tables and
/// arrays are walked where both hold the same kind; a field written in another shape, or not
/// written back at all, is not compared).
fn first_longer(given: &Value, written: &Value, path: String) -> Option<Longer> {
    match (given, written) {
        (Value::Table(given), Value::Table(written)) => given.iter().find_map(|(key, value)| {
            let inner = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            first_longer(value, written.get(key)?, inner)
        }),
        (Value::Array(given), Value::Array(written)) => {
            if given.len() > written.len() {
                let numbers = given
                    .iter()
                    .all(|v| matches!(v, Value::Integer(_) | Value::Float(_)));
                return Some(Longer {
                    path,
                    found: given.len(),
                    kept: written.len(),
                    numbers,
                });
            }
            given
                .iter()
                .zip(written)
                .enumerate()
                .find_map(|(i, (g, w))| first_longer(g, w, format!("{path}[{i}]")))
        }
        _ => None,
    }
}

/// Byte offset of the field at `path` (`walls[3].center`, `goal.center`, `name`): its key after
/// the header of its table, or the header itself when the key is not found.
fn offset_of(text: &str, path: &str) -> usize {
    let (table, key) = path.rsplit_once('.').unwrap_or(("", path));
    let key = key.split('[').next().unwrap_or(key);
    let start = match table.split_once('[') {
        _ if table.is_empty() => 0,
        Some((name, rest)) if !name.contains('.') => {
            let nth = rest.split(']').next().and_then(|n| n.parse().ok());
            nth.map_or(0, |n| extent::line_offset(text, &format!("[[{name}]]"), n))
        }
        _ => text.find(&format!("[{table}]")).unwrap_or(0),
    };
    text[start..].find(key).map_or(start, |i| start + i)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::world::World;

    const HEAD: &str = "format = \"mazesim-world\"\nversion = 1\nname = \"t\"\n";

    fn seed_maze_text() -> String {
        World::builtin("seed-maze").unwrap().to_toml().unwrap()
    }

    #[test]
    fn a_point_with_a_third_number_is_refused_naming_its_field() {
        let text = seed_maze_text();
        let first = text.find("center = [").unwrap() + "center = [".len();
        let longer = format!("{}9.0, {}", &text[..first], &text[first..]);
        let err = World::from_toml(&longer, "t.toml").unwrap_err().to_string();
        assert!(err.contains("expected 2 numbers, found 3"), "{err}");
        assert!(err.contains("center"), "{err}");
    }

    #[test]
    fn a_profile_table_row_with_a_fourth_number_is_refused() {
        use crate::robot::RobotProfile;
        let text = RobotProfile::builtin("e-puck").unwrap().to_toml().unwrap();
        let inner = text.find("table = [[").unwrap() + "table = [[".len();
        let longer = format!("{}7.0, {}", &text[..inner], &text[inner..]);
        let err = RobotProfile::from_toml(&longer, "p.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains("expected 3 numbers, found 4"), "{err}");
        RobotProfile::from_toml(&text, "p.toml").unwrap();
    }

    #[test]
    fn every_builtin_world_and_profile_reads_without_a_refusal() {
        for name in crate::world::builtin_world_names() {
            let text = World::builtin(&name).unwrap().to_toml().unwrap();
            World::from_toml(&text, &name).unwrap();
        }
        for name in crate::robot::robot_profile_names() {
            crate::robot::RobotProfile::builtin(&name).unwrap();
        }
    }

    #[test]
    fn finds_the_line_of_a_field_in_an_array_of_tables() {
        let text = format!("{HEAD}[[walls]]\ncenter = [0, 0]\n[[walls]]\ncenter = [1, 2, 3]\n");
        let offset = offset_of(&text, "walls[1].center");
        assert!(text[offset..].starts_with("center = [1, 2, 3]"));
        let goal = format!("{HEAD}[goal]\ncenter = [1, 2]\n");
        assert!(goal[offset_of(&goal, "goal.center")..].starts_with("center = [1, 2]"));
        assert_eq!(offset_of(&goal, "name"), goal.find("name").unwrap());
    }
}
