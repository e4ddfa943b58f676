//! COSMOS V1/V2 files (COSMOS Strong Motion Data Format, ver. 1.20, COSMOS Strong Motion
//! Programs Board, 15 Aug 2001). A file holds one or more channel blocks:
//!
//! ```text
//! Corrected accelerogram   (Format v01.20 with 13 text lines) …   text header (line 1 gives its length)
//! … 12 more text lines (line 5: station code in columns 29–34; line 13: "no value" markers
//!   in columns 65–71 (integer) and 73–80 (real))
//!  100 Integer-header values follow on  10 lines, Format= (10I8)
//!  …                                                              #54: orientation (deg; 400 up, 500 down)
//!  100 Real-header values follow on  17 lines, Format= (6F13.6)
//!  …                                                              #62: sampling interval (ms)
//!    2 Comment line(s) follow, each starting with a "|":
//! | …
//!     2000 acceleration pts, approx   20 secs, units=cm/sec2(04), Format=(8F10.5)
//!  …samples…
//! End-of-data for Chan  1 acceleration
//! ```
//! A V2 block goes on with velocity and displacement series in the same layout; they are
//! skipped (the processing integrates the acceleration itself). Units codes (Table 2 of the
//! format): 02 g, 04 cm/s², 10 gal.

use crate::error::{DcfmError, Result};

use super::lines::{fortran_format, line_error, parse_number, split_fixed, Lines};
use super::{positive_step, sample_count, Format};
use crate::motion::record::{Axis, Record, RecordComponent};
use crate::motion::units::AccelUnits;

/// Read every channel block of a COSMOS V1/V2 file. `dt` is used where the real header
/// gives no sampling interval.
pub(super) fn read(text: &str, label: &str, dt_given: Option<f64>) -> Result<Record> {
    let mut lines = Lines::new(text, label);
    let mut components = Vec::new();
    let mut station = String::new();
    let mut description = String::new();
    let mut units_seen: Option<AccelUnits> = None;
    let mut dt_seen: Option<f64> = None;
    while lines.peek().is_some_and(|l| !l.trim().is_empty()) {
        let block = read_block(&mut lines, label, dt_given)?;
        if let Some(dt) = dt_seen {
            if (block.dt - dt).abs() > 1e-9 * dt {
                return Err(line_error(
                    label,
                    block.first_line,
                    block.dt,
                    &format!("the same sampling interval in every channel ({dt} s)"),
                ));
            }
        }
        dt_seen = Some(block.dt);
        units_seen.get_or_insert(block.units);
        if station.is_empty() {
            station = block.station;
            description = block.description;
        }
        components.push(block.component);
        while lines.peek().is_some_and(|l| l.trim().is_empty()) {
            lines.next("")?;
        }
    }
    let (Some(dt), Some(units)) = (dt_seen, units_seen) else {
        return Err(line_error(
            label,
            1,
            "no channel block",
            "a COSMOS header (\"… (Format v01.20 with 13 text lines)\")",
        ));
    };
    Ok(Record {
        source: label.to_string(),
        format: Format::Cosmos,
        station,
        description,
        units,
        dt,
        components,
    })
}

struct Block {
    first_line: usize,
    dt: f64,
    units: AccelUnits,
    station: String,
    description: String,
    component: RecordComponent,
}

