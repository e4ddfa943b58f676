//! Readers of ground-motion record formats, all in Rust: one file → one [`Record`].
//!
//! | format | name | units | dt | components |
//! |---|---|---|---|---|
//! | one/two/many-column text | `text` | required (or `# units = …` comment) | given, from a time column, or `# dt = …` | one per column |
//! | CSV (header row optional) | `csv` | as text | as text | one per column |
//! | PEER NGA `.AT2` (old and new headers) | `at2` | header (`UNITS OF G`) | header | one |
//! | K-NET / KiK-net ASCII | `knet` | header (`Scale Factor 3920(gal)/6182761`) | header (`Sampling Freq(Hz)`) | one |
//! | COSMOS V1/V2 (format v01.20) | `cosmos` | data header (`units=cm/sec2(04)`) | real header #62 (ms) | one per channel block |
//! | USGS SMC | `smc` | cm/s² (format) | real header #2 (samples/s) | one |
//!
//! Every error names the file, the line and the value. No reader panics on any input
//! (proptest in `tests/motion_readers.rs`).

mod at2;
mod cosmos;
mod knet;
pub(crate) mod lines;
mod smc;
mod text;

use std::fmt;
use std::path::Path;

use crate::error::{DcfmError, Result};

use super::record::Record;
use super::units::AccelUnits;

/// A record file format.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Whitespace-separated columns.
    Text,
    /// Comma- or semicolon-separated columns.
    Csv,
    /// PEER NGA `.AT2`.
    PeerAt2,
    /// K-NET / KiK-net ASCII (NIED).
    Knet,
    /// COSMOS V1/V2 (format v01.20).
    Cosmos,
    /// USGS SMC.
    Smc,
    /// Made by the synthetic generator.
    Synthetic,
    /// Samples handed over by a program (the Python module: numpy arrays, ObsPy traces).
    Arrays,
}

impl Format {
    /// The names accepted for `format` (and `--format`).
    pub const NAMES: &'static str =
        "auto, text, csv, at2 (peer), knet (kiknet), cosmos (v1, v2), smc";

    /// The format called `name`; `None` means auto-detection.
    pub fn parse(name: &str) -> std::result::Result<Option<Format>, String> {
        Ok(Some(match name.trim().to_ascii_lowercase().as_str() {
            "auto" => return Ok(None),
            "text" | "txt" | "columns" => Format::Text,
            "csv" => Format::Csv,
            "at2" | "peer" | "peer_at2" | "nga" => Format::PeerAt2,
            "knet" | "kiknet" | "k-net" | "kik-net" | "nied" => Format::Knet,
            "cosmos" | "v1" | "v2" | "cosmos_v1" | "cosmos_v2" => Format::Cosmos,
            "smc" | "usgs_smc" => Format::Smc,
            other => {
                return Err(format!(
                    "unknown format \"{other}\": known formats are {}",
                    Self::NAMES
                ))
            }
        }))
    }

