//! Implicit (backward-Euler) return mapping in principal effective-stress space.
//!
//! Unknowns: the plastic multiplier Δλ and the two hardening variables y_t = b_t ε̃ᵖ_t,
//! y_c = b_c ε̃ᵖ_c. Because the flow direction of eq. (26) is coaxial with σ̄, the returned
//! principal stresses are an explicit function of Δλ alone ([`Potential::returned`]), and
//! so are the hardening variables through the Lee–Fenves (1998) evolution laws
//!
//!   Δε̃ᵖ_t = r(σ̂) Δλ ⟨m̂₁⟩,   Δε̃ᵖ_c = (1 − r(σ̂)) Δλ ⟨−m̂₃⟩,
//!
//! (the brackets keep the variables monotone when the dilatant potential makes every
//! principal plastic strain rate positive). The local system is thereby condensed to one
//! scalar equation F(Δλ) = 0 of eq. (25), solved by a bracketing Anderson–Björck
//! (regula falsi) iteration: bounded, derivative free, and always left on the admissible side F ≤ 0.
//!
//! The iteration runs on the returned q = √(3J̄₂) rather than on Δλ whenever the trial has
//! a deviator: Δλ is explicit in q ([`Potential::returned_at_q`]) while q in Δλ is the root
//! of a quartic, so each evaluation of F is a closed form instead of an inner Newton
//! iteration (−10 % of the damaging plastic-damage cube's time, docs/benchmarks.md).

use super::hardening::SofteningLaw;
use super::potential::{Potential, TrialSplit};
use super::yield_surface::{tension_weight, YieldSurface};

/// Cap on the bracket expansions of the local solve.
const MAX_EXPAND: usize = 200;
/// Default cap on the regula-falsi iterations of the local solve.
pub const MAX_ITER: usize = 200;

/// Everything the local problem needs, for one characteristic length.
#[derive(Clone, Copy, Debug)]
pub struct LocalProblem<'a> {
    /// Bulk modulus K (Pa).
    pub bulk: f64,
    /// Shear modulus μ (Pa).
    pub mu: f64,
    /// Eq. (25).
    pub surface: &'a YieldSurface,
    /// Eq. (26).
    pub potential: &'a Potential,
    /// Tension law of this element (strength scaled by the regularisation).
    pub tension: SofteningLaw,
    /// Compression law of this element.
    pub compression: SofteningLaw,
    /// Scales b_t, b_c for this element's characteristic length.
    pub b_t: f64,
    /// See `b_t`.
    pub b_c: f64,
    /// Softening dissipation densities g_t = ∫f_t dε̃ᵖ_t, g_c (J/m³) of this element.
    pub g_t: f64,
    /// See `g_t`.
    pub g_c: f64,
    /// Convergence tolerance on F (Pa).
    pub tol: f64,
    /// Cap on the regula-falsi iterations ([`MAX_ITER`]).
    pub max_iter: usize,
}

/// Hardening state at the start of a return and its effective cohesions.
#[derive(Clone, Copy, Debug)]
pub struct Start {
    /// y_t at the start of the step.
    pub y_t: f64,
    /// y_c at the start of the step.
    pub y_c: f64,
    /// c̄_t(y_t) (Pa).
    pub ct: f64,
    /// c̄_c(y_c) (Pa).
    pub cc: f64,
}

/// Result of a return.
#[derive(Clone, Copy, Debug)]
pub struct Returned {
    /// Plastic multiplier Δλ.
    pub dlam: f64,
    /// Principal flow direction m̂ at the returned stress.
    pub m: [f64; 3],
    /// Hardening variables at the end of the step.
    pub y_t: f64,
    /// See `y_t`.
    pub y_c: f64,
    /// F at the returned point (Pa).
    pub f: f64,
    /// Whether |F| ≤ tol (or the bracket collapsed onto a discontinuity).
    pub converged: bool,
}

/// c̄(y) of `law`: the start cohesion `c0` while y is still the start value `y0`.
#[inline]
fn cohesion(law: &SofteningLaw, y: f64, y0: f64, c0: f64) -> f64 {
    if y == y0 {
        c0
    } else {
        law.effective(y)
    }
}

