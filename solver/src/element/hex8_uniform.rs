//! One-point hex8 with the uniform-strain (mean) gradient and Flanagan–Belytschko
//! hourglass control (Flanagan & Belytschko 1981, IJNME 17:679–706, eqs. 14–16 and 55).
//!
//! The mean gradient b_ai = (1/V) ∫ ∂N_a/∂x_i dV is integrated exactly (2×2×2 Gauss), so
//! the element passes the constant-strain patch test on any trilinear shape. Hourglass
//! shape vectors γ_αa = Γ_αa − (Σ_b Γ_αb x_bj) b_aj are orthogonal to every linear field;
//! the stiffness-type hourglass force is f_ai = κ Σ_α γ_αa q_αi, q_αi = Σ_a γ_αa u_ai, with
//! κ = ε_hg (λ+2μ) V (b_ai b_ai) / 8 from the initial elastic moduli.
//!
//! With a damaging material the kernel uses κ (1 − D), D the point's damage after its
//! update ([`Material::stiffness_factor`]; exactly κ for elastic materials): the
//! stabilisation stands for the element's resistance to its linearly varying strain
//! modes, which the damaged material provides in a fully integrated element, and is taken
//! from the current material moduli (Flanagan & Belytschko 1981 §4; Belytschko, Liu &
//! Moran 2000 §8.7). With the initial κ a cracked element kept its undamaged stiffness in
//! the twelve hourglass modes and carried force across its crack through them
//! (docs/plastic_damage.md §8).
//!
//! The kernel uses the split form of γ (issue #2): with h_αj = Σ_b Γ_αb x_bj and the mean
//! displacement gradient G_ij = Σ_a u_ai b_aj,
//!
//! ```text
//! q_αi = (Γu)_αi − Σ_j h_αj G_ij
//! f_ai = Σ_j b_aj P_ij + Σ_α Γ_αa (κ q_αi),   P_ij = V σ_ij − Σ_α h_αj κ q_αi
//! ```
//!
//! so an element stores b, h, V and κ (304 bytes instead of 464 with γ), G is computed once
//! for the strain and the hourglass modes, and Γ (entries ±1) costs only additions.

use crate::element::hex8_shape::{cartesian_derivatives, gauss_points, NODE_XI};
use crate::element::lanes::{run_lane_work, Lane, LaneWork, Simd};
use crate::material::{Elastic, Material, PointContext, Voigt};
use seq_macro::seq;

/// Hourglass base vectors Γ_α (α = ηζ, ζξ, ξη, ξηζ) at the nodes, as a constant
/// (equal to [`hourglass_base`], tested).
pub const GAMMA: [[f64; 8]; 4] = [
    [1.0, 1.0, -1.0, -1.0, -1.0, -1.0, 1.0, 1.0],
    [1.0, -1.0, -1.0, 1.0, -1.0, 1.0, 1.0, -1.0],
    [1.0, -1.0, 1.0, -1.0, 1.0, -1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0, 1.0, 1.0, -1.0, 1.0, -1.0],
];

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

/// Precomputed geometry of one one-point element (304 bytes).
#[derive(Clone, Copy, Debug, Default)]
pub struct UniformGeometry {
    /// Mean gradient b_ai (1/m).
    pub b: [[f64; 3]; 8],
    /// h_αj = Σ_b Γ_αb x_bj (m): the hourglass shape vectors are γ_αa = Γ_αa − h_αj b_aj.
    pub h: [[f64; 3]; 4],
    /// Volume V (m³).
    pub volume: f64,
    /// Hourglass stiffness κ (N/m).
    pub kappa: f64,
}

/// Mean displacement gradient G_ij = Σ_a u_ai b_aj and Γu, computed together.
pub type GradientAndModes = ([[f64; 3]; 3], [[f64; 3]; 4]);

