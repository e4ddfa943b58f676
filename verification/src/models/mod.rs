//! Model builders shared by the cases.

pub mod column;
