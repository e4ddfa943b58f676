//! Boundary conditions: fixed and prescribed degrees of freedom; absorbing boundaries
//! (Lysmer dashpots, viscous-spring) on the model's outside; the seismic input through
//! them; the free field.

pub mod absorbing;
pub mod centred_dashpot;
mod constraints;
pub mod face_tensors;
pub mod free_field;
pub(crate) mod per_slot;
pub mod seismic_input;
pub mod system;

pub use absorbing::{AbsorbingKind, AbsorbingSpec};
pub use constraints::{Constraints, MotionKind, Prescribed};
pub use system::{BoundaryInputs, BoundarySystem};
