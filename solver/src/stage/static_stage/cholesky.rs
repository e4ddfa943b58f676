//! Sparse Cholesky factorisation K = L Lᵀ of the assembled stiffness (faer), with a
//! fill-reducing ordering and a check of every pivot.
//!
//! - Ordering: approximate minimum degree (faer's AMD) and geometric nested dissection
//!   (`nested_dissection.rs`), both on the graph of the nodes and expanded to their DOFs
//!   (the DOFs of a node have the same sparsity, so ordering the 9× smaller node graph
//!   gives the same fill at a fraction of the cost); the one whose symbolic factor has
//!   fewer nonzeros is used (nested dissection on 3D meshes, by a factor of 2–4).
//! - Factorisation: faer chooses the supernodal (dense BLAS-3 blocks) or simplicial form
//!   from the flop count per nonzero of L; either can be forced (`CholeskyKind`). On 3D
//!   meshes supernodal wins by far (measured in `docs/static_stage.md`).
//! - Sequential (`Par::Seq`): the result does not depend on the number of threads.
//! - Pivots: a pivot d_j = L_jj² that is not positive, or below 1e-10 of the diagonal
//!   entry K_jj it started from, means that the stiffness has no positive value in some
//!   direction: a body or a node free to move (unconstrained rigid body, a node held by
//!   nothing, zero hourglass stiffness). The error names the DOF (node, direction).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::{LltError, LltRegularization};
use faer::sparse::linalg::cholesky::{
    factorize_symbolic_cholesky, supernodal::SupernodalLltRef, CholeskySymbolicParams,
    SymbolicCholesky, SymbolicCholeskyRaw, SymmetricOrdering,
};
use faer::sparse::linalg::{amd, SupernodalThreshold};
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};
use faer::{Conj, MatMut, Par, Side, Spec};

use super::assembly::Stiffness;

/// Which factorisation faer uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum CholeskyKind {
    /// faer's choice from the flop count (supernodal on 3D meshes).
    #[default]
    Auto,
    Simplicial,
    Supernodal,
}

/// A failed factorisation: the equation (in the stiffness' numbering) where the pivot
/// failed and its value relative to the diagonal, or a resource error.
#[derive(Clone, Debug, PartialEq)]
pub enum FactorError {
    /// Pivot d of equation `eq` is ≤ 0 or ≤ 1e-10 K_jj (`ratio` = d / K_jj).
    Pivot { eq: usize, ratio: f64 },
    /// Memory or index overflow in faer.
    Resource(String),
}

/// Relative size below which a pivot is taken as zero.
pub const PIVOT_TOLERANCE: f64 = 1e-10;

/// The factorisation of one stiffness.
pub struct Factorization {
    symbolic: SymbolicCholesky<usize>,
    values: Vec<f64>,
    n: usize,
    /// Nonzeros of L.
    pub l_nnz: usize,
    /// Supernodal (true) or simplicial.
    pub supernodal: bool,
    /// The fill-reducing ordering used.
    pub ordering: Ordering,
}

/// Fill-reducing ordering of the equations.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (faer) on the node graph.
    MinimumDegree,
    /// Geometric nested dissection on the node graph.
    NestedDissection,
}

/// Expand a node order to the DOF permutation (`fwd[new] = old`, and its inverse).
fn expand(k: &Stiffness, node_order: &[usize]) -> (Vec<usize>, Vec<usize>) {
    let mut fwd = Vec::with_capacity(k.n);
    for &node in node_order {
        fwd.extend(k.node_eqs[node].iter().map(|&e| e as usize));
    }
    let mut inv = vec![0usize; k.n];
    for (new, &old) in fwd.iter().enumerate() {
        inv[old] = new;
    }
    (fwd, inv)
}

/// The DOF permutation from AMD on the node graph: `fwd[new] = old`.
fn node_amd_permutation(k: &Stiffness) -> Result<(Vec<usize>, Vec<usize>), FactorError> {
    let nn = k.node_eqs.len();
    let mut fwd_n = vec![0usize; nn];
    let mut inv_n = vec![0usize; nn];
    let graph =
        SymbolicSparseColMatRef::new_checked(nn, nn, &k.node_col_ptr, None, &k.node_row_idx);
    let req = amd::order_scratch::<usize>(nn, k.node_row_idx.len());
    let mut mem = MemBuffer::try_new(req)
        .map_err(|_| FactorError::Resource("out of memory in AMD".into()))?;
    amd::order(
        &mut fwd_n,
        &mut inv_n,
        graph,
        amd::Control::default(),
        MemStack::new(&mut mem),
    )
    .map_err(|e| FactorError::Resource(format!("AMD ordering: {e:?}")))?;
    Ok(expand(k, &fwd_n))
}

