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

/// Most digits a numeral of a message keeps as written: every `u64` (a seed) has at most 20.
const MOST_DIGITS_KEPT: usize = 21;

/// `message` with each numeral of more than [`MOST_DIGITS_KEPT`] digits, which Rust's `{}` of an
/// `f64` writes in full (1e300 as 301 digits, 1e-300 as 0.000...0001), written as Python
/// writes such a float (`1e+300`, `1e-300`, `2.512e+122`); and without the integer type a TOML
/// reader names (`found integer 99999999999999999999 as i128`). The one pass every message of
/// the core's takes on its way to Python.
pub fn readable_numbers(message: &str) -> String {
    let bytes = message.as_bytes();
    let mut out = String::with_capacity(message.len());
    let (mut i, mut copied) = (0usize, 0usize);
    while i < bytes.len() {
        let starts = bytes[i].is_ascii_digit()
            && (i == 0 || !(bytes[i - 1].is_ascii_alphanumeric() || bytes[i - 1] == b'.'));
        if !starts {
            i += 1;
            continue;
        }
        let mut end = i;
        let mut point = false;
        while end < bytes.len()
            && (bytes[end].is_ascii_digit()
                || (bytes[end] == b'.'
                    && !point
                    && end + 1 < bytes.len()
                    && bytes[end + 1].is_ascii_digit()))
        {
            point |= bytes[end] == b'.';
            end += 1;
        }
        let numeral = &message[i..end];
        let digits = numeral.bytes().filter(u8::is_ascii_digit).count();
        if digits > MOST_DIGITS_KEPT {
            if let Ok(value) = numeral.parse::<f64>() {
                out.push_str(&message[copied..i]);
                out.push_str(&python_float(value));
                copied = end;
            }
        }
        i = end;
    }
    out.push_str(&message[copied..]);
    for kind in [" as i128", " as u128", " as i64", " as u64"] {
        out = out.replace(&format!("`{kind}"), "`");
    }
    out
}

/// A float as Python's `repr` writes one in exponent form: `1e+300`, `2.512e+122`, `1e-300`.
fn python_float(value: f64) -> String {
    let written = format!("{value:e}");
    match written.split_once('e') {
        Some((mantissa, exponent)) if !exponent.starts_with('-') => {
            format!("{mantissa}e+{exponent}")
        }
        _ => written,
    }
}

/// Result with the core's error.
pub type Result<T> = std::result::Result<T, Error>;

#[cfg(test)]
mod tests {
    use super::readable_numbers;

    #[test]
    fn long_numerals_are_written_as_python_writes_floats_and_short_ones_kept() {
        let huge = format!("found {}", 1e300_f64);
        assert_eq!(readable_numbers(&huge), "found 1e+300");
        let tiny = format!("found {} ms", 1e-300_f64);
        assert_eq!(readable_numbers(&tiny), "found 1e-300 ms");
        let noisy = format!("at most 10000 rad/s, found {}", 2.512e122_f64);
        assert_eq!(
            readable_numbers(&noisy),
            "at most 10000 rad/s, found 2.512e+122"
        );
        // A seed past 64 bits, line numbers, decimals and versions keep their digits.
        let kept = "p.toml:12:3: seed in 0..=18446744073709551615, found 18446744073709551616 \
                    (0.0015 m, R2023b, v1.2)";
        assert_eq!(readable_numbers(kept), kept);
        assert_eq!(
            readable_numbers("found integer `99999999999999999999` as i128"),
            "found integer `99999999999999999999`"
        );
    }
}
