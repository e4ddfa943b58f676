//! A static step solved directly: K Δu = f_ext − f_int(u) with the assembled initial
//! stiffness (exact for linear elastic material, one solve), then the material update at
//! u + Δu and the out-of-balance that is left. Bonded contact pairs are tied; after the
//! solve every tie force is checked against the bond (eqs. 12 and 14), since a tie cannot
//! break.

use super::assembly::assemble;
use super::cholesky::FactorError;
use super::conjugate_gradients::CgError;
use super::dofs::DofMap;
use super::forces::{commit_states, ForceBuffers, OutOfBalance};
use super::linear_solver::{self, LinearSettings, LinearSolveError, LinearSolverUsed};
use super::restraint::check_restrained;
use crate::contact::geom::{dot, norm, tangential};
use crate::contact::PairState;
use crate::element::groups::GroupGeometry;
use crate::error::{DcfmError, Result};
use crate::model::Model;

/// What a direct solve did.
#[derive(Clone, Copy, Debug)]
pub struct DirectOutcome {
    /// Out-of-balance before and after.
    pub before: OutOfBalance,
    pub after: OutOfBalance,
    /// Equations and stored nonzeros of K (upper triangle).
    pub equations: usize,
    pub k_nnz: usize,
    /// The linear solver used (Cholesky: nonzeros of L, supernodal or simplicial;
    /// conjugate gradients: iterations).
    pub linear: LinearSolverUsed,
    /// Seconds spent in assembly, factorisation (or the iterations) and solve.
    pub seconds: [f64; 3],
}

/// Why a direct solve is not possible for the model's contact state (`None`: it is), and
/// the ties of the bonded pairs.
pub fn contact_ties(model: &Model) -> std::result::Result<Vec<(u32, u32)>, String> {
    let Some(c) = model.contact.as_ref() else {
        return Ok(Vec::new());
    };
    let mut ties = Vec::new();
    for (k, a, b, state) in c.active_pairs() {
        if state != PairState::Bonded {
            return Err(format!(
                "interface '{}': the pair of nodes {a} and {b} is {state:?}, not bonded (a direct \
                 solve ties bonded pairs only): use solver = \"relaxation\"",
                c.interface_name(k)
            ));
        }
        ties.push((a, b));
    }
    for k in 0..c.len() {
        if c.has_active_surface_nodes(k) {
            return Err(format!(
                "interface '{}' has nodes in point-to-surface contact (not possible in a direct \
                 solve): use solver = \"relaxation\"",
                c.interface_name(k)
            ));
        }
    }
    Ok(ties)
}

/// One-point groups without hourglass stiffness leave zero-energy modes.
fn check_hourglass(model: &Model) -> std::result::Result<(), String> {
    for g in &model.groups {
        if let GroupGeometry::Uniform(geo) = &g.geometry {
            if geo.first().is_some_and(|x| x.kappa == 0.0) {
                return Err(format!(
                    "region '{}': one-point elements with hourglass = 0 have zero-energy modes and \
                     no static stiffness against them: give the region a hourglass coefficient > 0 \
                     or full integration",
                    g.name
                ));
            }
        }
    }
    Ok(())
}