/// Symbolic factorisation of `k` under the permutation (`fwd`, `inv`).
fn symbolic(
    k: &Stiffness,
    fwd: &[usize],
    inv: &[usize],
    kind: CholeskyKind,
) -> Result<SymbolicCholesky<usize>, FactorError> {
    let perm = faer::perm::PermRef::new_checked(fwd, inv, k.n);
    let pattern = SymbolicSparseColMatRef::new_checked(k.n, k.n, &k.col_ptr, None, &k.row_idx);
    let threshold = match kind {
        CholeskyKind::Auto => SupernodalThreshold::AUTO,
        CholeskyKind::Simplicial => SupernodalThreshold::FORCE_SIMPLICIAL,
        CholeskyKind::Supernodal => SupernodalThreshold::FORCE_SUPERNODAL,
    };
    let params = CholeskySymbolicParams {
        supernodal_flop_ratio_threshold: threshold,
        ..Default::default()
    };
    factorize_symbolic_cholesky(
        pattern,
        Side::Upper,
        SymmetricOrdering::Custom(perm),
        params,
    )
    .map_err(|e| FactorError::Resource(format!("symbolic Cholesky: {e:?}")))
}

/// The ordering and the symbolic factorisation of a stiffness: the size of the factor is
/// known before any number of it is computed.
pub struct Analysis {
    symbolic: SymbolicCholesky<usize>,
    fwd: Vec<usize>,
    ordering: Ordering,
}

impl Analysis {
    /// Order and analyse `k` (upper triangle).
    pub fn new(k: &Stiffness, kind: CholeskyKind) -> Result<Self, FactorError> {
        // The ordering that fills less: AMD or nested dissection (both on the node graph).
        let (fwd_a, inv_a) = node_amd_permutation(k)?;
        let sym_a = symbolic(k, &fwd_a, &inv_a, kind)?;
        let nd = super::nested_dissection::order(&k.node_col_ptr, &k.node_row_idx, &k.node_coords);
        let (fwd_d, inv_d) = expand(k, &nd);
        let sym_d = symbolic(k, &fwd_d, &inv_d, kind)?;
        let (symbolic, fwd, ordering) = if sym_d.len_val() < sym_a.len_val() {
            (sym_d, fwd_d, Ordering::NestedDissection)
        } else {
            (sym_a, fwd_a, Ordering::MinimumDegree)
        };
        Ok(Self {
            symbolic,
            fwd,
            ordering,
        })
    }

    /// Nonzeros of L (8 bytes each).
    pub fn l_nnz(&self) -> usize {
        self.symbolic.len_val()
    }

    /// Factorise `k` (the stiffness analysed).
    pub fn factorize(self, k: &Stiffness) -> Result<Factorization, FactorError> {
        let Self {
            symbolic,
            fwd,
            ordering,
        } = self;
        let n = k.n;
        let pattern = SymbolicSparseColMatRef::new_checked(n, n, &k.col_ptr, None, &k.row_idx);
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let req = symbolic.factorize_numeric_llt_scratch::<f64>(par, Spec::default());
        let mut mem = MemBuffer::try_new(req).map_err(|_| {
            FactorError::Resource("out of memory in the Cholesky factorisation".into())
        })?;
        let a = SparseColMatRef::new(pattern, &k.values);
        let supernodal = matches!(symbolic.raw(), SymbolicCholeskyRaw::Supernodal(_));
        let outcome = symbolic.factorize_numeric_llt(
            &mut values,
            a,
            Side::Upper,
            LltRegularization::default(),
            par,
            MemStack::new(&mut mem),
            Spec::default(),
        );
        // Permuted position of the failed pivot: simplicial reports it 1-based, supernodal
        // 0-based (faer 0.24).
        if let Err(e) = outcome {
            let LltError::NonPositivePivot { index } = e;
            let pos = if supernodal {
                index
            } else {
                index.saturating_sub(1)
            };
            let pos = pos.min(n.saturating_sub(1));
            return Err(FactorError::Pivot {
                eq: fwd[pos],
                ratio: f64::NAN,
            });
        }
        let fact = Factorization {
            l_nnz: values.len(),
            symbolic,
            values,
            n,
            supernodal,
            ordering,
        };
        // Pivot check: d_j = L_jj² against K_jj of the same (permuted) equation.
        let diag = fact.l_diagonal();
        let mut worst: Option<(usize, f64)> = None;
        for (pos, &l) in diag.iter().enumerate() {
            let eq = fwd[pos];
            let kjj = k.diagonal(eq);
            let ratio = if kjj > 0.0 { l * l / kjj } else { 0.0 };
            if ratio <= PIVOT_TOLERANCE && worst.is_none_or(|w| ratio < w.1) {
                worst = Some((eq, ratio));
            }
        }
        if let Some((eq, ratio)) = worst {
            return Err(FactorError::Pivot { eq, ratio });
        }
        Ok(fact)
    }
}

