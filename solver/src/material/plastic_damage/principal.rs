//! Spectral (principal) decomposition of symmetric Voigt tensors with nalgebra's
//! `SymmetricEigen` on the 3×3 (stack only, no allocation).

use crate::material::Voigt;
use nalgebra::{Matrix3, Vector3};

/// Stress-like Voigt (tensor shear components) → symmetric 3×3.
#[inline]
fn to_matrix(s: &Voigt) -> Matrix3<f64> {
    Matrix3::new(s[0], s[3], s[5], s[3], s[1], s[4], s[5], s[4], s[2])
}

/// Indices of three values in descending order.
#[inline]
fn descending(v: &Vector3<f64>) -> [usize; 3] {
    let mut idx = [0usize, 1, 2];
    if v[idx[0]] < v[idx[1]] {
        idx.swap(0, 1);
    }
    if v[idx[1]] < v[idx[2]] {
        idx.swap(1, 2);
    }
    if v[idx[0]] < v[idx[1]] {
        idx.swap(0, 1);
    }
    idx
}

/// Principal values σ̂₁ ≥ σ̂₂ ≥ σ̂₃ of a stress-like Voigt vector.
#[inline]
pub fn principal_values(s: &Voigt) -> [f64; 3] {
    let v = to_matrix(s).symmetric_eigenvalues();
    let i = descending(&v);
    [v[i[0]], v[i[1]], v[i[2]]]
}

/// Principal values (descending) and the matching unit eigenvectors (columns).
#[derive(Clone, Copy, Debug)]
pub struct Spectral {
    /// σ̂₁ ≥ σ̂₂ ≥ σ̂₃.
    pub values: [f64; 3],
    /// Eigenvector of each value.
    pub vectors: [Vector3<f64>; 3],
}

impl Spectral {
    /// Decompose a stress-like Voigt vector.
    #[inline]
    pub fn of(s: &Voigt) -> Self {
        let e = to_matrix(s).symmetric_eigen();
        let i = descending(&e.eigenvalues);
        Self {
            values: [
                e.eigenvalues[i[0]],
                e.eigenvalues[i[1]],
                e.eigenvalues[i[2]],
            ],
            vectors: [
                e.eigenvectors.column(i[0]).into_owned(),
                e.eigenvectors.column(i[1]).into_owned(),
                e.eigenvectors.column(i[2]).into_owned(),
            ],
        }
    }

    /// Σ cᵢ nᵢ⊗nᵢ as a strain-like Voigt vector (engineering shear = 2 × tensor shear).
    #[inline]
    pub fn strain_voigt(&self, c: &[f64; 3]) -> Voigt {
        let mut t = [0.0; 6];
        for (n, &ck) in self.vectors.iter().zip(c.iter()) {
            t[0] += ck * n[0] * n[0];
            t[1] += ck * n[1] * n[1];
            t[2] += ck * n[2] * n[2];
            t[3] += 2.0 * ck * n[0] * n[1];
            t[4] += 2.0 * ck * n[1] * n[2];
            t[5] += 2.0 * ck * n[2] * n[0];
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reconstructs_the_tensor() {
        let s = [3.0, -1.0, 2.0, 0.5, -0.7, 1.1];
        let sp = Spectral::of(&s);
        assert!(sp.values[0] >= sp.values[1] && sp.values[1] >= sp.values[2]);
        let back = sp.strain_voigt(&sp.values);
        let expect = [3.0, -1.0, 2.0, 1.0, -1.4, 2.2];
        for i in 0..6 {
            assert!((back[i] - expect[i]).abs() < 1e-12, "{i}");
        }
        let v = principal_values(&s);
        for (a, b) in v.iter().zip(sp.values.iter()) {
            assert!((a - b).abs() < 1e-12);
        }
    }
}
