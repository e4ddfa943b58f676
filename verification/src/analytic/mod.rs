//! Closed-form reference solutions, validated on construction.

pub mod dalembert;
pub mod geostatic;
pub mod kirsch;
pub mod point_mass_junction;
pub mod site_response;

pub use dalembert::{HalfSinePulse1D, PulseShape};
pub use geostatic::ConfinedColumn;
pub use kirsch::Kirsch;
pub use site_response::{LayerOnHalfSpace, SoilDamping};