impl UniformGeometry {
    /// Geometry of an element with nodal coordinates `x`; `None` if det J ≤ 0 somewhere.
    ///
    /// Computed from the coordinates relative to the first node, x_a − x_1: b, V and (as
    /// Σ_a Γ_αa = 0) h depend on differences of coordinates only, so the geometry is the
    /// same, bit for bit, wherever the same cell lies whenever the differences are — the
    /// repeated cells of a structured mesh, which [`UniformSet`] then stores once — and it
    /// carries no rounding of the absolute coordinates (a 1 m cell 100 m from the origin
    /// loses two digits to them).
    ///
    /// [`UniformSet`]: crate::element::uniform_set::UniformSet
    pub fn new(x: &[[f64; 3]; 8], elastic: &Elastic, hourglass: f64) -> Option<Self> {
        let x0 = x[0];
        let x: [[f64; 3]; 8] = x.map(|xa| std::array::from_fn(|j| xa[j] - x0[j]));
        let x = &x;
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
        let mut h = [[0.0; 3]; 4];
        for (al, row) in h.iter_mut().enumerate() {
            for (a, xa) in x.iter().enumerate() {
                for j in 0..3 {
                    row[j] += GAMMA[al][a] * xa[j];
                }
            }
        }
        let bb: f64 = b.iter().flatten().map(|v| v * v).sum();
        let kappa = hourglass * elastic.p_modulus() * volume * bb / 8.0;
        Some(Self {
            b,
            h,
            volume,
            kappa,
        })
    }

    /// Hourglass shape vectors γ_αa = Γ_αa − Σ_j h_αj b_aj (not stored; for checks).
    pub fn gamma(&self) -> [[f64; 8]; 4] {
        std::array::from_fn(|al| {
            std::array::from_fn(|a| {
                GAMMA[al][a]
                    - (self.h[al][0] * self.b[a][0]
                        + self.h[al][1] * self.b[a][1]
                        + self.h[al][2] * self.b[a][2])
            })
        })
    }

    /// Mean displacement gradient G_ij = Σ_a u_ai b_aj and (Γu)_αi.
    #[inline(always)]
    pub fn gradient_and_modes(&self, u: &[[f64; 3]; 8]) -> GradientAndModes {
        gradient_and_modes_of(pulp::Scalar::new(), &self.b, u)
    }

    /// Hourglass modes q_αi = (Γu)_αi − Σ_j h_αj G_ij from G and Γu.
    #[inline(always)]
    fn modes_from(&self, g: &[[f64; 3]; 3], gu: &[[f64; 3]; 4]) -> [[f64; 3]; 4] {
        modes_from_of(pulp::Scalar::new(), &self.h, g, gu)
    }

    /// Strain ε = Σ_a B_a u_a (Voigt, engineering shear). Run under the lanes' dispatch
    /// ([`run_lane_work`]) so that its fused multiply-adds are the CPU's FMA instructions,
    /// not calls of the C library's `fma`, from any caller (the step's kernels, already
    /// dispatched, use [`gradient_and_modes_of`]).
    #[inline(always)]
    pub fn strain(&self, u: &[[f64; 3]; 8]) -> Voigt {
        run_lane_work(Strain { geo: self, u })
    }

    /// [`Self::strain`] in the instruction set it is compiled for.
    #[inline(always)]
    fn strain_fused(&self, u: &[[f64; 3]; 8]) -> Voigt {
        let mut g = [[0.0; 3]; 3];
        for a in 0..8 {
            for i in 0..3 {
                for j in 0..3 {
                    g[i][j] = u[a][i].mul_add(self.b[a][j], g[i][j]);
                }
            }
        }
        strain_of(&g)
    }

    /// Hourglass generalised displacements q_αi = Σ_a γ_αa u_ai, under the lanes' dispatch
    /// like [`Self::strain`].
    #[inline(always)]
    pub fn hourglass_modes(&self, u: &[[f64; 3]; 8]) -> [[f64; 3]; 4] {
        run_lane_work(Modes { geo: self, u })
    }

    /// Nodal forces V Bᵀσ + κ Σ_α γ_α q_α, written into `f`.
    #[inline(always)]
    pub fn forces(&self, s: &Voigt, q: &[[f64; 3]; 4], f: &mut [[f64; 3]; 8]) {
        let kq = q.map(|r| r.map(|x| self.kappa * x));
        self.forces_kq(s, &kq, f);
    }

    /// Nodal forces from σ and κq: f_ai = Σ_j b_aj P_ij + Σ_α Γ_αa (κq)_αi.
    #[inline(always)]
    fn forces_kq(&self, s: &Voigt, kq: &[[f64; 3]; 4], f: &mut [[f64; 3]; 8]) {
        *f = forces_kq_of(pulp::Scalar::new(), &self.b, &self.h, self.volume, s, kq);
    }

