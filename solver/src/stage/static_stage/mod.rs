//! The static stage (paper §4.6: "static analysis of the surrounding rock excavation and
//! concrete structure ... provided the initial conditions for a dynamic analysis"):
//! in-situ stress, excavation in sequence with the release of the excavated elements'
//! forces, placement (activation) of concrete, each step solved to static equilibrium, the
//! resulting state handed to the dynamic stage. See `docs/static_stage.md`.
//!
//! [`run`], in order:
//! 1. the elements placed by a later step start inactive; the static boundary conditions
//!    replace the dynamic ones; nodes of no active element are dormant (fixed, no mass);
//! 2. in-situ step: none, gravity (solve under the model's loads at t = 0), or a given
//!    field σ₀(z) set as the initial strain of the points and equilibrated (its initial
//!    out-of-balance reported);
//! 3. for every step: excavate its sets (their elements leave the groups: the
//!    out-of-balance of the remaining body, f_ext − f_int, is exactly the release load
//!    Σ Bᵀσ − body force of the removed elements at the boundary nodes), place its sets
//!    (stress-free at the current displacements, their weight on from then on, their
//!    contact pairs bonded at rest), let the interfaces of its `bond` list act (held out
//!    of contact until then, bonded at rest in the offset reached), then solve: directly
//!    (sparse Cholesky of the initial stiffness, [`direct`]) or by dynamic relaxation
//!    ([`relaxation`], in substeps of the release load);
//! 4. reactions of the static supports; the dynamic constraints restored.
//!
//! The model is moved in and handed back (the relaxation lends it to the explicit core).

pub mod activation;
pub mod assembly;
pub mod checkpoint;
pub mod cholesky;
pub mod conjugate_gradients;
pub mod direct;
pub mod dofs;
pub mod forces;
pub mod history;
pub mod in_situ;
pub mod linear_solver;
pub mod loads;
pub mod nested_dissection;
pub mod plan;
pub mod relaxation;
pub mod restraint;
pub mod result;

pub use activation::Activation;
pub use forces::OutOfBalance;
pub use history::HistoryRow;
use linear_solver::{LinearSolverChoice, LinearSolverUsed};
pub use plan::{
    Convergence, ElementSet, InSitu, Layer, RelaxationDamping, RelaxationSettings, StaticLoad,
    StaticPlan, StaticStep, StepSolver, StressProfile, TablePoint,
};
pub use result::{add_hand_over_loads, start_dynamic, StaticResult, StepReport};

use crate::boundary::Constraints;
use crate::error::{DcfmError, Result};
use crate::model::Model;
use dofs::DofMap;
use forces::ForceBuffers;

/// The static loads of the current configuration: the model's loads at t = 0 (gravity on
/// the active masses, nodal loads) and the plan's static loads.
fn step_loads(model: &Model, plan: &StaticPlan, active: &[bool]) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let n = model.mesh.n_nodes();
    let mut persistent = vec![[0.0; 3]; n];
    loads::add_static_loads(model, &plan.loads, active, &mut persistent);
    let mut total = persistent.clone();
    loads::add_model_loads(model, &mut total);
    (total, persistent)
}

/// Damaged volume of eq. (27) over the active groups: [tension, compression, either].
fn damaged_volume(model: &Model, plan: &StaticPlan) -> [f64; 3] {
    let mut v = [0.0; 3];
    for g in &model.groups {
        let d = g.damaged_volume(plan.damage_threshold, plan.damage_per_element);
        for k in 0..3 {
            v[k] += d[k];
        }
    }
    v
}

/// Everything one step needs besides the model.
struct StepContext<'a> {
    plan: &'a StaticPlan,
    act: &'a Activation,
    bufs: &'a mut ForceBuffers,
    history: &'a mut Vec<HistoryRow>,
}

