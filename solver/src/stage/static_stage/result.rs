//! What the static stage hands to the dynamic stage, and the function that starts the
//! dynamic stage from it.
//!
//! The model itself comes back from [`super::run`] in its post-static configuration:
//! excavated elements out of the groups, placed elements in (with their references),
//! committed material states (plastic strain, damage), contact pairs and their states,
//! dormant nodes fixed, the constraints of the dynamic stage (`[boundary]`) restored. The
//! [`StaticResult`] adds the displacements, the reactions of the static supports, the
//! static loads that stay on, the out-of-balance and the damaged volume.

use serde::Serialize;

use super::forces::OutOfBalance;
use super::history::HistoryRow;
use super::linear_solver::LinearSolverChoice;
use super::plan::StepSolver;
use crate::error::Result;
use crate::load::{NodalLoad, TimeFunction};
use crate::model::Model;
use crate::stage::Simulation;

/// Report of one step of the static stage.
#[derive(Clone, Debug, Serialize)]
pub struct StepReport {
    pub name: String,
    pub solver: StepSolver,
    /// Relaxation iterations; for a direct step 1 with the Cholesky factor, the conjugate
    /// gradients' iterations with them.
    pub iterations: usize,
    /// Out-of-balance when the step starts (release forces, loads of placed elements) and
    /// at its end.
    pub initial: OutOfBalance,
    pub out_of_balance: OutOfBalance,
    /// Active elements after the step.
    pub active_elements: usize,
    /// Damaged volume of eq. (27) after the step (m³): [tension, compression, either].
    pub damaged_volume: [f64; 3],
    /// Direct solve: equations, stored nonzeros of K (upper triangle) and of L, whether
    /// the factorisation was supernodal, and the seconds in assembly, factorisation, solve.
    pub equations: usize,
    pub stiffness_nonzeros: usize,
    pub factor_nonzeros: usize,
    pub supernodal: bool,
    /// The linear solver of a direct step (`None` for a relaxation step).
    pub linear_solver: Option<LinearSolverChoice>,
    pub seconds: [f64; 3],
}

/// The static state that starts the dynamic stage.
#[derive(Clone, Debug, Default)]
pub struct StaticResult {
    /// Displacements at the end of the stage (m); dormant nodes keep the value they had
    /// when their last element went.
    pub u: Vec<[f64; 3]>,
    /// Displacements after the in-situ step (m): `u − u_in_situ` is what the excavation
    /// and construction steps caused.
    pub u_in_situ: Vec<[f64; 3]>,
    /// Reactions of the static stage's constrained DOFs (N, the force the support applies;
    /// zero in the free directions of a listed node), per active node with a constraint.
    pub reactions: Vec<(u32, [f64; 3])>,
    /// Nodal forces of the static loads (pressures, tractions, static nodal forces) at the
    /// end of the stage (N): they stay on in the dynamic stage.
    pub static_loads: Vec<(u32, [f64; 3])>,
    /// Out-of-balance of a given in-situ field before its equilibration.
    pub initial_field_out_of_balance: Option<OutOfBalance>,
    /// One report per step (the in-situ step first, if any).
    pub steps: Vec<StepReport>,
    /// Out-of-balance at the end of the stage.
    pub out_of_balance: OutOfBalance,
    /// Damaged volume at the end of the stage (m³): [tension, compression, either].
    pub damaged_volume: [f64; 3],
    /// Convergence history.
    pub history: Vec<HistoryRow>,
    /// Active flag of every element at the end of the stage.
    pub active: Vec<bool>,
}

impl StaticResult {
    /// u − u_in_situ: the displacement caused by the excavation and construction steps.
    pub fn displacement_since_in_situ(&self) -> Vec<[f64; 3]> {
        self.u
            .iter()
            .zip(&self.u_in_situ)
            .map(|(a, b)| std::array::from_fn(|d| a[d] - b[d]))
            .collect()
    }
}

/// The constant nodal loads that keep the dynamic model in the static equilibrium: the
/// static loads, plus the reaction of every static support whose DOF the dynamic model
/// leaves free (e.g. a base fixed in the static stage and absorbing in the dynamic one).
/// Added to `model.nodal_loads` (one load per node).
pub fn add_hand_over_loads(model: &mut Model, result: &StaticResult) {
    let n = model.mesh.n_nodes();
    let mut f = vec![[0.0; 3]; n];
    for &(i, v) in &result.static_loads {
        for d in 0..3 {
            f[i as usize][d] += v[d];
        }
    }
    for &(i, r) in &result.reactions {
        let free = !model.constraints.constrained[i as usize];
        for d in 0..3 {
            if free & (1 << d) != 0 {
                f[i as usize][d] += r[d];
            }
        }
    }
    for (i, fi) in f.iter().enumerate() {
        if fi.iter().any(|&x| x != 0.0) {
            model.nodal_loads.push(NodalLoad {
                nodes: vec![i as u32],
                force: *fi,
                history: TimeFunction::Constant { value: 1.0 },
            });
        }
    }
}

/// Start the dynamic stage from the static state: the hand-over loads added
/// ([`add_hand_over_loads`]), the displacements set, velocities from the case's initial
/// velocities (none by default). `dt` must not exceed `safety` × the critical step. With
/// no input the model stays at rest (its first step sees the static out-of-balance only).
pub fn start_dynamic(
    mut model: Model,
    result: &StaticResult,
    dt: f64,
    safety: f64,
) -> Result<Simulation> {
    add_hand_over_loads(&mut model, result);
    // Anchor bars are installed now, in the static stage's final configuration.
    // Their steel mass goes back onto the host nodes, whose masses the activation
    // recomputed from the active elements.
    if let Some(anchors) = model.anchors.as_mut() {
        anchors.install_at(&model.mesh, &result.u);
        anchors.add_host_masses(&model.mesh, &mut model.mass);
        model.refresh_inverse_mass();
    }
    let mut sim = Simulation::new(model, dt, safety)?;
    sim.u.copy_from_slice(&result.u);
    // Absorbing springs are measured from the static state.
    if let Some(b) = sim.model.boundaries.as_mut() {
        b.set_static_displacement(&result.u);
    }
    sim.restart_energy_account();
    Ok(sim)
}
