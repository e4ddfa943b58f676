//! The TOML case format (serde schema) and its translation into a validated [`Model`].
//!
//! Every problem with the input becomes a [`DcfmError`] naming the file, the field path, the
//! value and what was expected; nothing panics. The format is documented with examples in
//! `docs/case_format.md`.

mod build;
pub mod fingerprint;
pub mod probes;
mod schema;
mod static_schema;
pub mod warnings;

pub use build::{build_materials, load_case, parse_case, parse_case_with_motions, Case};
pub use schema::*;
pub use static_schema::*;
pub use warnings::CaseWarning;
