//! PEER NGA `.AT2` acceleration files (PEER Ground Motion Database, "NGA" flat files).
//!
//! Four header lines, then the samples, several per line:
//! ```text
//! PEER NGA STRONG MOTION DATABASE RECORD
//! KOBE 01/16/95 2046, NISHI-AKASHI, 090 (CUE)          event, date, station, component
//! ACCELERATION TIME HISTORY IN UNITS OF G
//! 4096    0.0100    NPTS, DT                           old header
//! NPTS=  6000, DT=   .0050 SEC                         new header (NGA-West2)
//! ```

use crate::error::Result;

use super::lines::{line_error, parse_number, split_free, Lines};
use super::{positive_step, sample_count, Format};
use crate::motion::record::{Axis, Record, RecordComponent};
use crate::motion::units::AccelUnits;

/// Read an AT2 file.
pub(super) fn read(text: &str, label: &str) -> Result<Record> {
    let mut lines = Lines::new(text, label);
    lines.next("the title line of a PEER AT2 header")?;
    let (_, description) = lines.next("the event/station/component line of a PEER AT2 header")?;
    let (n3, kind) = lines.next("the line \"ACCELERATION TIME SERIES IN UNITS OF …\"")?;
    let upper = kind.to_ascii_uppercase();
    if !upper.contains("ACCELERATION") {
        return Err(line_error(
            label,
            n3,
            format!("\"{}\"", kind.trim()),
            "an acceleration record (\"ACCELERATION … IN UNITS OF G\")",
        ));
    }
    let units_name = upper
        .split("UNITS OF")
        .nth(1)
        .map(|s| s.trim().to_string())
        .unwrap_or_default();
    let units = AccelUnits::parse(&units_name).ok_or_else(|| {
        line_error(
            label,
            n3,
            format!("\"{}\"", kind.trim()),
            &format!(
                "\"… IN UNITS OF <units>\" with units among {}",
                AccelUnits::NAMES
            ),
        )
    })?;
    let (n4, counts) = lines.next("the NPTS, DT line of a PEER AT2 header")?;
    let (npts, dt) = npts_dt(counts, label, n4)?;
    let factor = units.to_si();
    let values = lines.read_values(npts, "acceleration", &split_free)?;
    lines.expect_no_more_values(npts, &|_| false)?;
    // "EVENT DATE, STATION, COMPONENT" — the last two comma-separated fields.
    let parts: Vec<&str> = description.split(',').map(str::trim).collect();
    let component = parts
        .last()
        .and_then(|c| c.split_whitespace().next())
        .unwrap_or("")
        .to_string();
    let station = if parts.len() >= 2 {
        parts[parts.len() - 2].to_string()
    } else {
        String::new()
    };
    Ok(Record {
        source: label.to_string(),
        format: Format::PeerAt2,
        station,
        description: description.trim().to_string(),
        units,
        dt,
        components: vec![RecordComponent {
            axis: Axis::guess(&component),
            name: component,
            acceleration: values.into_iter().map(|v| v * factor).collect(),
            header_peak: None,
        }],
    })
}

/// npts and dt from `4096 0.0100 NPTS, DT` or `NPTS= 6000, DT= .0050 SEC`.
fn npts_dt(line: &str, label: &str, n: usize) -> Result<(usize, f64)> {
    let upper = line.to_ascii_uppercase();
    let expected = "\"NPTS, DT\" values (\"4096 0.01 NPTS, DT\" or \"NPTS= 4096, DT= 0.01 SEC\")";
    let (npts_token, dt_token) =
        if let (Some(a), Some(b)) = (upper.find("NPTS="), upper.find("DT=")) {
            let after = |i: usize| -> String {
                upper[i..]
                    .split(|c: char| c == ',' || c.is_whitespace())
                    .find(|s| !s.is_empty())
                    .unwrap_or("")
                    .to_string()
            };
            (after(a + 5), after(b + 3))
        } else {
            let toks: Vec<&str> = upper
                .split([' ', ',', '\t'])
                .filter(|s| !s.is_empty())
                .collect();
            if toks.len() < 2 {
                return Err(line_error(
                    label,
                    n,
                    format!("\"{}\"", line.trim()),
                    expected,
                ));
            }
            (toks[0].to_string(), toks[1].to_string())
        };
    let npts = sample_count(label, n, &npts_token)
        .map_err(|_| line_error(label, n, format!("\"{}\"", line.trim()), expected))?;
    let dt =
        parse_number(&dt_token).map_err(|e| line_error(label, n, e, "DT, a sampling step in s"))?;
    Ok((npts, positive_step(label, n, dt)?))
}
