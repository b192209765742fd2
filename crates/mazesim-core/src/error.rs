//! The one error type of the core. Every variant says what was expected, what was found, and where.

use std::fmt;

/// Where a problem sits in a text file.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file path or a name such as `<string>` or `builtin:seed-maze`.
    pub source: String,
    /// 1-based line.
    pub line: usize,
    /// 1-based column.
    pub column: usize,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}:{}", self.source, self.line, self.column)
    }
}

/// Everything that can go wrong in mazesim's core.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A world or robot profile file does not follow its format.
    #[error("{location}: field `{field}`: {message}")]
    Format {
        /// File, line and column.
        location: Location,
        /// Dotted path of the field, e.g. `walls[2].size`.
        field: String,
        /// What was expected and what was found.
        message: String,
    },
    /// A built-in world, robot profile or other named thing does not exist.
    #[error("unknown {kind} {name:?}; available: {}", available.join(", "))]
    UnknownName {
        /// What kind of name: "world", "robot profile".
        kind: &'static str,
        /// The name asked for.
        name: String,
        /// The names that exist.
        available: Vec<String>,
    },
    /// An action (wheel speeds) that cannot be applied: NaN or infinite.
    #[error("{0}")]
    InvalidAction(String),
    /// Any other argument out of its domain.
    #[error("{0}")]
    InvalidArgument(String),
    /// Reading or writing a file failed.
    #[error("{path}: {message}")]
    Io {
        /// The file.
        path: String,
        /// The operating system's message.
        message: String,
    },
}

/// Result with the core's error.
pub type Result<T> = std::result::Result<T, Error>;
