//! One-point hex8 elements eight at a time in SIMD lanes (issue 11 item 1): the geometry of
//! a group's one-point elements is kept a second time as structure of arrays in blocks of
//! [`LANES`] consecutive elements ([`UniformBlock`]: each value of [`UniformGeometry`] one
//! [`F64s`] of eight elements), so that the kernel loads it with wide loads; the nodal
//! displacements are gathered one lane vector at a time, the material points of the eight
//! elements are updated together ([`Material::update_elements_in_place`]), and the forces
//! come back as lanes.
//!
//! The formulas are those of the scalar kernel, written once for both
//! ([`gradient_and_modes_of`] and its siblings, generic over
//! [`Lane`](crate::element::lanes::Lane)): each
//! lane performs the IEEE operations of
//! [`internal_force_in_place`](crate::element::hex8_uniform::internal_force_in_place) in the same
//! order, so forces, stresses and states are the scalar kernel's bit for bit (tested below
//! and on whole runs in `tests/element_lanes.rs`). An earlier attempt that gathered the
//! geometry from the array of structures into lanes at every step was slower than the
//! scalar kernel (docs/benchmarks.md, 2026-11-28): narrow stores read back by wide loads.
//! A group keeps its blocks, like its elements' geometry, once per distinct block
//! ([`UniformSet`](crate::element::uniform_set::UniformSet)).

use crate::element::hex8_uniform::{
    forces_kq_of, gradient_and_modes_of, modes_from_of, strain_of, UniformGeometry,
};
use crate::element::lanes::{F64s, LaneWork, NodalLanes, Simd, VoigtLanes, LANES};
use crate::lanes8;
use crate::material::{Material, PointContext};
use seq_macro::seq;

// The lanes are written out eight at a time below.
const _: () = assert!(LANES == 8);

/// The geometry of [`LANES`] consecutive one-point elements, value by value in lanes (304
/// bytes per element, like [`UniformGeometry`]).
#[derive(Clone, Copy, Debug, Default)]
pub struct UniformBlock {
    /// Mean gradient b_ai (1/m).
    pub b: [[F64s; 3]; 8],
    /// h_αj = Σ_b Γ_αb x_bj (m).
    pub h: [[F64s; 3]; 4],
    /// Volume V (m³).
    pub volume: F64s,
    /// Hourglass stiffness κ (N/m).
    pub kappa: F64s,
}

impl UniformBlock {
    /// The block of the elements `geo` (exactly [`LANES`] of them).
    pub fn new(geo: &[UniformGeometry; LANES]) -> Self {
        let lanes = |f: &dyn Fn(&UniformGeometry) -> f64| F64s(std::array::from_fn(|l| f(&geo[l])));
        Self {
            b: std::array::from_fn(|a| std::array::from_fn(|i| lanes(&|g| g.b[a][i]))),
            h: std::array::from_fn(|al| std::array::from_fn(|j| lanes(&|g| g.h[al][j]))),
            volume: lanes(&|g| g.volume),
            kappa: lanes(&|g| g.kappa),
        }
    }
}

