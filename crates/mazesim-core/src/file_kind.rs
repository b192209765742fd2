//! The kinds of files mazesim reads and writes, told apart by what they hold and by their names.
//!
//! A file of one kind given where another is expected (a world file as a robot profile, a
//! profile as a world, a recorded run or a Webots world read as TOML) is named for what it is,
//! with where it is taken, instead of being refused for the first field the other kind lacks;
//! and a world is saved only under a name its loader reads back as a world.

use std::path::Path;

use crate::error::{Error, Result};

/// A kind of file mazesim reads.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    /// A world file (TOML starting `format = "mazesim-world"`).
    World,
    /// A robot profile (TOML with a top-level `wheel_radius` or `axle_length`).
    RobotProfile,
    /// A Webots world (`#VRML_SIM` header, no `PROTO`).
    WebotsWorld,
    /// A Webots PROTO file (`#VRML_SIM` header and a `PROTO` declaration).
    WebotsProto,
    /// A JSON file of mazesim's own, by its `"format"`: a policy, a checkpoint, a run...
    Json(JsonKind),
}

/// The JSON files of mazesim, by the `"format"` they start with.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JsonKind {
    /// `"mazesim-policy"`: a trained policy's `policy.json`.
    Policy,
    /// `"mazesim-training-checkpoint"`: a training run's checkpoint.
    TrainingCheckpoint,
    /// `"mazesim-run"`: a recorded run.
    Run,
    /// `"mazesim-transfer-study"`: a transfer study's result.
    TransferStudy,
}

/// The `"format"` tags of mazesim's JSON files, each with its kind.
const JSON_FORMATS: [(&str, JsonKind); 4] = [
    ("mazesim-policy", JsonKind::Policy),
    ("mazesim-training-checkpoint", JsonKind::TrainingCheckpoint),
    ("mazesim-run", JsonKind::Run),
    ("mazesim-transfer-study", JsonKind::TransferStudy),
];

/// How many bytes of a file the sniff reads: every kind shows itself in its first lines.
const SNIFFED_BYTES: usize = 64 * 1024;

impl FileKind {
    /// What the kind is, with its article.
    pub fn name(self) -> &'static str {
        match self {
            FileKind::World => "a mazesim world file",
            FileKind::RobotProfile => "a robot profile",
            FileKind::WebotsWorld => "a Webots world (.wbt)",
            FileKind::WebotsProto => "a Webots PROTO file",
            FileKind::Json(JsonKind::Policy) => "a trained policy (policy.json)",
            FileKind::Json(JsonKind::TrainingCheckpoint) => "a training checkpoint",
            FileKind::Json(JsonKind::Run) => "a recorded run",
            FileKind::Json(JsonKind::TransferStudy) => "a transfer study's result",
        }
    }

    /// Where a file of this kind is taken.
    pub fn where_taken(self) -> &'static str {
        match self {
            FileKind::World => "pass it as a world (`--world`, `load_world`, `World.load`)",
            FileKind::RobotProfile => "pass it as a robot (`--robot`, `RobotProfile.load`)",
            FileKind::WebotsWorld => {
                "pass it under a .wbt name as a world (`--world`, `load_world`) or import it \
                 (`mazesim import-wbt`)"
            }
            FileKind::WebotsProto => "a Webots world that uses it is what mazesim reads",
            FileKind::Json(JsonKind::Policy) => "pass its folder as `--policy`",
            FileKind::Json(JsonKind::TrainingCheckpoint) => {
                "resume it with `mazesim train --resume`"
            }
            FileKind::Json(JsonKind::Run) => "replay it with `mazesim replay`",
            FileKind::Json(JsonKind::TransferStudy) => "read it with `mazesim transfer`",
        }
    }

    /// The kind of file `text` is, from its first lines, or None when it is none of them.
    pub fn sniff(text: &str) -> Option<FileKind> {
        let mut end = text.len().min(SNIFFED_BYTES);
        while !text.is_char_boundary(end) {
            end -= 1;
        }
        let head = text[..end].trim_start_matches('\u{feff}').trim_start();
        if head.starts_with("#VRML_SIM") {
            let proto = head
                .lines()
                .any(|line| line.trim_start().starts_with("PROTO "));
            return Some(if proto {
                FileKind::WebotsProto
            } else {
                FileKind::WebotsWorld
            });
        }
        if head.starts_with('{') {
            return json_format(head).map(FileKind::Json);
        }
        toml_kind(head)
    }
}

