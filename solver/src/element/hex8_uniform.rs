//! One-point hex8 with the uniform-strain (mean) gradient and Flanagan–Belytschko
//! hourglass control (Flanagan & Belytschko 1981, IJNME 17:679–706, eqs. 14–16 and 55).
//!
//! The mean gradient b_ai = (1/V) ∫ ∂N_a/∂x_i dV is integrated exactly (2×2×2 Gauss), so
//! the element passes the constant-strain patch test on any trilinear shape. Hourglass
//! shape vectors γ_αa = Γ_αa − (Σ_b Γ_αb x_bj) b_aj are orthogonal to every linear field;
//! the stiffness-type hourglass force is f_ai = κ Σ_α γ_αa q_αi, q_αi = Σ_a γ_αa u_ai, with
//! κ = ε_hg (λ+2μ) V (b_ai b_ai) / 8 from the initial elastic moduli.

use crate::element::hex8_shape::{cartesian_derivatives, gauss_points, NODE_XI};
use crate::material::{Elastic, Material, PointContext, Voigt};

/// Hourglass base vectors Γ_α (α = ηζ, ζξ, ξη, ξηζ) at the nodes.
pub fn hourglass_base() -> [[f64; 8]; 4] {
    let mut g = [[0.0; 8]; 4];
    for (a, n) in NODE_XI.iter().enumerate() {
        g[0][a] = n[1] * n[2];
        g[1][a] = n[2] * n[0];
        g[2][a] = n[0] * n[1];
        g[3][a] = n[0] * n[1] * n[2];
    }
    g
}

/// Precomputed geometry of one one-point element (464 bytes).
#[derive(Clone, Copy, Debug, Default)]
pub struct UniformGeometry {
    /// Mean gradient b_ai (1/m).
    pub b: [[f64; 3]; 8],
    /// Volume V (m³).
    pub volume: f64,
    /// Hourglass shape vectors γ_αa.
    pub gamma: [[f64; 8]; 4],
    /// Hourglass stiffness κ (N/m).
    pub kappa: f64,
}

impl UniformGeometry {
    /// Geometry of an element with nodal coordinates `x`; `None` if det J ≤ 0 somewhere.
    pub fn new(x: &[[f64; 3]; 8], elastic: &Elastic, hourglass: f64) -> Option<Self> {
        let mut bv = [[0.0; 3]; 8];
        let mut volume = 0.0;
        for p in gauss_points() {
            let (d, det) = cartesian_derivatives(x, &p)?;
            volume += det;
            for a in 0..8 {
                for i in 0..3 {
                    bv[a][i] += d[a][i] * det;
                }
            }
        }
        let b = bv.map(|r| r.map(|v| v / volume));
        let base = hourglass_base();
        let mut gamma = [[0.0; 8]; 4];
        for al in 0..4 {
            let mut gx = [0.0; 3];
            for a in 0..8 {
                for j in 0..3 {
                    gx[j] += base[al][a] * x[a][j];
                }
            }
            for a in 0..8 {
                gamma[al][a] = base[al][a] - (gx[0] * b[a][0] + gx[1] * b[a][1] + gx[2] * b[a][2]);
            }
        }
        let bb: f64 = b.iter().flatten().map(|v| v * v).sum();
        let kappa = hourglass * elastic.p_modulus() * volume * bb / 8.0;
        Some(Self {
            b,
            volume,
            gamma,
            kappa,
        })
    }

    /// Strain ε = Σ_a B_a u_a (Voigt, engineering shear).
    #[inline(always)]
    pub fn strain(&self, u: &[[f64; 3]; 8]) -> Voigt {
        let mut e = [0.0; 6];
        for a in 0..8 {
            let (bx, by, bz) = (self.b[a][0], self.b[a][1], self.b[a][2]);
            let (ux, uy, uz) = (u[a][0], u[a][1], u[a][2]);
            e[0] += bx * ux;
            e[1] += by * uy;
            e[2] += bz * uz;
            e[3] += by * ux + bx * uy;
            e[4] += bz * uy + by * uz;
            e[5] += bx * uz + bz * ux;
        }
        e
    }

