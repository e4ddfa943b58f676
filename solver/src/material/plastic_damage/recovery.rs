//! Stiffness recovery on crack closure: the nominal stress σ from the effective stress
//! σ̄ = E₀ : (ε − εᵖ) and the damage D_t, D_c (see `docs/plastic_damage.md` §1 "Stiffness
//! recovery").
//!
//! * [`Recovery::LeeFenves`] — the paper's eq. (24): σ = (1 − D) σ̄,
//!   D = 1 − (1 − D_c)(1 − s D_t), s = s₀ + (1 − s₀) r(σ̄). D depends on the stress state
//!   through r(σ̄), so σ is not the gradient of an energy: closed strain cycles through
//!   crack closure can return more work than they took (docs §7).
//! * [`Recovery::Consistent`] — derived from the complementary (Gibbs) energy
//!
//!   χ(σ) = [A ½ σ : C₀ : σ + (φ/2E₀) Σᵢ ⟨σ̂ᵢ⟩²] / (1 − D_c),
//!   A = 1/(1 − s₀ D_t),  φ = 1/(1 − D_t) − A ≥ 0,
//!
//!   (C₀ = E₀⁻¹; the crack compliance φ acts on the tensile principal stresses, as in
//!   Ortiz 1985, *Mech. Mater.* 4, 67–93), so that εᵉ = ε − εᵖ = ∂χ/∂σ. χ is convex and C¹
//!   in σ (Σ⟨σ̂ᵢ⟩² is a convex spectral function with gradient σ⁺), so σ(εᵉ) is the
//!   gradient of the Helmholtz energy ψ = sup_σ (σ:εᵉ − χ) — elastic cycles at fixed damage
//!   return exactly the work they took — and ∂χ/∂D_t, ∂χ/∂D_c ≥ 0 (∂φ/∂D_t =
//!   1/(1−D_t)² − s₀/(1−s₀D_t)² ≥ 0), so the damage part of the dissipation
//!   (∂χ/∂D)·Ḋ is ≥ 0. In uniaxial stress it is eq. (24): slope (1 − D_c)(1 − D_t)E₀ with
//!   the crack open, (1 − D_c)(1 − s₀D_t)E₀ closed; s₀ = 1 is eq. (24) in every state.
//!
//! The consistent stress is coaxial with εᵉ (χ is isotropic). With t_i = E₀(1 − D_c) e_i
//! for the principal elastic strains e_i = ((1+ν)σ̄_i − ν tr σ̄)/E₀ and P the set of
//! principal directions in tension, (1 − D_c) εᵉ = ∂χ/∂σ reads
//! k_i σ_i − Aν S = t_i, k_i = A(1+ν) + φ [i ∈ P], S = Σσ_j, so
//! S = (Σ t_i/k_i)/(1 − Aν Σ 1/k_i), σ_i = (t_i + AνS)/k_i. The principal stresses keep
//! the order of the e_i (the gradient of a symmetric convex function is order preserving),
//! so P is one of ∅, {1}, {1,2}, {1,2,3}: the one whose σ_i have the signs it assumes.

use super::principal::{definiteness, eigenprojector, principal_values, Definiteness, Spectral};
use super::yield_surface::{invariants, largest_value_bound, tension_weight};
use crate::element::lanes::Lane;
use crate::material::Voigt;

/// How tensile damage is recovered when a crack closes.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Recovery {
    /// From the Gibbs energy χ above: no energy is created on any strain cycle.
    Consistent,
    /// Eq. (24) with s = s₀ + (1 − s₀) r(σ̄) (Lee & Fenves 1998): the paper's model and the
    /// default (docs/plastic_damage.md §7).
    #[default]
    LeeFenves,
}

/// An effective stress σ̄ with its invariants Ī₁, √(3J̄₂) and, once asked for, its
/// principal values: what the weight r(σ̄) of eq. (24) and the consistent rule both classify
/// σ̄ by, each formed once per nominal stress (the same values as forming them in each).
pub struct Classified<'a> {
    eff: &'a Voigt,
    i1: f64,
    q: f64,
    values: Option<[f64; 3]>,
}

impl<'a> Classified<'a> {
    /// Ī₁ and √(3J̄₂) of `eff` now; its principal values when first needed.
    #[inline]
    pub fn new(eff: &'a Voigt) -> Self {
        let (i1, q) = invariants(eff);
        Self {
            eff,
            i1,
            q,
            values: None,
        }
    }

