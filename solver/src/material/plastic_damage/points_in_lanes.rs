//! The update of the eight Gauss points of a fully integrated element with the points in
//! SIMD lanes (issue 11): the never-yielded check of [`PlasticDamage::virgin_elastic`]
//! (trial effective stress, invariant bound of eq. 25) for the eight points at once, and
//! the shortcut of [`PlasticDamage::yielded_elastic`] under either recovery rule for a
//! yielded point inside its surface by the invariant bound (the bound, the nominal stress
//! of `recovery_in_lanes` and the dissipation in lanes), and the general update
//! ([`PlasticDamage::update`]) for the points that take neither. Each lane performs the
//! scalar path's IEEE operations in the same order, so states and stresses are those of
//! eight calls of [`PlasticDamage::update`] bit for bit (tested in
//! `element::hex8_full_lanes`, and the nominal stress in `recovery_in_lanes`).

use super::recovery_in_lanes::{consistent_stress_lanes, lee_fenves_stress_lanes};
use super::{
    dissipated_after, slot, virgin_bound, virgin_bracket_in, virgin_bracket_lanes,
    write_virgin_lane, PlasticDamage, Recovery,
};
use crate::element::lanes::{
    elastic_stress_in, part, parts, set_part, F64s, Simd, VoigtLanes, LANES,
};
use crate::material::{PointContext, Voigt};

/// What the yielded-elastic shortcut gives the points of an element that take it in lanes
/// ([`PlasticDamage::yielded_lanes`]): which lanes, their nominal stresses, the D slot
/// and the dissipation density to store.
struct YieldedLanes {
    pass: [bool; LANES],
    sigma: VoigtLanes,
    damage: F64s,
    dissipated: F64s,
}

impl YieldedLanes {
    /// The new state of lane `g` over its old values in `n` (a yielded-elastic step keeps
    /// εᵖ, y_t, y_c and the fracture energy): [`PlasticDamage::commit`]'s writes.
    #[inline(always)]
    fn write(&self, n: &mut [f64], strain: &VoigtLanes, g: usize) {
        for i in 0..6 {
            n[slot::STRAIN + i] = strain[i][g];
            n[slot::STRESS + i] = self.sigma[i][g];
        }
        n[slot::DAMAGE] = self.damage[g];
        n[slot::DISSIPATED] = self.dissipated[g];
    }
}

impl PlasticDamage {
    /// The never-yielded shortcut of the eight points of an element whose states are
    /// `states` (point g at `states[g·LEN..]`), strain lane g for point g: the effective
    /// stresses σ̄ = E₀ : (ε − εᵖ) in lanes and which points pass
    /// [`PlasticDamage::virgin_elastic`]'s check (never yielded, finite strain, inside the
    /// initial surface by the margin). Reads the states only.
    #[inline(always)]
    fn virgin_lanes<S: Simd>(
        &self,
        simd: S,
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
        let any = candidate.iter().any(|&c| c);
        let (beta, limit) = if any {
            self.virgin_bound_for(ctx.char_length.max(1e-12))
        } else {
            (-1.0, 0.0)
        };
        // σ̄ = E₀ : (ε − εᵖ) and the bracket, one vector of points at a time in the
        // vectors of `simd` (as `F64s` operators the compiler kept them in memory).
        let mut eff = [F64s::ZERO; 6];
        let mut bracket = F64s::ZERO;
        for p in 0..parts::<S>() {
            let mut trial = [simd.splat_f64s(0.0); 6];
            for (i, t) in trial.iter_mut().enumerate() {
                *t = simd.sub_f64s(part::<S>(&strain[i], p), part::<S>(&plastic[i], p));
            }
            let stress = elastic_stress_in(simd, el.lambda, el.mu, &trial);
            for (e, s) in eff.iter_mut().zip(stress) {
                set_part::<S>(e, p, s);
            }
            if any {
                let b = virgin_bracket_in(simd, &self.surface, simd.splat_f64s(beta), &stress);
                set_part::<S>(&mut bracket, p, b);
            }
        }
        let mut pass = [false; LANES];
        for (g, pass_g) in pass.iter_mut().enumerate() {
            *pass_g = candidate[g] && beta >= 0.0 && bracket[g] <= limit;
        }
        (eff, pass)
    }