/// Solve the current configuration to equilibrium with `solver`.
#[allow(clippy::too_many_arguments)]
fn solve_step(
    mut model: Model,
    u: &mut [[f64; 3]],
    cx: &mut StepContext,
    solver: StepSolver,
    convergence: Convergence,
    substeps: usize,
    index: usize,
    name: &str,
) -> Result<(Model, StepReport)> {
    let (f_ext, _) = step_loads(&model, cx.plan, &cx.act.active);
    let label = format!("step {index} '{name}'");
    let mut report = StepReport {
        name: name.to_string(),
        solver,
        iterations: 1,
        initial: OutOfBalance::default(),
        out_of_balance: OutOfBalance::default(),
        active_elements: cx.act.n_active(),
        damaged_volume: [0.0; 3],
        equations: 0,
        stiffness_nonzeros: 0,
        factor_nonzeros: 0,
        supernodal: false,
        linear_solver: None,
        seconds: [0.0; 3],
    };
    match solver {
        StepSolver::Direct => {
            let out = direct::solve(
                &mut model,
                u,
                &f_ext,
                &cx.act.dormant,
                cx.bufs,
                &cx.plan.linear,
                &label,
            )?;
            if out.after.ratio > convergence.tolerance {
                let x = model.mesh.coords[out.after.node];
                return Err(DcfmError::Static {
                    step: label,
                    message: format!(
                        "the direct solve left an out-of-balance ratio {:.3e} (tolerance {:.1e}): \
                         the material is not linear in this step (it yielded or damaged); the \
                         largest out-of-balance force, {:.4e} N along {}, is at node {} ({:.4}, \
                         {:.4}, {:.4}); use solver = \"relaxation\"",
                        out.after.ratio,
                        convergence.tolerance,
                        out.after.max,
                        ["x", "y", "z"][out.after.dof],
                        out.after.node,
                        x[0],
                        x[1],
                        x[2]
                    ),
                });
            }
            cx.history.push(HistoryRow {
                step: index,
                substep: 1,
                iteration: 1,
                ratio: out.after.ratio,
                max_force: out.after.max,
                node: out.after.node,
                dof: out.after.dof,
                kinetic: 0.0,
            });
            report.initial = out.before;
            report.out_of_balance = out.after;
            report.equations = out.equations;
            report.stiffness_nonzeros = out.k_nnz;
            match out.linear {
                LinearSolverUsed::Cholesky { l_nnz, supernodal } => {
                    report.factor_nonzeros = l_nnz;
                    report.supernodal = supernodal;
                    report.linear_solver = Some(LinearSolverChoice::Cholesky);
                }
                LinearSolverUsed::ConjugateGradients { iterations, .. } => {
                    report.iterations = iterations;
                    report.linear_solver = Some(LinearSolverChoice::ConjugateGradients);
                }
            }
            report.seconds = out.seconds;
        }
        StepSolver::Relaxation => {
            // The elastic direct solution as a start, where the contact state allows it and
            // the load is applied at once.
            if cx.plan.relaxation.predictor && substeps <= 1 && direct::contact_ties(&model).is_ok()
            {
                let mut trial = u.to_vec();
                let saved_states: Vec<_> =
                    model.groups.iter().map(|g| g.states().clone()).collect();
                match direct::solve(
                    &mut model,
                    &mut trial,
                    &f_ext,
                    &cx.act.dormant,
                    cx.bufs,
                    &cx.plan.linear,
                    &label,
                ) {
                    Ok(_) => u.copy_from_slice(&trial),
                    Err(_) => {
                        for (g, s) in model.groups.iter_mut().zip(saved_states) {
                            g.replace_states(s);
                        }
                    }
                }
            }
            let support = if substeps > 1 {
                cx.bufs.internal_forces(&mut model, u);
                Some(
                    cx.bufs
                        .f_int
                        .iter()
                        .zip(&f_ext)
                        .map(|(i, e)| std::array::from_fn(|d| i[d] - e[d]))
                        .collect::<Vec<[f64; 3]>>(),
                )
            } else {
                None
            };
            let input = relaxation::RelaxInput {
                f_ext: &f_ext,
                support: support.as_deref(),
                substeps,
                dormant: &cx.act.dormant,
                settings: cx.plan.relaxation,
                convergence,
                step_index: index,
                step: &label,
            };
            let (m, out) = relaxation::relax(model, u, &input, cx.bufs, cx.history)?;
            model = m;
            report.iterations = out.iterations;
            report.initial = out.before;
            report.out_of_balance = out.after;
        }
    }
    report.damaged_volume = damaged_volume(&model, cx.plan);
    Ok((model, report))
}