    /// `self` with the principal values of σ̄ given ([`principal_values`] of σ̄, computed
    /// by the caller: the values [`Self::values`] would form, bit for bit).
    #[inline]
    pub fn with_values(self, values: [f64; 3]) -> Self {
        Self {
            values: Some(values),
            ..self
        }
    }

    /// The effective stress σ̄.
    #[inline]
    pub fn stress(&self) -> &'a Voigt {
        self.eff
    }

    /// Every principal value ≤ 0 by the bound Ī₁/3 + (2/3)√(3J̄₂) ≤ 0.
    #[inline]
    fn surely_compressed(&self) -> bool {
        largest_value_bound(self.i1, self.q) <= 0.0
    }

    /// [`principal_values`] of σ̄, formed at the first call.
    #[inline]
    fn values(&mut self) -> [f64; 3] {
        let eff = self.eff;
        *self.values.get_or_insert_with(|| principal_values(eff))
    }
}

/// The weight r(σ̄) of eq. (24) where the signs of the principal values settle it: 1 in
/// pure tension (every principal value ≥ 0), 0 in pure compression (every one ≤ 0),
/// decided from the invariant bounds Ī₁/3 ∓ (2/3)√(3J̄₂) of `eff` (its invariants `i1`,
/// `q` of [`invariants`]) first, then from the signs of I₁, I₂, I₃ ([`definiteness`],
/// which also settles the uniaxial and biaxial states the bounds leave open); `None` for a
/// mixed state, whose r needs the principal values.
#[inline(always)]
pub fn weight_by_signs(i1: f64, q: f64, eff: &Voigt) -> Option<f64> {
    if i1 / 3.0 - 2.0 * q / 3.0 >= 0.0 {
        return Some(1.0);
    }
    if largest_value_bound(i1, q) <= 0.0 {
        return Some(0.0);
    }
    match definiteness(eff) {
        Definiteness::NonPositive => Some(0.0),
        Definiteness::NonNegative => Some(1.0),
        Definiteness::Indefinite => None,
    }
}

/// r(σ̄) of eq. (24): [`weight_by_signs`], and from the principal values only for a mixed
/// state.
fn weight(c: &mut Classified) -> f64 {
    weight_by_signs(c.i1, c.q, c.eff).unwrap_or_else(|| tension_weight(&c.values()))
}

/// D of eq. (24), D = 1 − (1 − D_c)(1 − s D_t), s = s₀ + (1 − s₀) r(σ̄).
#[inline]
pub fn lee_fenves_damage(c: &mut Classified, dt: f64, dc: f64, s0: f64) -> f64 {
    if dt == 0.0 {
        return dc;
    }
    cracked_damage(weight(c), dt, dc, s0)
}

/// D of eq. (24) of a cracked point (D_t ≠ 0) from its weight r = r(σ̄):
/// 1 − (1 − D_c)(1 − s D_t), s = s₀ + (1 − s₀) r (one point, or one per lane).
#[inline(always)]
pub fn cracked_damage<T: Lane>(r: T, dt: T, dc: T, s0: f64) -> T {
    let one = T::splat(1.0);
    let s = T::splat(s0) + T::splat(1.0 - s0) * r;
    one - (one - dc) * (one - s * dt)
}

/// Principal consistent stresses for sorted principal effective stresses `p` (σ̂₁ ≥ σ̂₂ ≥
/// σ̂₃) and `m` directions in tension (P = the first `m`).
#[inline]
fn principal_stresses(p: &[f64; 3], m: usize, dc: f64, a: f64, phi: f64, nu: f64) -> [f64; 3] {
    let tr = p[0] + p[1] + p[2];
    let t = [
        (1.0 - dc) * ((1.0 + nu) * p[0] - nu * tr),
        (1.0 - dc) * ((1.0 + nu) * p[1] - nu * tr),
        (1.0 - dc) * ((1.0 + nu) * p[2] - nu * tr),
    ];
    let k = |i: usize| a * (1.0 + nu) + if i < m { phi } else { 0.0 };
    let (mut num, mut inv) = (0.0, 0.0);
    for (i, ti) in t.iter().enumerate() {
        num += ti / k(i);
        inv += 1.0 / k(i);
    }
    let s = num / (1.0 - a * nu * inv);
    [
        (t[0] + a * nu * s) / k(0),
        (t[1] + a * nu * s) / k(1),
        (t[2] + a * nu * s) / k(2),
    ]
}

