//! Closed-form reference solutions, validated on construction.

pub mod dalembert;

pub use dalembert::{HalfSinePulse1D, PulseShape};
