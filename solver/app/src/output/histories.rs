//! CSV time histories (`histories.csv`): one header line of column names, then one row of
//! numbers per recorded step, each written as `{:.9e}` (ten significant digits, exponent
//! form; `NaN` and `inf` as Rust prints them).
//!
//! Rows are buffered and flushed every [`HistoryWriter::with_flush_every`] rows (default
//! [`DEFAULT_FLUSH_EVERY`]), on [`HistoryWriter::finish`] (which also syncs to disk) and,
//! best effort, on drop. A row is handed to the buffer whole, so the file holds whole rows
//! except if the process dies inside a write; [`HistoryWriter::open_append`] repairs such a
//! torn last line when a run is resumed.

use std::fs::{File, OpenOptions};
use std::io::{BufWriter, Read, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use super::label;
use dcfm::error::{DcfmError, Result};

/// Rows between flushes unless [`HistoryWriter::with_flush_every`] says otherwise.
pub const DEFAULT_FLUSH_EVERY: usize = 100;

/// A CSV history file being written.
#[derive(Debug)]
pub struct HistoryWriter {
    path: PathBuf,
    out: Option<BufWriter<File>>,
    columns: usize,
    flush_every: usize,
    unflushed: usize,
    line: String,
}

/// The header line (without newline); names with a comma, quote or newline are quoted.
fn header_line(header: &[String]) -> String {
    header
        .iter()
        .map(|h| {
            if h.contains([',', '"', '\n', '\r']) {
                format!("\"{}\"", h.replace('"', "\"\""))
            } else {
                h.clone()
            }
        })
        .collect::<Vec<_>>()
        .join(",")
}

impl HistoryWriter {
    /// Create (or truncate) `path` and write the header.
    pub fn create(path: &Path, header: &[String]) -> Result<Self> {
        let io = |e| DcfmError::io(label(path), e);
        Self::check_header(path, header)?;
        let file = File::create(path).map_err(io)?;
        let mut w = Self::new(path, file, header.len());
        let out = w.out.as_mut().expect("open");
        writeln!(out, "{}", header_line(header)).map_err(io)?;
        out.flush().map_err(io)?;
        Ok(w)
    }

    /// Open `path` to append rows (a resumed run). A missing or empty file is created with
    /// the header; an existing file must have exactly this header; a torn last line (the
    /// previous run died inside a write) is cut off.
    pub fn open_append(path: &Path, header: &[String]) -> Result<Self> {
        Self::open_resume(path, header, None)
    }

    /// Like [`HistoryWriter::open_append`], and also drops the rows whose first column (the
    /// time) is greater than `time` (beyond the 1e-9 relative precision of the written
    /// times): a run restarted from a checkpoint at `time` writes them again.
    pub fn open_append_after(path: &Path, header: &[String], time: f64) -> Result<Self> {
        Self::open_resume(path, header, Some(time))
    }

    fn open_resume(path: &Path, header: &[String], time: Option<f64>) -> Result<Self> {
        let io = |e| DcfmError::io(label(path), e);
        Self::check_header(path, header)?;
        if !path.exists() {
            return Self::create(path, header);
        }
        let mut file = OpenOptions::new()
            .read(true)
            .write(true)
            .open(path)
            .map_err(io)?;
        let mut text = String::new();
        file.read_to_string(&mut text).map_err(io)?;
        if text.is_empty() {
            drop(file);
            return Self::create(path, header);
        }
        let expected = header_line(header);
        let first = text.lines().next().unwrap_or("");
        if first != expected {
            return Err(DcfmError::invalid(
                label(path),
                "header",
                first,
                format!("the header of this run, {expected}"),
            ));
        }
        // Keep whole lines only, and (if asked) only rows up to `time`.
        let mut keep = 0usize;
        for (i, line) in text.split_inclusive('\n').enumerate() {
            if !line.ends_with('\n') {
                break;
            }
            if i > 0 {
                if let Some(t) = time {
                    let first: f64 = line
                        .split(',')
                        .next()
                        .and_then(|s| s.trim().parse().ok())
                        .ok_or_else(|| DcfmError::Parse {
                            file: label(path),
                            message: format!("line {}: first column is not a time", i + 1),
                        })?;
                    // Times are written with ten significant digits: a row printed at the
                    // restart time itself may read back up to half a unit in the last
                    // place above it, and must be kept.
                    if first > t + 1e-9 * t.abs() {
                        break;
                    }
                }
            }
            keep += line.len();
        }
        if keep == 0 {
            // Only a torn header line: start over.
            drop(file);
            return Self::create(path, header);
        }
        file.set_len(keep as u64).map_err(io)?;
        file.seek(SeekFrom::End(0)).map_err(io)?;
        Ok(Self::new(path, file, header.len()))
    }

    fn check_header(path: &Path, header: &[String]) -> Result<()> {
        if header.is_empty() {
            return Err(DcfmError::invalid(
                label(path),
                "header",
                "[]",
                "at least one column",
            ));
        }
        Ok(())
    }

    fn new(path: &Path, file: File, columns: usize) -> Self {
        Self {
            path: path.to_path_buf(),
            out: Some(BufWriter::with_capacity(1 << 16, file)),
            columns,
            flush_every: DEFAULT_FLUSH_EVERY,
            unflushed: 0,
            line: String::new(),
        }
    }

    /// Flush every `rows` rows (at least 1).
    pub fn with_flush_every(mut self, rows: usize) -> Self {
        self.flush_every = rows.max(1);
        self
    }

    /// Number of columns (the header's length).
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// The file being written.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Append one row; it must have one value per column.
    pub fn append(&mut self, row: &[f64]) -> Result<()> {
        use std::fmt::Write as _;
        if row.len() != self.columns {
            return Err(DcfmError::invalid(
                label(&self.path),
                "row",
                format!("{} values", row.len()),
                format!("{} values, one per column", self.columns),
            ));
        }
        self.line.clear();
        for (i, v) in row.iter().enumerate() {
            if i > 0 {
                self.line.push(',');
            }
            let _ = write!(self.line, "{v:.9e}");
        }
        self.line.push('\n');
        let io = |e| DcfmError::io(label(&self.path), e);
        let out = self
            .out
            .as_mut()
            .expect("a HistoryWriter is open until finish");
        out.write_all(self.line.as_bytes()).map_err(io)?;
        self.unflushed += 1;
        if self.unflushed >= self.flush_every {
            self.flush()?;
        }
        Ok(())
    }

    /// Write the buffered rows to the file.
    pub fn flush(&mut self) -> Result<()> {
        if let Some(out) = self.out.as_mut() {
            out.flush()
                .map_err(|e| DcfmError::io(label(&self.path), e))?;
        }
        self.unflushed = 0;
        Ok(())
    }

    /// Flush, sync to disk and close.
    pub fn finish(mut self) -> Result<()> {
        let io = |e| DcfmError::io(label(&self.path), e);
        if let Some(out) = self.out.take() {
            let file = out.into_inner().map_err(|e| io(e.into_error()))?;
            file.sync_all().map_err(io)?;
        }
        Ok(())
    }
}

impl Drop for HistoryWriter {
    fn drop(&mut self) {
        if let Some(out) = self.out.as_mut() {
            let _ = out.flush();
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::output::test_dir;

    fn header() -> Vec<String> {
        ["time", "u_x crest", "energy, kinetic"]
            .map(String::from)
            .to_vec()
    }

    fn rows(path: &Path) -> Vec<Vec<f64>> {
        std::fs::read_to_string(path)
            .unwrap()
            .lines()
            .skip(1)
            .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
            .collect()
    }

    #[test]
    fn header_rows_and_precision() {
        let dir = test_dir("hist");
        let path = dir.join("histories.csv");
        let mut h = HistoryWriter::create(&path, &header()).unwrap();
        h.append(&[0.0, -1.234567890123e-5, 1.0 / 3.0]).unwrap();
        h.append(&[1e-3, f64::NAN, 6.02e23]).unwrap();
        h.finish().unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        let mut lines = text.lines();
        assert_eq!(lines.next().unwrap(), "time,u_x crest,\"energy, kinetic\"");
        assert_eq!(
            lines.next().unwrap(),
            "0.000000000e0,-1.234567890e-5,3.333333333e-1"
        );
        let r = rows(&path);
        assert_eq!(r.len(), 2);
        assert!(r[1][1].is_nan());
        assert_eq!(r[1][2], 6.02e23);
        assert!((r[0][2] - 1.0 / 3.0).abs() < 1e-10);
    }

    #[test]
    fn buffered_until_flush_every_and_flushed_on_drop() {
        let dir = test_dir("hist-flush");
        let path = dir.join("h.csv");
        let mut h = HistoryWriter::create(&path, &header())
            .unwrap()
            .with_flush_every(3);
        h.append(&[0.0, 0.0, 0.0]).unwrap();
        h.append(&[1.0, 0.0, 0.0]).unwrap();
        assert_eq!(rows(&path).len(), 0, "two rows are still buffered");
        h.append(&[2.0, 0.0, 0.0]).unwrap();
        assert_eq!(rows(&path).len(), 3, "the third row flushes");
        h.append(&[3.0, 0.0, 0.0]).unwrap();
        drop(h);
        assert_eq!(rows(&path).len(), 4, "drop flushes");
    }

    #[test]
    fn wrong_row_length_is_an_error() {
        let dir = test_dir("hist-len");
        let path = dir.join("h.csv");
        let mut h = HistoryWriter::create(&path, &header()).unwrap();
        let msg = h.append(&[1.0]).unwrap_err().to_string();
        assert!(msg.contains("h.csv") && msg.contains("3 values"), "{msg}");
        assert!(HistoryWriter::create(&path, &[]).is_err());
    }

    #[test]
    fn open_append_resumes_repairs_and_checks_header() {
        let dir = test_dir("hist-append");
        let path = dir.join("h.csv");
        // Missing file: created with the header.
        let mut h = HistoryWriter::open_append(&path, &header()).unwrap();
        for t in 0..4 {
            h.append(&[t as f64, 1.0, 2.0]).unwrap();
        }
        h.finish().unwrap();
        // A torn last line, as after a crash inside a write.
        let mut f = OpenOptions::new().append(true).open(&path).unwrap();
        f.write_all(b"4.000000000e0,1.0").unwrap();
        drop(f);
        let mut h = HistoryWriter::open_append(&path, &header()).unwrap();
        h.append(&[4.0, 5.0, 6.0]).unwrap();
        h.finish().unwrap();
        let r = rows(&path);
        assert_eq!(r.len(), 5);
        assert_eq!(r[4], vec![4.0, 5.0, 6.0]);
        // Restart from a checkpoint at t = 2: rows after it go.
        let mut h = HistoryWriter::open_append_after(&path, &header(), 2.0).unwrap();
        h.append(&[2.5, 0.0, 0.0]).unwrap();
        h.finish().unwrap();
        let times: Vec<f64> = rows(&path).iter().map(|r| r[0]).collect();
        assert_eq!(times, vec![0.0, 1.0, 2.0, 2.5]);
        // Another run's file is not appended to.
        let other = ["t".to_string()];
        let msg = HistoryWriter::open_append(&path, &other)
            .unwrap_err()
            .to_string();
        assert!(msg.contains("h.csv") && msg.contains("header"), "{msg}");
    }
}
