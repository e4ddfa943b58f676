//! Verification suite of dcfm: analytic reference solutions (library types shared by the
//! tests, the runner and the report), one file per case, and the runner that writes
//! `results.json` and `reports/verification.md`.

// Index loops over the fixed-size arrays of the kernels (8 nodes, 3 directions, 6 Voigt
// components) read like the equations they implement and vectorise as well as iterators.
#![allow(clippy::needless_range_loop)]

pub mod analytic;
pub mod cases;
pub mod models;
pub mod record;
pub mod report;

pub use record::{Check, CheckRow};