    /// Stiffness-proportional damping force β K0 v (initial elastic stiffness, hourglass
    /// included), written into `f`.
    #[inline(always)]
    pub fn damping_forces(
        &self,
        elastic: &Elastic,
        v: &[[f64; 3]; 8],
        beta: f64,
        f: &mut [[f64; 3]; 8],
    ) {
        let (g, gu) = self.gradient_and_modes(v);
        let s = elastic.stress(&strain_of(&g)).map(|x| beta * x);
        let kq = self
            .modes_from(&g, &gu)
            .map(|r| r.map(|x| beta * self.kappa * x));
        self.forces_kq(&s, &kq, f);
    }
}

/// [`UniformGeometry::strain`] as the work of its dispatch.
struct Strain<'a> {
    geo: &'a UniformGeometry,
    u: &'a [[f64; 3]; 8],
}

impl LaneWork for Strain<'_> {
    type Output = Voigt;
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) -> Voigt {
        self.geo.strain_fused(self.u)
    }
}

/// [`UniformGeometry::hourglass_modes`] as the work of its dispatch.
struct Modes<'a> {
    geo: &'a UniformGeometry,
    u: &'a [[f64; 3]; 8],
}

impl LaneWork for Modes<'_> {
    type Output = [[f64; 3]; 4];
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) -> [[f64; 3]; 4] {
        let (g, gu) = self.geo.gradient_and_modes(self.u);
        self.geo.modes_from(&g, &gu)
    }
}

/// Mean displacement gradient G_ij = Σ_a u_ai b_aj and (Γu)_αi of the mean gradient `b`,
/// for one element (`f64`) or one element per lane ([`F64s`](crate::element::lanes::F64s)):
/// the same IEEE operations in the same order either way.
///
/// The loops over nodes and components are unrolled in the source (`seq!`): with lanes, a
/// loop left to the compiler was vectorised across the nodes with gathers and scatters
/// instead of across the lanes (measured, docs/benchmarks.md), and `array::from_fn`
/// closures holding vector arithmetic were left out of line.
#[inline(always)]
pub(crate) fn gradient_and_modes_of<T: Lane, S: Simd>(
    simd: S,
    b: &[[T; 3]; 8],
    u: &[[T; 3]; 8],
) -> ([[T; 3]; 3], [[T; 3]; 4]) {
    let zero = T::splat(0.0);
    let mut g = [[zero; 3]; 3];
    let mut gu = [[zero; 3]; 4];
    seq!(A in 0..8 {
        seq!(I in 0..3 {
            seq!(J in 0..3 {
                g[I][J] = u[A][I].mul_add(simd, b[A][J], g[I][J]);
            });
            seq!(AL in 0..4 {
                gu[AL][I] = T::splat(GAMMA[AL][A]).mul_add(simd, u[A][I], gu[AL][I]);
            });
        });
    });
    (g, gu)
}

/// Hourglass modes q_αi = (Γu)_αi − Σ_j h_αj G_ij from G and Γu (generic and unrolled like
/// [`gradient_and_modes_of`]).
#[inline(always)]
pub(crate) fn modes_from_of<T: Lane, S: Simd>(
    simd: S,
    h: &[[T; 3]; 4],
    g: &[[T; 3]; 3],
    gu: &[[T; 3]; 4],
) -> [[T; 3]; 4] {
    let mut q = [[T::splat(0.0); 3]; 4];
    seq!(AL in 0..4 {
        seq!(I in 0..3 {
            q[AL][I] = gu[AL][I]
                - h[AL][2].mul_add(simd, g[I][2], h[AL][1].mul_add(simd, g[I][1], h[AL][0] * g[I][0]));
        });
    });
    q
}

