//! Analysis stages: the static stage (in-situ stress, excavation, activation), the
//! explicit dynamic driver and its energy accounting.

pub mod checkpoint;
pub mod checkpoint_seal;
mod contact_overlap;
pub mod dynamic;
pub mod energy;
pub mod schedule;
pub mod static_stage;
pub mod subcycling;

pub use dynamic::Simulation;
pub use energy::Energies;
pub use schedule::StepSchedule;
