//! The update of eight one-point elements' points with the elements in SIMD lanes (issue
//! 11): the never-yielded check of [`PlasticDamage::virgin_elastic`] for eight points of
//! eight different elements at once (each with its own state and characteristic length),
//! the general update ([`PlasticDamage::update`]) for the points that fail it. Each lane
//! performs the scalar check's IEEE operations in the same order, so states and stresses
//! are those of eight calls of [`PlasticDamage::update_in_place`] bit for bit (tested in
//! `element::hex8_uniform_lanes`).

use super::{slot, virgin_bracket_lanes, write_virgin_lane, PlasticDamage};
use crate::element::lanes::{elastic_stress_lanes, F64s, Simd, VoigtLanes, LANES};
use crate::lanes8;
use crate::material::{PointContext, Voigt};
use seq_macro::seq;

// The lanes are written out eight at a time below.
const _: () = assert!(LANES == 8);

impl PlasticDamage {
    /// Update the point of each of eight elements in place, element l at strain lane l, its
    /// state `states[l]` (the committed state on entry, the new one on return) and context
    /// `ctx[l]`. Returns the nominal stresses (one lane per element) and, per element,
    /// whether its hardening moved. The same as [`PlasticDamage::update_in_place`] element by
    /// element, bit for bit.
    #[inline(always)]
    #[allow(clippy::identity_op)] // `seq!` writes PLASTIC + 0 for the first component
    pub fn update_elements_in_place<S: Simd>(
        &self,
        simd: S,
        strain: &VoigtLanes,
        states: &mut [&mut [f64]; LANES],
        ctx: &[PointContext; LANES],
    ) -> (VoigtLanes, [bool; LANES]) {
        // The elements whose point the shortcut may take: never yielded (the strains'
        // finiteness, which `update` checks first, joins the mask below, after the
        // arithmetic, so that this branch waits on the states alone).
        let mut virgin = [false; LANES];
        let mut any = false;
        for l in 0..LANES {
            let s = &states[l];
            virgin[l] = s[slot::Y_T] == 0.0 && s[slot::Y_C] == 0.0;
            any |= virgin[l];
        }
        let mut sigma = [F64s::ZERO; 6];
        let mut moved = [false; LANES];
        let mut pass = [false; LANES];
        if any {
            // σ̄ = E₀ : (ε − εᵖ), the plastic strains read one component at a time.
            let mut plastic = [F64s::ZERO; 6];
            seq!(I in 0..6 {
                plastic[I] = lanes8!(l => states[l][slot::PLASTIC + I]);
            });
            // An optimisation barrier (like the displacements' in `element::groups`): the
            // vectors are stored whole and read back as vectors, so that the arithmetic
            // below is vectorised across the lanes.
            std::hint::black_box(&mut plastic);
            let mut trial = [F64s::ZERO; 6];
            for i in 0..6 {
                trial[i] = strain[i] - plastic[i];
            }
            let el = &self.elastic;
            let eff = elastic_stress_lanes(simd, el.lambda, el.mu, &trial);
            let (beta, limit) = match self.virgin_bound {
                Some((beta, limit)) => (F64s::splat(beta), F64s::splat(limit)),
                None => {
                    let (mut beta, mut limit) = (F64s::ZERO, F64s::ZERO);
                    for l in 0..LANES {
                        (beta[l], limit[l]) = self.virgin_bound_for(ctx[l].char_length.max(1e-12));
                    }
                    (beta, limit)
                }
            };
            let bracket = virgin_bracket_lanes(simd, &self.surface, &beta, &eff);
            // The mask without branches (`&` on bools): finite strains ((ε − ε) = 0 is
            // false for ±∞ and NaN), β ≥ 0 and the bracket within the limit.
            let mut finite = [true; LANES];
            for e in strain {
                #[allow(clippy::eq_op)] // ε − ε: 0 when ε is finite, NaN when not
                let zero = *e - *e;
                for l in 0..LANES {
                    finite[l] &= zero[l] == 0.0;
                }
            }
            let mut all = true;
            for l in 0..LANES {
                pass[l] = virgin[l] & finite[l] & (beta[l] >= 0.0) & (bracket[l] <= limit[l]);
                all &= pass[l];
            }
            if all {
                seq!(L in 0..8 {
                    write_virgin_lane(states[L], strain, &eff, L);
                });
                return (eff, moved);
            }
            for l in 0..LANES {
                if pass[l] {
                    write_virgin_lane(states[l], strain, &eff, l);
                    for i in 0..6 {
                        sigma[i][l] = eff[i][l];
                    }
                }
            }
        }
        for l in 0..LANES {
            if !pass[l] {
                let mut point: Voigt = [0.0; 6];
                for i in 0..6 {
                    point[i] = strain[i][l];
                }
                let (s, m) = self.update_general_in_place(&point, states[l], &ctx[l]);
                moved[l] = m;
                for i in 0..6 {
                    sigma[i][l] = s[i];
                }
            }
        }
        (sigma, moved)
    }
}
