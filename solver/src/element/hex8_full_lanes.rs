//! Fully integrated hex8 with its eight Gauss points in SIMD lanes (issue 11): one element
//! at a time, each [`F64s`] holding one value per Gauss point, so that the geometry
//! ([`FullGeometry`], stored point-minor) is loaded as it lies and nothing is gathered or
//! transposed. Each lane performs the IEEE operations of the scalar kernel
//! ([`crate::element::hex8_full::internal_force_with_initial_strain`]) in the same order,
//! its fused multiply-adds included,
//! so the forces and the material states are the scalar ones bit for bit (tested on random
//! elements and materials, and through whole runs in `solver/tests/element_lanes.rs`).
//!
//! Per Gauss point g (as in `hex8_full`):
//!
//! ```text
//! H_ik = Σ_a u_ai ∂N_a/∂ξ_k,   G = H J⁻¹,   ε = sym G,   σ = material update of ε (+ ε₀)
//! P_ik = w det J Σ_j σ_ij (J⁻¹)_kj,   f_ai += Σ_k ∂N_a/∂ξ_k P_ik   (g = 0, …, 7 in turn)
//! ```
//!
//! The strain and P are formed with the points in lanes (u_ai broadcast, ∂N_a/∂ξ_k of the
//! eight points a constant vector); the nodal sums f_ai run over the points in order with
//! the **nodes** in lanes (P_ik of point g broadcast), the scalar kernel's accumulation
//! order. The material update between them is the scalar one, point by point, except for
//! linear elasticity, whose stress is computed in lanes.

use crate::element::hex8_full::{FullGeometry, NATURAL_DERIVATIVES};
use crate::element::lanes::{
    elastic_stress_lanes, fused_sum3, part, parts, set_part, F64s, LaneWork, Simd, VoigtLanes,
    LANES,
};
#[cfg(doc)]
use crate::material::PlasticDamage;
use crate::material::{Material, PointContext, Voigt};

const _: () = assert!(LANES == 8, "one lane per Gauss point of the 2×2×2 rule");

/// ∂N_a/∂ξ_k with the points in lanes: `POINT_DERIVATIVES[a][k][g]` is
/// `NATURAL_DERIVATIVES[g][a][k]`.
const POINT_DERIVATIVES: [[F64s; 3]; 8] = derivative_lanes(true);

/// ∂N_a/∂ξ_k with the nodes in lanes: `NODE_DERIVATIVES[g][k][a]` is
/// `NATURAL_DERIVATIVES[g][a][k]`.
const NODE_DERIVATIVES: [[F64s; 3]; 8] = derivative_lanes(false);

/// [`NATURAL_DERIVATIVES`] regrouped with the points (`points_in_lanes`) or the nodes in
/// lanes.
const fn derivative_lanes(points_in_lanes: bool) -> [[F64s; 3]; 8] {
    let mut t = [[F64s::ZERO; 3]; 8];
    let mut g = 0;
    while g < 8 {
        let mut a = 0;
        while a < 8 {
            let mut k = 0;
            while k < 3 {
                let d = NATURAL_DERIVATIVES[g][a][k];
                if points_in_lanes {
                    t[a][k].0[g] = d;
                } else {
                    t[g][k].0[a] = d;
                }
                k += 1;
            }
            a += 1;
        }
        g += 1;
    }
    t
}

