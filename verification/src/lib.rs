//! Verification suite of dcfm: analytic reference solutions (library types shared by the
//! tests, the runner and the report), one file per case, and the runner that writes
//! `results.json` and `reports/verification.md`.

pub mod analytic;
pub mod cases;
pub mod models;
pub mod record;
pub mod report;

pub use record::{Check, CheckRow};