/// Nominal stress of the consistent rule (module doc) for effective stress `eff`,
/// damage `dt`, `dc`, recovery floor `s0` and Poisson's ratio `nu`. Allocation free;
/// principal values only for a state the invariant bound does not show compressed, one
/// eigenvector only for a mixed tension–compression state of a point with D_t > 0.
#[cfg(test)]
pub fn consistent_stress(eff: &Voigt, dt: f64, dc: f64, s0: f64, nu: f64) -> Voigt {
    consistent_stress_of(&mut Classified::new(eff), dt, dc, s0, nu)
}

/// [`consistent_stress`] of a [`Classified`] effective stress (its invariants and principal
/// values shared with [`lee_fenves_damage`]).
pub fn consistent_stress_of(c: &mut Classified, dt: f64, dc: f64, s0: f64, nu: f64) -> Voigt {
    let eff = c.eff;
    let (a, phi) = recovery_factors(dt, s0);
    if phi.is_nan() || phi <= 0.0 {
        // D_t = 0 or s₀ = 1: isotropic, σ = (1 − D_c)(1 − s₀D_t) σ̄.
        return eff.map(|v| v * (1.0 - dc) / a);
    }
    if c.surely_compressed() {
        // Pure compression: P = ∅.
        return eff.map(|v| v * (1.0 - dc) / a);
    }
    let p = c.values();
    let (m, sig) = select(&p, dc, a, phi, nu);
    // σᵢ = ((1 − D_c)(1+ν) σ̂ᵢ + C)/kᵢ with C = AνS − (1 − D_c)ν tr σ̄ (`offset`,
    // principal_stresses):
    // one linear map g_k(λ) = ((1 − D_c)(1+ν)λ + C)/k per set, applied to σ̄ as a whole.
    let (a1, offset, k0) = map_coefficients(&p, &sig, dc, a, nu);
    let (k, lone) = match set_map(m, &p) {
        SetMap::Linear { tension, lone } => (if tension { k0 + phi } else { k0 }, lone),
        SetMap::Split => {
            let sp = Spectral::with_values(eff, p);
            let sig = principal_stresses(&sp.values, m, dc, a, phi, nu);
            return sp.stress_voigt(&sig);
        }
    };
    let c1 = a1 / k;
    let c0 = offset / k;
    let mut out = linear_map(eff, c1, c0);
    if let Some(i) = lone {
        let correction = lone_correction(eff, &p, i, sig[i], (a1, offset, k));
        for (o, v) in out.iter_mut().zip(correction) {
            *o += v;
        }
    }
    out
}

/// How the consistent stress of a tension set is formed from σ̄ ([`set_map`]).
pub(super) enum SetMap {
    /// σ = g_k(σ̄), plus (σᵢ − g_k(σ̂ᵢ)) nᵢ⊗nᵢ for the `lone` direction i when there is one
    /// ([`lone_correction`]); k is that of a direction in tension when `tension`.
    Linear { tension: bool, lone: Option<usize> },
    /// The close pair split between the sets: each of its directions is needed.
    Split,
}

/// The form of the consistent stress for the tension set of the first `m` directions of the
/// sorted principal values `p`: every kᵢ equal (m = 0 or 3) is one map g_k; the direction
/// whose value is farther from the middle one ([`Spectral::with_values`]'s choice, whose
/// eigenvector alone is accurate to rounding over the gap) alone in its set — n₁ in tension
/// or n₃ in compression — is g_k of the other two plus one eigenvector, no plane basis.
#[inline(always)]
pub(super) fn set_map(m: usize, p: &[f64; 3]) -> SetMap {
    let top_isolated = p[0] - p[1] >= p[1] - p[2];
    match (m, top_isolated) {
        (0, _) => SetMap::Linear {
            tension: false,
            lone: None,
        },
        (3, _) => SetMap::Linear {
            tension: true,
            lone: None,
        },
        (1, true) => SetMap::Linear {
            tension: false,
            lone: Some(0),
        },
        (2, false) => SetMap::Linear {
            tension: true,
            lone: Some(2),
        },
        _ => SetMap::Split,
    }
}

