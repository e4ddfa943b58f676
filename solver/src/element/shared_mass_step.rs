//! A sharper critical step: the Irons–Treharne bound with the nodal masses shared among the
//! elements by weights (issue 11, `time.stable_step = "shared_mass"`).
//!
//! For **any** split of the lumped nodal masses into nonnegative element parts,
//! M = Σ_e M_e (M_e diagonal on the element's nodes), and any x on the free DOFs,
//!
//! ```text
//! xᵀKx = Σ_e x_eᵀ K_e x_e ≤ Σ_e λ_e x_eᵀ M_e x_e ≤ (max_e λ_e) xᵀMx,
//! ```
//!
//! λ_e the largest eigenvalue of M_e^{-1/2} K_e M_e^{-1/2} on the element's free DOFs, so
//! ω²_max ≤ max_e λ_e (Irons 1970; Belytschko, Liu & Moran 2000, §6.2.3, take for M_e the
//! element's own lumped masses l_e, which gives `element_max_eigenvalue`'s bound). A small
//! element between larger ones shares its nodes with them; given more of those nodes' mass
//! (which the larger elements, far from their own limit, can spare) its λ_e drops. The
//! split used is M_e,a = M_a w_e l_e,a / Σ_{e'∋a} w_e' l_e',a with element weights w_e,
//! balanced in [`ROUNDS`] rounds (w_e ← w_e λ_e / max λ, floored at 10⁻³): every round's split is a
//! valid one, so whatever the rounds reach is a bound, never an estimate.
//!
//! Cost: λ_e needs the element's stiffness (`element::stiffness`) and a 24 × 24 symmetric
//! eigenproblem. An element is evaluated exactly only while its cheap upper bound
//! Λ_e · max_a l_e,a / M_e,a (Λ_e ≥ its own-mass λ_e: the element step's bound, scaled by
//! the worst mass ratio, as M_e ≥ (min_a M_e,a / l_e,a) l_e) reaches half the round's
//! largest; for the others the cheap bound stands in, in the weights and in the result.

use crate::element::stiffness::ElementStiffness;
use nalgebra::{DMatrix, SymmetricEigen};
use rayon::prelude::*;

/// One element of the bound: its nodes, its own lumped masses and a bound on its own-mass
/// λ (ω²_max,e, e.g. (2/Δt_e)² from the element step).
#[derive(Clone, Copy, Debug)]
pub struct SharedElement {
    pub conn: [u32; 8],
    pub own_mass: [f64; 8],
    pub own_bound: f64,
}

/// Number of balancing rounds.
pub const ROUNDS: usize = 32;

/// Result of [`shared_mass_bound`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SharedMassBound {
    /// Bound on ω²_max of M⁻¹K (1/s²).
    pub omega_squared: f64,
    /// Index (in the input) of the element that sets it.
    pub element: usize,
    /// Elements whose λ was evaluated exactly (the others by their cheap bound).
    pub evaluated: usize,
}

/// λ_max of diag(m)^{-1/2} K diag(m)^{-1/2} on the DOFs free in `free` (bit d of node a).
fn split_eigenvalue(k: &ElementStiffness, m: &[f64; 8], free: &[u8; 8]) -> f64 {
    let dofs: Vec<usize> = (0..24)
        .filter(|&i| free[i / 3] & (1 << (i % 3)) != 0)
        .collect();
    if dofs.is_empty() {
        return 0.0;
    }
    let s = DMatrix::from_fn(dofs.len(), dofs.len(), |p, q| {
        let (i, j) = (dofs[p], dofs[q]);
        0.5 * (k[i][j] + k[j][i]) / (m[i / 3] * m[j / 3]).sqrt()
    });
    SymmetricEigen::new(s)
        .eigenvalues
        .iter()
        .copied()
        .fold(0.0, f64::max)
}

/// The bound for `elements` on nodes of masses `node_mass` whose free DOFs are the bits
/// of `free` (bit d: DOF d free; a node without a free DOF is left out of every element's
/// λ); `stiffness(i)` gives element i's initial elastic stiffness. Deterministic: the
/// result does not depend on the number of threads.
pub fn shared_mass_bound(
    elements: &[SharedElement],
    node_mass: &[f64],
    free: &[u8],
    stiffness: impl Fn(usize) -> ElementStiffness + Sync,
) -> SharedMassBound {
    let n = node_mass.len();
    let mut weight = vec![1.0f64; elements.len()];
    let mut stiff: Vec<Option<Box<ElementStiffness>>> = vec![None; elements.len()];
    let mut best = SharedMassBound {
        omega_squared: f64::INFINITY,
        element: 0,
        evaluated: 0,
    };
    let frees: Vec<[u8; 8]> = elements
        .iter()
        .map(|e| e.conn.map(|a| free[a as usize] & 0b111))
        .collect();
    for _ in 0..ROUNDS {
        let mut shared = vec![0.0f64; n];
        for (e, &w) in elements.iter().zip(&weight) {
            for a in 0..8 {
                shared[e.conn[a] as usize] += w * e.own_mass[a];
            }
        }
        let split = |i: usize| -> [f64; 8] {
            let e = &elements[i];
            std::array::from_fn(|a| {
                let node = e.conn[a] as usize;
                node_mass[node] * (weight[i] * e.own_mass[a] / shared[node])
            })
        };
        // The cheap bound of every element.
        let cheap: Vec<f64> = (0..elements.len())
            .into_par_iter()
            .map(|i| {
                let m = split(i);
                let e = &elements[i];
                let ratio = (0..8)
                    .filter(|&a| frees[i][a] != 0)
                    .map(|a| e.own_mass[a] / m[a])
                    .fold(0.0, f64::max);
                e.own_bound * ratio
            })
            .collect();
        let top = cheap.iter().copied().fold(0.0, f64::max);
        // Exact evaluation for the elements whose cheap bound reaches half the largest,
        // so that the round's maximum is exact where it matters.
        let newly: Vec<usize> = (0..elements.len())
            .filter(|&i| {
                stiff[i].is_none() && cheap[i] >= 0.5 * top && frees[i].iter().any(|&f| f != 0)
            })
            .collect();
        let computed: Vec<(usize, Box<ElementStiffness>)> = newly
            .par_iter()
            .map(|&i| (i, Box::new(stiffness(i))))
            .collect();
        for (i, k) in computed {
            stiff[i] = Some(k);
        }
        // Both are bounds: the smaller stands.
        let lambda: Vec<f64> = (0..elements.len())
            .into_par_iter()
            .map(|i| match &stiff[i] {
                Some(k) => split_eigenvalue(k, &split(i), &frees[i]).min(cheap[i]),
                None => cheap[i],
            })
            .collect();
        let (element, omega_squared) = lambda
            .iter()
            .copied()
            .enumerate()
            .fold((0, 0.0), |acc, (i, l)| if l > acc.1 { (i, l) } else { acc });
        if omega_squared < best.omega_squared {
            best = SharedMassBound {
                omega_squared,
                element,
                evaluated: stiff.iter().filter(|k| k.is_some()).count(),
            };
        }
        if omega_squared.is_nan() || omega_squared <= 0.0 {
            break;
        }
        // More of its nodes' mass to an element near the largest λ, less to one far from it.
        for (w, &l) in weight.iter_mut().zip(&lambda) {
            *w *= (l / omega_squared).max(1e-3);
        }
    }
    best
}
