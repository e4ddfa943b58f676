//! A static step by dynamic relaxation: the explicit core ([`Simulation`]) steps the model
//! under the constant static loads, with kinetic or viscous damping, until the
//! out-of-balance ratio falls below the tolerance (Otter 1966; Underwood 1983). Everything
//! the explicit model has — plastic-damage, contact with bond-slip — takes part.
//!
//! - Out-of-balance at Uⁿ: the step gives M (V^{n+½} − V^{n−½})/Δt + α M V^{n−½} =
//!   Fⁿ − f_int(Uⁿ) + Rⁿ (contact forces included), so r = M(a + α V^{n−½}) exactly.
//! - Kinetic damping: at every peak of the kinetic energy (½ Σ M |V^{n+½}|² below the
//!   previous step's) the motion restarts from rest at Uⁿ: V^{n−½} = −½Δt aⁿ, so that the
//!   full-step velocity is zero there (Barnes 1988's restart at the peak).
//! - Viscous damping: c = 2ω₀M with ω₀² = xᵀ(f_int(U) − f_int(U₀)) / xᵀMx, x = U − U₀
//!   (Rayleigh quotient of the displacement so far; Underwood 1983), α Δt ≤ ½.
//! - Mass scaling (relaxation only): M_i = ½ max_d Σ_e Σ_q |K^e_(i,d) q| with Δt = 1, so
//!   the Gershgorin bound keeps ω_max ≤ √2 < 2 and all elements advance at the same rate;
//!   gravity keeps the physical masses (it enters as a nodal load).
//! - Release in substeps: with the support forces S = f_int(U) − F at the step's start,
//!   the loads F + (1 − k/n) S are relaxed in turn for k = 1..n.

use super::dofs::DofMap;
use super::forces::{ForceBuffers, OutOfBalance};
use super::history::HistoryRow;
use super::plan::{Convergence, RelaxationDamping, RelaxationSettings};
use crate::error::{DcfmError, Result};
use crate::load::{NodalLoad, TimeFunction};
use crate::model::{Model, Rayleigh};
use crate::stage::Simulation;

/// What a relaxation did.
#[derive(Clone, Copy, Debug)]
pub struct RelaxOutcome {
    pub iterations: usize,
    /// Out-of-balance at the start and at the converged state.
    pub before: OutOfBalance,
    pub after: OutOfBalance,
}

/// The step to relax.
pub struct RelaxInput<'a> {
    /// The loads of the step (final).
    pub f_ext: &'a [[f64; 3]],
    /// Support forces S released over `substeps` (None: the loads at once).
    pub support: Option<&'a [[f64; 3]]>,
    pub substeps: usize,
    pub dormant: &'a [bool],
    pub settings: RelaxationSettings,
    pub convergence: Convergence,
    /// Index of the step in the history.
    pub step_index: usize,
    /// Name of the step (errors).
    pub step: &'a str,
}

/// Fictitious masses of the relaxation (Δt = 1): ½ max_d Σ_e Σ_q |K^e_(i,d) q|.
pub fn scaled_masses(model: &Model) -> Vec<f64> {
    let n = model.mesh.n_nodes();
    let mut row = vec![[0.0f64; 3]; n];
    for g in &model.groups {
        for le in 0..g.len() {
            let k = g.element_stiffness(le);
            for (a, &node) in g.conn[le].iter().enumerate() {
                for d in 0..3 {
                    let s: f64 = k[3 * a + d].iter().map(|x| x.abs()).sum();
                    row[node as usize][d] += s;
                }
            }
        }
    }
    row.iter().map(|r| 0.5 * r[0].max(r[1]).max(r[2])).collect()
}

/// Saved parts of the model that the relaxation replaces.
struct Saved {
    gravity: Option<crate::load::Gravity>,
    nodal_loads: Vec<NodalLoad>,
    damping: Rayleigh,
    initial_velocity: Vec<(Vec<u32>, [f64; 3])>,
    mass: Vec<f64>,
}

