//! Closed-form reference solutions, validated on construction.

pub mod dalembert;
pub mod geostatic;
pub mod kirsch;

pub use dalembert::{HalfSinePulse1D, PulseShape};
pub use geostatic::ConfinedColumn;
pub use kirsch::Kirsch;
