//! # dcfm-app — the `dcfm` command line around the core
//!
//! What only an application needs, kept out of the core library (`dcfm`) so that the
//! Python module links the core alone: the run driver with its progress bar and
//! checkpoint files ([`run`]), and the files a run writes ([`output`]: VTU/PVD, CSV
//! histories, the JSON summary, atomic writes). The binary `dcfm` (src/main.rs) parses
//! the command line.

pub mod estimate;
pub mod frames;
pub mod mesh_cmd;
pub mod motion_cmd;
pub mod output;
pub mod peaks;
pub mod progress;
pub mod run;
pub mod static_run;