/// Solve the step: `u` is updated, the material states are committed.
pub fn solve(
    model: &mut Model,
    u: &mut [[f64; 3]],
    f_ext: &[[f64; 3]],
    dormant: &[bool],
    bufs: &mut ForceBuffers,
    linear: &LinearSettings,
    step: &str,
) -> Result<DirectOutcome> {
    let fail = |message: String| DcfmError::Static {
        step: step.to_string(),
        message,
    };
    let ties = contact_ties(model).map_err(fail)?;
    check_hourglass(model).map_err(fail)?;
    check_restrained(model, &model.constraints.constrained, &ties).map_err(|e| match e {
        DcfmError::InvalidInput {
            value, expected, ..
        } => fail(format!("{value} {expected}")),
        other => other,
    })?;
    let dofs = DofMap::new(&model.constraints.constrained, dormant, &ties);
    let mut scratch = Vec::new();
    bufs.internal_forces(model, u);
    let before = OutOfBalance::measure(&dofs, f_ext, &bufs.f_int, &mut scratch);
    let t0 = std::time::Instant::now();
    let k = assemble(model, &dofs);
    let t1 = std::time::Instant::now();
    let mut rhs = vec![0.0; dofs.n_eq];
    let r: Vec<[f64; 3]> = f_ext
        .iter()
        .zip(&bufs.f_int)
        .map(|(e, i)| std::array::from_fn(|d| e[d] - i[d]))
        .collect();
    dofs.gather(&r, &mut rhs);
    let at_equation = |eq: usize| {
        let (node, d) = dofs.owner[eq];
        let x = model.mesh.coords[node as usize];
        format!(
            "at node {node} ({}) at ({:.4}, {:.4}, {:.4})",
            ["x", "y", "z"][d as usize],
            x[0],
            x[1],
            x[2]
        )
    };
    let (used, times) =
        linear_solver::solve_in_place(&k, &mut rhs, linear).map_err(|e| match e {
            LinearSolveError::Factor(FactorError::Pivot { eq, ratio }) => fail(format!(
            "stiffness not positive definite {}: pivot / diagonal = {ratio:.3e}; nothing holds \
             this DOF (a mechanism, a node or body free to move)",
            at_equation(eq)
        )),
            LinearSolveError::Factor(FactorError::Resource(m)) => fail(m),
            LinearSolveError::Iterative(CgError::NotPositiveDefinite { iteration, eq }) => {
                fail(format!(
                    "conjugate gradients: the stiffness is not positive definite ({}); nothing \
                 holds some DOFs (a mechanism, a node or body free to move)",
                    match eq {
                        Some(eq) => format!("the diagonal block {}", at_equation(eq)),
                        None => format!("pᵀKp ≤ 0 at iteration {iteration}"),
                    }
                ))
            }
            LinearSolveError::Iterative(CgError::NotConverged {
                iterations,
                relative_residual,
            }) => fail(format!(
                "conjugate gradients reached a relative residual of {relative_residual:.3e} in \
             {iterations} iterations, not static.cg_tolerance = {:.1e}: raise \
             static.cg_max_iterations, or set static.linear_solver = \"cholesky\" where its \
             factor fits in memory",
                linear.cg.tolerance
            )),
        })?;
    if let Some(bad) = rhs.iter().position(|x| !x.is_finite()) {
        let (node, d) = dofs.owner[bad];
        return Err(fail(format!(
            "the solve gave a non-finite displacement at node {node} ({})",
            ["x", "y", "z"][d as usize]
        )));
    }
    dofs.scatter_add(&rhs, u);
    bufs.internal_forces(model, u);
    commit_states(model);
    let after = OutOfBalance::measure(&dofs, f_ext, &bufs.f_int, &mut scratch);
    check_ties(model, &ties, f_ext, &bufs.f_int).map_err(fail)?;
    Ok(DirectOutcome {
        before,
        after,
        equations: dofs.n_eq,
        k_nnz: k.nnz(),
        linear: used,
        seconds: [(t1 - t0).as_secs_f64(), times[0], times[1]],
    })
}

/// The force each tie carries, R_a = f_int,a − f_ext,a on node a of the pair, within the
/// bond: λ = −R·n ≥ 0 with |T| ≤ μs λ + cA (eq. 12), or √(|T|² + λ²) ≤ σt A in tension
/// (eq. 14). A tie beyond them would have broken: the step needs the relaxation.
fn check_ties(
    model: &Model,
    ties: &[(u32, u32)],
    f_ext: &[[f64; 3]],
    f_int: &[[f64; 3]],
) -> std::result::Result<(), String> {
    let Some(c) = model.contact.as_ref() else {
        return Ok(());
    };
    if ties.is_empty() {
        return Ok(());
    }
    for (k, a, _b, _) in c.active_pairs() {
        let Some((mu_s, shear, tensile, n)) = c.pair_strength(k, a) else {
            continue;
        };
        let ai = a as usize;
        let mask = model.constraints.constrained[ai];
        let r: [f64; 3] = std::array::from_fn(|d| {
            if mask & (1 << d) != 0 {
                0.0
            } else {
                f_int[ai][d] - f_ext[ai][d]
            }
        });
        let lambda = -dot(r, n);
        let t = norm(tangential(r, n));
        // Round-off slack: 1e-9 of the force.
        let slack = 1e-9 * norm(r);
        let ok = if lambda >= 0.0 {
            t <= mu_s * lambda + shear + slack
        } else {
            (t * t + lambda * lambda).sqrt() <= tensile + slack
        };
        if !ok {
            let x = model.mesh.coords[ai];
            return Err(format!(
                "interface '{}': the bond of node {a} at ({:.4}, {:.4}, {:.4}) would carry a normal \
                 force {lambda:.4e} N (compression positive) and a shear force {t:.4e} N, beyond its \
                 strength (cA = {shear:.4e} N, σt A = {tensile:.4e} N, μs = {mu_s}): the bond breaks; \
                 use solver = \"relaxation\" for this step",
                c.interface_name(k),
                x[0],
                x[1],
                x[2]
            ));
        }
    }
    Ok(())
}
