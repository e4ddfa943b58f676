//! Element stiffness matrices of the hex8 for the static direct solve: the exact Jacobian
//! ∂f_int/∂u of the explicit kernels' internal force with the initial elastic moduli E₀,
//! so that a static solution is an equilibrium of the explicit model.
//!
//! DOF order: node-major, `3a + i` (node a of the element, direction i).
//!
//! - **Full 2×2×2** ([`full_stiffness`]): K = Σ_g (w det J)_g Bᵀ_g D B_g with the Cartesian
//!   derivatives ∂N_a/∂x_j = Σ_k ∂N_a/∂ξ_k (J⁻¹)_kj of `hex8_full` (Zienkiewicz, Taylor &
//!   Zhu 2005, eq. 6.16).
//! - **One-point** ([`uniform_stiffness`]): the kernel of `hex8_uniform` computes
//!   f_ai = V Σ_j b_aj σ_ij + κ Σ_α γ_αa q_αi with σ = D ε(b u) and q_αi = Σ_b γ_αb u_bi
//!   (Flanagan & Belytschko 1981, eqs. 14–16 and 55), so
//!
//!   ```text
//!   K_(ai)(bk) = V (Bᵀ D B)_(ai)(bk) + κ δ_ik Σ_α γ_αa γ_αb,   γ_αa = Γ_αa − Σ_j h_αj b_aj
//!   ```
//!
//!   with κ = ε_hg (λ+2μ) V (b·b)/8 as stored in the geometry: the hourglass stiffness the
//!   explicit kernel applies, not an approximation of it.
//!
//! Both are checked against a central finite difference of the kernels' internal force
//! (the kernels are linear for elastic material, so the difference is exact to round-off),
//! for symmetry and for the six rigid-body modes in the null space.

use crate::element::hex8_full::{FullGeometry, NATURAL_DERIVATIVES};
use crate::element::hex8_uniform::UniformGeometry;
use crate::material::Elastic;

/// A 24 × 24 element stiffness, DOF `3a + i`.
pub type ElementStiffness = [[f64; 24]; 24];

/// Isotropic elastic matrix D (Voigt xx, yy, zz, xy, yz, zx; engineering shear).
fn elastic_matrix(el: &Elastic) -> [[f64; 6]; 6] {
    let (l, m) = (el.lambda, el.mu);
    let mut d = [[0.0; 6]; 6];
    for i in 0..3 {
        for j in 0..3 {
            d[i][j] = l;
        }
        d[i][i] = l + 2.0 * m;
        d[3 + i][3 + i] = m;
    }
    d
}

/// Add w Bᵀ D B to `k` for the Cartesian derivatives `dn` (∂N_a/∂x_j).
fn add_btdb(k: &mut ElementStiffness, dn: &[[f64; 3]; 8], d: &[[f64; 6]; 6], w: f64) {
    // B columns of node a: ε = Σ_a B_a u_a with B_a (6 × 3).
    let b_of = |a: usize| -> [[f64; 3]; 6] {
        let [x, y, z] = dn[a];
        [
            [x, 0.0, 0.0],
            [0.0, y, 0.0],
            [0.0, 0.0, z],
            [y, x, 0.0],
            [0.0, z, y],
            [z, 0.0, x],
        ]
    };
    let bs: [[[f64; 3]; 6]; 8] = std::array::from_fn(b_of);
    // DB_b (6 × 3) for every node b.
    let db: [[[f64; 3]; 6]; 8] = std::array::from_fn(|b| {
        std::array::from_fn(|r| {
            std::array::from_fn(|kk| (0..6).map(|s| d[r][s] * bs[b][s][kk]).sum::<f64>())
        })
    });
    for a in 0..8 {
        for i in 0..3 {
            for b in 0..8 {
                for kk in 0..3 {
                    let v: f64 = (0..6).map(|r| bs[a][r][i] * db[b][r][kk]).sum();
                    k[3 * a + i][3 * b + kk] += w * v;
                }
            }
        }
    }
}

