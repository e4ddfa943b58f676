//! K-NET / KiK-net ASCII files (NIED, Japan): 17 header lines `Key  value`, then integer
//! counts, 8 per line.
//!
//! ```text
//! Station Code      AKT013
//! Sampling Freq(Hz) 100Hz
//! Dir.              E-W             (KiK-net: 1–3 borehole NS/EW/UD, 4–6 surface)
//! Scale Factor      3920(gal)/6182761
//! Max. Acc. (gal)   4.383
//! Memo.
//!   -18205   -17995   …
//! ```
//! acceleration = count × 3920/6182761 in the units in parentheses (gal). The counts carry
//! the recorder's offset; the header's `Max. Acc.` is the peak after removing the mean
//! (which the default processing does).

use crate::error::Result;

use super::lines::{line_error, parse_number, split_free, Lines};
use super::{positive_step, Format};
use crate::motion::record::{Axis, Record, RecordComponent};
use crate::motion::units::AccelUnits;

/// Read a K-NET / KiK-net ASCII file.
pub(super) fn read(text: &str, label: &str) -> Result<Record> {
    let mut lines = Lines::new(text, label);
    let mut station = String::new();
    let mut origin = String::new();
    let mut freq: Option<(usize, f64)> = None;
    let mut dir: Option<String> = None;
    let mut scale: Option<(f64, AccelUnits)> = None;
    let mut accmax: Option<f64> = None;
    loop {
        let (n, line) = lines.next("the K-NET header (up to the \"Memo.\" line)")?;
        let value = |key_len: usize| line.get(key_len..).unwrap_or("").trim().to_string();
        if line.starts_with("Memo.") {
            break;
        } else if line.starts_with("Origin Time") {
            origin = value(11);
        } else if line.starts_with("Station Code") {
            station = value(12);
        } else if line.starts_with("Sampling Freq(Hz)") {
            let v = value(17);
            let digits: String = v
                .chars()
                .take_while(|c| c.is_ascii_digit() || *c == '.')
                .collect();
            let f = parse_number(&digits).map_err(|_| {
                line_error(
                    label,
                    n,
                    format!("\"{v}\""),
                    "a sampling frequency such as \"100Hz\"",
                )
            })?;
            freq = Some((n, f));
        } else if line.starts_with("Dir.") {
            dir = Some(value(4));
        } else if line.starts_with("Scale Factor") {
            let v = value(12);
            scale = Some(scale_factor(&v).ok_or_else(|| {
                line_error(
                    label,
                    n,
                    format!("\"{v}\""),
                    "a scale factor such as \"3920(gal)/6182761\"",
                )
            })?);
        } else if line.starts_with("Max. Acc.") {
            let v = line.rsplit(')').next().unwrap_or("").trim().to_string();
            accmax = parse_number(&v).ok();
        } else if n == 1 && !line.starts_with("Origin Time") {
            return Err(line_error(
                label,
                n,
                format!("\"{}\"", line.trim()),
                "a K-NET header (\"Origin Time …\")",
            ));
        }
    }
    let (nf, f) = freq.ok_or_else(|| {
        line_error(
            label,
            lines.line_number(),
            "no \"Sampling Freq(Hz)\" line",
            "a sampling frequency in the header",
        )
    })?;
    let dt = positive_step(label, nf, 1.0 / f)?;
    let (factor, units) = scale.ok_or_else(|| {
        line_error(
            label,
            lines.line_number(),
            "no \"Scale Factor\" line",
            "a scale factor in the header",
        )
    })?;
    let mut counts = Vec::new();
    while !lines.at_end() {
        let (n, line) = lines.next("data")?;
        for t in split_free(line) {
            counts.push(parse_number(&t).map_err(|e| line_error(label, n, e, "an integer count"))?);
        }
    }
    let to_si = factor * units.to_si();
    let name = dir.unwrap_or_default();
    let kik = match name.trim() {
        "1" => Some("NS1"),
        "2" => Some("EW1"),
        "3" => Some("UD1"),
        "4" => Some("NS2"),
        "5" => Some("EW2"),
        "6" => Some("UD2"),
        _ => None,
    };
    let name = kik
        .map(str::to_string)
        .unwrap_or_else(|| name.replace('-', ""));
    Ok(Record {
        source: label.to_string(),
        format: Format::Knet,
        station,
        description: origin,
        units,
        dt,
        components: vec![RecordComponent {
            axis: Axis::guess(&name),
            name,
            acceleration: counts.into_iter().map(|c| c * to_si).collect(),
            header_peak: accmax.map(|a| a * AccelUnits::Gal.to_si()),
        }],
    })
}

/// `3920(gal)/6182761` → (3920/6182761, gal).
fn scale_factor(s: &str) -> Option<(f64, AccelUnits)> {
    let (num, rest) = s.split_once('(')?;
    let (unit, den) = rest.split_once(')')?;
    let den = den.trim().strip_prefix('/')?;
    let num = parse_number(num).ok()?;
    let den = parse_number(den).ok()?;
    let units = AccelUnits::parse(unit)?;
    (den != 0.0).then_some((num / den, units))
}
