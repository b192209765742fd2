//! The first line of a `.wbt` file, `#VRML_SIM <version> utf8`, and the Webots version in it.
//!
//! Versions seen in the wild: `V8.5` ... `V8.6.2` (Webots 8), `R2018a` ... `R2025a`, some with a
//! `-revN` suffix (`R2019a-rev1`). Worlds up to R2021b (and the `R2021c` development files) use
//! the old Y-up PROTOs and default to the NUE convention; R2022a turned both to ENU (z up).

use std::fmt;

use crate::error::{Error, Result};
use crate::file_kind::{named_for_its_kind, FileKind};

/// The newest Webots release this reader was checked against.
pub const NEWEST_KNOWN: WbtVersion = WbtVersion::Release {
    year: 2025,
    letter: 'a',
    revision: 0,
};

/// A Webots version as written in a world file's header.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum WbtVersion {
    /// `V<major>.<minor>[.<patch>]`, Webots 8 and older.
    Numbered {
        /// Major version.
        major: u32,
        /// Minor version.
        minor: u32,
        /// Patch level (0 when absent).
        patch: u32,
    },
    /// `R<year><letter>[-rev<n>]`, from Webots R2018a on.
    Release {
        /// Year of the release.
        year: u32,
        /// The release of that year: `a`, `b`, ...
        letter: char,
        /// Revision (0 when absent).
        revision: u32,
    },
}

impl WbtVersion {
    /// Parses `R2023b`, `R2019a-rev1` or `V8.5`.
    pub fn parse(text: &str) -> Option<WbtVersion> {
        if let Some(rest) = text.strip_prefix('V') {
            let mut parts = rest.split('.');
            let major = parts.next()?.parse().ok()?;
            let minor = parts.next().map_or(Some(0), |p| p.parse().ok())?;
            let patch = parts.next().map_or(Some(0), |p| p.parse().ok())?;
            if parts.next().is_some() {
                return None;
            }
            return Some(WbtVersion::Numbered {
                major,
                minor,
                patch,
            });
        }
        let rest = text.strip_prefix('R')?;
        let (release, revision) = match rest.split_once("-rev") {
            Some((release, n)) => (release, n.parse().ok()?),
            None => (rest, 0),
        };
        let year_digits = release.get(..4)?;
        if !year_digits.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let mut tail = release[4..].chars();
        let letter = tail.next().filter(char::is_ascii_lowercase)?;
        if tail.next().is_some() {
            return None;
        }
        Some(WbtVersion::Release {
            year: year_digits.parse().ok()?,
            letter,
            revision,
        })
    }

    /// Whether PROTOs and primitives of this version are Z-up (R2022a and later). Before, they
    /// were Y-up: a `Cylinder`'s axis and a `Plane`'s normal were y and robots faced -z.
    pub fn has_z_up_protos(&self) -> bool {
        match *self {
            WbtVersion::Numbered { .. } => false,
            WbtVersion::Release { year, .. } => year >= 2022,
        }
    }

    fn order_key(&self) -> (u32, u32, u32) {
        match *self {
            WbtVersion::Numbered {
                major,
                minor,
                patch,
            } => (major, minor, patch),
            WbtVersion::Release {
                year,
                letter,
                revision,
            } => (year, letter as u32, revision),
        }
    }
}

impl fmt::Display for WbtVersion {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            WbtVersion::Numbered {
                major,
                minor,
                patch: 0,
            } => write!(f, "V{major}.{minor}"),
            WbtVersion::Numbered {
                major,
                minor,
                patch,
            } => write!(f, "V{major}.{minor}.{patch}"),
            WbtVersion::Release {
                year,
                letter,
                revision: 0,
            } => write!(f, "R{year}{letter}"),
            WbtVersion::Release {
                year,
                letter,
                revision,
            } => write!(f, "R{year}{letter}-rev{revision}"),
        }
    }
}

/// Reads the header line; returns the version and warnings about it.
pub fn parse_header(text: &str, source: &str) -> Result<(WbtVersion, Vec<String>)> {
    let first = text
        .trim_start_matches('\u{feff}')
        .lines()
        .next()
        .unwrap_or("");
    let mut words = first.split_whitespace();
    if words.next() != Some("#VRML_SIM") {
        let shown: String = first.chars().take(40).collect();
        let refused = Error::format_at(
            source,
            1,
            1,
            "(header)",
            format!("expected the Webots world header `#VRML_SIM <version> utf8`, found `{shown}`"),
        );
        return Err(named_for_its_kind(
            text,
            source,
            FileKind::WebotsWorld,
            refused,
        ));
    }
    let column = first.find("#VRML_SIM").unwrap_or(0) + "#VRML_SIM".len() + 2;
    let Some(word) = words.next() else {
        return Err(Error::format_at(
            source,
            1,
            column,
            "(header)",
            "expected a Webots version such as R2023b or V8.5 after #VRML_SIM, found nothing",
        ));
    };
    let version = WbtVersion::parse(word).ok_or_else(|| {
        Error::format_at(
            source,
            1,
            column,
            "(header)",
            format!(
                "expected a Webots version such as R2023b, R2019a-rev1 or V8.5, found `{word}`"
            ),
        )
    })?;
    let mut warnings = Vec::new();
    match words.next() {
        Some("utf8") | None => {}
        Some(other) => warnings.push(format!(
            "line 1: expected the encoding `utf8` in the header, found `{other}`; read as UTF-8"
        )),
    }
    if version.order_key() > NEWEST_KNOWN.order_key()
        && matches!(version, WbtVersion::Release { .. })
    {
        warnings.push(format!(
            "line 1: Webots {version} is newer than {NEWEST_KNOWN}, the newest version this reader \
             knows; read with the conventions of {NEWEST_KNOWN}"
        ));
    }
    if let WbtVersion::Numbered { major, minor, .. } = version {
        if (major, minor) < (8, 5) {
            warnings.push(format!(
                "line 1: Webots {version} is older than V8.5, the oldest version this reader \
                 knows; read with the conventions of V8.5"
            ));
        }
    }
    Ok((version, warnings))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_every_version_form() {
        for (text, z_up) in [
            ("V8.5", false),
            ("V8.6.2", false),
            ("R2018a", false),
            ("R2019a-rev1", false),
            ("R2020b-rev2", false),
            ("R2021b", false),
            ("R2021c", false),
            ("R2022a", true),
            ("R2023b", true),
            ("R2025a", true),
        ] {
            let v = WbtVersion::parse(text).unwrap_or_else(|| panic!("{text}"));
            assert_eq!(v.to_string(), text);
            assert_eq!(v.has_z_up_protos(), z_up, "{text}");
        }
        for bad in [
            "",
            "R",
            "R20a",
            "R2023",
            "R2023B",
            "R2023bb",
            "V",
            "V8.x",
            "8.5",
            "R2023b-rev",
        ] {
            assert!(WbtVersion::parse(bad).is_none(), "{bad}");
        }
    }

    #[test]
    fn header_errors_point_at_line_one() {
        let err = parse_header("#VRML V2.0 utf8\n", "w.wbt").unwrap_err();
        assert!(err.to_string().starts_with("w.wbt:1:1:"), "{err}");
        let err = parse_header("#VRML_SIM R20x utf8\n", "w.wbt").unwrap_err();
        assert!(err.to_string().starts_with("w.wbt:1:11:"), "{err}");
        let (_, warnings) = parse_header("#VRML_SIM R2027a utf8\n", "w.wbt").unwrap();
        assert_eq!(warnings.len(), 1);
    }
}
