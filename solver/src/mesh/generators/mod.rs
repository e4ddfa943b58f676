//! Parametric mesh generators: whole models — the underground powerhouse ([`cavern`])
//! and its Yingxiuwan preset ([`yingxiuwan`]) — and the plate with a circular hole of the
//! Kirsch case ([`plate_with_hole`]).

pub mod cavern;
pub mod plate_with_hole;
pub mod yingxiuwan;

pub use plate_with_hole::PlateWithHoleSpec;