    /// Hourglass generalised displacements q_αi.
    #[inline(always)]
    pub fn hourglass_modes(&self, u: &[[f64; 3]; 8]) -> [[f64; 3]; 4] {
        let mut q = [[0.0; 3]; 4];
        for al in 0..4 {
            for a in 0..8 {
                let g = self.gamma[al][a];
                q[al][0] += g * u[a][0];
                q[al][1] += g * u[a][1];
                q[al][2] += g * u[a][2];
            }
        }
        q
    }

    /// Nodal forces V Bᵀσ + κ Σ_α γ_α q_α, written into `f`.
    #[inline(always)]
    pub fn forces(&self, s: &Voigt, q: &[[f64; 3]; 4], f: &mut [[f64; 3]; 8]) {
        let v = self.volume;
        for a in 0..8 {
            let (bx, by, bz) = (self.b[a][0] * v, self.b[a][1] * v, self.b[a][2] * v);
            let mut fx = bx * s[0] + by * s[3] + bz * s[5];
            let mut fy = bx * s[3] + by * s[1] + bz * s[4];
            let mut fz = bx * s[5] + by * s[4] + bz * s[2];
            for al in 0..4 {
                let g = self.kappa * self.gamma[al][a];
                fx += g * q[al][0];
                fy += g * q[al][1];
                fz += g * q[al][2];
            }
            f[a] = [fx, fy, fz];
        }
    }
}

/// Internal force of one one-point element (the K U term of eq. 1 for a nonlinear
/// material): strain from `u`, stress from the material (state `old` → `new`), nodal
/// forces V Bᵀσ plus the hourglass forces. Returns the stress.
#[inline(always)]
pub fn internal_force(
    geo: &UniformGeometry,
    material: &Material,
    u: &[[f64; 3]; 8],
    old: &[f64],
    new: &mut [f64],
    ctx: &PointContext,
    f: &mut [[f64; 3]; 8],
) -> Voigt {
    let eps = geo.strain(u);
    let sigma = material.update(&eps, old, new, ctx);
    let q = geo.hourglass_modes(u);
    geo.forces(&sigma, &q, f);
    sigma
}

#[cfg(test)]
mod tests {
    use super::*;

    fn distorted() -> [[f64; 3]; 8] {
        [
            [0.0, 0.0, 0.0],
            [1.1, 0.05, -0.02],
            [1.2, 0.9, 0.1],
            [-0.1, 1.05, 0.0],
            [0.05, -0.1, 1.0],
            [1.0, 0.1, 1.2],
            [1.1, 1.1, 0.95],
            [0.0, 0.9, 1.1],
        ]
    }

    #[test]
    fn mean_gradient_reproduces_linear_field_and_hourglass_vanishes() {
        let x = distorted();
        let el = Elastic::new("m", 1e9, 0.3, 1000.0).unwrap();
        let g = UniformGeometry::new(&x, &el, 0.05).unwrap();
        let grad = [[1e-3, 2e-3, -1e-3], [0.5e-3, -2e-3, 0.0], [0.0, 1e-3, 3e-3]];
        let u: [[f64; 3]; 8] = std::array::from_fn(|a| {
            std::array::from_fn(|i| 0.01 + (0..3).map(|j| grad[i][j] * x[a][j]).sum::<f64>())
        });
        let e = g.strain(&u);
        let expect = [
            grad[0][0],
            grad[1][1],
            grad[2][2],
            grad[0][1] + grad[1][0],
            grad[1][2] + grad[2][1],
            grad[0][2] + grad[2][0],
        ];
        for i in 0..6 {
            assert!(
                (e[i] - expect[i]).abs() < 1e-15,
                "{i}: {} vs {}",
                e[i],
                expect[i]
            );
        }
        let q = g.hourglass_modes(&u);
        for row in q {
            for v in row {
                assert!(v.abs() < 1e-15);
            }
        }
    }
}