/// Strain ε(u) at the eight Gauss points, one lane per point: lane g is
/// [`FullGeometry::strain`]`(g, u)` bit for bit. Written in the vectors of `simd`
/// ([`part`]), one vector of points at a time: with AVX2 four points, so that the nine
/// sums H_ik and J⁻¹ stay in the sixteen registers (as `F64s` arithmetic the compiler
/// spilled them, docs/benchmarks.md, stop 60).
#[inline(always)]
pub fn point_strains<S: Simd>(simd: S, geo: &FullGeometry, u: &[[f64; 3]; 8]) -> VoigtLanes {
    let ji = &geo.jinv;
    let mut e = [F64s::ZERO; 6];
    for p in 0..parts::<S>() {
        // H_ik = Σ_a u_ai d_ak, accumulated from zero in node order by fused
        // multiply-adds.
        let mut h = [[simd.splat_f64s(0.0); 3]; 3];
        for (a, ua) in u.iter().enumerate() {
            let d = &POINT_DERIVATIVES[a];
            let dk = [
                part::<S>(&d[0], p),
                part::<S>(&d[1], p),
                part::<S>(&d[2], p),
            ];
            for i in 0..3 {
                let uai = simd.splat_f64s(ua[i]);
                for k in 0..3 {
                    h[i][k] = simd.mul_add_f64s(uai, dk[k], h[i][k]);
                }
            }
        }
        // G = H J⁻¹ (loops, not `array::from_fn`: its closures were not inlined into
        // the dispatched code, 2.9× slower, measured).
        let mut jt = [[simd.splat_f64s(0.0); 3]; 3];
        for (c, jt_c) in jt.iter_mut().enumerate() {
            for (r, jt_cr) in jt_c.iter_mut().enumerate() {
                *jt_cr = part::<S>(&ji[r][c], p);
            }
        }
        let mut gr = [[simd.splat_f64s(0.0); 3]; 3];
        for (gr_i, h_i) in gr.iter_mut().zip(&h) {
            for (gr_ic, jt_c) in gr_i.iter_mut().zip(&jt) {
                *gr_ic = fused_sum3(simd, *h_i, *jt_c);
            }
        }
        set_part::<S>(&mut e[0], p, gr[0][0]);
        set_part::<S>(&mut e[1], p, gr[1][1]);
        set_part::<S>(&mut e[2], p, gr[2][2]);
        set_part::<S>(&mut e[3], p, simd.add_f64s(gr[0][1], gr[1][0]));
        set_part::<S>(&mut e[4], p, simd.add_f64s(gr[1][2], gr[2][1]));
        set_part::<S>(&mut e[5], p, simd.add_f64s(gr[2][0], gr[0][2]));
    }
    e
}

/// Nodal forces Σ_g w det J B_gᵀ σ_g of the stresses `s` of the eight points (one lane per
/// point): [`FullGeometry::add_forces`] for g = 0, …, 7 from zero, bit for bit. In the
/// vectors of `simd` like [`point_strains`]: P with the points in vectors, then the nodal
/// sums with the nodes in vectors (as `F64s` arithmetic the compiler packed the three
/// components into one vector instead of the nodes, stop 60).
#[inline(always)]
pub fn point_forces<S: Simd>(simd: S, geo: &FullGeometry, s: &VoigtLanes) -> [[f64; 3]; 8] {
    let ji = &geo.jinv;
    // P_ik = w det J Σ_j σ_ij (J⁻¹)_kj, points in lanes.
    let sig = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
    let mut pk = [[F64s::ZERO; 3]; 3];
    for p in 0..parts::<S>() {
        let w = part::<S>(&geo.wdet, p);
        for (i, sig_i) in sig.iter().enumerate() {
            let si = [
                part::<S>(&sig_i[0], p),
                part::<S>(&sig_i[1], p),
                part::<S>(&sig_i[2], p),
            ];
            for k in 0..3 {
                let jk = [
                    part::<S>(&ji[k][0], p),
                    part::<S>(&ji[k][1], p),
                    part::<S>(&ji[k][2], p),
                ];
                set_part::<S>(&mut pk[i][k], p, simd.mul_f64s(w, fused_sum3(simd, si, jk)));
            }
        }
    }
    // f_ai = Σ_g Σ_k ∂N_a/∂ξ_k P_ik(g), nodes in lanes, over the points in order.
    let mut f = [F64s::ZERO; 3];
    for p in 0..parts::<S>() {
        let mut acc = [simd.splat_f64s(0.0); 3];
        for (g, d) in NODE_DERIVATIVES.iter().enumerate() {
            let dk = [
                part::<S>(&d[0], p),
                part::<S>(&d[1], p),
                part::<S>(&d[2], p),
            ];
            for (i, acc_i) in acc.iter_mut().enumerate() {
                let pg = [
                    simd.splat_f64s(pk[i][0][g]),
                    simd.splat_f64s(pk[i][1][g]),
                    simd.splat_f64s(pk[i][2][g]),
                ];
                // f_ai + d₀ P_i0 + d₁ P_i1 + d₂ P_i2, three fused multiply-adds in turn
                *acc_i = simd.mul_add_f64s(
                    dk[2],
                    pg[2],
                    simd.mul_add_f64s(dk[1], pg[1], simd.mul_add_f64s(dk[0], pg[0], *acc_i)),
                );
            }
        }
        for (fi, acc_i) in f.iter_mut().zip(acc) {
            set_part::<S>(fi, p, acc_i);
        }
    }
    std::array::from_fn(|a| [f[0][a], f[1][a], f[2][a]])
}

