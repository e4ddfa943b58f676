//! Verification suite of dcfm: analytic reference solutions (library types shared by the
//! tests and the runner), one file per case with its metadata in the registry
//! ([`cases::all`]), and the runner that writes `results.json` and `series.json`, from
//! which `reports/generate.py` writes the report.

// Index loops over the fixed-size arrays of the kernels (8 nodes, 3 directions, 6 Voigt
// components) read like the equations they implement and vectorise as well as iterators.
#![allow(clippy::needless_range_loop)]

pub mod analytic;
pub mod cases;
pub mod models;
pub mod record;

pub use record::{CaseOutput, Check, CheckRow, Series};