    /// [`PlasticDamage::yielded_elastic`] for the points of an element in lanes, under the
    /// Lee–Fenves rule, and under the consistent rule with D not read by the element: a
    /// point that has yielded (y_t or y_c ≠ 0), has a finite strain, was not taken by the
    /// never-yielded check (`virgin`) and is inside its surface by the invariant bound
    /// keeps its internal variables; its nominal stress, D slot and dissipation are those
    /// of [`PlasticDamage::commit`] for an unchanged state, bit for bit. Points the bound
    /// leaves open (tested at their exact principal values by the scalar path: measured no
    /// faster in lanes, docs/benchmarks.md), points outside, and, under the consistent
    /// rule, points whose D is read take the scalar path, which decides as before. `eff`:
    /// σ̄ = E₀ : (ε − εᵖ) per lane ([`Self::virgin_lanes`]). Reads the states only.
    #[inline(always)]
    fn yielded_lanes<S: Simd>(
        &self,
        simd: S,
        strain: &VoigtLanes,
        eff: &VoigtLanes,
        states: &[f64],
        virgin: &[bool; LANES],
        ctx: &PointContext,
    ) -> YieldedLanes {
        const N: usize = slot::LEN;
        let mut out = YieldedLanes {
            pass: [false; LANES],
            sigma: [F64s::ZERO; 6],
            damage: F64s::ZERO,
            dissipated: F64s::ZERO,
        };
        let rule = self.constants.recovery;
        if rule == Recovery::Consistent && ctx.reads_damage {
            return out;
        }
        let states = &states[..LANES * N];
        let mut candidate = [false; LANES];
        let mut any = false;
        for (g, state) in states.chunks_exact(N).enumerate() {
            candidate[g] = !virgin[g]
                && (state[slot::Y_T] != 0.0 || state[slot::Y_C] != 0.0)
                && strain.iter().all(|e| e[g].is_finite());
            any |= candidate[g];
        }
        if !any {
            return out;
        }
        let (t, c) = self.element_laws(ctx.char_length.max(1e-12));
        // β < 0 fails the check (the bound needs F non-decreasing in σ̂_max).
        let (mut beta, mut limit) = (F64s::splat(-1.0), F64s::ZERO);
        let (mut d_t, mut d_c) = (F64s::ZERO, F64s::ZERO);
        for (g, state) in states.chunks_exact(N).enumerate() {
            if !candidate[g] {
                continue;
            }
            let (ct, dt) = t.law.effective_and_damage(state[slot::Y_T]);
            let (cc, dc) = c.law.effective_and_damage(state[slot::Y_C]);
            let (b, lim) = virgin_bound(&self.surface, ct, cc);
            (beta[g], limit[g], d_t[g], d_c[g]) = (b, lim, dt, dc);
        }
        let bracket = virgin_bracket_lanes(simd, &self.surface, &beta, eff);
        let mut any = false;
        for g in 0..LANES {
            out.pass[g] = candidate[g] && beta[g] >= 0.0 && bracket[g] <= limit[g];
            any |= out.pass[g];
        }
        if !any {
            return out;
        }
        let s0 = self.constants.s0;
        // σ and the D slot of `nominal_with`: under the consistent rule with D not read,
        // D is 0 for D_t = D_c = 0, else NaN; under the Lee–Fenves rule it is eq. (24)'s.
        let (sig, damage) = match rule {
            Recovery::Consistent => {
                let sig =
                    consistent_stress_lanes(eff, d_t, d_c, (s0, self.elastic.poisson), &out.pass);
                let damage = F64s(std::array::from_fn(|g| {
                    if d_t[g] == 0.0 && d_c[g] == 0.0 {
                        0.0
                    } else {
                        f64::NAN
                    }
                }));
                (sig, damage)
            }
            Recovery::LeeFenves => lee_fenves_stress_lanes(eff, d_t, d_c, s0, &out.pass),
        };
        // The state's σₙ, εₙ, εᵖ and dissipation, lane by lane.
        let (mut sig0, mut eps0, mut plastic) = ([F64s::ZERO; 6], [F64s::ZERO; 6], [F64s::ZERO; 6]);
        let mut old_dissipated = F64s::ZERO;
        for (g, state) in states.chunks_exact(N).enumerate() {
            for i in 0..6 {
                sig0[i][g] = state[slot::STRESS + i];
                eps0[i][g] = state[slot::STRAIN + i];
                plastic[i][g] = state[slot::PLASTIC + i];
            }
            old_dissipated[g] = state[slot::DISSIPATED];
        }
        // Stored whole and read back as vectors (as in `elements_in_lanes`), so that the
        // arithmetic below is vectorised across the lanes.
        std::hint::black_box((&mut sig0, &mut eps0, &mut plastic, &mut old_dissipated));
        // Total dissipation of `commit` for an unchanged state (εᵖ kept); unchanged where
        // D_t = 0.
        let moved = dissipated_after(
            old_dissipated,
            (&sig0, &eps0, &plastic),
            (&sig, strain, &plastic),
        );
        for g in 0..LANES {
            out.dissipated[g] = if d_t[g] == 0.0 {
                old_dissipated[g]
            } else {
                moved[g]
            };
        }
        out.damage = damage;
        out.sigma = sig;
        out
    }