/// Nodal forces from σ and κq: f_ai = Σ_j b_aj P_ij + Σ_α Γ_αa (κq)_αi with
/// P_ij = V σ_ij − Σ_α h_αj (κq)_αi (the split form of the module doc; generic and unrolled
/// like [`gradient_and_modes_of`]).
#[inline(always)]
pub(crate) fn forces_kq_of<T: Lane, S: Simd>(
    simd: S,
    b: &[[T; 3]; 8],
    h: &[[T; 3]; 4],
    volume: T,
    s: &[T; 6],
    kq: &[[T; 3]; 4],
) -> [[T; 3]; 8] {
    let sig = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
    let zero = T::splat(0.0);
    let mut p = [[zero; 3]; 3];
    seq!(I in 0..3 {
        seq!(J in 0..3 {
            p[I][J] = volume * sig[I][J]
                - h[3][J].mul_add(simd,
                    kq[3][I],
                    h[2][J].mul_add(simd, kq[2][I], h[1][J].mul_add(simd, kq[1][I], h[0][J] * kq[0][I])),
                );
        });
    });
    let mut f = [[zero; 3]; 8];
    seq!(A in 0..8 {
        seq!(I in 0..3 {
            // b₀p₀, then six fused multiply-adds in the order of the terms
            let mut t = b[A][0] * p[I][0];
            t = b[A][1].mul_add(simd, p[I][1], t);
            t = b[A][2].mul_add(simd, p[I][2], t);
            t = T::splat(GAMMA[0][A]).mul_add(simd, kq[0][I], t);
            t = T::splat(GAMMA[1][A]).mul_add(simd, kq[1][I], t);
            t = T::splat(GAMMA[2][A]).mul_add(simd, kq[2][I], t);
            f[A][I] = T::splat(GAMMA[3][A]).mul_add(simd, kq[3][I], t);
        });
    });
    f
}

/// Voigt strain (engineering shear) of a displacement gradient (generic like
/// [`gradient_and_modes_of`]).
#[inline(always)]
pub(crate) fn strain_of<T: Lane>(g: &[[T; 3]; 3]) -> [T; 6] {
    [
        g[0][0],
        g[1][1],
        g[2][2],
        g[0][1] + g[1][0],
        g[1][2] + g[2][1],
        g[2][0] + g[0][2],
    ]
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
    internal_force_with_initial_strain(geo, material, u, None, old, new, ctx, f)
}

/// [`internal_force`] with an initial strain ε₀ added to the strain of the displacements:
/// the material sees ε(u) + ε₀ (in-situ stress σ₀ = E₀ : ε₀, see `docs/static_stage.md`);
/// the hourglass forces see only u. With `eps0 = None` it is [`internal_force`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn internal_force_with_initial_strain(
    geo: &UniformGeometry,
    material: &Material,
    u: &[[f64; 3]; 8],
    eps0: Option<&Voigt>,
    old: &[f64],
    new: &mut [f64],
    ctx: &PointContext,
    f: &mut [[f64; 3]; 8],
) -> Voigt {
    let (g, gu) = geo.gradient_and_modes(u);
    let eps = strain_with_initial(&g, eps0);
    let sigma = material.update(&eps, old, new, ctx);
    add_element_forces(geo, material, &g, &gu, &sigma, new, f);
    sigma
}

/// [`internal_force_with_initial_strain`] with the element's material state updated in
/// place ([`Material::update_in_place`]): the same forces and state bit for bit. Returns
/// the stress and whether the hardening moved.
#[inline(always)]
pub fn internal_force_in_place(
    geo: &UniformGeometry,
    material: &Material,
    u: &[[f64; 3]; 8],
    eps0: Option<&Voigt>,
    state: &mut [f64],
    ctx: &PointContext,
    f: &mut [[f64; 3]; 8],
) -> (Voigt, bool) {
    let (g, gu) = geo.gradient_and_modes(u);
    let eps = strain_with_initial(&g, eps0);
    let (sigma, moved) = material.update_in_place(&eps, state, ctx);
    add_element_forces(geo, material, &g, &gu, &sigma, state, f);
    (sigma, moved)
}

/// Strain of the mean gradient `g` plus the initial strain `eps0`, if any.
#[inline(always)]
fn strain_with_initial(g: &[[f64; 3]; 3], eps0: Option<&Voigt>) -> Voigt {
    let mut eps = strain_of(g);
    if let Some(e0) = eps0 {
        for i in 0..6 {
            eps[i] += e0[i];
        }
    }
    eps
}

