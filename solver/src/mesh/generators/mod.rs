//! Parametric mesh generators.

pub mod plate_with_hole;

pub use plate_with_hole::PlateWithHoleSpec;
