//! Model builders shared by the cases.

pub mod column;
pub mod single_element;