/// Stiffness of a one-point element: V BᵀDB with the mean gradient plus the
/// Flanagan–Belytschko hourglass stiffness κ Σ_α γ_α γ_αᵀ ⊗ I₃ (the exact Jacobian of
/// `hex8_uniform::internal_force` for the elastic constants `el`).
pub fn uniform_stiffness(geo: &UniformGeometry, el: &Elastic) -> ElementStiffness {
    let mut k = [[0.0; 24]; 24];
    add_btdb(&mut k, &geo.b, &elastic_matrix(el), geo.volume);
    if geo.kappa != 0.0 {
        let gamma = geo.gamma();
        for a in 0..8 {
            for b in 0..8 {
                let g: f64 = (0..4).map(|al| gamma[al][a] * gamma[al][b]).sum();
                for i in 0..3 {
                    k[3 * a + i][3 * b + i] += geo.kappa * g;
                }
            }
        }
    }
    k
}

/// Stiffness of a fully integrated element: Σ_g (w det J)_g Bᵀ_g D B_g (the exact Jacobian
/// of `hex8_full::internal_force` for the elastic constants `el`).
pub fn full_stiffness(geo: &FullGeometry, el: &Elastic) -> ElementStiffness {
    let mut k = [[0.0; 24]; 24];
    let d = elastic_matrix(el);
    for g in 0..8 {
        let nd = &NATURAL_DERIVATIVES[g];
        let ji = &geo.point_jinv(g);
        let dn: [[f64; 3]; 8] = std::array::from_fn(|a| {
            std::array::from_fn(|j| nd[a][0] * ji[0][j] + nd[a][1] * ji[1][j] + nd[a][2] * ji[2][j])
        });
        add_btdb(&mut k, &dn, &d, geo.wdet[g]);
    }
    k
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::{hex8_full, hex8_uniform};
    use crate::material::{Material, PointContext};

    use crate::test_random::distorted_hex as distorted;

    fn ctx() -> PointContext {
        PointContext {
            char_length: 1.0,
            dt: 1e-4,
            reads_damage: false,
        }
    }

    /// Column j of the central finite difference (f(u + h e_j) − f(u − h e_j)) / 2h of a
    /// kernel's internal force around the displacement `u0`.
    type Kernel<'a> = &'a dyn Fn(&[[f64; 3]; 8]) -> [[f64; 3]; 8];

    fn fd_matrix(u0: &[[f64; 3]; 8], h: f64, f: Kernel) -> ElementStiffness {
        let mut k = [[0.0; 24]; 24];
        for j in 0..24 {
            let (mut up, mut um) = (*u0, *u0);
            up[j / 3][j % 3] += h;
            um[j / 3][j % 3] -= h;
            let (fp, fm) = (f(&up), f(&um));
            for i in 0..24 {
                k[i][j] = (fp[i / 3][i % 3] - fm[i / 3][i % 3]) / (2.0 * h);
            }
        }
        k
    }

    fn max_abs(k: &ElementStiffness) -> f64 {
        k.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()))
    }

    fn max_diff(a: &ElementStiffness, b: &ElementStiffness) -> f64 {
        let mut d = 0.0f64;
        for i in 0..24 {
            for j in 0..24 {
                d = d.max((a[i][j] - b[i][j]).abs());
            }
        }
        d
    }

    /// The six rigid-body modes of the element's reference configuration.
    fn rigid_modes(x: &[[f64; 3]; 8]) -> Vec<[[f64; 3]; 8]> {
        let mut modes = Vec::new();
        for d in 0..3 {
            let mut u = [[0.0; 3]; 8];
            for ua in u.iter_mut() {
                ua[d] = 1.0;
            }
            modes.push(u);
        }
        for w in [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]] {
            let u: [[f64; 3]; 8] = std::array::from_fn(|a| {
                let p = x[a];
                [
                    w[1] * p[2] - w[2] * p[1],
                    w[2] * p[0] - w[0] * p[2],
                    w[0] * p[1] - w[1] * p[0],
                ]
            });
            modes.push(u);
        }
        modes
    }

    fn apply(k: &ElementStiffness, u: &[[f64; 3]; 8]) -> [f64; 24] {
        std::array::from_fn(|i| (0..24).map(|j| k[i][j] * u[j / 3][j % 3]).sum())
    }

    fn check(k: &ElementStiffness, fd: &ElementStiffness, x: &[[f64; 3]; 8]) {
        let scale = max_abs(k);
        assert!(scale > 0.0);
        let err = max_diff(k, fd) / scale;
        assert!(err <= 1e-7, "K vs finite difference: {err:e}");
        let mut kt = *k;
        for i in 0..24 {
            for j in 0..24 {
                kt[i][j] = k[j][i];
            }
        }
        assert!(max_diff(k, &kt) <= 1e-12 * scale, "not symmetric");
        for (m, u) in rigid_modes(x).iter().enumerate() {
            let f = apply(k, u);
            let un = u.iter().flatten().fold(0.0f64, |a, v| a.max(v.abs()));
            let fm = f.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            assert!(fm <= 1e-12 * scale * un, "rigid mode {m}: |K r| = {fm:e}");
        }
    }

    fn displacement() -> [[f64; 3]; 8] {
        std::array::from_fn(|a| {
            let t = a as f64;
            [1e-4 * (t * 0.7).sin(), -2e-4 * (t * 1.3).cos(), 5e-5 * t]
        })
    }

    #[test]
    fn one_point_stiffness_is_the_kernel_jacobian() {
        let x = distorted();
        let el = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
        let mat = Material::Elastic(el);
        for hg in [0.0, 0.05, 0.3] {
            let geo = UniformGeometry::new(&x, &el, hg).unwrap();
            let k = uniform_stiffness(&geo, &el);
            let f = |u: &[[f64; 3]; 8]| {
                let mut f = [[0.0; 3]; 8];
                hex8_uniform::internal_force(&geo, &mat, u, &[], &mut [], &ctx(), &mut f);
                f
            };
            let fd = fd_matrix(&displacement(), 1e-6, &f);
            check(&k, &fd, &x);
        }
    }

    #[test]
    fn full_stiffness_is_the_kernel_jacobian() {
        let x = distorted();
        let el = Elastic::new("concrete", 25e9, 0.17, 2400.0).unwrap();
        let mat = Material::Elastic(el);
        let geo = FullGeometry::new(&x).unwrap();
        let k = full_stiffness(&geo, &el);
        let f = |u: &[[f64; 3]; 8]| {
            let mut f = [[0.0; 3]; 8];
            hex8_full::internal_force(&geo, &mat, u, &[], &mut [], &ctx(), &mut f);
            f
        };
        let fd = fd_matrix(&displacement(), 1e-6, &f);
        check(&k, &fd, &x);
    }

    /// Rank 18 (24 − 6 rigid modes) for full integration and for one-point with hourglass
    /// stiffness; with ε_hg = 0 the one-point element keeps its 12 hourglass modes (rank 6).
    #[test]
    fn ranks() {
        use nalgebra::DMatrix;
        let x = distorted();
        let el = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
        let rank = |k: &ElementStiffness| {
            let m = DMatrix::from_fn(24, 24, |i, j| k[i][j]);
            let ev = m.symmetric_eigenvalues();
            let top = ev.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            ev.iter().filter(|v| v.abs() > 1e-10 * top).count()
        };
        let full = full_stiffness(&FullGeometry::new(&x).unwrap(), &el);
        assert_eq!(rank(&full), 18);
        let one = uniform_stiffness(&UniformGeometry::new(&x, &el, 0.05).unwrap(), &el);
        assert_eq!(rank(&one), 18);
        let bare = uniform_stiffness(&UniformGeometry::new(&x, &el, 0.0).unwrap(), &el);
        assert_eq!(rank(&bare), 6);
    }
}
