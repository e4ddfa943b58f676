//! Internal forces of the active elements outside the explicit step, the out-of-balance
//! force and the reactions.
//!
//! The out-of-balance ratio is ‖r‖₂ / max(‖f_ext‖₂, ‖f_int‖₂) with r = f_ext − f_int
//! gathered over the equations (the free DOFs of the active nodes; the two nodes of a
//! tied pair sum), so that it compares the unbalanced force with the forces the body
//! carries (FLAC's "ratio" in the 2-norm; with an initial stress, f_int ≠ 0 at u = 0).

use super::dofs::{DofMap, NO_EQ};
use crate::element::groups::{add_internal_forces, ForceSettings};
use crate::model::Model;

/// Scratch buffers for force evaluations (allocated once per stage).
pub struct ForceBuffers {
    pub f_int: Vec<[f64; 3]>,
    f_damp: Vec<[f64; 3]>,
    zero_v: Vec<[f64; 3]>,
}

impl ForceBuffers {
    pub fn new(n_nodes: usize) -> Self {
        Self {
            f_int: vec![[0.0; 3]; n_nodes],
            f_damp: vec![[0.0; 3]; n_nodes],
            zero_v: vec![[0.0; 3]; n_nodes],
        }
    }

    /// f_int(u) of every active element into `self.f_int`, colour by colour (the explicit
    /// core's kernels: deterministic). The material states are written to their pending
    /// buffers; [`commit_states`] makes them the committed ones. Rate-independent update
    /// (a Duvaut–Lions viscosity is relaxed fully: Δt → ∞).
    pub fn internal_forces(&mut self, model: &mut Model, u: &[[f64; 3]]) {
        // Trial passes from the committed state: the states buffered (a model handed
        // back by the explicit core had them in place).
        for g in model.groups.iter_mut() {
            g.set_states_in_place(false);
        }
        self.f_int.iter_mut().for_each(|f| *f = [0.0; 3]);
        let settings = ForceSettings {
            beta: 0.0,
            dt: f64::MAX,
            due: None,
        };
        add_internal_forces(
            &mut model.groups,
            model.n_colours,
            u,
            &self.zero_v,
            |_| settings,
            &mut self.f_int,
            &mut self.f_damp,
        );
    }
}

/// Make the material states of the last [`ForceBuffers::internal_forces`] the committed
/// ones.
pub fn commit_states(model: &mut Model) {
    for g in model.groups.iter_mut() {
        g.commit_states();
    }
}

/// Out-of-balance of a state.
#[derive(Clone, Copy, Debug, Default, PartialEq, serde::Serialize)]
pub struct OutOfBalance {
    /// ‖r‖ / max(‖f_ext‖, ‖f_int‖) (0 when both vanish).
    pub ratio: f64,
    /// ‖r‖₂ (N).
    pub norm: f64,
    /// max(‖f_ext‖₂, ‖f_int‖₂) (N).
    pub reference: f64,
    /// Largest |r| of one DOF (N), its node and direction.
    pub max: f64,
    pub node: usize,
    pub dof: usize,
}

impl OutOfBalance {
    /// Measure r = f_ext − f_int over the equations of `dofs` (`scratch`: reused buffer).
    pub fn measure(
        dofs: &DofMap,
        f_ext: &[[f64; 3]],
        f_int: &[[f64; 3]],
        scratch: &mut Vec<f64>,
    ) -> Self {
        Self::evaluate(dofs, None, f_ext, f_int, scratch)
    }

    /// The same with the out-of-balance force `r` given per node (e.g. from the explicit
    /// step, contact forces included); f_ext and f_int give the reference.
    pub fn from_residual(
        dofs: &DofMap,
        r: &[[f64; 3]],
        f_ext: &[[f64; 3]],
        f_int: &[[f64; 3]],
        scratch: &mut Vec<f64>,
    ) -> Self {
        Self::evaluate(dofs, Some(r), f_ext, f_int, scratch)
    }

    fn evaluate(
        dofs: &DofMap,
        residual: Option<&[[f64; 3]]>,
        f_ext: &[[f64; 3]],
        f_int: &[[f64; 3]],
        scratch: &mut Vec<f64>,
    ) -> Self {
        let n = dofs.n_eq;
        scratch.clear();
        scratch.resize(3 * n, 0.0);
        let (e, rest) = scratch.split_at_mut(n);
        let (i, res) = rest.split_at_mut(n);
        dofs.gather(f_ext, e);
        dofs.gather(f_int, i);
        if let Some(r) = residual {
            dofs.gather(r, res);
        } else {
            for k in 0..n {
                res[k] = e[k] - i[k];
            }
        }
        let (mut rr, mut ee, mut ii) = (0.0, 0.0, 0.0);
        let mut worst = (0.0f64, 0usize);
        for k in 0..n {
            let r = res[k];
            rr += r * r;
            ee += e[k] * e[k];
            ii += i[k] * i[k];
            if r.abs() > worst.0 {
                worst = (r.abs(), k);
            }
        }
        let reference = ee.sqrt().max(ii.sqrt());
        let norm = rr.sqrt();
        let (node, dof) = dofs
            .owner
            .get(worst.1)
            .map_or((0, 0), |&(n, d)| (n as usize, d as usize));
        Self {
            ratio: if reference > 0.0 {
                norm / reference
            } else {
                0.0
            },
            norm,
            reference,
            max: worst.0,
            node,
            dof,
        }
    }
}

/// Reactions at the constrained DOFs (bit set in `constrained`) of the active nodes:
/// R = f_int − f_ext (the force the support applies). Nodes with no constrained DOF, and
/// dormant nodes, are left out; free DOFs of a listed node are 0.
pub fn reactions(
    constrained: &[u8],
    dormant: &[bool],
    f_ext: &[[f64; 3]],
    f_int: &[[f64; 3]],
) -> Vec<(u32, [f64; 3])> {
    let mut out = Vec::new();
    for i in 0..constrained.len() {
        if dormant[i] || constrained[i] == 0 {
            continue;
        }
        let r: [f64; 3] = std::array::from_fn(|d| {
            if constrained[i] & (1 << d) != 0 {
                f_int[i][d] - f_ext[i][d]
            } else {
                0.0
            }
        });
        out.push((i as u32, r));
    }
    out
}

/// Whether DOF d of node i has an equation.
#[inline]
pub fn is_free(dofs: &DofMap, i: usize, d: usize) -> bool {
    dofs.eq[i][d] != NO_EQ
}
