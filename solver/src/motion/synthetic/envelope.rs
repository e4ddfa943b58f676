//! Time envelope of the synthetic motion: a sum of strong phases, each a quadratic rise,
//! a plateau and an exponential decay (the trapezoidal-exponential shape of Jennings,
//! Housner & Tsai 1968, "Simulated earthquake motions", EERL Caltech), combined in energy:
//! e(t) = √(Σ_k e_k(t)²) — independent noise bursts add their powers — times a final
//! half-cosine fade to zero.

use serde::Deserialize;

/// One strong phase.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct Phase {
    /// Start of the rise (s): e_k = 0 before.
    pub rise: f64,
    /// Start of the plateau (s): e_k = level·((t − rise)/(start − rise))² during the rise.
    pub start: f64,
    /// End of the plateau (s).
    pub end: f64,
    /// Decay time constant after `end` (s): e_k = level·exp(−(t − end)/decay).
    pub decay: f64,
    /// Plateau level (relative).
    #[serde(default = "one")]
    pub level: f64,
}

fn one() -> f64 {
    1.0
}

impl Phase {
    /// e_k(t). Uses libm's exp (portable).
    pub fn value(&self, t: f64) -> f64 {
        if t < self.rise {
            0.0
        } else if t < self.start {
            let x = (t - self.rise) / (self.start - self.rise);
            self.level * x * x
        } else if t <= self.end {
            self.level
        } else {
            self.level * libm::exp(-(t - self.end) / self.decay)
        }
    }
}

/// e(t) = √(Σ e_k(t)²) × the fade over the last `fade` seconds before `duration`.
pub fn envelope(phases: &[Phase], t: f64, duration: f64, fade: f64) -> f64 {
    let power: f64 = phases
        .iter()
        .map(|p| {
            let e = p.value(t);
            e * e
        })
        .sum();
    let mut e = libm::sqrt(power);
    let to_end = duration - t;
    if fade > 0.0 && to_end < fade {
        let x = (to_end / fade).max(0.0);
        e *= 0.5 * (1.0 - libm::cos(std::f64::consts::PI * x));
    }
    e
}
