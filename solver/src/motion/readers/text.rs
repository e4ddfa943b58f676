//! Column text and CSV: one value per line, `time value` pairs, or several components in
//! columns (`t, EW, NS, UD`).
//!
//! Rules, in order:
//! - lines starting with `#`, `%` or `//` are comments; a comment `# dt = 0.01` or
//!   `# units = g` states the step or the units (as the case file could);
//! - a first non-comment line that is not all numbers is a header row naming the columns;
//!   a column named `t`, `time` or `time (s)` is the time column;
//! - without a header time column: given a dt, every column is a component; without one,
//!   a file of two or more columns has time in its first column;
//! - a time column must be uniform (|tᵢ − t₀ − i·dt| ≤ 10⁻⁴ dt), its step is the record's;
//! - every data row has the same number of fields.

use crate::error::{DcfmError, Result};

use super::lines::{line_error, parse_number};
use super::{Format, ReadOptions};
use crate::motion::record::{Axis, Record, RecordComponent};
use crate::motion::units::AccelUnits;

/// Read a column text (`csv = false`) or CSV file.
pub(super) fn read(text: &str, label: &str, options: &ReadOptions, csv: bool) -> Result<Record> {
    let mut comment_dt: Option<(usize, f64)> = None;
    let mut comment_units: Option<AccelUnits> = None;
    let mut header: Option<Vec<String>> = None;
    let mut rows: Vec<(usize, Vec<f64>)> = Vec::new();
    let split = |line: &str| -> Vec<String> {
        let fields: Vec<&str> = if csv || line.contains(',') || line.contains(';') {
            line.split([',', ';']).collect()
        } else {
            line.split_whitespace().collect()
        };
        fields.iter().map(|f| f.trim().to_string()).collect()
    };
    let mut fields_buf: Vec<&str> = Vec::new();
    for (i, raw) in text.lines().enumerate() {
        let n = i + 1;
        let line = raw.trim();
        if line.is_empty() {
            continue;
        }
        if let Some(c) = line
            .strip_prefix('#')
            .or_else(|| line.strip_prefix('%'))
            .or_else(|| line.strip_prefix("//"))
        {
            if let Some((key, value)) = c.split_once(['=', ':']) {
                match key.trim().to_ascii_lowercase().as_str() {
                    "dt" => {
                        let v = parse_number(value.trim().trim_end_matches('s').trim())
                            .map_err(|e| line_error(label, n, e, "a sampling step in s"))?;
                        comment_dt = Some((n, v));
                    }
                    "units" => {
                        comment_units = Some(AccelUnits::parse(value).ok_or_else(|| {
                            line_error(
                                label,
                                n,
                                value.trim(),
                                &format!("units among {}", AccelUnits::NAMES),
                            )
                        })?);
                    }
                    _ => {}
                }
            }
            continue;
        }
        let looks_numeric = |f: &String| {
            f.starts_with(|c: char| c.is_ascii_digit() || c == '-' || c == '+' || c == '.')
        };
        if rows.is_empty() && header.is_none() {
            let fields = split(line);
            if fields
                .iter()
                .all(|f| parse_number(f).is_err() && !looks_numeric(f))
            {
                // A header row: names only (a mistyped number is an error, not a name).
                header = Some(fields);
                continue;
            }
        }
        fields_buf.clear();
        if csv || line.contains([',', ';']) {
            fields_buf.extend(line.split([',', ';']).map(str::trim));
        } else {
            fields_buf.extend(line.split_whitespace());
        }
        let mut values = Vec::with_capacity(fields_buf.len());
        for f in &fields_buf {
            values.push(parse_number(f).map_err(|e| line_error(label, n, e, "a finite number"))?);
        }
        if let Some((_, first)) = rows.first() {
            if first.len() != values.len() {
                return Err(line_error(
                    label,
                    n,
                    format!("{} fields", values.len()),
                    &format!("{} fields like the first data row", first.len()),
                ));
            }
        }
        rows.push((n, values));
    }
    let Some((_, first)) = rows.first() else {
        return Err(DcfmError::invalid(
            label,
            "data",
            "no data rows",
            "at least 2 rows of numbers",
        ));
    };
    let ncol = first.len();
    if let Some(h) = &header {
        if h.len() != ncol {
            return Err(DcfmError::invalid(
                label,
                "header row",
                format!("{} names", h.len()),
                format!("one name per column ({ncol} columns)"),
            ));
        }
    }
    let is_time_name = |s: &str| {
        let s = s.trim().to_ascii_lowercase();
        s == "t"
            || s == "time"
            || s.starts_with("time ")
            || s.starts_with("time(")
            || s.starts_with("t (")
            || s.starts_with("t[")
    };
    let header_time = header
        .as_ref()
        .and_then(|h| h.iter().position(|s| is_time_name(s)));
    let given_dt = options.dt.or(comment_dt.map(|c| c.1));
    let time_col = match (header_time, given_dt) {
        (Some(c), _) => Some(c),
        (None, Some(_)) => None,
        (None, None) if ncol >= 2 => Some(0),
        (None, None) => {
            return Err(DcfmError::invalid(
                label,
                "dt",
                "none",
                "a sampling step: a one-column file needs dt (case: dt = …, CLI: --dt, or a `# dt = …` line)",
            ))
        }
    };
    let dt = match time_col {
        Some(c) => {
            if rows.len() < 2 {
                return Err(DcfmError::invalid(
                    label,
                    "data",
                    "1 row",
                    "at least 2 rows of numbers",
                ));
            }
            let t0 = rows[0].1[c];
            let step = rows[1].1[c] - t0;
            if !(step.is_finite() && step > 0.0) {
                return Err(line_error(
                    label,
                    rows[1].0,
                    rows[1].1[c],
                    "times that increase",
                ));
            }
            for (k, (n, r)) in rows.iter().enumerate() {
                let expected = t0 + k as f64 * step;
                if (r[c] - expected).abs() > 1e-4 * step {
                    return Err(line_error(
                        label,
                        *n,
                        r[c],
                        &format!("uniform sampling: t = {expected} (dt = {step} from the first two rows)"),
                    ));
                }
            }
            if let Some(dt) = given_dt {
                if (dt - step).abs() > 1e-6 * step {
                    return Err(DcfmError::invalid(
                        label,
                        "dt",
                        dt,
                        format!("the time column's step ({step} s), or leave dt unset"),
                    ));
                }
            }
            step
        }
        None => given_dt.unwrap_or(f64::NAN),
    };
    let units = match (options.units, comment_units) {
        (Some(a), Some(b)) if a != b => {
            return Err(DcfmError::invalid(
                label,
                "units",
                a,
                format!("the file's own `# units` ({b}), or leave units unset"),
            ))
        }
        (Some(a), _) => a,
        (None, Some(b)) => b,
        (None, None) => {
            return Err(DcfmError::invalid(
                label,
                "units",
                "none",
                format!(
                    "units for this {} file, which does not state them: one of {} (case: units = …, CLI: --units)",
                    if csv { "CSV" } else { "text" },
                    AccelUnits::NAMES
                ),
            ))
        }
    };
    let factor = units.to_si();
    let mut components = Vec::new();
    let data_cols: Vec<usize> = (0..ncol).filter(|&c| Some(c) != time_col).collect();
    if data_cols.is_empty() {
        return Err(DcfmError::invalid(
            label,
            "columns",
            ncol,
            "a column of accelerations besides time",
        ));
    }
    let default_names = ["x", "y", "z"];
    for (k, &c) in data_cols.iter().enumerate() {
        let name = match &header {
            Some(h) => h[c].clone(),
            None if data_cols.len() == 1 => "a".to_string(),
            None if data_cols.len() <= 3 => default_names[k].to_string(),
            None => format!("column {}", c + 1),
        };
        let axis = Axis::guess(&name);
        components.push(RecordComponent {
            axis,
            name,
            acceleration: rows.iter().map(|(_, r)| r[c] * factor).collect(),
            header_peak: None,
        });
    }
    Ok(Record {
        source: label.to_string(),
        format: if csv { Format::Csv } else { Format::Text },
        station: String::new(),
        description: String::new(),
        units,
        dt,
        components,
    })
}