    /// Update the eight points of an element, point g at strain lane g, its state
    /// `old[g·LEN..]` → `new[g·LEN..]`; returns the nominal stresses, one lane per point.
    /// The same states and stresses as [`PlasticDamage::update`] point by point.
    #[inline(always)]
    pub fn update_points<S: Simd>(
        &self,
        simd: S,
        strain: &VoigtLanes,
        old: &[f64],
        new: &mut [f64],
        ctx: &PointContext,
    ) -> VoigtLanes {
        const N: usize = slot::LEN;
        let old = &old[..LANES * N];
        let new = &mut new[..LANES * N];
        let (eff, pass) = self.virgin_lanes(simd, strain, old, ctx);
        if pass == [true; LANES] {
            // The elastic regime's common case: σ is σ̄ whole.
            for (g, (o, n)) in old.chunks_exact(N).zip(new.chunks_exact_mut(N)).enumerate() {
                n.copy_from_slice(o);
                write_virgin_lane(n, strain, &eff, g);
            }
            return eff;
        }
        let yielded = self.yielded_lanes(simd, strain, &eff, old, &pass, ctx);
        let mut sigma = [F64s::ZERO; 6];
        for (g, (o, n)) in old.chunks_exact(N).zip(new.chunks_exact_mut(N)).enumerate() {
            if pass[g] {
                n.copy_from_slice(o);
                write_virgin_lane(n, strain, &eff, g);
                for i in 0..6 {
                    sigma[i][g] = eff[i][g];
                }
            } else if yielded.pass[g] {
                n.copy_from_slice(o);
                yielded.write(n, strain, g);
                for i in 0..6 {
                    sigma[i][g] = yielded.sigma[i][g];
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
    pub fn update_points_in_place<S: Simd>(
        &self,
        simd: S,
        strain: &VoigtLanes,
        states: &mut [f64],
        ctx: &PointContext,
    ) -> (VoigtLanes, bool) {
        const N: usize = slot::LEN;
        let states = &mut states[..LANES * N];
        let (eff, pass) = self.virgin_lanes(simd, strain, states, ctx);
        if pass == [true; LANES] {
            // The elastic regime's common case: σ is σ̄ whole, no hardening moves.
            for (g, n) in states.chunks_exact_mut(N).enumerate() {
                write_virgin_lane(n, strain, &eff, g);
            }
            return (eff, false);
        }
        let yielded = self.yielded_lanes(simd, strain, &eff, states, &pass, ctx);
        let mut sigma = [F64s::ZERO; 6];
        let mut moved = false;
        for (g, n) in states.chunks_exact_mut(N).enumerate() {
            if pass[g] {
                write_virgin_lane(n, strain, &eff, g);
                for i in 0..6 {
                    sigma[i][g] = eff[i][g];
                }
            } else if yielded.pass[g] {
                yielded.write(n, strain, g);
                for i in 0..6 {
                    sigma[i][g] = yielded.sigma[i][g];
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
