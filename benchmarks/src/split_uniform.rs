//! The prototype of the one-point hex8 kernel that `dcfm::element::hex8_uniform` adopted
//! (issue #2): the same nodal forces from less data and fewer flops. It stays as an
//! independent implementation, compared with the solver's by a unit test and by the
//! `hex8_kernels` bench.
//!
//! The solver stored the hourglass shape vectors γ_αa = Γ_αa − Σ_j h_αj b_aj (32 values)
//! with h_αj = Σ_b Γ_αb x_bj. Written out (Flanagan & Belytschko 1981, eqs. 14–16),
//!
//! ```text
//! q_αi = Σ_a γ_αa u_ai = (Γu)_αi − Σ_j h_αj G_ij,         G_ij = Σ_a u_ai b_aj = ∂u_i/∂x_j
//! f_ai = V Σ_j b_aj σ_ij + κ Σ_α γ_αa q_αi
//!      = Σ_j b_aj P_ij + Σ_α Γ_αa (κ q_αi),               P_ij = V σ_ij − Σ_α h_αj κ q_αi
//! ```
//!
//! so an element needs only b (24), h (12), V and κ: 304 bytes instead of 464. The mean
//! displacement gradient G (whose symmetric part is the strain) is computed once and serves
//! both the strain and the hourglass modes, and Γ has entries ±1, so Γu and Γᵀq are additions.

use dcfm::element::hex8_uniform::UniformGeometry;
use dcfm::material::Elastic;

/// Hourglass base vectors Γ_α at the nodes (α = ηζ, ζξ, ξη, ξηζ; node order of
/// `hex8_shape::NODE_XI`), equal to `hex8_uniform::hourglass_base()`.
pub const GAMMA: [[f64; 8]; 4] = [
    [1.0, 1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0],
    [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0],
];

/// Geometry of one element in split form (304 bytes).
#[derive(Clone, Copy, Debug)]
pub struct SplitGeometry {
    /// Mean gradient b_aj (1/m).
    pub b: [[f64; 3]; 8],
    /// h_αj = Σ_b Γ_αb x_bj (m).
    pub h: [[f64; 3]; 4],
    /// Volume (m³).
    pub volume: f64,
    /// Hourglass stiffness κ (N/m).
    pub kappa: f64,
}

impl SplitGeometry {
    /// The split form of the solver's geometry of the element with nodal coordinates `x`.
    pub fn new(x: &[[f64; 3]; 8], g: &UniformGeometry) -> Self {
        let mut h = [[0.0; 3]; 4];
        for (al, row) in h.iter_mut().enumerate() {
            for (a, xa) in x.iter().enumerate() {
                for j in 0..3 {
                    row[j] += GAMMA[al][a] * xa[j];
                }
            }
        }
        Self {
            b: g.b,
            h,
            volume: g.volume,
            kappa: g.kappa,
        }
    }
}

/// Internal force of an elastic one-point element, written into `f`; returns the stress.
/// Same result as `hex8_uniform::internal_force` to rounding.
// The loops keep the index notation of the formulas above (a: node, i, j: axes, α: mode).
#[allow(clippy::needless_range_loop)]
#[inline(always)]
pub fn internal_force(
    geo: &SplitGeometry,
    elastic: &Elastic,
    u: &[[f64; 3]; 8],
    f: &mut [[f64; 3]; 8],
) -> [f64; 6] {
    // Mean displacement gradient G_ij and Γu.
    let mut g = [[0.0; 3]; 3];
    let mut gu = [[0.0; 3]; 4];
    for a in 0..8 {
        for i in 0..3 {
            for j in 0..3 {
                g[i][j] += u[a][i] * geo.b[a][j];
            }
            for al in 0..4 {
                gu[al][i] += GAMMA[al][a] * u[a][i];
            }
        }
    }
    let eps = [
        g[0][0],
        g[1][1],
        g[2][2],
        g[0][1] + g[1][0],
        g[1][2] + g[2][1],
        g[2][0] + g[0][2],
    ];
    let s = elastic.stress(&eps);
    // κ q_αi.
    let mut kq = [[0.0; 3]; 4];
    for al in 0..4 {
        for i in 0..3 {
            let hg = geo.h[al][0] * g[i][0] + geo.h[al][1] * g[i][1] + geo.h[al][2] * g[i][2];
            kq[al][i] = geo.kappa * (gu[al][i] - hg);
        }
    }
    // P_ij = V σ_ij − Σ_α h_αj κ q_αi (not symmetric).
    let v = geo.volume;
    let sig = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
    let mut p = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            p[i][j] = v * sig[i][j]
                - (geo.h[0][j] * kq[0][i]
                    + geo.h[1][j] * kq[1][i]
                    + geo.h[2][j] * kq[2][i]
                    + geo.h[3][j] * kq[3][i]);
        }
    }
    for a in 0..8 {
        for i in 0..3 {
            f[a][i] = geo.b[a][0] * p[i][0]
                + geo.b[a][1] * p[i][1]
                + geo.b[a][2] * p[i][2]
                + GAMMA[0][a] * kq[0][i]
                + GAMMA[1][a] * kq[1][i]
                + GAMMA[2][a] * kq[2][i]
                + GAMMA[3][a] * kq[3][i];
        }
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;
    use dcfm::element::hex8_uniform::{self, hourglass_base};
    use dcfm::material::{Material, PointContext};

    #[test]
    fn gamma_is_the_solvers_hourglass_base() {
        assert_eq!(GAMMA, hourglass_base());
    }

    #[test]
    fn same_forces_as_the_solver_kernel() {
        let x = [
            [0.0, 0.0, 0.0],
            [1.1, 0.05, -0.02],
            [1.0, 0.95, 0.03],
            [-0.04, 1.02, 0.0],
            [0.03, -0.02, 0.9],
            [1.05, 0.0, 1.1],
            [0.98, 1.07, 1.0],
            [0.0, 0.97, 1.04],
        ];
        let el = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
        let mat = Material::Elastic(el);
        let ug = UniformGeometry::new(&x, &el, 0.1).unwrap();
        let sg = SplitGeometry::new(&x, &ug);
        let u: [[f64; 3]; 8] = std::array::from_fn(|a| {
            let t = a as f64;
            [
                1e-3 * (t * 0.7).sin(),
                -2e-3 * (t * 1.3).cos(),
                5e-4 * t * t,
            ]
        });
        let ctx = PointContext {
            char_length: 1.0,
            dt: 1e-4,
        };
        let mut f_ref = [[0.0; 3]; 8];
        let s_ref = hex8_uniform::internal_force(&ug, &mat, &u, &[], &mut [], &ctx, &mut f_ref);
        let mut f = [[0.0; 3]; 8];
        let s = internal_force(&sg, &el, &u, &mut f);
        let scale = f_ref.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        assert!(scale > 0.0);
        for (a, b) in f.iter().flatten().zip(f_ref.iter().flatten()) {
            assert!((a - b).abs() <= 1e-12 * scale, "{a} vs {b}");
        }
        for (a, b) in s.iter().zip(&s_ref) {
            assert!((a - b).abs() <= 1e-12 * s_ref.iter().fold(0.0f64, |m, x| m.max(x.abs())));
        }
    }
}