/// (σᵢ − g_k(σ̂ᵢ)) nᵢ⊗nᵢ of the lone direction `i` (principal value `p[i]` of σ̄ = `eff`,
/// principal stress `sig_i`) for g_k(λ) = (a₁λ + C)/k, `(a1, offset, k)` = (a₁, C, k).
#[inline(always)]
pub(super) fn lone_correction(
    eff: &Voigt,
    p: &[f64; 3],
    i: usize,
    sig_i: f64,
    (a1, offset, k): (f64, f64, f64),
) -> Voigt {
    let w = sig_i - (a1 * p[i] + offset) / k;
    eigenprojector(eff, p[i]).map(|v| w * v)
}

/// What [`select`] forms once for its four candidate sets (one point, or one per lane):
/// tᵢ = (1 − D_c)((1+ν)σ̂ᵢ − ν tr σ̂), the two values kᵢ takes (index 0: outside P, 1: in
/// P), their inverses, the quotients tᵢ/k and Aν. Each candidate's stresses
/// ([`SetTerms::candidate`]) are [`principal_stresses`]`(p, m, …)` bit for bit: the same
/// operations on the same operands, formed once rather than once per set.
pub(super) struct SetTerms<T> {
    t: [T; 3],
    k: [T; 2],
    inv: [T; 2],
    quotient: [[T; 3]; 2],
    a_nu: T,
}

impl<T: Lane> SetTerms<T> {
    /// The terms for sorted principal effective stresses `p`, damage `dc`, A = `a`, φ = `phi`.
    #[inline(always)]
    pub(super) fn new(p: &[T; 3], dc: T, a: T, phi: T, nu: f64) -> Self {
        let one = T::splat(1.0);
        let nu_t = T::splat(nu);
        let tr = p[0] + p[1] + p[2];
        let t = std::array::from_fn(|i| (one - dc) * (T::splat(1.0 + nu) * p[i] - nu_t * tr));
        let k_open = a * T::splat(1.0 + nu);
        let k = [k_open + T::splat(0.0), k_open + phi];
        let inv = [one / k[0], one / k[1]];
        let quotient = std::array::from_fn(|j| std::array::from_fn(|i| t[i] / k[j]));
        Self {
            t,
            k,
            inv,
            quotient,
            a_nu: a * nu_t,
        }
    }

    /// The principal stresses of the set P = the first `m` directions and how far they
    /// violate the signs it assumes (Σ⟨−σᵢ⟩ over P plus Σ⟨σᵢ⟩ outside; 0 when consistent).
    #[inline(always)]
    pub(super) fn candidate(&self, m: usize) -> ([T; 3], T) {
        let zero = T::splat(0.0);
        let in_p = |i: usize| usize::from(i < m);
        let (mut num, mut inv_sum) = (zero, zero);
        for i in 0..3 {
            num = num + self.quotient[in_p(i)][i];
            inv_sum = inv_sum + self.inv[in_p(i)];
        }
        let sum = num / (T::splat(1.0) - self.a_nu * inv_sum);
        let s: [T; 3] = std::array::from_fn(|i| (self.t[i] + self.a_nu * sum) / self.k[in_p(i)]);
        let mut violation = zero;
        for (i, v) in s.iter().enumerate() {
            violation = violation + if i < m { (-*v).max(zero) } else { v.max(zero) };
        }
        (s, violation)
    }
}

/// The tension set P = first `m` directions whose stresses have the assumed signs; when
/// rounding leaves none exactly consistent, the least violating one (the first of equals).
fn select(p: &[f64; 3], dc: f64, a: f64, phi: f64, nu: f64) -> (usize, [f64; 3]) {
    let terms = SetTerms::new(p, dc, a, phi, nu);
    let mut best = (0, [0.0; 3], f64::INFINITY);
    for m in 0..=3 {
        let (s, violation) = terms.candidate(m);
        if violation == 0.0 {
            return (m, s);
        }
        if violation < best.2 {
            best = (m, s, violation);
        }
    }
    (best.0, best.1)
}

