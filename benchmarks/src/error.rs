//! Errors of the benchmark runner.

use std::path::PathBuf;

use thiserror::Error;

/// Everything that can stop a throughput run.
#[derive(Debug, Error)]
pub enum BenchError {
    /// The solver refused the model or the run went unstable.
    #[error("solver: {0}")]
    Solver(#[from] dcfm::DcfmError),
    /// A rayon pool with the requested number of threads could not be built.
    #[error("thread pool: {0}")]
    ThreadPool(#[from] rayon::ThreadPoolBuildError),
    /// Reading or appending the history file failed.
    #[error("{path}: {source}")]
    Io {
        path: PathBuf,
        #[source]
        source: std::io::Error,
    },
    /// A history line is not a throughput record.
    #[error("{path}:{line}: {source}")]
    Json {
        path: PathBuf,
        line: usize,
        #[source]
        source: serde_json::Error,
    },
    /// A configuration value that cannot be run (no size, zero threads, ...).
    #[error("configuration: {0}")]
    Config(String),
}
