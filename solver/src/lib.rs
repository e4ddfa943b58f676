//! # dcfm — explicit dynamics with the dynamic contact force method
//!
//! Explicit central-difference finite elements (hex8) in which a concrete structure and
//! the surrounding rock interact through the dynamic contact force method with bond-slip
//! (Yang, Chen & Xiao 2014), with a plastic-damage model for both materials.
//!
//! Data flow: case file → [`model::Model`] → static stage → dynamic stage
//! ([`stage::dynamic`]) → outputs. See `docs/ARCHITECTURE.md`.

pub mod contact;
pub mod error;
pub mod element;
pub mod material;
pub mod mesh;

pub use error::{DcfmError, Result};
