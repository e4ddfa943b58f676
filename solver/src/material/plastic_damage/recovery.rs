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

use super::principal::{definiteness, principal_values, Definiteness, Spectral};
use super::yield_surface::{invariants, tension_weight};
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

/// Where the effective stress lies: pure compression (every principal value ≤ 0),
/// pure tension (every one ≥ 0), or mixed, decided from the invariant bounds
/// Ī₁/3 ∓ (2/3)√(3J̄₂) first, then from the signs of I₁, I₂, I₃ ([`definiteness`], which
/// also settles the uniaxial and biaxial states the bounds leave open), and from the
/// principal values only for a mixed state.
fn weight(eff: &Voigt) -> f64 {
    let (i1, q) = invariants(eff);
    if i1 / 3.0 - 2.0 * q / 3.0 >= 0.0 {
        return 1.0;
    }
    if i1 / 3.0 + 2.0 * q / 3.0 <= 0.0 {
        return 0.0;
    }
    match definiteness(eff) {
        Definiteness::NonPositive => 0.0,
        Definiteness::NonNegative => 1.0,
        Definiteness::Indefinite => tension_weight(&principal_values(eff)),
    }
}

/// D of eq. (24), D = 1 − (1 − D_c)(1 − s D_t), s = s₀ + (1 − s₀) r(σ̄).
#[inline]
pub fn lee_fenves_damage(eff: &Voigt, dt: f64, dc: f64, s0: f64) -> f64 {
    if dt == 0.0 {
        return dc;
    }
    let s = s0 + (1.0 - s0) * weight(eff);
    1.0 - (1.0 - dc) * (1.0 - s * dt)
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
/// eigenvectors only for mixed tension–compression states of a point with D_t > 0.
pub fn consistent_stress(eff: &Voigt, dt: f64, dc: f64, s0: f64, nu: f64) -> Voigt {
    // D_t = 1 (e^(−y) underflows): the limit of an open crack carrying no tension; capped so
    // that A and φ stay finite (the stress changes by ~1e-12 of σ̄).
    let dt = dt.min(1.0 - 1e-12);
    let a = 1.0 / (1.0 - s0 * dt);
    let phi = 1.0 / (1.0 - dt) - a;
    if phi.is_nan() || phi <= 0.0 {
        // D_t = 0 or s₀ = 1: isotropic, σ = (1 − D_c)(1 − s₀D_t) σ̄.
        return eff.map(|v| v * (1.0 - dc) / a);
    }
    let (i1, q) = invariants(eff);
    if i1 / 3.0 + 2.0 * q / 3.0 <= 0.0 {
        // Pure compression: P = ∅.
        return eff.map(|v| v * (1.0 - dc) / a);
    }
    let p = principal_values(eff);
    let (m, sig) = select(&p, dc, a, phi, nu);
    if m == 0 || m == 3 {
        // Every k_i equal: σ = ((1 − D_c)(1+ν)/k) σ̄ + ((AνS − (1 − D_c)ν tr σ̄)/k) 1.
        let k = a * (1.0 + nu) + if m == 3 { phi } else { 0.0 };
        let tr = p[0] + p[1] + p[2];
        let s = sig[0] + sig[1] + sig[2];
        let c1 = (1.0 - dc) * (1.0 + nu) / k;
        let c0 = (a * nu * s - (1.0 - dc) * nu * tr) / k;
        return [
            c1 * eff[0] + c0,
            c1 * eff[1] + c0,
            c1 * eff[2] + c0,
            c1 * eff[3],
            c1 * eff[4],
            c1 * eff[5],
        ];
    }
    let sp = Spectral::of(eff);
    let sig = principal_stresses(&sp.values, m, dc, a, phi, nu);
    sp.stress_voigt(&sig)
}

/// The tension set P = first `m` directions whose stresses have the assumed signs; when
/// rounding leaves none exactly consistent, the least violating one.
fn select(p: &[f64; 3], dc: f64, a: f64, phi: f64, nu: f64) -> (usize, [f64; 3]) {
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
}
