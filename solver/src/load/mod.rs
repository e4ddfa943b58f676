//! Loads: time functions, nodal loads and gravity.

mod nodal;
pub mod time_function;

pub use nodal::{Gravity, NodalLoad};
pub use time_function::{MotionQuantity, TimeFunction};
