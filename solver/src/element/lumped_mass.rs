//! Lumped (row-sum) mass: M_a = ∫ ρ N_a dV, by 2×2×2 Gauss quadrature.

use crate::element::hex8_shape::{gauss_points, jacobian, shape, shape_derivatives};

/// Row-sum lumped nodal masses of one element of density `rho`; they add up to ρV.
pub fn element_masses(x: &[[f64; 3]; 8], rho: f64) -> [f64; 8] {
    let mut m = [0.0; 8];
    for p in gauss_points() {
        let n = shape(&p);
        let (_, det) = jacobian(x, &shape_derivatives(&p));
        for a in 0..8 {
            m[a] += rho * n[a] * det;
        }
    }
    m
}