    /// The canonical name.
    pub fn name(self) -> &'static str {
        match self {
            Format::Text => "text",
            Format::Csv => "csv",
            Format::PeerAt2 => "at2",
            Format::Knet => "knet",
            Format::Cosmos => "cosmos",
            Format::Smc => "smc",
            Format::Synthetic => "synthetic",
            Format::Arrays => "arrays",
        }
    }

    /// Guess the format from the file name and the first lines.
    pub fn detect(label: &str, text: &str) -> Format {
        let first = text.lines().next().unwrap_or("").to_ascii_uppercase();
        let third = text.lines().nth(2).unwrap_or("").to_ascii_uppercase();
        let ext = Path::new(label)
            .extension()
            .map(|e| e.to_string_lossy().to_ascii_lowercase())
            .unwrap_or_default();
        if first.starts_with("ORIGIN TIME") {
            Format::Knet
        } else if first.contains("(FORMAT V") {
            Format::Cosmos
        } else if first.contains("PEER") || ext == "at2" || third.contains("IN UNITS OF") {
            Format::PeerAt2
        } else if ext == "smc"
            || first
                .trim_start()
                .get(1..)
                .is_some_and(|r| r.trim().ends_with("ACCELEROGRAM"))
        {
            Format::Smc
        } else if ext == "csv" {
            Format::Csv
        } else {
            Format::Text
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What the caller knows that a file may not say.
#[derive(Clone, Debug, Default)]
pub struct ReadOptions {
    /// Format; `None`: detected from the name and the first lines.
    pub format: Option<Format>,
    /// Units of the samples, required where the file does not state them; where it
    /// does, they must agree.
    pub units: Option<AccelUnits>,
    /// Sampling step (s), required where the file does not give one; where it does, they
    /// must agree to 1e-6.
    pub dt: Option<f64>,
}

/// Read one record file.
pub fn read_file(path: &Path, options: &ReadOptions) -> Result<Record> {
    let label = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| DcfmError::io(&label, e))?;
    read_bytes(&bytes, &label, options)
}

/// Read a record from the bytes of a file (`label` names it in errors). Invalid UTF-8 is
/// replaced, so that the error names the line where a number does not parse.
pub fn read_bytes(bytes: &[u8], label: &str, options: &ReadOptions) -> Result<Record> {
    let text = String::from_utf8_lossy(bytes);
    read_str(&text, label, options)
}

/// Read a record from its text.
pub fn read_str(text: &str, label: &str, options: &ReadOptions) -> Result<Record> {
    if let Some(dt) = options.dt {
        if !(dt.is_finite() && dt > 0.0) {
            return Err(DcfmError::invalid(
                label,
                "dt",
                dt,
                "a finite sampling step > 0 s",
            ));
        }
    }
    let format = options
        .format
        .unwrap_or_else(|| Format::detect(label, text));
    let mut record = match format {
        Format::Text => text::read(text, label, options, false)?,
        Format::Csv => text::read(text, label, options, true)?,
        Format::PeerAt2 => at2::read(text, label)?,
        Format::Knet => knet::read(text, label)?,
        Format::Cosmos => cosmos::read(text, label, options.dt)?,
        Format::Smc => smc::read(text, label)?,
        Format::Synthetic | Format::Arrays => {
            return Err(DcfmError::invalid(
                label,
                "format",
                format.name(),
                "a file format; synthetic motions and arrays are made, not read",
            ))
        }
    };
    reconcile(&mut record, label, options)?;
    if record.npts() < 2 {
        return Err(DcfmError::invalid(
            label,
            "npts",
            record.npts(),
            "at least 2 samples",
        ));
    }
    Ok(record)
}

/// Check the caller's units and dt against the file's own.
fn reconcile(record: &mut Record, label: &str, options: &ReadOptions) -> Result<()> {
    if let Some(u) = options.units {
        if u != record.units && record.format != Format::Text && record.format != Format::Csv {
            return Err(DcfmError::invalid(
                label,
                "units",
                u,
                format!(
                    "the file's own units ({}), or leave units unset",
                    record.units
                ),
            ));
        }
    }
    if let Some(dt) = options.dt {
        if (dt - record.dt).abs() > 1e-6 * record.dt {
            return Err(DcfmError::invalid(
                label,
                "dt",
                dt,
                format!(
                    "the file's own sampling step ({} s), or leave dt unset",
                    record.dt
                ),
            ));
        }
    }
    if !(record.dt.is_finite() && record.dt > 0.0) {
        return Err(DcfmError::invalid(
            label,
            "dt",
            record.dt,
            "a finite sampling step > 0 s",
        ));
    }
    Ok(())
}

/// The step of a header, checked finite and positive.
pub(crate) fn positive_step(label: &str, line: usize, dt: f64) -> Result<f64> {
    if dt.is_finite() && dt > 0.0 {
        Ok(dt)
    } else {
        Err(lines::line_error(label, line, dt, "a sampling step > 0 s"))
    }
}

/// A sample count of a header, checked to be a whole number ≥ 1 and below 2³¹.
pub(crate) fn sample_count(label: &str, line: usize, token: &str) -> Result<usize> {
    let v = lines::parse_number(token)
        .map_err(|e| lines::line_error(label, line, e, "a number of points"))?;
    if v >= 1.0 && v < 2f64.powi(31) && v.fract() == 0.0 {
        Ok(v as usize)
    } else {
        Err(lines::line_error(
            label,
            line,
            token,
            "a whole number of points ≥ 1",
        ))
    }
}