fn read_block(lines: &mut Lines, label: &str, dt_given: Option<f64>) -> Result<Block> {
    let (n1, first) = lines.next("a COSMOS text header")?;
    let lower = first.to_ascii_lowercase();
    let Some(pos) = lower.find("(format v") else {
        return Err(line_error(
            label,
            n1,
            format!("\"{}\"", first.trim()),
            "a COSMOS header line \"… (Format v01.20 with 13 text lines)\"",
        ));
    };
    let n_text = lower[pos..]
        .split("with")
        .nth(1)
        .and_then(|s| s.split_whitespace().next())
        .and_then(|s| s.parse::<usize>().ok())
        .unwrap_or(13);
    if !(1..=1000).contains(&n_text) {
        return Err(line_error(
            label,
            n1,
            n_text,
            "a text header of 1 to 1000 lines",
        ));
    }
    let mut text = vec![first];
    for k in 1..n_text {
        text.push(
            lines
                .next(&format!("text header line {} of {n_text}", k + 1))?
                .1,
        );
    }
    let no_value_int = text
        .get(12)
        .and_then(|l| l.get(64..71))
        .and_then(|s| s.trim().parse::<i64>().ok())
        .unwrap_or(-999);
    let no_value_real = text
        .get(12)
        .and_then(|l| l.get(72..80))
        .and_then(|s| parse_number(s).ok())
        .unwrap_or(-999.0);
    let ints = header_block(lines, label, "Integer-header")?;
    let reals = header_block(lines, label, "Real-header")?;
    let (nc, comment_line) = lines.next("the \"Comment line(s) follow\" line")?;
    if !comment_line.to_ascii_lowercase().contains("comment") {
        return Err(line_error(
            label,
            nc,
            format!("\"{}\"", comment_line.trim()),
            "\"N Comment line(s) follow, …\"",
        ));
    }
    let n_comments = comment_line
        .split_whitespace()
        .next()
        .and_then(|s| s.parse::<usize>().ok())
        .ok_or_else(|| {
            line_error(
                label,
                nc,
                format!("\"{}\"", comment_line.trim()),
                "a number of comment lines",
            )
        })?;
    for k in 0..n_comments {
        lines.next(&format!("comment line {} of {n_comments}", k + 1))?;
    }
    // The sampling interval, real header #62 in ms.
    let dt = match reals.get(61) {
        Some(&(n, v)) if v > 0.0 && v != no_value_real => positive_step(label, n, v / 1000.0)?,
        _ => dt_given.ok_or_else(|| {
            DcfmError::invalid(
                label,
                "dt",
                "none",
                "a sampling step: real header #62 (ms) has no value; give dt",
            )
        })?,
    };
    let orientation = ints
        .get(53)
        .map(|&(_, v)| v as i64)
        .filter(|&v| v != no_value_int);
    let (component, axis) = match orientation {
        Some(400) => ("Up".to_string(), Some(Axis::Z)),
        Some(500) => ("Down".to_string(), Some(Axis::Z)),
        Some(a) => (format!("{a:03}"), Axis::guess(&format!("{a}"))),
        None => ("channel".to_string(), None),
    };
    let mut acceleration: Option<(Vec<f64>, AccelUnits)> = None;
    // Series of the block: acceleration, then (V2) velocity and displacement.
    while let Some(next) = lines.peek() {
        let lower = next.to_ascii_lowercase();
        if lower.contains("(format v") || next.trim().is_empty() {
            break;
        }
        let (nd, data_line) = lines.next("a data header")?;
        if lower.starts_with("end-of-data") {
            continue;
        }
        if !lower.contains("pts") {
            return Err(line_error(
                label,
                nd,
                format!("\"{}\"", data_line.trim()),
                "a data header \"N acceleration pts, approx S secs, units=cm/sec2(04), Format=(8F10.5)\"",
            ));
        }
        let mut toks = data_line.split_whitespace();
        let npts = sample_count(label, nd, toks.next().unwrap_or(""))?;
        let quantity = toks.next().unwrap_or("").to_ascii_lowercase();
        let fmt = lower
            .split("format=")
            .nth(1)
            .and_then(fortran_format)
            .ok_or_else(|| {
                line_error(
                    label,
                    nd,
                    format!("\"{}\"", data_line.trim()),
                    "a data format such as Format=(8F10.5)",
                )
            })?;
        let values = lines.read_values(npts, &quantity, &|l| split_fixed(l, fmt.1))?;
        if quantity.starts_with("accel") && acceleration.is_none() {
            let units = data_units(&lower).ok_or_else(|| {
                line_error(
                    label,
                    nd,
                    format!("\"{}\"", data_line.trim()),
                    &format!(
                        "units=… among cm/sec2(04), g(02), gal(10), m/sec2 ({})",
                        AccelUnits::NAMES
                    ),
                )
            })?;
            acceleration = Some((values, units));
        }
    }
    let Some((values, units)) = acceleration else {
        return Err(line_error(
            label,
            lines.line_number(),
            "no acceleration series",
            "an \"N acceleration pts …\" series in the block",
        ));
    };
    let factor = units.to_si();
    Ok(Block {
        first_line: n1,
        dt,
        units,
        station: text
            .get(4)
            .and_then(|l| l.get(28..34))
            .unwrap_or("")
            .trim()
            .to_string(),
        description: text
            .get(1)
            .map(|l| l.trim().to_string())
            .unwrap_or_default(),
        component: RecordComponent {
            name: component,
            axis,
            acceleration: values.into_iter().map(|v| v * factor).collect(),
            header_peak: None,
        },
    })
}

/// `N <kind>-header values follow on L lines, Format= (10I8)` and its values.
fn header_block(lines: &mut Lines, label: &str, kind: &str) -> Result<Vec<(usize, f64)>> {
    let (n, line) = lines.next(&format!("the \"{kind} values follow\" line"))?;
    let expected = format!("\"N {kind} values follow on L lines, Format= (…)\"");
    if !line
        .to_ascii_lowercase()
        .contains(&kind.to_ascii_lowercase())
    {
        return Err(line_error(
            label,
            n,
            format!("\"{}\"", line.trim()),
            &expected,
        ));
    }
    let count = line
        .split_whitespace()
        .next()
        .and_then(|s| s.parse::<usize>().ok())
        .filter(|&c| c <= 100_000)
        .ok_or_else(|| line_error(label, n, format!("\"{}\"", line.trim()), &expected))?;
    let (_, width) = line
        .split_once("=")
        .and_then(|(_, f)| fortran_format(f))
        .ok_or_else(|| line_error(label, n, format!("\"{}\"", line.trim()), &expected))?;
    let mut out = Vec::with_capacity(count);
    while out.len() < count {
        let (nl, l) = lines.next(&format!("{} more {kind} values", count - out.len()))?;
        for f in split_fixed(l, width) {
            let v = parse_number(&f)
                .map_err(|e| line_error(label, nl, e, &format!("a {kind} value")))?;
            out.push((nl, v));
        }
    }
    if out.len() != count {
        return Err(line_error(
            label,
            out.last().map(|x| x.0).unwrap_or(n),
            format!("{} values", out.len()),
            &format!("{count} {kind} values"),
        ));
    }
    Ok(out)
}

/// The acceleration units of a data header (`units=cm/sec2(04)`).
fn data_units(lower: &str) -> Option<AccelUnits> {
    let after = lower.split("units=").nth(1)?;
    let (name, rest) = after
        .split_once('(')
        .unwrap_or((after.split(',').next()?, ""));
    let code = rest
        .split(')')
        .next()
        .and_then(|c| c.trim().parse::<u32>().ok());
    match code {
        Some(2) => Some(AccelUnits::G),
        Some(4) | Some(10) => Some(AccelUnits::Gal),
        _ => AccelUnits::parse(name.trim()),
    }
}