/// The coefficients of the linear map g_k(λ) = ((1 − D_c)(1+ν)λ + C)/k of the consistent
/// stress (one point, or one per lane): (1 − D_c)(1+ν), C = AνS − (1 − D_c)ν tr σ̂ with S
/// the sum of the principal stresses `sig`, and k₀ = A(1+ν) (k of a direction outside P).
#[inline(always)]
pub(super) fn map_coefficients<T: Lane>(
    p: &[T; 3],
    sig: &[T; 3],
    dc: T,
    a: T,
    nu: f64,
) -> (T, T, T) {
    let one_minus_dc = T::splat(1.0) - dc;
    let nu_t = T::splat(nu);
    let tr = p[0] + p[1] + p[2];
    let s = sig[0] + sig[1] + sig[2];
    let a1 = one_minus_dc * T::splat(1.0 + nu);
    let offset = a * nu_t * s - one_minus_dc * nu_t * tr;
    (a1, offset, a * T::splat(1.0 + nu))
}

/// A = 1/(1 − s₀D_t) and φ = 1/(1 − D_t) − A of the consistent rule (one point, or one per
/// lane). D_t = 1 (e^(−y) underflows) is the limit of an open crack carrying no tension;
/// D_t is capped so that A and φ stay finite (the stress changes by ~1e-12 of σ̄).
#[inline(always)]
pub(super) fn recovery_factors<T: Lane>(dt: T, s0: f64) -> (T, T) {
    let one = T::splat(1.0);
    let dt = dt.min(T::splat(1.0 - 1e-12));
    let a = one / (one - T::splat(s0) * dt);
    (a, one / (one - dt) - a)
}

