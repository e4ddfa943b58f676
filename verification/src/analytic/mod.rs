//! Closed-form reference solutions, validated on construction.

pub mod dalembert;
pub mod site_response;

pub use dalembert::{HalfSinePulse1D, PulseShape};
pub use site_response::{LayerOnHalfSpace, SoilDamping};