impl Factorization {
    /// Order, analyse and factorise `k` (upper triangle).
    pub fn new(k: &Stiffness, kind: CholeskyKind) -> Result<Self, FactorError> {
        Analysis::new(k, kind)?.factorize(k)
    }

    /// L_jj in the permuted order.
    fn l_diagonal(&self) -> Vec<f64> {
        let mut d = vec![0.0; self.n];
        match self.symbolic.raw() {
            SymbolicCholeskyRaw::Simplicial(s) => {
                let cp = s.col_ptr();
                for (j, dj) in d.iter_mut().enumerate() {
                    *dj = self.values[cp[j]];
                }
            }
            SymbolicCholeskyRaw::Supernodal(s) => {
                let l = SupernodalLltRef::new(s, &self.values);
                for sn in 0..s.n_supernodes() {
                    let node = l.supernode(sn);
                    let start = node.start();
                    let m = node.val();
                    for k in 0..m.ncols() {
                        d[start + k] = m[(k, k)];
                    }
                }
            }
        }
        d
    }

    /// Solve K x = b in place (`b` becomes x).
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let par = Par::Seq;
        let req = self.symbolic.solve_in_place_scratch::<f64>(1, par);
        let mut mem = MemBuffer::new(req);
        let llt = faer::sparse::linalg::cholesky::LltRef::<'_, usize, f64>::new(
            &self.symbolic,
            &self.values,
        );
        let rhs = MatMut::from_column_major_slice_mut(b, self.n, 1);
        llt.solve_in_place_with_conj(Conj::No, rhs, par, MemStack::new(&mut mem));
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 1D chain of springs as a `Stiffness` (one equation per node).
    fn chain(n: usize, k_end: f64) -> Stiffness {
        let mut col_ptr = vec![0];
        let mut row_idx = Vec::new();
        let mut values = Vec::new();
        for c in 0..n {
            if c > 0 {
                row_idx.push(c - 1);
                values.push(-1.0);
            }
            row_idx.push(c);
            values.push(if c == 0 {
                1.0 + k_end
            } else if c + 1 == n {
                1.0
            } else {
                2.0
            });
            col_ptr.push(row_idx.len());
        }
        Stiffness {
            n,
            node_col_ptr: col_ptr.clone(),
            node_row_idx: row_idx.clone(),
            node_eqs: (0..n as u32).map(|e| vec![e]).collect(),
            node_coords: (0..n).map(|i| [i as f64, 0.0, 0.0]).collect(),
            col_ptr,
            row_idx,
            values,
        }
    }

    #[test]
    fn solves_a_spring_chain_both_kinds() {
        for kind in [
            CholeskyKind::Simplicial,
            CholeskyKind::Supernodal,
            CholeskyKind::Auto,
        ] {
            let k = chain(50, 1.0);
            let f = Factorization::new(&k, kind).unwrap();
            // Unit load at the free end: u_j = j + 1 (springs of stiffness 1 in series).
            let mut b = vec![0.0; 50];
            b[49] = 1.0;
            f.solve_in_place(&mut b);
            for (j, x) in b.iter().enumerate() {
                assert!((x - (j as f64 + 1.0)).abs() < 1e-10, "{kind:?} {j}: {x}");
            }
        }
    }

    #[test]
    fn singular_chain_names_an_equation() {
        for kind in [CholeskyKind::Simplicial, CholeskyKind::Supernodal] {
            let k = chain(20, 0.0);
            match Factorization::new(&k, kind) {
                Err(FactorError::Pivot { eq, ratio }) => {
                    assert!(eq < 20);
                    assert!(ratio.is_nan() || ratio <= PIVOT_TOLERANCE);
                }
                Err(e) => panic!("{kind:?}: {e:?}"),
                Ok(_) => panic!("{kind:?}: factorised a singular matrix"),
            }
        }
    }
}
