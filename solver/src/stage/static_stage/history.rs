//! Convergence history of the static stage: one row per recorded iteration of a step
//! (every `history_every` relaxation iterations and the last one; one row per direct
//! solve), written by the application as `static_histories.csv`.

use serde::Serialize;

/// One row of the static history.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct HistoryRow {
    /// Step index: 0 the in-situ step, k the k-th of `static.steps`.
    pub step: usize,
    /// Load increment of the step (1-based; release forces in substeps).
    pub substep: usize,
    /// Iteration within the step (relaxation; 1 for a direct solve).
    pub iteration: usize,
    /// Out-of-balance ratio ‖f_ext − f_int‖ / max(‖f_ext‖, ‖f_int‖).
    pub ratio: f64,
    /// Largest out-of-balance force of one DOF (N), its node and direction.
    pub max_force: f64,
    pub node: usize,
    pub dof: usize,
    /// Kinetic energy of the relaxation (J; 0 for a direct solve).
    pub kinetic: f64,
}

impl HistoryRow {
    /// Column names, in the order of [`HistoryRow::values`].
    pub const HEADER: [&'static str; 8] = [
        "step",
        "substep",
        "iteration",
        "out_of_balance_ratio",
        "max_out_of_balance",
        "node",
        "dof",
        "kinetic_energy",
    ];

    /// The row as numbers.
    pub fn values(&self) -> [f64; 8] {
        [
            self.step as f64,
            self.substep as f64,
            self.iteration as f64,
            self.ratio,
            self.max_force,
            self.node as f64,
            self.dof as f64,
            self.kinetic,
        ]
    }
}
