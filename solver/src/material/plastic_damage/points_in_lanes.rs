//! The update of the eight Gauss points of a fully integrated element with the points in
//! SIMD lanes (issue 11): the never-yielded check of [`PlasticDamage::virgin_elastic`]
//! (trial effective stress, invariant bound of eq. 25) for the eight points at once, and
//! the general update ([`PlasticDamage::update`]) for the points that fail it. Each lane
//! performs the scalar check's IEEE operations in the same order, so states and stresses
//! are those of eight calls of [`PlasticDamage::update`] bit for bit (tested in
//! `element::hex8_full_lanes`).

use super::{slot, virgin_bracket, write_virgin_lane, PlasticDamage};
use crate::element::lanes::{elastic_stress, F64s, VoigtLanes, LANES};
use crate::material::{PointContext, Voigt};

impl PlasticDamage {
    /// The never-yielded shortcut of the eight points of an element whose states are
    /// `states` (point g at `states[g·LEN..]`), strain lane g for point g: the effective
    /// stresses σ̄ = E₀ : (ε − εᵖ) in lanes and which points pass
    /// [`PlasticDamage::virgin_elastic`]'s check (never yielded, finite strain, inside the
    /// initial surface by the margin). Reads the states only.
    #[inline(always)]
    fn virgin_lanes(
        &self,
        strain: &VoigtLanes,
        states: &[f64],
        ctx: &PointContext,
    ) -> (VoigtLanes, [bool; LANES]) {
        const N: usize = slot::LEN;
        // The points the shortcut may take: never yielded, finite strain (else `update`
        // decides, as it does first).
        let mut candidate = [false; LANES];
        let mut plastic_rows = [[0.0; 6]; LANES];
        for (g, (row, state)) in plastic_rows
            .iter_mut()
            .zip(states.chunks_exact(N))
            .enumerate()
        {
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
            let (beta, limit) = self.virgin_bound_for(ctx.char_length.max(1e-12));
            let bracket = virgin_bracket(&self.surface, F64s::splat(beta), &eff);
            std::array::from_fn(|g| candidate[g] && beta >= 0.0 && bracket[g] <= limit)
        } else {
            [false; LANES]
        };
        (eff, pass)
    }

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
        let (eff, pass) = self.virgin_lanes(strain, old, ctx);
        let mut sigma = [F64s::ZERO; 6];
        for (g, (o, n)) in old.chunks_exact(N).zip(new.chunks_exact_mut(N)).enumerate() {
            if pass[g] {
                n.copy_from_slice(o);
                write_virgin_lane(n, strain, &eff, g);
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

    /// [`Self::update_points`] with the states updated in place (`states[g·LEN..]`, the
    /// committed state of point g on entry, its new state on return): a point that takes
    /// the never-yielded shortcut has only its strain, stress and D written (the rest of
    /// its state is the old one already), and only a point that takes the general update
    /// is first copied, alone, to the stack as its old state. The same states and
    /// stresses as [`Self::update_points`] bit for bit; second: whether the hardening of
    /// any point moved ([`PlasticDamage::hardening_moved`] of its old and new state).
    #[inline(always)]
    pub fn update_points_in_place(
        &self,
        strain: &VoigtLanes,
        states: &mut [f64],
        ctx: &PointContext,
    ) -> (VoigtLanes, bool) {
        const N: usize = slot::LEN;
        let states = &mut states[..LANES * N];
        let (eff, pass) = self.virgin_lanes(strain, states, ctx);
        let mut sigma = [F64s::ZERO; 6];
        let mut moved = false;
        for (g, n) in states.chunks_exact_mut(N).enumerate() {
            if pass[g] {
                write_virgin_lane(n, strain, &eff, g);
                for i in 0..6 {
                    sigma[i][g] = eff[i][g];
                }
            } else {
                let point: Voigt = std::array::from_fn(|i| strain[i][g]);
                let (s, m) = self.update_general_in_place(&point, n, ctx);
                moved |= m;
                for i in 0..6 {
                    sigma[i][g] = s[i];
                }
            }
        }
        (sigma, moved)
    }
}
