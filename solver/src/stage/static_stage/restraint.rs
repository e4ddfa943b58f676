//! Before a direct solve: every connected body (active elements joined by shared nodes and
//! by tied contact pairs) must be held against the six rigid-body motions by its
//! constrained DOFs, else K is singular. The check is exact and cheap (a 6 × 6 Gram matrix
//! per body) and names the body and the free motion, which a failed pivot cannot.

use nalgebra::{Matrix6, SymmetricEigen};

use super::dofs::find;
use crate::error::{DcfmError, Result};
use crate::model::Model;

/// Check that no body of active elements can move as a rigid body. `constrained` are the
/// node masks (dormant nodes have no active element and do not count), `ties` the node
/// pairs that move together.
pub fn check_restrained(model: &Model, constrained: &[u8], ties: &[(u32, u32)]) -> Result<()> {
    let n = model.mesh.n_nodes();
    let mut parent: Vec<u32> = (0..n as u32).collect();
    let union = |p: &mut Vec<u32>, a: u32, b: u32| {
        let (ra, rb) = (find(p, a), find(p, b));
        if ra != rb {
            p[ra.max(rb) as usize] = ra.min(rb);
        }
    };
    let mut in_body = vec![false; n];
    let mut elements_of = vec![0usize; n];
    for g in &model.groups {
        for conn in &g.conn {
            for &a in conn {
                in_body[a as usize] = true;
                union(&mut parent, conn[0], a);
            }
        }
    }
    for &(a, b) in ties {
        union(&mut parent, a, b);
    }
    for g in &model.groups {
        for conn in &g.conn {
            let r = find(&mut parent, conn[0]) as usize;
            elements_of[r] += 1;
        }
    }
    // Centroid and size of every body.
    let mut centre = vec![[0.0; 3]; n];
    let mut count = vec![0usize; n];
    let root: Vec<u32> = (0..n as u32).map(|i| find(&mut parent, i)).collect();
    for i in 0..n {
        if in_body[i] {
            let r = root[i] as usize;
            for d in 0..3 {
                centre[r][d] += model.mesh.coords[i][d];
            }
            count[r] += 1;
        }
    }
    for r in 0..n {
        if count[r] > 0 {
            centre[r] = centre[r].map(|c| c / count[r] as f64);
        }
    }
    let mut size = vec![0.0f64; n];
    for i in 0..n {
        if in_body[i] {
            let r = root[i] as usize;
            let x = model.mesh.coords[i];
            let d: f64 = (0..3)
                .map(|k| (x[k] - centre[r][k]).powi(2))
                .sum::<f64>()
                .sqrt();
            size[r] = size[r].max(d);
        }
    }
    // Gram matrix of the rigid modes restricted to the constrained DOFs.
    let mut gram: Vec<Option<Matrix6<f64>>> = vec![None; n];
    for i in 0..n {
        if !in_body[i] {
            continue;
        }
        let r = root[i] as usize;
        let g = gram[r].get_or_insert_with(Matrix6::zeros);
        if constrained[i] == 0 {
            continue;
        }
        let l = size[r].max(f64::MIN_POSITIVE);
        let x: [f64; 3] = std::array::from_fn(|k| (model.mesh.coords[i][k] - centre[r][k]) / l);
        for d in 0..3 {
            if constrained[i] & (1 << d) == 0 {
                continue;
            }
            // Component d of the six modes: translations e_m, rotations e_m × x.
            let mut v = [0.0; 6];
            v[d] = 1.0;
            let rot = [[0.0, -x[2], x[1]], [x[2], 0.0, -x[0]], [-x[1], x[0], 0.0]];
            v[3..6].copy_from_slice(&rot[d]);
            for p in 0..6 {
                for q in 0..6 {
                    g[(p, q)] += v[p] * v[q];
                }
            }
        }
    }
    const NAMES: [&str; 6] = [
        "translate along x",
        "translate along y",
        "translate along z",
        "rotate about x",
        "rotate about y",
        "rotate about z",
    ];
    for r in 0..n {
        let Some(g) = gram[r] else { continue };
        let eig = SymmetricEigen::new(g);
        let (k, &lmin) = eig
            .eigenvalues
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .expect("six eigenvalues");
        if lmin > 1e-9 {
            continue;
        }
        let v = eig.eigenvectors.column(k);
        let (m, _) = v
            .iter()
            .enumerate()
            .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))
            .expect("six components");
        let x = model.mesh.coords[r];
        return Err(DcfmError::invalid(
            "",
            "static",
            format!(
                "a body of {} active elements containing node {r} at ({:.3}, {:.3}, {:.3})",
                elements_of[r], x[0], x[1], x[2]
            ),
            format!(
                "is not restrained: it can {} (unconstrained rigid body: add static boundary \
                 conditions (static.fixed) or bond it to a supported body)",
                NAMES[m]
            ),
        ));
    }
    Ok(())
}
