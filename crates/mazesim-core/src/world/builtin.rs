//! Worlds embedded in the library, so an installed package finds them from any directory.

use crate::error::{Error, Result};

const BUILTIN: &[(&str, &str)] = &[
    (
        "seed-maze",
        include_str!("../../../../worlds/seed-maze.toml"),
    ),
    (
        "line-follow",
        include_str!("../../../../worlds/line-follow.toml"),
    ),
    ("arena", include_str!("../../../../worlds/arena.toml")),
];

/// Names of the built-in worlds.
pub fn builtin_world_names() -> Vec<String> {
    BUILTIN.iter().map(|(n, _)| n.to_string()).collect()
}

/// The file text of a built-in world.
pub fn builtin_world_text(name: &str) -> Result<&'static str> {
    BUILTIN
        .iter()
        .find(|(n, _)| *n == name)
        .map(|(_, t)| *t)
        .ok_or_else(|| Error::UnknownName {
            kind: "world",
            name: name.to_string(),
            available: builtin_world_names(),
        })
}
