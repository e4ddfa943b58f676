//! The assembled stiffness of the active elements over the equations of a [`DofMap`]:
//! the upper triangle of K in compressed sparse columns (rows sorted), built from the
//! node graph (3 × 3 blocks) and filled element by element in a fixed order, so the values
//! do not depend on the number of threads (the element matrices are computed in parallel
//! chunks, added serially).

use rayon::prelude::*;

use super::dofs::{DofMap, NO_EQ};
use crate::element::stiffness::ElementStiffness;
use crate::model::Model;

/// Elements per chunk whose matrices are computed in parallel before being added.
const CHUNK: usize = 2048;

/// The upper triangle (row ≤ column) of the assembled stiffness.
#[derive(Clone, Debug)]
pub struct Stiffness {
    /// Number of equations.
    pub n: usize,
    pub col_ptr: Vec<usize>,
    pub row_idx: Vec<usize>,
    pub values: Vec<f64>,
    /// Graph of the tie-group nodes that carry equations (upper triangle with diagonal,
    /// compact numbering): the fill-reducing ordering works on it (9× smaller than the DOF
    /// graph), then expands it to the equations.
    pub node_col_ptr: Vec<usize>,
    pub node_row_idx: Vec<usize>,
    /// Equations of each compact node, ascending.
    pub node_eqs: Vec<Vec<u32>>,
    /// Coordinates of each compact node (for the nested-dissection ordering).
    pub node_coords: Vec<[f64; 3]>,
}

impl Stiffness {
    /// Number of stored entries (upper triangle).
    pub fn nnz(&self) -> usize {
        self.row_idx.len()
    }

    /// Diagonal entry of equation `c`.
    pub fn diagonal(&self, c: usize) -> f64 {
        let rows = &self.row_idx[self.col_ptr[c]..self.col_ptr[c + 1]];
        match rows.binary_search(&c) {
            Ok(k) => self.values[self.col_ptr[c] + k],
            Err(_) => 0.0,
        }
    }

    /// y = K x (both triangles), for residual checks.
    pub fn multiply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for c in 0..self.n {
            for k in self.col_ptr[c]..self.col_ptr[c + 1] {
                let r = self.row_idx[k];
                let v = self.values[k];
                y[r] += v * x[c];
                if r != c {
                    y[c] += v * x[r];
                }
            }
        }
    }
}

/// Equations of the 24 DOFs of an element.
fn element_eqs(dofs: &DofMap, conn: &[u32; 8]) -> [u32; 24] {
    std::array::from_fn(|p| dofs.eq[conn[p / 3] as usize][p % 3])
}

/// Assemble the stiffness of every element of `model.groups` (the active ones) with the
/// initial elastic moduli, hourglass stiffness included.
pub fn assemble(model: &Model, dofs: &DofMap) -> Stiffness {
    let n_nodes = model.mesh.n_nodes();
    // Compact numbering of the tie groups that carry equations, in node order (so that the
    // equations, numbered by representative node, ascend with it).
    let mut compact = vec![u32::MAX; n_nodes];
    let mut node_eqs: Vec<Vec<u32>> = Vec::new();
    let mut node_coords = Vec::new();
    for i in 0..n_nodes {
        if dofs.group[i] as usize == i && dofs.eq[i].iter().any(|&e| e != NO_EQ) {
            compact[i] = node_eqs.len() as u32;
            node_eqs.push(dofs.eq[i].iter().copied().filter(|&e| e != NO_EQ).collect());
            node_coords.push(model.mesh.coords[i]);
        }
    }
    let nn = node_eqs.len();
    let rep = |a: u32| compact[dofs.group[a as usize] as usize];
    // Node adjacency (upper: neighbour ≤ node), sorted, unique.
    let mut adj: Vec<Vec<u32>> = vec![Vec::new(); nn];
    for g in &model.groups {
        for conn in &g.conn {
            let r: [u32; 8] = conn.map(rep);
            for &a in &r {
                if a == u32::MAX {
                    continue;
                }
                for &b in &r {
                    if b != u32::MAX && b <= a {
                        adj[a as usize].push(b);
                    }
                }
            }
        }
    }
    adj.par_iter_mut().for_each(|l| {
        l.sort_unstable();
        l.dedup();
    });
    let mut node_col_ptr = Vec::with_capacity(nn + 1);
    node_col_ptr.push(0);
    let mut node_row_idx = Vec::new();
    for l in &adj {
        node_row_idx.extend(l.iter().map(|&b| b as usize));
        node_col_ptr.push(node_row_idx.len());
    }
    // DOF pattern: column c of node a holds, for every neighbour b ≤ a, the equations of b
    // that are ≤ c (ascending because equations ascend with the compact node number).
    let n = dofs.n_eq;
    let mut col_ptr = vec![0usize; n + 1];
    let mut row_idx = Vec::new();
    for (a, l) in adj.iter().enumerate() {
        for &c in &node_eqs[a] {
            for &b in l {
                for &r in &node_eqs[b as usize] {
                    if r <= c {
                        row_idx.push(r as usize);
                    }
                }
            }
            col_ptr[c as usize + 1] = row_idx.len();
        }
    }
    drop(adj);
    // (Every equation belongs to exactly one compact node and they were visited in
    // equation order, so every column pointer was written.)
    let mut values = vec![0.0; row_idx.len()];
    let mut k_buf: Vec<ElementStiffness> = Vec::with_capacity(CHUNK);
    for g in &model.groups {
        for start in (0..g.len()).step_by(CHUNK) {
            let end = (start + CHUNK).min(g.len());
            (start..end)
                .into_par_iter()
                .map(|le| g.element_stiffness(le))
                .collect_into_vec(&mut k_buf);
            for (le, ke) in (start..end).zip(&k_buf) {
                let eqs = element_eqs(dofs, &g.conn[le]);
                for q in 0..24 {
                    let c = eqs[q];
                    if c == NO_EQ {
                        continue;
                    }
                    let c = c as usize;
                    let col = &row_idx[col_ptr[c]..col_ptr[c + 1]];
                    for p in 0..24 {
                        let r = eqs[p];
                        if r == NO_EQ || r as usize > c {
                            continue;
                        }
                        let k = col
                            .binary_search(&(r as usize))
                            .expect("pattern holds every element coupling");
                        values[col_ptr[c] + k] += ke[p][q];
                    }
                }
            }
        }
    }
    Stiffness {
        n,
        col_ptr,
        row_idx,
        values,
        node_col_ptr,
        node_row_idx,
        node_eqs,
        node_coords,
    }
}
