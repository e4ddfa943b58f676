//! The largest eigenvalue of the assembled M⁻¹K by a dense symmetric eigensolve: the exact
//! critical step 2/ω_max (Belytschko, Liu & Moran 2000, §6.2) of a small model, the
//! reference the element-wise step bounds are checked against (W13,
//! `tests/shared_mass_step.rs`). O(n³) in the free DOFs: a few thousand at most.

use nalgebra::DMatrix;

use crate::model::Model;
use crate::stage::static_stage::assembly::assemble;
use crate::stage::static_stage::dofs::DofMap;

/// ω²_max of M⁻¹K on the free DOFs of `model`: K of its element groups with the initial
/// elastic moduli (hourglass stiffness included, `static_stage::assembly`), M its lumped
/// nodal masses; the nodes of no element are left out.
pub fn omega_max_squared(model: &Model) -> f64 {
    let mut dormant = vec![true; model.mesh.n_nodes()];
    for group in &model.groups {
        for conn in &group.conn {
            for &a in conn {
                dormant[a as usize] = false;
            }
        }
    }
    let dofs = DofMap::new(&model.constraints.constrained, &dormant, &[]);
    let k = assemble(model, &dofs);
    let scale: Vec<f64> = dofs
        .owner
        .iter()
        .map(|&(node, _)| 1.0 / model.mass[node as usize].sqrt())
        .collect();
    let mut s = DMatrix::<f64>::zeros(k.n, k.n);
    for c in 0..k.n {
        for p in k.col_ptr[c]..k.col_ptr[c + 1] {
            let r = k.row_idx[p];
            let v = k.values[p] * scale[r] * scale[c];
            s[(r, c)] = v;
            s[(c, r)] = v;
        }
    }
    s.symmetric_eigen()
        .eigenvalues
        .iter()
        .fold(0.0, |a, &b| a.max(b))
}