/// Nodal forces V Bᵀσ plus the hourglass forces of stress `sigma` and the new material
/// state `new`, for the mean gradient `g` and hourglass amplitudes `gu`.
#[inline(always)]
fn add_element_forces(
    geo: &UniformGeometry,
    material: &Material,
    g: &[[f64; 3]; 3],
    gu: &[[f64; 3]; 4],
    sigma: &Voigt,
    new: &[f64],
    f: &mut [[f64; 3]; 8],
) {
    // Hourglass stiffness of the damaged material: κ (1 − D), exactly κ when elastic.
    let kappa = geo.kappa * material.stiffness_factor(new);
    let kq = geo.modes_from(g, gu).map(|r| r.map(|x| kappa * x));
    geo.forces_kq(sigma, &kq, f);
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::test_random::distorted_hex as distorted;

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

    #[test]
    fn gamma_constant_is_the_base_and_size_is_304_bytes() {
        assert_eq!(GAMMA, hourglass_base());
        assert_eq!(std::mem::size_of::<UniformGeometry>(), 304);
    }

    /// The split form gives the forces of the γ form V Bᵀσ + κ Σ_α γ_α (γ_α·u) to round-off.
    #[test]
    fn split_form_matches_gamma_form() {
        let x = distorted();
        let el = Elastic::new("m", 20e9, 0.25, 2700.0).unwrap();
        let mat = Material::Elastic(el);
        let g = UniformGeometry::new(&x, &el, 0.1).unwrap();
        let gamma = g.gamma();
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
            reads_damage: true,
        };
        let mut f = [[0.0; 3]; 8];
        let s = internal_force(&g, &mat, &u, &[], &mut [], &ctx, &mut f);
        let mut q = [[0.0; 3]; 4];
        for al in 0..4 {
            for a in 0..8 {
                for i in 0..3 {
                    q[al][i] += gamma[al][a] * u[a][i];
                }
            }
        }
        let scale = f.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        for a in 0..8 {
            let b = g.b[a].map(|v| v * g.volume);
            let mut r = [
                b[0] * s[0] + b[1] * s[3] + b[2] * s[5],
                b[0] * s[3] + b[1] * s[1] + b[2] * s[4],
                b[0] * s[5] + b[1] * s[4] + b[2] * s[2],
            ];
            for al in 0..4 {
                for i in 0..3 {
                    r[i] += g.kappa * gamma[al][a] * q[al][i];
                }
            }
            for i in 0..3 {
                assert!((f[a][i] - r[i]).abs() <= 1e-12 * scale, "{a},{i}");
            }
        }
        let qs = g.hourglass_modes(&u);
        for (a, b) in qs.iter().flatten().zip(q.iter().flatten()) {
            assert!((a - b).abs() <= 1e-15, "{a} vs {b}");
        }
    }

    /// A cracked one-point element resists an hourglass mode with κ (1 − D), D its damage
    /// after the update, and an elastic one with κ exactly (docs/plastic_damage.md §8).
    #[test]
    fn hourglass_stiffness_follows_the_damage() {
        use crate::material::plastic_damage::PlasticDamageParams;
        use crate::material::PlasticDamage;
        let x: [[f64; 3]; 8] = std::array::from_fn(|a| NODE_XI[a].map(|v| 0.5 * (v + 1.0)));
        let el = Elastic::new("c", 31e9, 0.18, 2400.0).unwrap();
        let pd = PlasticDamage::new(
            "c",
            el,
            &PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 200.0, 1e4),
        )
        .unwrap();
        let mat = Material::PlasticDamage(Box::new(pd));
        let g = UniformGeometry::new(&x, &el, 0.05).unwrap();
        let ctx = PointContext {
            char_length: 1.0,
            dt: 1e-5,
            reads_damage: true,
        };
        // Crack the point in uniaxial strain to ε_x = 4e-4.
        let n = mat.state_len();
        let mut old = vec![0.0; n];
        mat.init_state(&mut old);
        let mut new = old.clone();
        for k in 1..=100 {
            let eps = [4e-4 * k as f64 / 100.0, 0.0, 0.0, 0.0, 0.0, 0.0];
            mat.update(&eps, &old, &mut new, &ctx);
            old.copy_from_slice(&new);
        }
        let lin: [[f64; 3]; 8] = std::array::from_fn(|a| [4e-4 * x[a][0], 0.0, 0.0]);
        let s = 1e-6;
        let hg: [[f64; 3]; 8] = std::array::from_fn(|a| {
            let mut u = lin[a];
            u[1] += s * GAMMA[2][a];
            u
        });
        let (mut f_lin, mut f_hg) = ([[0.0; 3]; 8], [[0.0; 3]; 8]);
        let mut n1 = old.clone();
        internal_force(&g, &mat, &lin, &old, &mut n1, &ctx, &mut f_lin);
        let mut n2 = old.clone();
        internal_force(&g, &mat, &hg, &old, &mut n2, &ctx, &mut f_hg);
        let d = mat.damage(&n2);
        assert!(d > 0.3, "the point must be cracked, D = {d}");
        // The hourglass mode leaves the centroid strain (to round-off) and so the state.
        for (a, b) in n1.iter().zip(&n2) {
            assert!((a - b).abs() <= 1e-12 * (1.0 + a.abs()), "{n1:?} vs {n2:?}");
        }
        for a in 0..8 {
            let expect = g.kappa * (1.0 - d) * GAMMA[2][a] * 8.0 * s;
            let got = f_hg[a][1] - f_lin[a][1];
            assert!(
                (got - expect).abs() <= 1e-9 * expect.abs(),
                "node {a}: {got} vs {expect}"
            );
        }
        // Elastic: the full κ, bit for bit.
        let e = Material::Elastic(el);
        let (mut fe_lin, mut fe_hg) = ([[0.0; 3]; 8], [[0.0; 3]; 8]);
        internal_force(&g, &e, &lin, &[], &mut [], &ctx, &mut fe_lin);
        internal_force(&g, &e, &hg, &[], &mut [], &ctx, &mut fe_hg);
        for a in 0..8 {
            let expect = g.kappa * GAMMA[2][a] * 8.0 * s;
            let got = fe_hg[a][1] - fe_lin[a][1];
            assert!(
                (got - expect).abs() <= 1e-9 * expect.abs(),
                "elastic node {a}"
            );
        }
    }

    /// The kernel in place gives the buffered kernel's forces, stress and state bit for bit,
    /// and says whether the hardening moved: random displacements from well inside the
    /// elastic range to cracking, two steps (the second from the state the first left),
    /// with and without an initial strain.
    #[test]
    fn in_place_is_the_buffered_kernel_bit_for_bit() {
        use crate::test_random::{cracking_concrete, Lcg};
        let x = distorted();
        let (material, el) = cracking_concrete();
        let geo = UniformGeometry::new(&x, &el, 0.05).unwrap();
        let ctx = PointContext {
            char_length: 0.5,
            dt: 1e-4,
            reads_damage: true,
        };
        let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
        let mut rng = Lcg(0x1a2b_3c4d_0005);
        let mut moved_seen = [false; 2];
        for draw in 0..2000 {
            let mag = 1e-6 * (3e3f64).powf(rng.next());
            let u: [[f64; 3]; 8] =
                std::array::from_fn(|_| [mag * rng.sym(), mag * rng.sym(), mag * rng.sym()]);
            let e0: Voigt = std::array::from_fn(|_| 0.3 * mag * rng.sym());
            let mut old = vec![0.0; material.state_len()];
            material.init_state(&mut old);
            for step in 0..2 {
                let us = u.map(|ua| ua.map(|v| (1.0 + 0.5 * step as f64) * v));
                let eps0 = (draw % 2 == 1).then_some(&e0);
                let mut want = [[0.0; 3]; 8];
                let mut want_state = vec![0.0; material.state_len()];
                let want_sigma = internal_force_with_initial_strain(
                    &geo,
                    &material,
                    &us,
                    eps0,
                    &old,
                    &mut want_state,
                    &ctx,
                    &mut want,
                );
                let mut got = [[0.0; 3]; 8];
                let mut state = old.clone();
                let (sigma, moved) =
                    internal_force_in_place(&geo, &material, &us, eps0, &mut state, &ctx, &mut got);
                assert_eq!(
                    bits(got.as_flattened()),
                    bits(want.as_flattened()),
                    "draw {draw}"
                );
                assert_eq!(bits(&sigma), bits(&want_sigma), "draw {draw}");
                assert_eq!(bits(&state), bits(&want_state), "draw {draw}");
                assert_eq!(moved, material.hardening_moved(&old, &want_state));
                moved_seen[usize::from(moved)] = true;
                old = want_state;
            }
        }
        assert_eq!(moved_seen, [true, true]);
    }
}
