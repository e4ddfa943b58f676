//! Loads: time functions, nodal loads and gravity.

mod by_node;
mod nodal;
pub mod time_function;

pub use by_node::LoadsByNode;
pub use nodal::{Gravity, NodalLoad};
pub use time_function::{MotionQuantity, TimeFunction};
