//! # dcfm — explicit dynamics with the dynamic contact force method
//!
//! Explicit central-difference finite elements (hex8) in which a concrete structure and
//! the surrounding rock interact through the dynamic contact force method with bond-slip
//! (Yang, Chen & Xiao 2014), with a plastic-damage model for both materials.
//!
//! Data flow: case file → [`model::Model`] → static stage → dynamic stage
//! ([`stage::dynamic`]) → outputs. See `docs/ARCHITECTURE.md`.
//!
//! The library is the core alone: argument parsing, the progress bar, the run driver and
//! the files a run writes live in the `dcfm-app` crate (`solver/app/`).

// Index loops over the fixed-size arrays of the kernels (8 nodes, 3 directions, 6 Voigt
// components) read like the equations they implement and vectorise as well as iterators.
#![allow(clippy::needless_range_loop)]

pub mod boundary;
pub mod case;
pub mod contact;
pub mod dense_spectrum;
pub mod element;
pub mod error;
pub mod fnv;
pub mod load;
pub mod mass_scaling;
pub mod material;
pub mod mesh;
pub mod model;
pub mod motion;
pub mod readable;
pub mod stage;
pub mod step_limits;
#[cfg(test)]
mod test_random;

pub use error::{DcfmError, Result};