/// Internal force of one fully integrated element with the points in lanes: the forces and
/// the material states of [`crate::element::hex8_full::internal_force_with_initial_strain`]
/// (same arguments) bit for bit, without its volume-averaged stress. Linear elasticity is
/// computed in lanes; plastic-damage points by [`PlasticDamage::update_points`].
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn internal_force<S: Simd>(
    simd: S,
    geo: &FullGeometry,
    material: &Material,
    u: &[[f64; 3]; 8],
    eps0: Option<&[Voigt]>,
    old: &[f64],
    new: &mut [f64],
    ctx: &PointContext,
    f: &mut [[f64; 3]; 8],
) {
    let eps = strains_with_initial(simd, geo, u, eps0);
    let sigma = match material {
        Material::Elastic(e) => elastic_stress_lanes(simd, e.lambda, e.mu, &eps),
        Material::PlasticDamage(p) => p.update_points(simd, &eps, old, new, ctx),
    };
    *f = point_forces(simd, geo, &sigma);
}

/// [`internal_force`] with the element's material states updated in place (`states`: the
/// committed states on entry, the new ones on return; [`PlasticDamage::update_points_in_place`]):
/// the same forces and states bit for bit, without a copy of the element's states. Returns
/// whether the hardening of any point moved ([`Material::hardening_moved`] of the old and
/// the new state of some point).
#[allow(clippy::too_many_arguments)]
#[inline(always)]
pub fn internal_force_in_place<S: Simd>(
    simd: S,
    geo: &FullGeometry,
    material: &Material,
    u: &[[f64; 3]; 8],
    eps0: Option<&[Voigt]>,
    states: &mut [f64],
    ctx: &PointContext,
    f: &mut [[f64; 3]; 8],
) -> bool {
    let eps = strains_with_initial(simd, geo, u, eps0);
    let (sigma, moved) = match material {
        Material::Elastic(e) => (elastic_stress_lanes(simd, e.lambda, e.mu, &eps), false),
        Material::PlasticDamage(p) => p.update_points_in_place(simd, &eps, states, ctx),
    };
    *f = point_forces(simd, geo, &sigma);
    moved
}

/// Strains of the eight points ([`point_strains`]) plus the initial strains `eps0`, if any.
#[inline(always)]
fn strains_with_initial<S: Simd>(
    simd: S,
    geo: &FullGeometry,
    u: &[[f64; 3]; 8],
    eps0: Option<&[Voigt]>,
) -> VoigtLanes {
    let mut eps = point_strains(simd, geo, u);
    if let Some(e0) = eps0 {
        for (g, e0g) in e0.iter().enumerate().take(8) {
            for i in 0..6 {
                eps[i][g] += e0g[i];
            }
        }
    }
    eps
}

/// One call of [`internal_force`] as a [`LaneWork`], for callers outside the step (tests,
/// benchmarks) that want the code the step runs: `run_lane_work(InternalForce { .. })`.
pub struct InternalForce<'a> {
    pub geo: &'a FullGeometry,
    pub material: &'a Material,
    pub u: &'a [[f64; 3]; 8],
    pub eps0: Option<&'a [Voigt]>,
    pub old: &'a [f64],
    pub new: &'a mut [f64],
    pub ctx: &'a PointContext,
    pub f: &'a mut [[f64; 3]; 8],
}

