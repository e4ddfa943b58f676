//! Point-to-point contact of one node pair, eqs. (5)–(15), in the leapfrog form.
//!
//! Node `a` lies on surface a, node `b` on surface b, `n` is the unit normal of surface a at
//! `a` (pointing from a towards b). `R` is the force on node `a`; node `b` receives `−R`.
//! With inverse masses `w_a`, `w_b` (0 for a fully constrained node) the corrected
//! displacements are `U = Ū + Δt² w R`, so the stick force that satisfies eq. (5) is
//!
//! ```text
//!   R = (Δ₁ + Δ₂) / ((w_a + w_b) Δt²)                                  (6)–(7)
//!   Δ₁ = [(Ū_b − Ū_a)·n] n                                              (8)
//!   Δ₂ = (Ū_b − Ū_a) − (U_b − U_a)ⁿ − [((Ū_b − Ū_a) − (U_b − U_a)ⁿ)·n] n  (9)
//! ```
//!
//! (1/((w_a + w_b)Δt²) = 2MₐM_b/((Mₐ+M_b)Δt²)/2: the paper's factor with its Δt²/2 of
//! eq. (2) replaced by the Δt² of the leapfrog correction.)
//!
//! Sign convention: `λ = −R·n` is the normal force, positive in **compression** (the
//! force on `a` pushes it away from `b`); `T = R − (R·n) n` is the tangential force on `a`,
//! which drags `a` along with `b` and so opposes the slip of `a` relative to `b`.

use super::geom::{axpy, dot, norm, scale, sub, tangential};

/// Contact state of a pair (or of a node in point-to-surface contact).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[repr(u8)]
pub enum PairState {
    /// In contact, no relative motion, cohesion intact (the initial state).
    Bonded = 0,
    /// In contact, no relative motion, cohesion lost.
    Stick = 1,
    /// In contact, sliding with kinetic friction μd|N| (cohesion lost).
    Sliding = 2,
    /// Apart: R = 0 (cohesion lost).
    Separated = 3,
}

impl PairState {
    /// Numeric code written to the output fields.
    pub fn code(self) -> u8 {
        self as u8
    }
    /// Whether a transition `self → next` is one the model allows (bonded never returns).
    pub fn may_become(self, next: PairState) -> bool {
        next != PairState::Bonded || self == PairState::Bonded
    }
}

/// Strength parameters of one pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairParams {
    /// Static friction coefficient μs.
    pub mu_s: f64,
    /// Kinetic friction coefficient μd (≤ μs).
    pub mu_d: f64,
    /// Cohesive shear capacity cA (N), used only while bonded.
    pub shear_capacity: f64,
    /// Tensile capacity σt A (N) of eq. (14), used only while bonded.
    pub tensile_capacity: f64,
}

/// Kinematic input of one pair for one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairInput {
    /// Unit normal of surface a at node a (from a towards b).
    pub n: [f64; 3],
    /// w_a + w_b (inverse masses); must be > 0.
    pub w_sum: f64,
    /// Time step Δt.
    pub dt: f64,
    /// Predicted relative displacement Ū_b − Ū_a.
    pub rel_pred: [f64; 3],
    /// Relative displacement at the start of the step, U_bⁿ − U_aⁿ.
    pub rel_old: [f64; 3],
}

/// Result of one pair for one step.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PairOutcome {
    /// Contact force on node a (node b gets −r).
    pub r: [f64; 3],
    /// State after the step.
    pub state: PairState,
    /// Normal force λ = −r·n (compression positive).
    pub normal: f64,
    /// Tangential force on node a.
    pub tangential: [f64; 3],
}

