//! The update of the eight Gauss points of a fully integrated element with the points in
//! SIMD lanes (issue 11): the never-yielded check of [`PlasticDamage::virgin_elastic`]
//! (trial effective stress, invariant bound of eq. 25) for the eight points at once, and
//! the general update ([`PlasticDamage::update`]) for the points that fail it. Each lane
//! performs the scalar check's IEEE operations in the same order, so states and stresses
//! are those of eight calls of [`PlasticDamage::update`] bit for bit (tested in
//! `element::hex8_full_lanes`).

use super::{slot, virgin_bound, virgin_bracket, PlasticDamage};
use crate::element::lanes::{elastic_stress, F64s, VoigtLanes, LANES};
use crate::material::{PointContext, Voigt};

impl PlasticDamage {
    /// Update the eight points of an element, point g at strain lane g, its state
    /// `old[g·LEN..]` → `new[g·LEN..]`; returns the nominal stresses, one lane per point.
    /// The same states and stresses as [`PlasticDamage::update`] point by point.
    #[inline(always)]
    pub fn update_points(
        &self,
        strain: &VoigtLanes,
        old: &[f64],
        new: &mut [f64],
        ctx: &PointContext,
    ) -> VoigtLanes {
        const N: usize = slot::LEN;
        let old = &old[..LANES * N];
        let new = &mut new[..LANES * N];
        // The points the shortcut may take: never yielded, finite strain (else `update`
        // decides, as it does first).
        let mut candidate = [false; LANES];
        let mut plastic_rows = [[0.0; 6]; LANES];
        for (g, (row, state)) in plastic_rows.iter_mut().zip(old.chunks_exact(N)).enumerate() {
            candidate[g] = state[slot::Y_T] == 0.0
                && state[slot::Y_C] == 0.0
                && (0..6).all(|i| strain[i][g].is_finite());
            row.copy_from_slice(&state[slot::PLASTIC..slot::PLASTIC + 6]);
        }
        let plastic: [F64s; 6] =
            std::array::from_fn(|i| F64s(std::array::from_fn(|g| plastic_rows[g][i])));
        let el = &self.elastic;
        let trial: VoigtLanes = std::array::from_fn(|i| strain[i] - plastic[i]);
        let eff = elastic_stress(el.lambda, el.mu, &trial);
        let pass = if candidate.iter().any(|&c| c) {
            let l = ctx.char_length.max(1e-12);
            let (beta, limit) = self.virgin_bound.unwrap_or_else(|| {
                let (t, c) = self.element_laws(l);
                virgin_bound(&self.surface, t.law.f0, c.law.f0)
            });
            let bracket = virgin_bracket(&self.surface, beta, &eff);
            std::array::from_fn(|g| candidate[g] && beta >= 0.0 && bracket[g] <= limit)
        } else {
            [false; LANES]
        };
        let mut sigma = [F64s::ZERO; 6];
        for (g, (o, n)) in old.chunks_exact(N).zip(new.chunks_exact_mut(N)).enumerate() {
            if pass[g] {
                // Value by value from the lanes: a point's Voigt vectors are never staged
                // as arrays (a wide load of narrow stores stalls store forwarding).
                n.copy_from_slice(o);
                for i in 0..6 {
                    n[slot::STRAIN + i] = strain[i][g];
                    n[slot::STRESS + i] = eff[i][g];
                }
                n[slot::DAMAGE] = 0.0;
                for i in 0..6 {
                    sigma[i][g] = eff[i][g];
                }
            } else {
                let point: Voigt = std::array::from_fn(|i| strain[i][g]);
                let s = self.update(&point, o, n, ctx);
                for i in 0..6 {
                    sigma[i][g] = s[i];
                }
            }
        }
        sigma
    }
}
