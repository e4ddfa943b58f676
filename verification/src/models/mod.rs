//! Model builders shared by the cases.

pub mod column;
pub mod contact_blocks;
pub mod single_element;