/// g_k applied to σ̄ as a whole: c₁ σ̄ + c₀ I with c₁ = (1 − D_c)(1+ν)/k, c₀ = C/k.
#[inline(always)]
pub(super) fn linear_map<T: Lane>(eff: &[T; 6], c1: T, c0: T) -> [T; 6] {
    [
        c1 * eff[0] + c0,
        c1 * eff[1] + c0,
        c1 * eff[2] + c0,
        c1 * eff[3],
        c1 * eff[4],
        c1 * eff[5],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    const E: f64 = 31027e6;
    const NU: f64 = 0.18;

    fn compliance(sig: &[f64; 3], dt: f64, dc: f64, s0: f64) -> [f64; 3] {
        // (1 − D_c) E e_i = A((1+ν)σ_i − ν S) + φ⟨σ_i⟩.
        let a = 1.0 / (1.0 - s0 * dt);
        let phi = 1.0 / (1.0 - dt) - a;
        let s = sig[0] + sig[1] + sig[2];
        sig.map(|x| (a * ((1.0 + NU) * x - NU * s) + phi * x.max(0.0)) / ((1.0 - dc) * E))
    }

    fn effective(e: &[f64; 3]) -> Voigt {
        let lam = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
        let mu = E / (2.0 * (1.0 + NU));
        let tr = e[0] + e[1] + e[2];
        [
            lam * tr + 2.0 * mu * e[0],
            lam * tr + 2.0 * mu * e[1],
            lam * tr + 2.0 * mu * e[2],
            0.0,
            0.0,
            0.0,
        ]
    }

    #[test]
    fn inverts_the_gibbs_compliance_in_every_sign_pattern() {
        // Pick the stress, compute εᵉ = ∂χ/∂σ by hand, and recover the stress.
        for (dt, dc, s0) in [(0.6, 0.1, 0.0), (0.95, 0.0, 0.3), (0.3, 0.5, 0.0)] {
            for sig in [
                [2e6, 1e6, 0.5e6],
                [2e6, -1e6, -3e6],
                [2e6, 1e6, -3e6],
                [-1e6, -2e6, -3e6],
                [1e6, 0.0, 0.0],
                [-1e6, 0.0, 0.0],
            ] {
                let eff = effective(&compliance(&sig, dt, dc, s0));
                let out = consistent_stress(&eff, dt, dc, s0, NU);
                for i in 0..3 {
                    assert!((out[i] - sig[i]).abs() < 1e-6 * 3e6, "{sig:?} {out:?}");
                }
                assert!(out[3..].iter().all(|v| v.abs() < 1e-6));
            }
        }
    }

    /// The form with one projector against the full spectral sum Σ σᵢ nᵢ⊗nᵢ (every
    /// eigenpair, σᵢ by `select`): random rotated states of every sign pattern,
    /// with nearly double and double principal values, to 1e-10 of the largest component.
    #[test]
    fn one_projector_form_equals_the_spectral_sum() {
        use super::super::principal::rotated_voigt;
        use nalgebra::Rotation3;
        let mut lcg = crate::test_random::Lcg(0x0dd5_eed5_7e55_0001);
        let mut rand = move || lcg.next();
        let mut mixed = [0usize; 4];
        for case in 0..4000 {
            let (a, b) = (4e6 * (rand() - 0.5), 4e6 * (rand() - 0.5));
            let values = match case % 5 {
                0 => [a, b, 4e6 * (rand() - 0.5)],
                1 => [a, a, b],
                2 => [a, b, b],
                3 => [a, a * (1.0 + 1e-9 * rand()), b],
                _ => [a, b, b + 1e-3 * rand()],
            };
            let r = Rotation3::from_euler_angles(7.0 * rand(), 7.0 * rand(), 7.0 * rand());
            let eff = rotated_voigt(r.matrix(), values);
            let (dt, dc) = (0.02 + 0.97 * rand(), 0.6 * rand());
            let s0 = [0.0, 0.2, 0.7][case % 3];
            let out = consistent_stress(&eff, dt, dc, s0, NU);
            // Reference: the full spectral sum over the closed-form eigenpairs
            // (`Spectral`, checked against nalgebra's iterative solver in `principal.rs`),
            // the stresses of the tension set its values select.
            let sp = Spectral::of(&eff);
            let a_ = 1.0 / (1.0 - s0 * dt);
            let phi = 1.0 / (1.0 - dt) - a_;
            let (k, sig) = select(&sp.values, dc, a_, phi, NU);
            mixed[k] += 1;
            let reference = sp.stress_voigt(&sig);
            let scale = eff.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            for i in 0..6 {
                assert!(
                    (out[i] - reference[i]).abs() <= 1e-10 * scale,
                    "case {case}: {eff:?} dt {dt} dc {dc} s0 {s0}: {out:?} vs {reference:?}"
                );
            }
        }
        // Every tension set was exercised.
        assert!(mixed.iter().all(|&n| n > 100), "{mixed:?}");
    }

    #[test]
    fn uniaxial_stress_slopes_are_those_of_eq_24() {
        // Uniaxial stress σ e₁ (the state of eq. 24's uniaxial laws): the elastic strain of
        // χ is εᵉ₁ = σ/((1 − D_c)(1 − D_t)E) with the crack open and σ/((1 − D_c)(1 − s₀D_t)E)
        // closed, and the model maps E₀:εᵉ back to σ e₁.
        let (dt, dc, s0) = (0.6, 0.1, 0.25);
        for (sig, k) in [
            (1e6, (1.0 - dc) * (1.0 - dt)),
            (-1e6, (1.0 - dc) * (1.0 - s0 * dt)),
        ] {
            let e = compliance(&[sig, 0.0, 0.0], dt, dc, s0);
            assert!((e[0] - sig / (k * E)).abs() < 1e-12 * e[0].abs());
            let out = consistent_stress(&effective(&e), dt, dc, s0, NU);
            assert!((out[0] - sig).abs() < 1e-9 * 1e6, "{out:?}");
            assert!(out[1..].iter().all(|v| v.abs() < 1e-9 * 1e6), "{out:?}");
        }
        // Pure compression of any kind: σ = (1 − D_c)(1 − s₀D_t) σ̄.
        let eff = [-2e6, -1e6, -3e6, 0.5e6, 0.0, 0.2e6];
        let out = consistent_stress(&eff, dt, dc, s0, NU);
        for i in 0..6 {
            assert!((out[i] - (1.0 - dc) * (1.0 - s0 * dt) * eff[i]).abs() < 1e-9 * 2e6);
        }
        // s₀ = 1: eq. (24) in every state, σ = (1 − D_c)(1 − D_t) σ̄.
        let eff = [2e6, -1e6, 0.3e6, 0.4e6, -0.2e6, 0.1e6];
        let out = consistent_stress(&eff, 0.6, 0.1, 1.0, NU);
        for i in 0..6 {
            assert!((out[i] - 0.9 * 0.4 * eff[i]).abs() < 1e-9 * 2e6);
        }
    }

    #[test]
    fn closed_elastic_cycle_returns_the_work_it_took() {
        // Path independence at fixed damage: the work of σ(εᵉ) around a loop through open and
        // closed states vanishes (to the quadrature error, which falls as 1/n²).
        let (dt, dc, s0) = (0.7, 0.05, 0.0);
        let loop_work = |n: usize| {
            let mut w = 0.0;
            let pt = |t: f64| {
                let c = (2.0 * std::f64::consts::PI * t).cos();
                let s = (2.0 * std::f64::consts::PI * t).sin();
                [
                    1e-4 * c,
                    0.6e-4 * s,
                    -0.3e-4 * c + 0.2e-4 * s,
                    0.5e-4 * s,
                    0.0,
                    0.3e-4 * c,
                ]
            };
            let stress = |e: &[f64; 6]| {
                let lam = E * NU / ((1.0 + NU) * (1.0 - 2.0 * NU));
                let mu = E / (2.0 * (1.0 + NU));
                let tr = e[0] + e[1] + e[2];
                let eff = [
                    lam * tr + 2.0 * mu * e[0],
                    lam * tr + 2.0 * mu * e[1],
                    lam * tr + 2.0 * mu * e[2],
                    mu * e[3],
                    mu * e[4],
                    mu * e[5],
                ];
                consistent_stress(&eff, dt, dc, s0, NU)
            };
            let mut e0 = pt(0.0);
            let mut s0v = stress(&e0);
            for k in 1..=n {
                let e1 = pt(k as f64 / n as f64);
                let s1 = stress(&e1);
                for i in 0..6 {
                    w += 0.5 * (s0v[i] + s1[i]) * (e1[i] - e0[i]);
                }
                e0 = e1;
                s0v = s1;
            }
            w
        };
        let gross = 1e-4 * 1e-4 * E;
        let (w1, w2) = (loop_work(1000), loop_work(4000));
        assert!(w2.abs() < 1e-6 * gross, "{w1} {w2}");
        assert!(w2.abs() <= w1.abs() / 4.0 + 1e-9 * gross, "{w1} {w2}");
    }

    /// The selection as it was written before the shared quotients: each candidate set's
    /// stresses from [`principal_stresses`] on its own.
    fn select_per_set(p: &[f64; 3], dc: f64, a: f64, phi: f64, nu: f64) -> (usize, [f64; 3]) {
        let mut best = (0, [0.0; 3], f64::INFINITY);
        for m in 0..=3 {
            let s = principal_stresses(p, m, dc, a, phi, nu);
            let mut violation = 0.0f64;
            for (i, v) in s.iter().enumerate() {
                violation += if i < m { (-v).max(0.0) } else { v.max(0.0) };
            }
            if violation == 0.0 {
                return (m, s);
            }
            if violation < best.2 {
                best = (m, s, violation);
            }
        }
        (best.0, best.1)
    }

    /// `select` gives the set and the stresses of the per-set evaluation bit for bit, over
    /// every sign pattern of the principal values, damage from none to full, exact zeros
    /// and near-double roots.
    #[test]
    fn shared_quotients_select_the_per_set_result_bit_for_bit() {
        let mut rng = crate::test_random::Lcg(0x005e_1ec7_0b17);
        let mut sets = [0usize; 4];
        for draw in 0..20_000 {
            let mag = 10f64.powf(2.0 + 6.0 * rng.next());
            let mut p: [f64; 3] = std::array::from_fn(|_| mag * rng.sym());
            match draw % 5 {
                0 => p[1] = p[0] * (1.0 + 1e-13 * rng.sym()),
                1 => p[2] = 0.0,
                _ => {}
            }
            p.sort_by(|x, y| y.total_cmp(x));
            let dt = [rng.next(), 1.0 - 1e-12, 0.999 * rng.next().powi(8)][draw % 3];
            let dc = if draw % 4 == 0 { 0.0 } else { 0.9 * rng.next() };
            let s0 = if draw % 7 == 0 { 0.0 } else { rng.next() };
            let nu = 0.1 + 0.3 * rng.next();
            let a = 1.0 / (1.0 - s0 * dt);
            let phi = 1.0 / (1.0 - dt) - a;
            let (m, s) = select(&p, dc, a, phi, nu);
            let (m_ref, s_ref) = select_per_set(&p, dc, a, phi, nu);
            assert_eq!(m, m_ref, "draw {draw}: {p:?}");
            assert_eq!(
                s.map(f64::to_bits),
                s_ref.map(f64::to_bits),
                "draw {draw}: {p:?}"
            );
            sets[m] += 1;
        }
        // Every tension set is chosen in some draw.
        assert!(sets.iter().all(|&n| n > 100), "{sets:?}");
    }
}
