//! A motion as a case item: `[motions.NAME]` with a record file (or three), or a synthetic
//! motion, and its processing.
//!
//! ```toml
//! [motions.kobe]
//! file = "records/NIS090.AT2"        # relative to the case file
//! format = "auto"                    # auto | text | csv | at2 | knet | cosmos | smc
//! component = "x"                    # axis of a one-component record (default: from its name)
//! [motions.kobe.processing]
//! highpass = 0.1
//! lowpass = 25.0
//!
//! [motions.station]
//! files = ["a.EW", "a.NS", "a.UD"]   # three files of one station
//! components = ["x", "y", "z"]       # axis of each component, in reading order
//!
//! [motions.table]
//! file = "acc.txt"
//! units = "g"                        # required where the file does not say
//! dt = 0.01                          # required where the file does not say
//!
//! [motions.wolong]
//! synthetic = { preset = "wolong", seed = 1 }
//! ```

use std::path::Path;

use serde::Deserialize;

use crate::error::{DcfmError, Result};

use super::ground_motion::GroundMotion;
use super::processing::{process, ProcessingOptions};
use super::readers::{read_file, Format, ReadOptions};
use super::record::{Axis, Record};
use super::synthetic::SyntheticSpec;
use super::units::AccelUnits;

/// `[motions.NAME]`.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct MotionSpec {
    /// One record file (relative to the case file).
    #[serde(default)]
    pub file: Option<String>,
    /// Several files whose components make one motion (same dt).
    #[serde(default)]
    pub files: Option<Vec<String>>,
    /// Format name, default "auto".
    #[serde(default)]
    pub format: Option<String>,
    /// Units where the file does not state them.
    #[serde(default)]
    pub units: Option<String>,
    /// Step (s) where the file does not give it.
    #[serde(default)]
    pub dt: Option<f64>,
    /// Axis of a one-component record.
    #[serde(default)]
    pub component: Option<String>,
    /// Axis of each component in reading order ("x", "y", "z").
    #[serde(default)]
    pub components: Option<Vec<String>>,
    /// Processing (defaults: see `motion::processing`).
    #[serde(default)]
    pub processing: Option<ProcessingOptions>,
    /// A synthetic motion instead of a file.
    #[serde(default)]
    pub synthetic: Option<SyntheticSpec>,
}

impl MotionSpec {
    /// Read or generate, then process, the motion `name`; `file` is the case file (for
    /// errors), `dir` resolves relative paths.
    pub fn load(&self, name: &str, file: &str, dir: &Path) -> Result<GroundMotion> {
        let field = format!("motions.{name}");
        let sources = [
            self.file.is_some(),
            self.files.is_some(),
            self.synthetic.is_some(),
        ]
        .iter()
        .filter(|&&b| b)
        .count();
        if sources != 1 {
            return Err(DcfmError::invalid(
                file,
                &field,
                format!("{sources} sources"),
                "exactly one of file, files, synthetic",
            ));
        }
        let (mut record, mut provenance) = if let Some(syn) = &self.synthetic {
            for (key, set) in [
                ("format", self.format.is_some()),
                ("units", self.units.is_some()),
                ("dt", self.dt.is_some()),
                ("component", self.component.is_some()),
                ("components", self.components.is_some()),
            ] {
                if set {
                    return Err(DcfmError::invalid(
                        file,
                        format!("{field}.{key}"),
                        "set",
                        "not used with synthetic (give the generator's own parameters)",
                    ));
                }
            }
            syn.parameters(file, &format!("{field}.synthetic"))?
                .generate()
        } else {
            let options = self.read_options(file, &field)?;
            let paths: Vec<&String> = match (&self.file, &self.files) {
                (Some(f), _) => vec![f],
                (None, Some(fs)) => fs.iter().collect(),
                _ => Vec::new(),
            };
            if paths.is_empty() {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.files"),
                    "[]",
                    "at least one file",
                ));
            }
            let mut records = Vec::with_capacity(paths.len());
            for p in paths {
                records.push(read_file(&dir.join(p), &options)?);
            }
            let mut record = Record::combine(records)?;
            self.assign_axes(&mut record, file, &field)?;
            (record, Vec::new())
        };
        check_distinct_axes(&record, file, &field)?;
        let options = self.processing.clone().unwrap_or_default();
        let mut motion = process(
            &record,
            name,
            &options,
            file,
            &format!("{field}.processing"),
        )?;
        record.components.clear();
        provenance.append(&mut motion.provenance);
        motion.provenance = provenance;
        Ok(motion)
    }

    /// Reader options from `format`, `units`, `dt`.
    pub fn read_options(&self, file: &str, field: &str) -> Result<ReadOptions> {
        let format = match &self.format {
            Some(f) => Format::parse(f).map_err(|e| {
                DcfmError::invalid(file, format!("{field}.format"), format!("\"{f}\""), e)
            })?,
            None => None,
        };
        let units = match &self.units {
            Some(u) => Some(AccelUnits::parse(u).ok_or_else(|| {
                DcfmError::invalid(
                    file,
                    format!("{field}.units"),
                    format!("\"{u}\""),
                    format!("one of {}", AccelUnits::NAMES),
                )
            })?),
            None => None,
        };
        if let Some(dt) = self.dt {
            if !(dt.is_finite() && dt > 0.0) {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.dt"),
                    dt,
                    "a step > 0 s",
                ));
            }
        }
        Ok(ReadOptions {
            format,
            units,
            dt: self.dt,
        })
    }

    /// Apply `component` / `components`.
    fn assign_axes(&self, record: &mut Record, file: &str, field: &str) -> Result<()> {
        let list: Vec<(String, String)> = match (&self.component, &self.components) {
            (Some(_), Some(_)) => {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.component"),
                    "set",
                    "either component or components, not both",
                ))
            }
            (Some(c), None) => vec![("component".to_string(), c.clone())],
            (None, Some(cs)) => cs
                .iter()
                .enumerate()
                .map(|(k, c)| (format!("components[{k}]"), c.clone()))
                .collect(),
            (None, None) => return Ok(()),
        };
        if list.len() != record.components.len() {
            return Err(DcfmError::invalid(
                file,
                format!(
                    "{field}.{}",
                    if self.component.is_some() {
                        "component"
                    } else {
                        "components"
                    }
                ),
                format!("{} axes", list.len()),
                format!(
                    "one axis per component of the record ({} read)",
                    record.components.len()
                ),
            ));
        }
        for ((key, axis), c) in list.iter().zip(record.components.iter_mut()) {
            c.axis = Some(Axis::parse(axis).ok_or_else(|| {
                DcfmError::invalid(
                    file,
                    format!("{field}.{key}"),
                    format!("\"{axis}\""),
                    "an axis: x, y or z",
                )
            })?);
        }
        Ok(())
    }
}

/// Two components may not drive the same axis.
fn check_distinct_axes(record: &Record, file: &str, field: &str) -> Result<()> {
    for (i, a) in record.components.iter().enumerate() {
        for b in &record.components[i + 1..] {
            if a.axis.is_some() && a.axis == b.axis {
                return Err(DcfmError::invalid(
                    file,
                    field,
                    format!(
                        "components \"{}\" and \"{}\" both on {}",
                        a.name,
                        b.name,
                        a.axis.map(|x| x.name()).unwrap_or("")
                    ),
                    "one component per axis (set components = [\"x\", \"y\", \"z\"])",
                ));
            }
        }
    }
    Ok(())
}
