//! Checked scalar types of the file formats: a value that deserialises is a value that is valid,
//! so the TOML reader reports a bad one with its line, column and field.

use serde::{de, Deserialize, Deserializer, Serialize};

macro_rules! checked_f64 {
    ($(#[$doc:meta])* $name:ident, $check:expr, $expected:literal) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy, PartialEq, Serialize)]
        #[serde(transparent)]
        pub struct $name(pub f64);

        impl<'de> Deserialize<'de> for $name {
            fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
                let v = f64::deserialize(d)?;
                let ok: fn(f64) -> bool = $check;
                if ok(v) {
                    Ok(Self(v))
                } else {
                    Err(de::Error::custom(format!("expected {}, found {}", $expected, v)))
                }
            }
        }

        impl $name {
            /// The plain number.
            pub fn get(self) -> f64 {
                self.0
            }
        }
    };
}

checked_f64!(
    /// Any finite number (a coordinate, an angle).
    Finite,
    |v| v.is_finite(),
    "a finite number"
);
checked_f64!(
    /// A finite number above zero (a length, a time step).
    Positive,
    |v| v.is_finite() && v > 0.0,
    "a number above zero"
);
checked_f64!(
    /// A finite number at or above zero (a friction coefficient).
    NonNegative,
    |v| v.is_finite() && v >= 0.0,
    "a number at or above zero"
);
checked_f64!(
    /// A reflection factor in (0, 1] as Webots' infra-red model uses it.
    Reflectance,
    |v| v.is_finite() && v > 0.0 && v <= 1.0,
    "a reflectance factor in (0, 1] (1 = white, 0.2 = black)"
);
checked_f64!(
    /// A fraction in [0, 1) (of motion lost to wheel slip).
    SlipFraction,
    |v| v.is_finite() && (0.0..1.0).contains(&v),
    "a fraction in [0, 1)"
);

checked_f64!(
    /// One level of a colour in [0, 1] (Webots' `SFColor` components).
    ColourLevel,
    |v| v.is_finite() && (0.0..=1.0).contains(&v),
    "a colour level in [0, 1]"
);

/// A colour `[red, green, blue]`, each level in [0, 1], as a camera sees it.
pub type Colour = [ColourLevel; 3];

/// A colour from plain numbers, each level clamped to [0, 1] (NaN read as 0).
pub fn colour(rgb: [f64; 3]) -> Colour {
    rgb.map(|c| ColourLevel(if c.is_nan() { 0.0 } else { c.clamp(0.0, 1.0) }))
}

/// Converts a colour to plain numbers.
pub fn rgb(c: &Colour) -> [f64; 3] {
    [c[0].0, c[1].0, c[2].0]
}

/// A point or vector `[x, y]` in metres.
pub type Point = [Finite; 2];

/// Converts a point to plain numbers.
pub fn xy(p: &Point) -> [f64; 2] {
    [p[0].0, p[1].0]
}

/// A size `[sx, sy]` in metres, both above zero.
pub type Size = [Positive; 2];

/// A header field that must hold one exact string.
#[derive(Debug, Clone, PartialEq, Serialize)]
#[serde(transparent)]
pub struct FormatTag(pub String);

/// The only value of the `format` header of a world file.
pub const WORLD_FORMAT_TAG: &str = "mazesim-world";
/// The world format version this reader writes and reads.
pub const WORLD_FORMAT_VERSION: i64 = 1;

impl<'de> Deserialize<'de> for FormatTag {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        if s == WORLD_FORMAT_TAG {
            Ok(Self(s))
        } else {
            Err(de::Error::custom(format!(
                "expected \"{WORLD_FORMAT_TAG}\", found {s:?}"
            )))
        }
    }
}

/// The world format version, checked against the versions this reader knows.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(transparent)]
pub struct FormatVersion(pub i64);

impl<'de> Deserialize<'de> for FormatVersion {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let v = i64::deserialize(d)?;
        if v == WORLD_FORMAT_VERSION {
            Ok(Self(v))
        } else {
            Err(de::Error::custom(format!(
                "expected format version {WORLD_FORMAT_VERSION} (the one this mazesim reads), found {v}"
            )))
        }
    }
}

/// A barcode: a string of `0` and `1`, five bits, the first met first along the checkpoint's yaw.
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct BarcodeBits(pub String);

/// Number of bars of a checkpoint barcode (report section 4.2).
pub const BARCODE_BITS: usize = 5;

impl<'de> Deserialize<'de> for BarcodeBits {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let s = String::deserialize(d)?;
        if s.len() == BARCODE_BITS && s.chars().all(|c| c == '0' || c == '1') {
            Ok(Self(s))
        } else {
            Err(de::Error::custom(format!(
                "expected {BARCODE_BITS} bits of 0 and 1 such as \"10110\", found {s:?}"
            )))
        }
    }
}

impl BarcodeBits {
    /// The bits, first met first.
    pub fn bits(&self) -> Vec<bool> {
        self.0.chars().map(|c| c == '1').collect()
    }
}
