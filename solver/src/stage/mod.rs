//! Analysis stages: the explicit dynamic driver and its energy accounting.

pub mod checkpoint;
pub mod dynamic;
pub mod energy;

pub use dynamic::Simulation;
pub use energy::Energies;