/// Run the static stage on `model` (built from the case, every element in its group): the
/// model comes back in its post-static configuration with the dynamic constraints, and
/// the [`StaticResult`].
pub fn run(mut model: Model, plan: &StaticPlan) -> Result<(Model, StaticResult)> {
    // The absorbing boundaries belong to the dynamic stage: the static stage holds the
    // model on its own supports ([[static.fixed]]), so dashpots and springs stay out of
    // its equilibrium (the direct solve and the relaxation agree without them).
    let boundaries = model.boundaries.take();
    // Anchor bars (yingxiuwan branch): not part of the static stage; they are installed in
    // the static stage's final configuration when the dynamic stage starts
    // (`start_dynamic`), so the excavation's displacements load them no more than the
    // bolts that are grouted after it.
    let anchors = model.anchors.take();
    let n = model.mesh.n_nodes();
    let dynamic_constraints: Constraints = model.constraints.clone();
    let mut act = Activation::new(&model);
    for &e in &plan.initially_inactive {
        act.active[e as usize] = false;
    }
    let mut u = vec![[0.0; 3]; n];
    if let Some(c) = model.contact.as_mut() {
        for &(i, _) in plan.steps.iter().flat_map(|st| &st.bond) {
            c.set_held(i, true);
        }
    }
    act.apply(&mut model, &plan.constraints, &u, &[]);
    let mut bufs = ForceBuffers::new(n);
    let mut history = Vec::new();
    let mut result = StaticResult::default();
    // In-situ step.
    let in_situ = match &plan.in_situ {
        InSitu::None => None,
        InSitu::Gravity {
            solver,
            convergence,
        } => Some((*solver, *convergence, "in-situ (gravity)")),
        InSitu::Field {
            profile,
            solver,
            convergence,
        } => {
            let g = loads::gravity_magnitude(&model);
            in_situ::set_field(&mut model, profile, g)?;
            let (f_ext, _) = step_loads(&model, plan, &act.active);
            let dofs = DofMap::new(&model.constraints.constrained, &act.dormant, &[]);
            bufs.internal_forces(&mut model, &u);
            let mut scratch = Vec::new();
            result.initial_field_out_of_balance = Some(OutOfBalance::measure(
                &dofs,
                &f_ext,
                &bufs.f_int,
                &mut scratch,
            ));
            Some((*solver, *convergence, "in-situ (given field)"))
        }
    };
    if let Some((solver, convergence, name)) = in_situ {
        let mut cx = StepContext {
            plan,
            act: &act,
            bufs: &mut bufs,
            history: &mut history,
        };
        let (m, report) = solve_step(model, &mut u, &mut cx, solver, convergence, 1, 0, name)?;
        model = m;
        result.steps.push(report);
    }
    result.u_in_situ = u.clone();
    for (k, step) in plan.steps.iter().enumerate() {
        let label = format!("step {} '{}'", k + 1, step.name);
        for set in &step.excavate {
            if let Some(&e) = set.elements.iter().find(|&&e| !act.active[e as usize]) {
                return Err(DcfmError::Static {
                    step: label,
                    message: format!(
                        "excavate '{}': element {e} is not active (already removed, or not yet placed)",
                        set.name
                    ),
                });
            }
            for &e in &set.elements {
                act.active[e as usize] = false;
            }
        }
        let mut placed = Vec::new();
        for set in &step.activate {
            if let Some(&e) = set.elements.iter().find(|&&e| act.active[e as usize]) {
                return Err(DcfmError::Static {
                    step: label,
                    message: format!(
                        "activate '{}': element {e} is already active (a set is placed once)",
                        set.name
                    ),
                });
            }
            for &e in &set.elements {
                act.active[e as usize] = true;
                placed.push(e);
            }
        }
        if act.n_active() == 0 {
            return Err(DcfmError::Static {
                step: label,
                message: "no active element is left".into(),
            });
        }
        if let Some(c) = model.contact.as_mut() {
            for &(i, _) in &step.bond {
                c.set_held(i, false);
            }
        }
        act.apply(&mut model, &plan.constraints, &u, &placed);
        let mut cx = StepContext {
            plan,
            act: &act,
            bufs: &mut bufs,
            history: &mut history,
        };
        let (m, report) = solve_step(
            model,
            &mut u,
            &mut cx,
            step.solver,
            step.convergence,
            step.substeps,
            k + 1,
            &step.name,
        )?;
        model = m;
        result.steps.push(report);
    }
    // Reactions of the static supports, the final out-of-balance, the hand-over.
    let (f_ext, persistent) = step_loads(&model, plan, &act.active);
    bufs.internal_forces(&mut model, &u);
    result.reactions = forces::reactions(
        &model.constraints.constrained,
        &act.dormant,
        &f_ext,
        &bufs.f_int,
    );
    result.out_of_balance = result
        .steps
        .last()
        .map_or(OutOfBalance::default(), |s| s.out_of_balance);
    result.static_loads = persistent
        .iter()
        .enumerate()
        .filter(|(i, f)| !act.dormant[*i] && f.iter().any(|&x| x != 0.0))
        .map(|(i, f)| (i as u32, *f))
        .collect();
    result.damaged_volume = damaged_volume(&model, plan);
    act.constrain(&mut model, &dynamic_constraints);
    result.u = u;
    result.history = history;
    result.active = act.active.clone();
    model.boundaries = boundaries;
    model.anchors = anchors;
    Ok((model, result))
}

#[cfg(test)]
mod tests;
