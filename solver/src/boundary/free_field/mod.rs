//! The free field: the motion the ground would have without the model's cavern and
//! structures, computed alongside the main grid in the same explicit step and felt by
//! the main grid through its boundaries (FLAC3D's free-field boundary; Nielsen 2006).
//!
//! - [`column`]: 1D layered columns (vertically incident P, SV, SH), transmitting or
//!   rigid base, free surface on top; used for the seismic input at the base, for the
//!   coupling of a model top lying below the ground surface, and at the vertical edges
//!   where two free-field walls meet.

pub mod column;

use serde::Deserialize;

use crate::boundary::absorbing::SetNames;

/// `[boundary.free_field]`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FreeFieldSection {
    /// The model's top face set when it lies below the ground surface: coupled to the
    /// free-field column at its depth (dashpots on the relative velocity plus the
    /// overburden's free-field traction). Needs `[[seismic.overburden]]`.
    #[serde(default)]
    pub top: Option<SetNames>,
}
