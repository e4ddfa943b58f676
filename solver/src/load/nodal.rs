//! Nodal loads and gravity (body force ρ g on the lumped masses).

use crate::load::TimeFunction;

/// A force per node on a node set, scaled by a history: F(t) = force · h(t).
#[derive(Clone, Debug)]
pub struct NodalLoad {
    pub nodes: Vec<u32>,
    pub force: [f64; 3],
    pub history: TimeFunction,
}

/// Gravity g · h(t) (m/s²) acting on every free node; with lumped mass the consistent
/// body force ∫ρ g N_a dV equals M_a g.
#[derive(Clone, Debug)]
pub struct Gravity {
    pub acceleration: [f64; 3],
    pub history: TimeFunction,
}