/// The kind of a JSON text from its `"format"` value, if it is one of mazesim's.
fn json_format(head: &str) -> Option<JsonKind> {
    let after = &head[head.find("\"format\"")? + "\"format\"".len()..];
    let value = after.trim_start().strip_prefix(':')?.trim_start();
    let value = value.strip_prefix('"')?;
    let tag = &value[..value.find('"')?];
    JSON_FORMATS
        .iter()
        .find(|(name, _)| *name == tag)
        .map(|(_, kind)| *kind)
}

/// The kind of a TOML text from its top-level keys (those before its first table header).
fn toml_kind(head: &str) -> Option<FileKind> {
    for line in head.lines() {
        let line = line.trim();
        if line.starts_with('[') {
            break;
        }
        let Some((key, value)) = line.split_once('=') else {
            continue;
        };
        let key = key.trim().trim_matches('"');
        let value = value
            .split('#')
            .next()
            .unwrap_or("")
            .trim()
            .trim_matches('"');
        if key == "format" && value == crate::world::values::WORLD_FORMAT_TAG {
            return Some(FileKind::World);
        }
        if key == "wheel_radius" || key == "axle_length" {
            return Some(FileKind::RobotProfile);
        }
    }
    None
}

/// `error`, the refusal of `text` (named `source`) read as `expected`, or, when `text` is a file
/// of another kind, the error that says which kind it is and where it is taken.
pub fn named_for_its_kind(text: &str, source: &str, expected: FileKind, error: Error) -> Error {
    match FileKind::sniff(text) {
        Some(found) if found != expected => crate::world::locate::format_error(
            source,
            text,
            0,
            Some("(top level)"),
            format!(
                "expected {}, found {}: {}",
                expected.name(),
                found.name(),
                found.where_taken()
            ),
        ),
        _ => error,
    }
}

/// Refuses to save a world under `path` when the file it makes would not be read back as a
/// world file: a name not ending in `.toml` (`load_world` reads a `.wbt` file as a Webots world,
/// any other name hides what the file is). A device, FIFO or terminal (`/dev/stdout`) is
/// written into whatever its name.
pub fn check_world_file_name(path: &Path) -> Result<()> {
    let toml = path
        .extension()
        .is_some_and(|suffix| suffix.eq_ignore_ascii_case("toml"));
    if toml || !crate::io::replaces_a_file(path)? {
        return Ok(());
    }
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into(),
    );
    let why = if path
        .extension()
        .is_some_and(|suffix| suffix.eq_ignore_ascii_case("wbt"))
    {
        "a .wbt file is read back as a Webots world"
    } else {
        "a world file's name says it is one, and `load_world` reads .toml and .wbt files"
    };
    Err(Error::InvalidArgument(format!(
        "cannot save the world to {}: expected a world file ending in .toml, found {name:?} \
         ({why})",
        path.display()
    )))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_kind_is_told_by_its_first_lines() {
        let world = "# my maze\nformat = \"mazesim-world\"\nversion = 1\n";
        assert_eq!(FileKind::sniff(world), Some(FileKind::World));
        let profile = "name = \"mine\"\nwheel_radius = 0.02\n[models.ir]\nkind = \"infrared\"\n";
        assert_eq!(FileKind::sniff(profile), Some(FileKind::RobotProfile));
        let wbt = "#VRML_SIM R2023b utf8\nWorldInfo { }\n";
        assert_eq!(FileKind::sniff(wbt), Some(FileKind::WebotsWorld));
        let proto = "#VRML_SIM R2023b utf8\nPROTO Box [ ] { Solid { } }\n";
        assert_eq!(FileKind::sniff(proto), Some(FileKind::WebotsProto));
        let run = "{\n  \"format\" : \"mazesim-run\", \"version\": \"1.3\"}";
        assert_eq!(FileKind::sniff(run), Some(FileKind::Json(JsonKind::Run)));
        // A key of a table is not a top-level key; other texts are no kind.
        assert_eq!(FileKind::sniff("[robot]\nwheel_radius = 0.02\n"), None);
        assert_eq!(FileKind::sniff("{\"format\": \"other\"}"), None);
        assert_eq!(FileKind::sniff(""), None);
    }

    #[test]
    fn a_world_is_saved_under_a_toml_name_or_into_a_device() {
        for name in ["w.wbt", "w.png", "w", "w.TOML.bak"] {
            let refused = check_world_file_name(Path::new(name))
                .unwrap_err()
                .to_string();
            assert!(
                refused.contains("expected a world file ending in .toml"),
                "{refused}"
            );
        }
        assert!(check_world_file_name(Path::new("w.wbt"))
            .unwrap_err()
            .to_string()
            .contains("read back as a Webots world"));
        assert!(check_world_file_name(Path::new("maze.Toml")).is_ok());
        assert!(check_world_file_name(Path::new("/dev/null")).is_ok());
    }
}
