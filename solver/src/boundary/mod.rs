//! Boundary conditions: fixed and prescribed degrees of freedom.

mod constraints;

pub use constraints::{Constraints, MotionKind, Prescribed};
