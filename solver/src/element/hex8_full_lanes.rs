//! Fully integrated elastic hex8 in SIMD lanes (issue 11): the internal forces of
//! [`LANES`] elements at once, each lane doing the IEEE operations of the scalar kernel
//! ([`crate::element::hex8_full::internal_force`] with an elastic material) in the same
//! order, so that the forces are the scalar ones bit for bit (tested on random elements).
//!
//! Per Gauss point g and lane (as in `hex8_full`):
//!
//! ```text
//! H_ik = Σ_a u_ai ∂N_a/∂ξ_k,   G = H J⁻¹,   ε = sym G,   σ = λ tr ε I + 2μ ε
//! P_ik = w det J Σ_j σ_ij (J⁻¹)_kj,   f_ai += Σ_k ∂N_a/∂ξ_k P_ik
//! ```
//!
//! The geometry stays stored per element ([`FullGeometry`], 640 bytes); J⁻¹ and w det J of
//! one point are gathered into lanes as the point is reached.

use crate::element::hex8_full::{FullGeometry, NATURAL_DERIVATIVES};
use crate::element::lanes::{elastic_stress, F64s, NodalLanes, LANES};

/// J⁻¹ and w det J of Gauss point `g` of the elements of a lane block.
#[inline(always)]
fn point_geometry(geo: &[&FullGeometry; LANES], g: usize) -> ([[F64s; 3]; 3], F64s) {
    let mut ji = [[F64s::ZERO; 3]; 3];
    let mut w = F64s::ZERO;
    for (l, e) in geo.iter().enumerate() {
        for k in 0..3 {
            for j in 0..3 {
                ji[k][j].0[l] = e.jinv[g][k][j];
            }
        }
        w.0[l] = e.wdet[g];
    }
    (ji, w)
}

/// Internal forces of [`LANES`] fully integrated linear elastic elements (Lamé λ, μ) with
/// nodal displacements `u`: lane l of the result is `hex8_full::internal_force` of
/// element l, bit for bit.
#[inline(always)]
pub fn elastic_internal_forces(
    geo: &[&FullGeometry; LANES],
    lambda: f64,
    mu: f64,
    u: &NodalLanes,
) -> NodalLanes {
    let mut f = [[F64s::ZERO; 3]; 8];
    for (g, d) in NATURAL_DERIVATIVES.iter().enumerate() {
        let (ji, w) = point_geometry(geo, g);
        // H_ik = Σ_a u_ai d_ak, accumulated from zero in node order (FullGeometry::gradient).
        let mut h = [[F64s::ZERO; 3]; 3];
        for a in 0..8 {
            for i in 0..3 {
                for k in 0..3 {
                    h[i][k] = h[i][k] + u[a][i] * F64s::splat(d[a][k]);
                }
            }
        }
        let gr: [[F64s; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|j| h[i][0] * ji[0][j] + h[i][1] * ji[1][j] + h[i][2] * ji[2][j])
        });
        let eps = [
            gr[0][0],
            gr[1][1],
            gr[2][2],
            gr[0][1] + gr[1][0],
            gr[1][2] + gr[2][1],
            gr[2][0] + gr[0][2],
        ];
        let s = elastic_stress(lambda, mu, &eps);
        // FullGeometry::add_forces.
        let sig = [[s[0], s[3], s[5]], [s[3], s[1], s[4]], [s[5], s[4], s[2]]];
        let p: [[F64s; 3]; 3] = std::array::from_fn(|i| {
            std::array::from_fn(|k| {
                w * (sig[i][0] * ji[k][0] + sig[i][1] * ji[k][1] + sig[i][2] * ji[k][2])
            })
        });
        for a in 0..8 {
            let (d0, d1, d2) = (
                F64s::splat(d[a][0]),
                F64s::splat(d[a][1]),
                F64s::splat(d[a][2]),
            );
            for i in 0..3 {
                f[a][i] = f[a][i] + (d0 * p[i][0] + d1 * p[i][1] + d2 * p[i][2]);
            }
        }
    }
    f
}

/// The nodal values of [`LANES`] elements as lanes (`x[l]` is element l's).
#[inline(always)]
pub fn to_lanes(x: &[[[f64; 3]; 8]; LANES]) -> NodalLanes {
    let mut out = [[F64s::ZERO; 3]; 8];
    for (l, xl) in x.iter().enumerate() {
        for a in 0..8 {
            for i in 0..3 {
                out[a][i].0[l] = xl[a][i];
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8_full::internal_force;
    use crate::element::lanes::{dispatch, lane_of};
    use crate::material::{Elastic, Material, PointContext};
    use crate::mesh::hex8_shape::NODE_XI;

    /// A small deterministic generator (64-bit LCG, top 53 bits) for random elements.
    struct Lcg(u64);
    impl Lcg {
        fn next(&mut self) -> f64 {
            self.0 = self
                .0
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (self.0 >> 11) as f64 / (1u64 << 53) as f64
        }
        fn sym(&mut self) -> f64 {
            2.0 * self.next() - 1.0
        }
    }

    /// A randomly stretched, sheared and distorted hex8 (corners moved by up to 15 % of
    /// the edge) and random displacements spanning several orders of magnitude.
    fn random_element(rng: &mut Lcg) -> (FullGeometry, [[f64; 3]; 8]) {
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
                let mag = 10f64.powf(-6.0 + 4.0 * rng.next());
                let u =
                    std::array::from_fn(|_| [mag * rng.sym(), mag * rng.sym(), mag * rng.sym()]);
                return (geo, u);
            }
        }
    }

    #[test]
    fn lanes_give_the_scalar_forces_bit_for_bit_on_random_elements() {
        let mut rng = Lcg(0x5eed_1234_abcd_0001);
        let elastic = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
        let mat = Material::Elastic(elastic);
        let ctx = PointContext {
            char_length: 1.0,
            dt: 1e-4,
        };
        for _block in 0..200 {
            let elems: [(FullGeometry, [[f64; 3]; 8]); LANES] =
                std::array::from_fn(|_| random_element(&mut rng));
            let geo: [&FullGeometry; LANES] = std::array::from_fn(|l| &elems[l].0);
            let u = to_lanes(&std::array::from_fn(|l| elems[l].1));
            let plain = elastic_internal_forces(&geo, elastic.lambda, elastic.mu, &u);
            let simd = dispatch(|| elastic_internal_forces(&geo, elastic.lambda, elastic.mu, &u));
            for (l, (g, ue)) in elems.iter().enumerate() {
                let mut f = [[0.0; 3]; 8];
                internal_force(g, &mat, ue, &[], &mut [], &ctx, &mut f);
                for (got, want) in [lane_of(&plain, l), lane_of(&simd, l)].iter().zip([f, f]) {
                    for a in 0..8 {
                        for i in 0..3 {
                            assert_eq!(
                                got[a][i].to_bits(),
                                want[a][i].to_bits(),
                                "lane {l} node {a} dir {i}: {} vs {}",
                                got[a][i],
                                want[a][i]
                            );
                        }
                    }
                }
            }
        }
    }
}