impl LaneWork for InternalForce<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: Simd>(self, simd: S) {
        internal_force(
            simd,
            self.geo,
            self.material,
            self.u,
            self.eps0,
            self.old,
            self.new,
            self.ctx,
            self.f,
        )
    }
}

/// Stiffness-proportional damping force β K0 v of a fully integrated element with the
/// points in lanes: the scalar `damping_force_full` of `element::groups` bit for bit
/// (elastic stress of the strain of v, scaled by β, integrated).
#[inline(always)]
pub fn damping_force<S: Simd>(
    simd: S,
    geo: &FullGeometry,
    lambda: f64,
    mu: f64,
    v: &[[f64; 3]; 8],
    beta: f64,
) -> [[f64; 3]; 8] {
    let s = elastic_stress_lanes(simd, lambda, mu, &point_strains(simd, geo, v));
    let b = F64s::splat(beta);
    point_forces(simd, geo, &s.map(|x| b * x))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8_full::internal_force_with_initial_strain;
    use crate::element::lanes::run_lane_work;
    use crate::material::Elastic;
    use crate::mesh::hex8_shape::NODE_XI;

    use crate::test_random::{cracking_concrete, Lcg};

    /// A randomly stretched, sheared and distorted hex8 (corners moved by up to 15 % of
    /// the edge) and random displacements of magnitude `mag`.
    fn random_element(rng: &mut Lcg, mag: f64) -> (FullGeometry, [[f64; 3]; 8]) {
        let scale = [
            0.2 + 3.0 * rng.next(),
            0.2 + 3.0 * rng.next(),
            0.2 + 3.0 * rng.next(),
        ];
        let shear = 0.3 * rng.sym();
        loop {
            let x: [[f64; 3]; 8] = std::array::from_fn(|a| {
                let n = NODE_XI[a];
                [
                    scale[0] * (0.5 * n[0] + 0.15 * rng.sym()) + shear * n[2],
                    scale[1] * (0.5 * n[1] + 0.15 * rng.sym()),
                    scale[2] * (0.5 * n[2] + 0.15 * rng.sym()),
                ]
            });
            if let Some(geo) = FullGeometry::new(&x) {
                let u =
                    std::array::from_fn(|_| [mag * rng.sym(), mag * rng.sym(), mag * rng.sym()]);
                return (geo, u);
            }
        }
    }

    fn bits(v: &[f64]) -> Vec<u64> {
        v.iter().map(|x| x.to_bits()).collect()
    }

    struct Damping<'a>(&'a FullGeometry, &'a Elastic, &'a [[f64; 3]; 8]);

    impl LaneWork for Damping<'_> {
        type Output = [[f64; 3]; 8];
        #[inline(always)]
        fn run<S: Simd>(self, simd: S) -> [[f64; 3]; 8] {
            damping_force(simd, self.0, self.1.lambda, self.1.mu, self.2, 1e-4)
        }
    }

    /// Forces and states the same bit for bit (`what`: the case, for the message).
    fn assert_same(
        got: &[[f64; 3]; 8],
        want: &[[f64; 3]; 8],
        got_state: &[f64],
        want_state: &[f64],
        what: &str,
    ) {
        assert_eq!(
            bits(got.as_flattened()),
            bits(want.as_flattened()),
            "forces, {what}"
        );
        assert_eq!(bits(got_state), bits(want_state), "states, {what}");
    }

    /// [`internal_force_in_place`] as a [`LaneWork`].
    struct InPlace<'a> {
        geo: &'a FullGeometry,
        material: &'a Material,
        u: &'a [[f64; 3]; 8],
        eps0: Option<&'a [Voigt]>,
        states: &'a mut [f64],
        ctx: &'a PointContext,
        f: &'a mut [[f64; 3]; 8],
    }

    impl LaneWork for InPlace<'_> {
        type Output = bool;
        #[inline(always)]
        fn run<S: Simd>(self, simd: S) -> bool {
            internal_force_in_place(
                simd,
                self.geo,
                self.material,
                self.u,
                self.eps0,
                self.states,
                self.ctx,
                self.f,
            )
        }
    }

    /// Forces and states of the lane kernel (dispatched and under pulp's scalar fallback,
    /// the path of a CPU without vectors; buffered and in place)
    /// against the scalar kernel, for `draws` random elements, with and without an initial
    /// strain; in place also whether some point's hardening moved. Three steps: loading
    /// from the virgin state, further loading, and unloading (damaged points inside their
    /// surface). Returns the number of points updated to a damaged and to an undamaged
    /// state, whether the in-place kernel reported [no hardening moved, some moved] in some
    /// draw, and the number of damaged points whose update kept their hardening.
    fn compare(
        material: &Material,
        mag: (f64, f64),
        draws: usize,
        (seed, reads_damage): (u64, bool),
    ) -> (usize, usize, [bool; 2], usize) {
        let mut rng = Lcg(seed);
        let stride = material.state_len();
        let (mut damaged, mut intact) = (0, 0);
        let mut moved_seen = [false; 2];
        let mut kept_damaged = 0;
        for draw in 0..draws {
            let m = mag.0 * (mag.1 / mag.0).powf(rng.next());
            let (geo, u) = random_element(&mut rng, m);
            let e0: Vec<Voigt> = (0..8)
                .map(|_| std::array::from_fn(|_| 0.3 * m * rng.sym()))
                .collect();
            let mut old = vec![0.0; 8 * stride];
            for s in old.chunks_exact_mut(stride.max(1)).take(8) {
                material.init_state(s);
            }
            let ctx = PointContext {
                char_length: 0.1 + rng.next(),
                dt: 1e-4,
                reads_damage,
            };
            // Three steps: from the virgin state, then from the state the first left (some
            // points yielded and damaged) to a larger displacement, then back to a smaller
            // one (most damaged points unload inside their surface).
            for factor in [1.0, 1.5, 1.2] {
                let us = u.map(|ua| ua.map(|x| factor * x));
                let mut next = Vec::new();
                for eps0 in [None, Some(&e0[..])] {
                    let mut want = [[0.0; 3]; 8];
                    let mut want_state = vec![0.0; 8 * stride];
                    internal_force_with_initial_strain(
                        &geo,
                        material,
                        &us,
                        eps0,
                        &old,
                        &mut want_state,
                        &ctx,
                        &mut want,
                    );
                    for dispatched in [false, true] {
                        let mut got = [[0.0; 3]; 8];
                        let mut got_state = vec![0.0; 8 * stride];
                        let call = InternalForce {
                            geo: &geo,
                            material,
                            u: &us,
                            eps0,
                            old: &old,
                            new: &mut got_state,
                            ctx: &ctx,
                            f: &mut got,
                        };
                        if dispatched {
                            run_lane_work(call)
                        } else {
                            call.run(pulp::Scalar::new())
                        }
                        let what = format!(
                            "draw {draw}, initial strain {}, dispatched {dispatched}",
                            eps0.is_some()
                        );
                        assert_same(&got, &want, &got_state, &want_state, &what);
                    }
                    // In place: the committed states overwritten by the new ones.
                    let want_moved = old
                        .chunks_exact(stride.max(1))
                        .zip(want_state.chunks_exact(stride.max(1)))
                        .any(|(o, n)| material.hardening_moved(o, n));
                    for dispatched in [false, true] {
                        let mut got = [[0.0; 3]; 8];
                        let mut states = old.clone();
                        let call = InPlace {
                            geo: &geo,
                            material,
                            u: &us,
                            eps0,
                            states: &mut states,
                            ctx: &ctx,
                            f: &mut got,
                        };
                        let moved = if dispatched {
                            run_lane_work(call)
                        } else {
                            call.run(pulp::Scalar::new())
                        };
                        let what = format!(
                            "in place, draw {draw}, initial strain {}, dispatched {dispatched}",
                            eps0.is_some()
                        );
                        assert_same(&got, &want, &states, &want_state, &what);
                        assert_eq!(moved, want_moved, "hardening moved, draw {draw}");
                        moved_seen[usize::from(moved)] = true;
                    }
                    for (o, state) in old
                        .chunks_exact(stride.max(1))
                        .zip(want_state.chunks_exact(stride.max(1)))
                    {
                        match material.tensile_and_compressive_damage(state) {
                            Some((dt, dc)) if dt > 0.0 || dc > 0.0 => {
                                damaged += 1;
                                kept_damaged += usize::from(!material.hardening_moved(o, state));
                            }
                            _ => intact += 1,
                        }
                    }
                    next = want_state;
                }
                old = next;
            }
        }
        (damaged, intact, moved_seen, kept_damaged)
    }

    #[test]
    fn lanes_give_the_scalar_forces_bit_for_bit_for_an_elastic_material() {
        let elastic = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
        compare(
            &Material::Elastic(elastic),
            (1e-6, 1e-2),
            300,
            (0x5eed_1234_abcd_0001, false),
        );
    }

    #[test]
    fn lanes_give_the_scalar_forces_and_states_bit_for_bit_for_plastic_damage() {
        // Displacements from well inside the elastic range to cracking and crushing
        // (ε_t0 ≈ 1e-4 on ≈ 1 m elements).
        // The Lee–Fenves rule (the default), whose damaged points inside their surface take
        // the yielded-elastic shortcut in lanes whether or not the element reads D.
        let (material, _) = cracking_concrete();
        for (seed, reads_damage) in [(0x0dd_ba11_cafe_0002, false), (0x0dd_ba11_cafe_0004, true)] {
            let (damaged, intact, moved_seen, kept) =
                compare(&material, (1e-6, 3e-3), 300, (seed, reads_damage));
            // Both the never-yielded shortcut and the return mapping are exercised, damaged
            // points keep their hardening, and the in-place kernel saw elements whose
            // hardening moved and elements whose did not.
            assert!(
                damaged > 500 && intact > 500 && kept > 300,
                "{damaged} damaged, {intact} intact points, {kept} damaged and kept"
            );
            assert_eq!(moved_seen, [true, true]);
        }
    }

    /// The consistent recovery rule (the Yingxiuwan concrete's), whose damaged points
    /// inside their surface take the yielded-elastic shortcut in lanes: forces and states
    /// as the scalar update's, bit for bit, with many such points.
    #[test]
    fn lanes_give_the_scalar_forces_and_states_bit_for_bit_under_the_consistent_rule() {
        use crate::material::plastic_damage::{PlasticDamageParams, Recovery};
        let el = Elastic::new("concrete", 30e9, 0.2, 2400.0).unwrap();
        let params = PlasticDamageParams {
            recovery: Recovery::Consistent,
            ..PlasticDamageParams::from_strengths(3e6, 20e6, 30e6, 100.0, 10e3)
        };
        let pd = crate::material::PlasticDamage::new("concrete", el, &params).unwrap();
        let material = Material::PlasticDamage(Box::new(pd));
        let (damaged, intact, moved_seen, kept) =
            compare(&material, (1e-6, 3e-3), 300, (0xc0_5157_e470_0003, false));
        assert!(
            damaged > 500 && intact > 500 && kept > 300,
            "{damaged} damaged, {intact} intact points, {kept} damaged and kept"
        );
        assert_eq!(moved_seen, [true, true]);
    }

    #[test]
    fn damping_lanes_give_the_scalar_forces_bit_for_bit() {
        let el = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
        let mut rng = Lcg(0xda3b_0003);
        for _ in 0..100 {
            let (geo, v) = random_element(&mut rng, 1e-1);
            let mut want = [[0.0; 3]; 8];
            for g in 0..8 {
                let s = el.stress(&geo.strain(g, &v)).map(|x| 1e-4 * x);
                geo.add_forces(g, &s, &mut want);
            }
            let got = run_lane_work(Damping(&geo, &el, &v));
            assert_eq!(bits(got.as_flattened()), bits(want.as_flattened()));
            let fallback = Damping(&geo, &el, &v).run(pulp::Scalar::new());
            assert_eq!(bits(fallback.as_flattened()), bits(want.as_flattened()));
        }
    }
}
