//! Benchmark support for dcfm.
//!
//! - [`cube`]: the structured elastic cubes every benchmark times;
//! - [`runner`]: the whole-run throughput runner behind the `throughput` binary;
//! - [`case_run`]: whole runs of a case file as records (the `case_run` binary);
//! - [`record`]: one JSON record per timed configuration;
//! - [`history`]: the append-only `benchmarks/history.jsonl` of those records;
//! - [`static_solve`]: the static stage's sparse direct solve of an n³ cube (issue #7);
//! - [`scipy_csr`]: the scipy CSR leapfrog on the same cube, run through Python (issue 11);
//! - [`speedup`] and [`targets`]: what the runner prints at the end (thread speed-ups and
//!   the throughput targets of issues #2, #3, #4 and #7);
//! - [`git`], [`timestamp`]: provenance of a record (commit, UTC time);
//! - [`cputime`]: CPU time of the process, to flag runs starved by other processes;
//! - [`memory`]: peak resident memory per case;
//! - [`error`]: the runner's error type.

pub mod case_run;
pub mod cputime;
pub mod cube;
pub mod error;
pub mod git;
pub mod history;
pub mod machine;
pub mod memory;
pub mod record;
pub mod runner;
pub mod scipy_csr;
pub mod speedup;
pub mod static_solve;
pub mod targets;
pub mod timestamp;

pub use error::BenchError;
pub use record::ThroughputRecord;
pub use runner::{run, run_with_notes, RunConfig};
pub use scipy_csr::ScipyBaseline;
