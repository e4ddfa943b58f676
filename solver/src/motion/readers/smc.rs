//! USGS SMC ("strong-motion CD") files, as the USGS National Strong-Motion Project
//! distributes them (format description: USGS NSMP, "SMC format", smcfmt).
//!
//! 11 text lines (line 1: data type, `2 CORRECTED ACCELEROGRAM`; line 6: `station = …
//! component= 360`; line 7: `pk acc = 3.91E+1`), 48 integers in `(8I10)` (#16 the number
//! of comment lines, #17 the number of samples; −32768 = no value), 50 reals in `(5E15.7)`
//! (#2 the sampling rate in samples/s; 1.7E+38 = no value), the comment lines (`|`), then
//! the samples in `(8E10.4)` — fixed fields that run into each other. Accelerations are in
//! cm/s².

use crate::error::Result;

use super::lines::{line_error, parse_number, split_fixed, Lines};
use super::{positive_step, sample_count, Format};
use crate::motion::record::{Axis, Record, RecordComponent};
use crate::motion::units::AccelUnits;

/// Read an SMC file.
pub(super) fn read(text: &str, label: &str) -> Result<Record> {
    let mut lines = Lines::new(text, label);
    let mut header = Vec::with_capacity(11);
    for k in 0..11 {
        header.push(lines.next(&format!("text header line {} of 11 of an SMC file", k + 1))?);
    }
    let (n1, kind) = header[0];
    let code = kind.trim_start().chars().next();
    if !(matches!(code, Some('1') | Some('2'))
        && kind.to_ascii_uppercase().contains("ACCELEROGRAM"))
    {
        return Err(line_error(
            label,
            n1,
            format!("\"{}\"", kind.trim()),
            "an SMC accelerogram (\"1 UNCORRECTED ACCELEROGRAM\" or \"2 CORRECTED ACCELEROGRAM\")",
        ));
    }
    let ints = fixed_block(&mut lines, label, 6, 8, 10, "integer header (8I10)")?;
    let reals = fixed_block(&mut lines, label, 10, 5, 15, "real header (5E15.7)")?;
    let (nc_line, nc_tok) = &ints[15];
    let n_comments = sample_count(label, *nc_line, nc_tok).or_else(|e| {
        if nc_tok.trim() == "0" {
            Ok(0)
        } else {
            Err(e)
        }
    })?;
    let (np_line, np_tok) = &ints[16];
    let npts = sample_count(label, *np_line, np_tok)?;
    let (sr_line, sr_tok) = &reals[1];
    let rate = parse_number(sr_tok)
        .map_err(|e| line_error(label, *sr_line, e, "the sampling rate (samples/s)"))?;
    if !(rate > 0.0 && rate < 1e30) {
        return Err(line_error(
            label,
            *sr_line,
            rate,
            "a sampling rate > 0 (real header #2)",
        ));
    }
    let dt = positive_step(label, *sr_line, 1.0 / rate)?;
    for k in 0..n_comments {
        lines.next(&format!("comment line {} of {n_comments}", k + 1))?;
    }
    let values = lines.read_values(npts, "acceleration", &|l| split_fixed(l, 10))?;
    lines.expect_no_more_values(npts, &|_| false)?;
    let station_line = header[5].1;
    let (station, component) = match station_line.split_once("component=") {
        Some((s, c)) => (
            s.trim().trim_start_matches("station =").trim().to_string(),
            c.trim().to_string(),
        ),
        None => (station_line.trim().to_string(), String::new()),
    };
    let peak = header[6]
        .1
        .split("pk acc =")
        .nth(1)
        .and_then(|s| parse_number(s.split_whitespace().next().unwrap_or("")).ok())
        .map(|p| p * AccelUnits::Gal.to_si());
    let factor = AccelUnits::Gal.to_si();
    Ok(Record {
        source: label.to_string(),
        format: Format::Smc,
        station,
        description: header[3].1.trim().to_string(),
        units: AccelUnits::Gal,
        dt,
        components: vec![RecordComponent {
            axis: Axis::guess(&component),
            name: component,
            acceleration: values.into_iter().map(|v| v * factor).collect(),
            header_peak: peak,
        }],
    })
}

/// `count` fields of `width` characters on each of `n_lines` lines, with their line numbers.
fn fixed_block(
    lines: &mut Lines,
    label: &str,
    n_lines: usize,
    count: usize,
    width: usize,
    what: &str,
) -> Result<Vec<(usize, String)>> {
    let mut out = Vec::with_capacity(n_lines * count);
    for k in 0..n_lines {
        let (n, line) = lines.next(&format!("line {} of {n_lines} of the {what}", k + 1))?;
        let fields = split_fixed(line, width);
        if fields.len() != count {
            return Err(line_error(
                label,
                n,
                format!("{} fields", fields.len()),
                &format!("{count} fields of {width} characters ({what})"),
            ));
        }
        out.extend(fields.into_iter().map(|f| (n, f)));
    }
    Ok(out)
}
