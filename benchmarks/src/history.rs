//! `benchmarks/history.jsonl`: one [`ThroughputRecord`] per line, appended by every
//! recorded run, never rewritten.

use std::fs::OpenOptions;
use std::io::Write;
use std::path::{Path, PathBuf};

use crate::error::BenchError;
use crate::record::ThroughputRecord;

/// The workspace root (the parent of this crate's manifest directory).
pub fn workspace_root() -> PathBuf {
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR"));
    manifest.parent().unwrap_or(manifest).to_path_buf()
}

/// `<workspace root>/benchmarks/history.jsonl`.
pub fn default_history_path() -> PathBuf {
    workspace_root().join("benchmarks").join("history.jsonl")
}

/// Append `record` as one line to `path`, creating the file if missing.
pub fn append(path: &Path, record: &ThroughputRecord) -> Result<(), BenchError> {
    let io = |source| BenchError::Io {
        path: path.to_path_buf(),
        source,
    };
    let mut file = OpenOptions::new()
        .create(true)
        .append(true)
        .open(path)
        .map_err(io)?;
    let mut line = record.to_json_line();
    line.push('\n');
    // One write call per line so concurrent appenders do not interleave within a line.
    file.write_all(line.as_bytes()).map_err(io)
}

/// Every record of `path` in file order (blank lines skipped; unknown keys ignored).
pub fn read(path: &Path) -> Result<Vec<ThroughputRecord>, BenchError> {
    let text = std::fs::read_to_string(path).map_err(|source| BenchError::Io {
        path: path.to_path_buf(),
        source,
    })?;
    text.lines()
        .enumerate()
        .filter(|(_, l)| !l.trim().is_empty())
        .map(|(i, l)| {
            serde_json::from_str(l).map_err(|source| BenchError::Json {
                path: path.to_path_buf(),
                line: i + 1,
                source,
            })
        })
        .collect()
}
