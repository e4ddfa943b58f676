//! No code. This crate only enables, on dependencies shared by the workspace's builds,
//! the union of the features those builds ask for, so that Cargo compiles each of them
//! once (see its Cargo.toml).
