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

impl Location {
    /// A file as a whole (line and column 0): what it holds together is refused, not one line.
    pub fn whole(source: &str) -> Self {
        Location {
            source: source.to_string(),
            line: 0,
            column: 0,
        }
    }
}

impl Error {
    /// The format error at `line` and `column` (1-based) of `source`, in field `field`.
    pub fn format_at(
        source: &str,
        line: usize,
        column: usize,
        field: impl Into<String>,
        message: impl Into<String>,
    ) -> Error {
        Error::Format {
            location: Location {
                source: source.to_string(),
                line,
                column,
            },
            field: field.into(),
            message: message.into(),
        }
    }
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.line == 0 {
            return write!(f, "{}", self.source);
        }
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
        /// What was being done and the operating system's reason.
        message: String,
        /// The operating system's error number, when the OS gave one.
        errno: Option<i32>,
        /// The operating system's reason alone (as C's `strerror`), when the OS gave one.
        reason: Option<String>,
    },
    /// A simulator snapshot that cannot be restored: not a snapshot, truncated or corrupt, of
    /// another format version, or taken in another world, with another robot or control step.
    #[error("{0}")]
    Snapshot(String),
    /// A long call stopped because the caller asked (Ctrl-C).
    #[error("interrupted")]
    Interrupted,

    /// A simulator or batch is in use by a call that cannot be waited for (a re-entrant call on
    /// the same thread, or a call of a thread that a forked child does not have).
    #[error("{0}")]
    Busy(String),
    /// A bug in mazesim: a panic caught before it reached the caller.
    #[error("internal error, please report: {0}")]
    Internal(String),
}

impl Error {
    /// An IO error of `path` while doing `what` ("cannot read the world file"), keeping the
    /// operating system's error number and reason.
    pub fn io(path: &std::path::Path, what: &str, err: &std::io::Error) -> Error {
        let reason = os_reason(err);
        Error::Io {
            path: path.display().to_string(),
            message: format!("{what}: {reason}"),
            errno: err.raw_os_error(),
            reason: Some(reason),
        }
    }
}

/// The reason of an IO error as the OS words it, without Rust's " (os error N)" suffix.
fn os_reason(err: &std::io::Error) -> String {
    let text = err.to_string();
    match (err.raw_os_error(), text.rfind(" (os error ")) {
        (Some(_), Some(at)) => text[..at].to_string(),
        _ => text,
    }
}

/// Result with the core's error.
pub type Result<T> = std::result::Result<T, Error>;