/// Relax the step from `u` (updated to the converged state; material states committed
/// there). The model is handed to the explicit core and back.
#[allow(clippy::manual_is_multiple_of)] // is_multiple_of needs Rust 1.87; rust-version is 1.85
pub fn relax(
    mut model: Model,
    u: &mut [[f64; 3]],
    input: &RelaxInput,
    bufs: &mut ForceBuffers,
    history: &mut Vec<HistoryRow>,
) -> Result<(Model, RelaxOutcome)> {
    let n = model.mesh.n_nodes();
    let dofs = DofMap::new(&model.constraints.constrained, input.dormant, &[]);
    let mut scratch = Vec::new();
    bufs.internal_forces(&mut model, u);
    let f_start = bufs.f_int.clone();
    let substeps = input.substeps.max(1);
    let load_at = |k: usize, out: &mut Vec<[f64; 3]>| {
        out.clear();
        out.extend_from_slice(input.f_ext);
        if let Some(s) = input.support {
            let w = 1.0 - k as f64 / substeps as f64;
            for (o, si) in out.iter_mut().zip(s) {
                for d in 0..3 {
                    o[d] += w * si[d];
                }
            }
        }
    };
    let mut f_now = Vec::with_capacity(n);
    load_at(0, &mut f_now);
    let before = OutOfBalance::measure(&dofs, input.f_ext, &f_start, &mut scratch);
    // The loads as nodal loads of the explicit model (one per loaded node).
    let loaded: Vec<u32> = (0..n as u32)
        .filter(|&i| {
            let i = i as usize;
            !input.dormant[i]
                && (input.f_ext[i].iter().any(|&x| x != 0.0)
                    || input
                        .support
                        .is_some_and(|s| s[i].iter().any(|&x| x != 0.0)))
        })
        .collect();
    let saved = Saved {
        gravity: model.gravity.take(),
        nodal_loads: std::mem::take(&mut model.nodal_loads),
        damping: model.damping,
        initial_velocity: std::mem::take(&mut model.initial_velocity),
        mass: model.mass.clone(),
    };
    model.damping = Rayleigh::default();
    model.nodal_loads = loaded
        .iter()
        .map(|&i| NodalLoad {
            nodes: vec![i],
            force: [0.0; 3],
            history: TimeFunction::Constant { value: 1.0 },
        })
        .collect();
    let dt = if input.settings.mass_scaling {
        model.mass = scaled_masses(&model);
        1.0
    } else {
        // The step for the static supports in place now (the dynamic stage's prescribed
        // elements may move here).
        input.settings.safety * model.stable_step_now().critical
    };
    let mut sim = Simulation::new_unchecked(model, dt);
    sim.u.copy_from_slice(u);
    sim.v.iter_mut().for_each(|v| *v = [0.0; 3]);
    sim.restart_energy_account();
    let mut u_prev = sim.u.clone();
    let mut v_prev = sim.v.clone();
    let mut r = vec![[0.0; 3]; n];
    let mut iterations = 0usize;
    let mut last = before;
    let conv = input.convergence;
    let every = input.settings.history_every.max(1);
    let viscous = input.settings.damping == RelaxationDamping::Viscous;
    for k in 1..=substeps {
        load_at(k, &mut f_now);
        for (load, &i) in sim.model.nodal_loads.iter_mut().zip(&loaded) {
            load.force = f_now[i as usize];
        }
        let mut ke_prev = 0.0;
        let mut it = 0usize;
        loop {
            if it >= conv.max_iterations {
                let x = sim.model.mesh.coords[last.node];
                return Err(DcfmError::Static {
                    step: input.step.to_string(),
                    message: format!(
                        "dynamic relaxation did not converge in {} iterations{}: out-of-balance \
                         ratio {:.3e} (tolerance {:.1e}); the largest out-of-balance force, \
                         {:.4e} N along {}, is at node {} ({:.4}, {:.4}, {:.4}) — a mechanism, \
                         a failing zone or too tight a tolerance",
                        conv.max_iterations,
                        if substeps > 1 {
                            format!(" (substep {k} of {substeps})")
                        } else {
                            String::new()
                        },
                        last.ratio,
                        conv.tolerance,
                        last.max,
                        ["x", "y", "z"][last.dof],
                        last.node,
                        x[0],
                        x[1],
                        x[2]
                    ),
                });
            }
            it += 1;
            iterations += 1;
            u_prev.copy_from_slice(&sim.u);
            v_prev.copy_from_slice(&sim.v);
            sim.step()?;
            let alpha = sim.model.damping.alpha;
            for i in 0..n {
                let m = sim.model.mass[i];
                for d in 0..3 {
                    r[i][d] = m * (sim.a[i][d] + alpha * v_prev[i][d]);
                }
            }
            last =
                OutOfBalance::from_residual(&dofs, &r, &f_now, sim.internal_force(), &mut scratch);
            let ke: f64 = sim
                .v
                .iter()
                .zip(&sim.model.mass)
                .map(|(v, m)| 0.5 * m * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]))
                .sum();
            let converged = last.ratio <= conv.tolerance;
            if it % every == 0 || converged {
                history.push(HistoryRow {
                    step: input.step_index,
                    substep: k,
                    iteration: it,
                    ratio: last.ratio,
                    max_force: last.max,
                    node: last.node,
                    dof: last.dof,
                    kinetic: ke,
                });
            }
            if converged {
                break;
            }
            if viscous {
                // ω₀² from the Rayleigh quotient of x = Uⁿ − U₀.
                let f = sim.internal_force();
                let (mut num, mut den) = (0.0, 0.0);
                for i in 0..n {
                    let m = sim.model.mass[i];
                    for d in 0..3 {
                        let x = u_prev[i][d] - u[i][d];
                        num += x * (f[i][d] - f_start[i][d]);
                        den += m * x * x;
                    }
                }
                if den > 0.0 && num > 0.0 {
                    // α Δt ≤ ½ keeps the damped leapfrog stable for ω²Δt² ≤ 4 − 2αΔt = 3,
                    // above the ω²Δt² ≤ 2 of the mass scaling.
                    sim.model.damping.alpha = (2.0 * (num / den).sqrt()).min(0.5 / dt);
                }
            } else if ke < ke_prev {
                // Kinetic-energy peak near tⁿ: restart from rest at Uⁿ. At rest means a
                // zero full-step velocity, ½(V^{n−½} + V^{n+½}) = 0, so V^{n−½} =
                // −½Δt aⁿ (aⁿ = M⁻¹ rⁿ of this step, contact included). Merely zeroing
                // V^{n+½} would leave the half kick ½Δt aⁿ in every mode and pump energy
                // into the highest ones (it went unstable in testing).
                sim.u.copy_from_slice(&u_prev);
                for (v, a) in sim.v.iter_mut().zip(&sim.a) {
                    *v = a.map(|x| -0.5 * dt * x);
                }
                sim.restart_energy_account();
                ke_prev = 0.0;
            } else {
                ke_prev = ke;
            }
        }
    }
    // The converged state is Uⁿ of the last step (its residual was measured, its material
    // states are the committed ones).
    u.copy_from_slice(&u_prev);
    let mut model = sim.model;
    model.gravity = saved.gravity;
    model.nodal_loads = saved.nodal_loads;
    model.damping = saved.damping;
    model.initial_velocity = saved.initial_velocity;
    model.mass = saved.mass;
    model.refresh_inverse_mass();
    Ok((
        model,
        RelaxOutcome {
            iterations,
            before,
            after: last,
        },
    ))
}