/// [`crate::element::hex8_uniform::internal_force_in_place`] of the eight elements of `block`
/// (the material's arithmetic in the vectors of `simd`): nodal
/// displacements `u` (one lane per element), initial strains `eps0` (if any), the
/// elements' states `states[l]` updated in place with contexts `ctx[l]`. Returns the
/// nodal forces in lanes and, per element, whether its hardening moved — bit for bit the
/// scalar kernel's.
#[inline(always)]
pub fn internal_forces_in_place<S: Simd>(
    simd: S,
    block: &UniformBlock,
    material: &Material,
    u: &NodalLanes,
    eps0: Option<&VoigtLanes>,
    states: &mut [&mut [f64]; LANES],
    ctx: &[PointContext; LANES],
) -> (NodalLanes, [bool; LANES]) {
    let (g, gu) = gradient_and_modes_of(simd, &block.b, u);
    let mut eps = strain_of(&g);
    if let Some(e0) = eps0 {
        for i in 0..6 {
            eps[i] = eps[i] + e0[i];
        }
    }
    let (sigma, moved) = material.update_elements_in_place(simd, &eps, states, ctx);
    // Hourglass stiffness of the damaged material: κ (1 − D), exactly κ when elastic.
    let mut factor = F64s::ZERO;
    for l in 0..LANES {
        factor[l] = material.stiffness_factor(states[l]);
    }
    let kappa = block.kappa * factor;
    let mut kq = modes_from_of(simd, &block.h, &g, &gu);
    for row in kq.iter_mut() {
        for x in row.iter_mut() {
            *x = kappa * *x;
        }
    }
    let f = forces_kq_of(simd, &block.b, &block.h, block.volume, &sigma, &kq);
    (f, moved)
}

/// [`internal_forces_in_place`] as a [`LaneWork`] of its own: called from the dispatched
/// force pass, it is compiled apart from it, with its inputs as vectors in memory. Inlined
/// into the pass, the compiler vectorised it only partly (slower than the scalar kernel,
/// measured).
pub struct LaneKernel<'a, 's> {
    /// The elements' geometry.
    pub block: &'a UniformBlock,
    /// Their material.
    pub material: &'a Material,
    /// Their nodal displacements.
    pub u: &'a NodalLanes,
    /// Their initial strains, if any.
    pub eps0: Option<&'a VoigtLanes>,
    /// Their states, updated in place.
    pub states: &'a mut [&'s mut [f64]; LANES],
    /// Their contexts.
    pub ctx: &'a [PointContext; LANES],
}

impl LaneWork for LaneKernel<'_, '_> {
    type Output = (NodalLanes, [bool; LANES]);
    #[inline(always)]
    fn run<S: Simd>(self, simd: S) -> Self::Output {
        internal_forces_in_place(
            simd,
            self.block,
            self.material,
            self.u,
            self.eps0,
            self.states,
            self.ctx,
        )
    }
}

/// Nodal values `x[conn[l][a]] − reference[l][a]` of eight elements in lanes, one lane
/// vector at a time (each vector built from its eight loads in registers, never staged
/// through memory as scalars). Unrolled in the source like the kernel's formulas
/// ([`gradient_and_modes_of`]).
#[inline(always)]
pub fn gather_relative(
    x: &[[f64; 3]],
    conn: &[[u32; 8]; LANES],
    reference: Option<&[[[f64; 3]; 8]; LANES]>,
) -> NodalLanes {
    let mut out = [[F64s::ZERO; 3]; 8];
    seq!(A in 0..8 {
        seq!(I in 0..3 {
            out[A][I] = lanes8!(l => x[conn[l][A] as usize][I]);
        });
    });
    if let Some(r) = reference {
        seq!(A in 0..8 {
            seq!(I in 0..3 {
                out[A][I] = out[A][I] - lanes8!(l => r[l][A][I]);
            });
        });
    }
    out
}

/// A Voigt vector per element of eight, in lanes.
#[inline(always)]
pub fn voigt_lanes(v: &[[f64; 6]; LANES]) -> VoigtLanes {
    let mut out = [F64s::ZERO; 6];
    seq!(I in 0..6 {
        out[I] = lanes8!(l => v[l][I]);
    });
    out
}