/// Solve one pair for one step: trial stick force from eqs. (6)–(9), then the checks
/// (12)–(15) with the state rules of `docs/contact.md`:
///
/// - compression (λ ≥ 0, eq. (12)): stick while |T| ≤ μs λ + cA (cA only while bonded),
///   else slide with |T| = μd λ (eq. (13)) and lose the cohesion;
/// - tension (λ < 0, eq. (14)): a bonded pair holds while √(|T|² + λ²) ≤ σt A; otherwise,
///   and always without cohesion, the pair separates with R = 0 (eq. (15));
/// - a separated pair comes back into contact when the predicted gap closes (λ > 0),
///   without cohesion; a sliding pair sticks again when its demand drops to μs λ.
#[inline]
pub fn solve_pair(state: PairState, p: &PairParams, inp: &PairInput) -> PairOutcome {
    let n = inp.n;
    let k = 1.0 / (inp.w_sum * inp.dt * inp.dt);
    let bonded = state == PairState::Bonded;
    // Normal target after the step: zero gap (eq. (5)); a gap or penetration already
    // present at tⁿ — only possible where another constraint moved a node of the pair
    // (a node shared with a second interface or with point-to-surface contact) — is held
    // by a bond, and a penetration is held, not pushed out, by a contact without bond, so
    // that the pair forces never do positive work.
    let gap_old = dot(inp.rel_old, n);
    let target = if bonded { gap_old } else { gap_old.min(0.0) };
    let gap_pred = dot(inp.rel_pred, n) - target;
    let incr = sub(inp.rel_pred, inp.rel_old);
    let d2 = tangential(incr, n);
    let lambda = -k * gap_pred;
    let t = scale(k, d2);
    let t_mag = norm(t);
    let separated = PairOutcome {
        r: [0.0; 3],
        state: PairState::Separated,
        normal: 0.0,
        tangential: [0.0; 3],
    };
    if lambda < 0.0 || (state == PairState::Separated && lambda <= 0.0) {
        // Tensile demand (or a pair that stays open).
        if bonded && (t_mag * t_mag + lambda * lambda).sqrt() <= p.tensile_capacity {
            return PairOutcome {
                r: axpy(t, -lambda, n),
                state: PairState::Bonded,
                normal: lambda,
                tangential: t,
            };
        }
        return separated;
    }
    let cap = p.mu_s * lambda + if bonded { p.shear_capacity } else { 0.0 };
    if t_mag <= cap {
        return PairOutcome {
            r: axpy(t, -lambda, n),
            state: if bonded {
                PairState::Bonded
            } else {
                PairState::Stick
            },
            normal: lambda,
            tangential: t,
        };
    }
    let ts = scale(p.mu_d * lambda / t_mag, t);
    PairOutcome {
        r: axpy(ts, -lambda, n),
        state: PairState::Sliding,
        normal: lambda,
        tangential: ts,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const DT: f64 = 1e-3;

    /// Two masses (1 and 3) at rest, loads on mass 1 (node a): the predictor moves only
    /// node a, Ū_a = Δt² F / m_a. The normal n points from a towards b (+x);
    /// "compressive" pushes a towards b (+x), "pulling apart" pushes it along −x.
    fn w9(state: PairState, fx: f64, fy: f64) -> (PairOutcome, [f64; 3], [f64; 3]) {
        let (ma, mb) = (1.0, 3.0);
        let p = PairParams {
            mu_s: 0.5,
            mu_d: 0.4,
            shear_capacity: 5.0,
            tensile_capacity: 5.0,
        };
        let ua = [DT * DT * fx / ma, DT * DT * fy / ma, 0.0];
        let inp = PairInput {
            n: [1.0, 0.0, 0.0],
            w_sum: 1.0 / ma + 1.0 / mb,
            dt: DT,
            rel_pred: scale(-1.0, ua),
            rel_old: [0.0; 3],
        };
        let out = solve_pair(state, &p, &inp);
        // accelerations after correction
        let acc_a = [(fx + out.r[0]) / ma, (fy + out.r[1]) / ma, 0.0];
        let acc_b = [-out.r[0] / mb, -out.r[1] / mb, 0.0];
        (out, acc_a, acc_b)
    }

    fn close(a: f64, b: f64) -> bool {
        (a - b).abs() <= 1e-10 * b.abs().max(1.0)
    }

    #[test]
    fn w9_compressive_stick() {
        let (o, aa, ab) = w9(PairState::Bonded, 20.0, 0.0);
        assert_eq!(o.state, PairState::Bonded);
        assert!(close(o.normal, 15.0), "{}", o.normal);
        assert!(close(aa[0], 5.0) && close(ab[0], 5.0), "{aa:?} {ab:?}");
    }

    #[test]
    fn w9_pull_10_separates() {
        let (o, _, _) = w9(PairState::Bonded, -10.0, 0.0);
        assert_eq!(o.state, PairState::Separated);
        assert_eq!(o.r, [0.0; 3]);
    }

    #[test]
    fn w9_pull_4_bonded_sticks_unbonded_separates() {
        let (o, aa, ab) = w9(PairState::Bonded, -4.0, 0.0);
        assert_eq!(o.state, PairState::Bonded);
        assert!(close(o.normal, -3.0));
        assert!(close(aa[0], -1.0) && close(ab[0], -1.0));
        for s in [PairState::Stick, PairState::Sliding, PairState::Separated] {
            let (o, _, _) = w9(s, -4.0, 0.0);
            assert_eq!(o.state, PairState::Separated);
            assert_eq!(o.r, [0.0; 3]);
        }
    }

    #[test]
    fn w9_tangential_cases() {
        let (o, _, _) = w9(PairState::Bonded, 20.0, 8.0);
        assert_eq!(o.state, PairState::Bonded);
        assert!(close(-o.tangential[1], 6.0));
        let (o, _, _) = w9(PairState::Stick, 20.0, 8.0);
        assert_eq!(o.state, PairState::Stick);
        assert!(close(-o.tangential[1], 6.0));

        let (o, aa, ab) = w9(PairState::Stick, 20.0, 16.0);
        assert_eq!(o.state, PairState::Sliding);
        assert!(close(-o.tangential[1], 6.0) && close(o.normal, 15.0));
        assert!(close(aa[1], 10.0) && close(ab[1], 2.0), "{aa:?} {ab:?}");

        let (o, _, _) = w9(PairState::Bonded, 20.0, 16.0);
        assert_eq!(o.state, PairState::Bonded);
        assert!(close(-o.tangential[1], 12.0));

        let (o, _, _) = w9(PairState::Bonded, 20.0, 18.0);
        assert_eq!(o.state, PairState::Sliding);
        assert!(close(-o.tangential[1], 6.0));
    }

    /// W8: c = 0.2 MPa, A = 0.25 m² → cA = 50 kN. Kernel-level: demands are set directly
    /// through the predicted relative displacement (w_sum Δt² = 1 so R_trial = Δ).
    fn w8(state: PairState, normal_demand: f64, shear_demand: f64) -> PairOutcome {
        let p = PairParams {
            mu_s: 0.6,
            mu_d: 0.45,
            shear_capacity: 0.2e6 * 0.25,
            tensile_capacity: 0.2e6 * 0.25,
        };
        let inp = PairInput {
            n: [0.0, 0.0, 1.0],
            w_sum: 1.0,
            dt: 1.0,
            rel_pred: [shear_demand, 0.0, -normal_demand],
            rel_old: [0.0; 3],
        };
        solve_pair(state, &p, &inp)
    }

    #[test]
    fn w8_tension_ramp_debonds_at_50kn_and_never_rebonds() {
        // Ramp 10⁶ t N: holds up to 50 kN (t = 0.05 s), separates just above.
        let o = w8(PairState::Bonded, -50e3, 0.0);
        assert_eq!(o.state, PairState::Bonded);
        let o = w8(PairState::Bonded, -50.001e3, 0.0);
        assert_eq!(o.state, PairState::Separated);
        // Tensile capacity zero for ever.
        let o = w8(PairState::Separated, -1.0, 0.0);
        assert_eq!(o.state, PairState::Separated);
        // Recompression still transmits force, without cohesion.
        let o = w8(PairState::Separated, 30e3, 0.0);
        assert_eq!(o.state, PairState::Stick);
        assert!(close(o.normal, 30e3));
    }

    #[test]
    fn w8_shear_slip_at_80kn_then_kinetic() {
        let o = w8(PairState::Bonded, 50e3, 80e3);
        assert_eq!(o.state, PairState::Bonded);
        assert!(close(norm(o.tangential), 80e3));
        let o = w8(PairState::Bonded, 50e3, 80.001e3);
        assert_eq!(o.state, PairState::Sliding);
        assert!(close(norm(o.tangential), 22.5e3));
        // Cohesion is gone: the next step sticks only up to μs N = 30 kN.
        let o = w8(PairState::Sliding, 50e3, 40e3);
        assert_eq!(o.state, PairState::Sliding);
        assert!(close(norm(o.tangential), 22.5e3));
        let o = w8(PairState::Sliding, 50e3, 30e3);
        assert_eq!(o.state, PairState::Stick);
    }
}