impl LocalProblem<'_> {
    /// The start-of-step hardening (y_t0, y_c0) with its effective cohesions c̄_t, c̄_c
    /// (eq. 25's strengths), each evaluated once per return.
    #[inline]
    pub fn start(&self, y_t0: f64, y_c0: f64) -> Start {
        Start {
            y_t: y_t0,
            y_c: y_c0,
            ct: self.tension.effective(y_t0),
            cc: self.compression.effective(y_c0),
        }
    }

    /// State after a return of size Δλ from the trial. A hardening variable that did not
    /// move keeps its start cohesion (the same value `effective` would give again).
    #[inline]
    fn evaluate(&self, trial: &TrialSplit, start: &Start, dlam: f64) -> Returned {
        let (s, m, q) = self
            .potential
            .returned_from(trial, dlam, self.bulk, self.mu);
        self.hardened(start, s, m, q, dlam)
    }

    /// [`Self::evaluate`] of the return that leaves √(3J̄₂) = q (qᵗʳ ≥ q > 0), its Δλ
    /// explicit ([`Potential::returned_at_q`]).
    #[inline]
    fn evaluate_at_q(&self, trial: &TrialSplit, start: &Start, q: f64) -> Returned {
        let (s, m, dlam) = self.potential.returned_at_q(trial, q, self.bulk, self.mu);
        self.hardened(start, s, m, q, dlam)
    }

    /// The hardening variables and F after a return of size Δλ to principal stress `s`
    /// (√(3J̄₂) = q) with flow direction `m`.
    #[inline(always)]
    fn hardened(&self, start: &Start, s: [f64; 3], m: [f64; 3], q: f64, dlam: f64) -> Returned {
        let r = tension_weight(&s);
        let y_t = start.y_t + self.b_t * r * dlam * m[0].max(0.0);
        let y_c = start.y_c + self.b_c * (1.0 - r) * dlam * (-m[2]).max(0.0);
        let ct = cohesion(&self.tension, y_t, start.y_t, start.ct);
        let cc = cohesion(&self.compression, y_c, start.y_c, start.cc);
        Returned {
            dlam,
            m,
            y_t,
            y_c,
            // √(3J̄₂) of s is the returned q (s's deviator is the trial's scaled to it)
            f: self.surface.value_from(s[0] + s[1] + s[2], q, s[0], ct, cc),
            converged: false,
        }
    }

    /// Return the sorted principal trial stress `trial` (with F(trial) > 0) to the yield
    /// surface from the hardening state `start` ([`Self::start`]).
    ///
    /// The unknown is q = √(3J̄₂) of the returned stress when the trial has a deviator —
    /// each evaluation then explicit ([`Potential::returned_at_q`]) — and Δλ itself for a
    /// hydrostatic trial (q stays 0). Either way the iteration runs on a variable x that
    /// grows with Δλ (x = −q, or x = Δλ) from the trial's x₀ (F > 0).
    pub fn solve(&self, trial: &[f64; 3], start: &Start) -> Returned {
        let split = TrialSplit::of(trial);
        // F(trial) = `surface.value(trial, ..)`, with the split's √(3J̄₂)
        let f_tr = self.surface.value_from(
            trial[0] + trial[1] + trial[2],
            split.q,
            trial[0],
            start.ct,
            start.cc,
        );
        let trial = &split;
        if f_tr <= self.tol {
            // Inside to within the tolerance (the caller's check may use other rounding).
            return Returned {
                converged: true,
                ..self.evaluate(trial, start, 0.0)
            };
        }
        let three_mu = 3.0 * self.mu;
        if trial.q > 0.0 {
            // x = −q; the k-th bracket probe is the q of a return with 3μΔλ ≥ 4ᵏ F(trial)
            // ([`Potential::q_below`]).
            self.bracket_and_refine(
                -trial.q,
                f_tr,
                |c| -self.potential.q_below(trial.q, c),
                |x| self.evaluate_at_q(trial, start, -x),
            )
        } else {
            self.bracket_and_refine(
                0.0,
                f_tr,
                |c| (c / three_mu).max(f64::MIN_POSITIVE),
                |x| self.evaluate(trial, start, x),
            )
        }
    }

    /// Root of F(x) = 0 for F decreasing in x with F(`x0`) = `f0` > 0: probes
    /// `probe(c)` for c = F(trial), 4 F(trial), 16 F(trial), … until F ≤ 0 (F → −∞ as
    /// Δλ → ∞ because the mean stress falls as K Δλ tan ψ), then a bracketing
    /// Anderson–Björck regula falsi, always left on the admissible side F ≤ 0.
    #[inline(always)]
    fn bracket_and_refine(
        &self,
        x0: f64,
        f0: f64,
        probe: impl Fn(f64) -> f64,
        at: impl Fn(f64) -> Returned,
    ) -> Returned {
        let (mut a, mut fa) = (x0, f0);
        let mut c = f0;
        let mut hi = probe(c);
        let mut at_hi = at(hi);
        let mut expanded = 0;
        // (written so that a NaN F also enters the loop and returns)
        while at_hi.f.is_nan() || at_hi.f > 0.0 {
            if !at_hi.f.is_finite() || expanded == MAX_EXPAND {
                return at_hi;
            }
            if at_hi.f.abs() <= self.tol {
                at_hi.converged = true;
                return at_hi;
            }
            a = hi;
            fa = at_hi.f;
            c *= 4.0;
            hi = probe(c);
            at_hi = at(hi);
            expanded += 1;
        }
        if at_hi.f.abs() <= self.tol {
            at_hi.converged = true;
            return at_hi;
        }
        // Regula falsi (Anderson–Björck) on [a, b] with F(a) > 0 ≥ F(b).
        let (mut b, mut fb) = (hi, at_hi.f);
        let mut best = at_hi;
        let mut side = 0i8;
        for _ in 0..self.max_iter {
            let mut x = (a * fb - b * fa) / (fb - fa);
            if !(x > a && x < b) {
                x = 0.5 * (a + b);
            }
            let at_x = at(x);
            if !at_x.f.is_finite() {
                break;
            }
            if at_x.f.abs() <= self.tol {
                return Returned {
                    converged: true,
                    ..at_x
                };
            }
            // Anderson–Björck: when the same end is kept twice, scale its value by
            // 1 − F(x)/F(replaced end) (0.5 when that is not positive).
            if at_x.f > 0.0 {
                if side == 1 {
                    let k = 1.0 - at_x.f / fa;
                    fb *= if k > 0.0 { k } else { 0.5 };
                }
                a = x;
                fa = at_x.f;
                side = 1;
            } else {
                if side == -1 {
                    let k = 1.0 - at_x.f / fb;
                    fa *= if k > 0.0 { k } else { 0.5 };
                }
                b = x;
                fb = at_x.f;
                best = at_x;
                side = -1;
            }
            if b - a <= 4.0 * f64::EPSILON * b.abs() {
                // F jumps across the root (the weight r is discontinuous at σ̄ = 0): the
                // admissible end of the collapsed bracket is the answer.
                return Returned {
                    converged: true,
                    ..best
                };
            }
        }
        best
    }
}
