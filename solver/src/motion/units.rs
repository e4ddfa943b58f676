//! Acceleration units of a record and their factor to SI (m/s²).
//!
//! Standard gravity g = 9.80665 m/s² (CGPM 1901, the value every strong-motion agency uses
//! for records given "in g"); 1 gal = 1 cm/s² = 0.01 m/s².

use std::fmt;

/// Standard gravity (m/s²).
pub const STANDARD_GRAVITY: f64 = 9.80665;

/// Units of an acceleration series. Every motion is held in m/s² inside the solver.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum AccelUnits {
    /// Fractions of standard gravity.
    G,
    /// cm/s² (gal).
    Gal,
    /// m/s².
    MetrePerSecond2,
}

impl AccelUnits {
    /// The names accepted in case files and on the command line.
    pub const NAMES: &'static str = "g, gal (= cm/s2, cm/s^2, cm/s/s), m/s2 (= m/s^2, m/s/s)";

    /// Factor that turns a value in these units into m/s².
    pub fn to_si(self) -> f64 {
        match self {
            AccelUnits::G => STANDARD_GRAVITY,
            AccelUnits::Gal => 0.01,
            AccelUnits::MetrePerSecond2 => 1.0,
        }
    }

    /// Parse a unit name (case-insensitive; `²`, `^2`, `2` and `/s/s` all mean squared).
    pub fn parse(name: &str) -> Option<Self> {
        let n: String = name
            .trim()
            .to_ascii_lowercase()
            .replace('²', "2")
            .replace("^2", "2")
            .replace("/s/s", "/s2")
            .replace("/sec2", "/s2")
            .replace("/sec/sec", "/s2")
            .chars()
            .filter(|c| !c.is_whitespace())
            .collect();
        match n.as_str() {
            "g" => Some(AccelUnits::G),
            "gal" | "cm/s2" | "cms2" | "cm/s**2" => Some(AccelUnits::Gal),
            "m/s2" | "ms2" | "m/s**2" | "si" => Some(AccelUnits::MetrePerSecond2),
            _ => None,
        }
    }
}

impl fmt::Display for AccelUnits {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            AccelUnits::G => "g",
            AccelUnits::Gal => "cm/s²",
            AccelUnits::MetrePerSecond2 => "m/s²",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_and_factors() {
        for (s, u) in [
            ("g", AccelUnits::G),
            ("G", AccelUnits::G),
            ("gal", AccelUnits::Gal),
            ("cm/s^2", AccelUnits::Gal),
            ("cm/s²", AccelUnits::Gal),
            ("cm/sec2", AccelUnits::Gal),
            ("m/s/s", AccelUnits::MetrePerSecond2),
            ("m/s2", AccelUnits::MetrePerSecond2),
        ] {
            assert_eq!(AccelUnits::parse(s), Some(u), "{s}");
        }
        assert_eq!(AccelUnits::parse("furlong"), None);
        // 1 g, 980.665 gal and 9.80665 m/s² are the same acceleration.
        assert_eq!(AccelUnits::G.to_si(), 980.665 * AccelUnits::Gal.to_si());
    }
}
