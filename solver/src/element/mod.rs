//! Hex8 element: shape functions, precomputed geometry, internal-force kernels
//! (one-point with Flanagan–Belytschko hourglass control, full 2×2×2; the elastic full
//! kernel also in SIMD lanes, `hex8_full_lanes`), lumped mass and the stable time step.

pub mod anchor_bar;
pub mod anchor_mat;
pub mod anchor_pattern;
pub mod colouring;
pub mod damage_marks;
pub mod damage_scan;
pub mod elastic_matrices;
pub mod fields;
pub mod groups;
pub mod hex8_full;
pub mod hex8_full_lanes;
pub mod hex8_uniform;
pub mod hex8_uniform_lanes;
pub mod host_locate;
pub mod lanes;
pub mod lumped_mass;
pub mod shared_mass_step;
pub mod stable_step;
pub mod stiffness;
pub mod uniform_set;

/// The trilinear hex8 geometry lives with the mesh (its Jacobian checks validate meshes);
/// the kernels use it from here.
pub use crate::mesh::hex8_shape;

use serde::Deserialize;

/// Integration rule of a region's hex8 elements.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Deserialize, Default)]
#[serde(rename_all = "snake_case")]
pub enum Integration {
    /// One point at the centre with the uniform-strain (mean) gradient and
    /// Flanagan–Belytschko hourglass control.
    #[default]
    OnePoint,
    /// Full 2×2×2 Gauss integration.
    Full,
}

impl Integration {
    /// Integration points per element.
    pub fn points(self) -> usize {
        match self {
            Integration::OnePoint => 1,
            Integration::Full => 8,
        }
    }

    /// Name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            Integration::OnePoint => "one_point",
            Integration::Full => "full",
        }
    }
}