/// Lane `l` of nodal lanes `f` into `out` (unrolled like [`gather_relative`]).
#[inline(always)]
pub fn write_lane(f: &NodalLanes, l: usize, out: &mut [[f64; 3]; 8]) {
    seq!(A in 0..8 {
        seq!(I in 0..3 {
            out[A][I] = f[A][I][l];
        });
    });
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8_shape::NODE_XI;
    use crate::element::hex8_uniform::internal_force_in_place;
    use crate::element::lanes::{lane_of, run_lane_work, LaneWork, Simd};
    use crate::material::plastic_damage::{PlasticDamageParams, Regularisation};
    use crate::material::{Elastic, PlasticDamage, Voigt};
    use crate::test_random::{cracking_concrete, Lcg};

    /// The three materials the kernel meets: cracking concrete (strength bound the same
    /// for every element), the same under the total regularisation (bound per element
    /// length), linear elasticity (no state).
    fn materials() -> Vec<Material> {
        let (pd, el) = cracking_concrete();
        let mut params = PlasticDamageParams::from_strengths(3e6, 20e6, 30e6, 100.0, 10e3);
        params.regularisation = Regularisation::Total;
        let total = PlasticDamage::new("total", el, &params).unwrap();
        vec![
            pd,
            Material::PlasticDamage(Box::new(total)),
            Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2600.0).unwrap()),
        ]
    }

    /// A distorted element of size 0.3–3 m.
    fn element(rng: &mut Lcg) -> [[f64; 3]; 8] {
        let size = 0.3 * (10f64).powf(rng.next());
        std::array::from_fn(|a| NODE_XI[a].map(|v| size * (0.5 * (v + 1.0) + 0.12 * rng.sym())))
    }

    struct Lanes<'a> {
        block: &'a UniformBlock,
        material: &'a Material,
        u: &'a NodalLanes,
        eps0: Option<&'a VoigtLanes>,
        states: &'a mut [Vec<f64>; LANES],
        ctx: &'a [PointContext; LANES],
    }

    impl LaneWork for Lanes<'_> {
        type Output = (NodalLanes, [bool; LANES]);
        #[inline(always)]
        fn run<S: Simd>(self, simd: S) -> Self::Output {
            let mut s = self.states.each_mut().map(|v| v.as_mut_slice());
            internal_forces_in_place(
                simd,
                self.block,
                self.material,
                self.u,
                self.eps0,
                &mut s,
                self.ctx,
            )
        }
    }

    /// Eight random elements at once give the scalar kernel's forces, states and "moved"
    /// bit for bit, dispatched like the force pass and not: displacements from well
    /// inside the elastic range to cracking (mixed within a block), two steps (the second
    /// from the states the first left), with and without initial strains and reference
    /// displacements, with a node whose displacement is not finite every tenth draw, for
    /// each material.
    #[test]
    fn eight_elements_in_lanes_are_the_scalar_kernel_bit_for_bit() {
        // Bit for bit, except that every NaN counts as one (IEEE 754 leaves the sign and
        // payload of a NaN result to the operand order, which the lanes do not keep).
        let bits = |v: &[f64]| {
            v.iter()
                .map(|x| if x.is_nan() { u64::MAX } else { x.to_bits() })
                .collect::<Vec<_>>()
        };
        let mut rng = Lcg(0x5eed_0008_1a2b);
        for (m, material) in materials().into_iter().enumerate() {
            let el = *material.elastic();
            let mut seen = [false; 2];
            for draw in 0..300 {
                let x: [[[f64; 3]; 8]; LANES] = std::array::from_fn(|_| element(&mut rng));
                let geo: [UniformGeometry; LANES] =
                    x.map(|x| UniformGeometry::new(&x, &el, 0.05).unwrap());
                let block = UniformBlock::new(&geo);
                let ctx: [PointContext; LANES] = std::array::from_fn(|l| PointContext {
                    char_length: crate::element::stable_step::characteristic_length(
                        &x[l],
                        geo[l].volume,
                    ),
                    dt: 1e-4,
                    reads_damage: true,
                });
                // Nodes: the first 24 of a pool, so that elements share nodes.
                let mut pool: Vec<[f64; 3]> = (0..40)
                    .map(|_| {
                        let mag = 1e-6 * (3e3f64).powf(rng.next());
                        [mag * rng.sym(), mag * rng.sym(), mag * rng.sym()]
                    })
                    .collect();
                // Every tenth draw, one node's displacement not finite (NaN, +∞ or −∞):
                // the elements on it leave the never-yielded shortcut as the scalar
                // check's finiteness test sends them.
                if draw % 10 == 9 {
                    let bad = [f64::NAN, f64::INFINITY, f64::NEG_INFINITY][(draw / 10) % 3];
                    pool[(draw / 10) % 24][draw % 3] = bad;
                }
                let conn: [[u32; 8]; LANES] =
                    std::array::from_fn(|_| std::array::from_fn(|_| (rng.next() * 24.0) as u32));
                let reference: [[[f64; 3]; 8]; LANES] = std::array::from_fn(|_| {
                    std::array::from_fn(|_| [1e-6 * rng.sym(), 1e-6 * rng.sym(), 0.0])
                });
                let e0: [Voigt; LANES] =
                    std::array::from_fn(|_| std::array::from_fn(|_| 2e-5 * rng.sym()));
                let with_e0 = draw % 2 == 1;
                let with_reference = draw % 3 == 1;
                let mut scalar_states: [Vec<f64>; LANES] = std::array::from_fn(|_| {
                    let mut s = vec![0.0; material.state_len()];
                    material.init_state(&mut s);
                    s
                });
                let mut lane_states = scalar_states.clone();
                for step in 0..2 {
                    let scale = 1.0 + 0.7 * step as f64;
                    let nodes: Vec<[f64; 3]> = pool.iter().map(|p| p.map(|v| scale * v)).collect();
                    let u = gather_relative(&nodes, &conn, with_reference.then_some(&reference));
                    let e0l = voigt_lanes(&e0);
                    let eps0 = with_e0.then_some(&e0l);
                    let mut plain_states = lane_states.clone();
                    let (f, moved) = run_lane_work(Lanes {
                        block: &block,
                        material: &material,
                        u: &u,
                        eps0,
                        states: &mut lane_states,
                        ctx: &ctx,
                    });
                    let (f_plain, moved_plain) = Lanes {
                        block: &block,
                        material: &material,
                        u: &u,
                        eps0,
                        states: &mut plain_states,
                        ctx: &ctx,
                    }
                    .run(pulp::Scalar::new());
                    for l in 0..LANES {
                        let mut ue: [[f64; 3]; 8] =
                            std::array::from_fn(|a| nodes[conn[l][a] as usize]);
                        if with_reference {
                            for a in 0..8 {
                                for d in 0..3 {
                                    ue[a][d] -= reference[l][a][d];
                                }
                            }
                        }
                        let old = scalar_states[l].clone();
                        let mut want = [[0.0; 3]; 8];
                        let (_, want_moved) = internal_force_in_place(
                            &geo[l],
                            &material,
                            &ue,
                            with_e0.then_some(&e0[l]),
                            &mut scalar_states[l],
                            &ctx[l],
                            &mut want,
                        );
                        let what = format!("material {m} draw {draw} step {step} lane {l}");
                        assert_eq!(
                            bits(lane_of(&f, l).as_flattened()),
                            bits(want.as_flattened()),
                            "{what}"
                        );
                        assert_eq!(
                            bits(lane_of(&f_plain, l).as_flattened()),
                            bits(want.as_flattened()),
                            "{what}"
                        );
                        assert_eq!(bits(&lane_states[l]), bits(&scalar_states[l]), "{what}");
                        assert_eq!(bits(&plain_states[l]), bits(&scalar_states[l]), "{what}");
                        assert_eq!(
                            (moved[l], moved_plain[l]),
                            (want_moved, want_moved),
                            "{what}"
                        );
                        if material.has_damage() {
                            seen[usize::from(material.hardening_moved(&old, &scalar_states[l]))] =
                                true;
                        }
                    }
                }
            }
            if material.has_damage() {
                assert_eq!(seen, [true, true], "material {m}: both regimes met");
            }
        }
    }
}
