//! A record as read from its file(s): uniformly sampled acceleration components in m/s²,
//! with the header facts worth keeping (format, station, original units, header peaks).

use crate::error::{DcfmError, Result};

use super::readers::Format;
use super::units::AccelUnits;

/// The direction a component points to in the model (x east, y north, z up).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Axis {
    X,
    Y,
    Z,
}

impl Axis {
    /// 0, 1, 2 for x, y, z.
    pub fn index(self) -> usize {
        match self {
            Axis::X => 0,
            Axis::Y => 1,
            Axis::Z => 2,
        }
    }

    /// "x", "y" or "z".
    pub fn name(self) -> &'static str {
        ["x", "y", "z"][self.index()]
    }

    /// The axis named `s` ("x"/"y"/"z", case-insensitive).
    pub fn parse(s: &str) -> Option<Self> {
        match s.trim().to_ascii_lowercase().as_str() {
            "x" => Some(Axis::X),
            "y" => Some(Axis::Y),
            "z" => Some(Axis::Z),
            _ => None,
        }
    }

    /// The axis a component name implies, by the usual conventions: east–west (EW, E, 090,
    /// 270, HNE, HN2, …) → x, north–south (NS, N, 000, 360, 180, HNN, HN1) → y, up–down (UD,
    /// UP, V, Z, HNZ) → z. `None` when the name says nothing (the user then maps it).
    pub fn guess(name: &str) -> Option<Self> {
        let n: String = name
            .trim()
            .to_ascii_uppercase()
            .chars()
            .filter(|c| c.is_ascii_alphanumeric())
            .collect();
        let horizontal_angle = |a: i64| -> Option<Axis> {
            match a.rem_euclid(360) {
                90 | 270 => Some(Axis::X),
                0 | 180 => Some(Axis::Y),
                _ => None,
            }
        };
        if let Ok(a) = n.parse::<i64>() {
            return horizontal_angle(a);
        }
        // Trailing digits (KiK-net "EW1", "NS2", …) do not change the direction.
        let core = n.trim_end_matches(|c: char| c.is_ascii_digit());
        match core {
            "EW" | "E" | "EAST" | "WE" | "W" | "HNE" | "HLE" | "BHE" | "HHE" | "X" => Some(Axis::X),
            "NS" | "N" | "NORTH" | "SN" | "S" | "HNN" | "HLN" | "BHN" | "HHN" | "Y" => {
                Some(Axis::Y)
            }
            "UD" | "UP" | "U" | "V" | "VERT" | "VERTICAL" | "DU" | "Z" | "HNZ" | "HLZ" | "BHZ"
            | "HHZ" => Some(Axis::Z),
            _ => None,
        }
    }
}

/// One component of a record.
#[derive(Clone, Debug, PartialEq)]
pub struct RecordComponent {
    /// The name the file gives it ("EW", "090", "NS2", "x", a CSV column header, …).
    pub name: String,
    /// The model axis it drives, when known (from the name or from the user).
    pub axis: Option<Axis>,
    /// Acceleration samples (m/s²), the first at t = 0.
    pub acceleration: Vec<f64>,
    /// The peak |a| the file's header states, in m/s², when it states one.
    pub header_peak: Option<f64>,
}

/// A uniformly sampled record: one to three acceleration components.
#[derive(Clone, Debug, PartialEq)]
pub struct Record {
    /// The file(s) it came from (or "synthetic …").
    pub source: String,
    pub format: Format,
    /// Station code or name, if the header has one.
    pub station: String,
    /// Event or description line, if the header has one.
    pub description: String,
    /// Units the file stores (samples are converted to m/s²).
    pub units: AccelUnits,
    /// Sampling step (s).
    pub dt: f64,
    pub components: Vec<RecordComponent>,
}

impl Record {
    /// Number of samples (the shortest component).
    pub fn npts(&self) -> usize {
        self.components
            .iter()
            .map(|c| c.acceleration.len())
            .min()
            .unwrap_or(0)
    }

    /// Put the components of several single-file records together (three files of one
    /// station, say). They must share dt to 1e-9 relative; the longer ones are cut to the
    /// shortest (recorded in the description).
    pub fn combine(records: Vec<Record>) -> Result<Record> {
        let mut it = records.into_iter();
        let Some(mut first) = it.next() else {
            return Err(DcfmError::invalid("", "files", "[]", "at least one file"));
        };
        for r in it {
            if (r.dt - first.dt).abs() > 1e-9 * first.dt {
                return Err(DcfmError::invalid(
                    &r.source,
                    "dt",
                    r.dt,
                    format!(
                        "the same sampling step as {} (dt = {})",
                        first.source, first.dt
                    ),
                ));
            }
            if r.units != first.units {
                first
                    .description
                    .push_str(&format!("; {} stored in {} (converted)", r.source, r.units));
            }
            first.source.push_str(&format!(" + {}", r.source));
            if first.station.is_empty() {
                first.station = r.station;
            }
            first.components.extend(r.components);
        }
        let n = first.npts();
        for c in &mut first.components {
            c.acceleration.truncate(n);
        }
        Ok(first)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_guesses() {
        for (s, a) in [
            ("EW", Some(Axis::X)),
            ("E-W", Some(Axis::X)),
            ("090", Some(Axis::X)),
            ("360", Some(Axis::Y)),
            ("NS2", Some(Axis::Y)),
            ("U-D", Some(Axis::Z)),
            ("HNZ", Some(Axis::Z)),
            ("045", None),
            ("foo", None),
        ] {
            assert_eq!(Axis::guess(s), a, "{s}");
        }
    }
}
