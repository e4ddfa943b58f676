//! W15b — Arias intensity and significant duration of a sine.
//!
//! Goal: I_a = π/(2g) ∫a² dt and the Husid-curve times are computed right.
//!
//! ```text
//!   a(t) = A sin(2πt/T), A = 3 m/s², T = 0.5 s, n = 10 whole periods, Δt = T/200
//!   I_a = π A² nT/(4g)
//!   H(t) = (t/2 − T sin(4πt/T)/(8π)) / (nT/2): t₅ and t₉₅ solved from it by bisection
//! ```
//!
//! Reference: docs/verification_references.md §W15 (Arias 1970; Trifunac & Brady 1975 for D5–95).
//! Tolerance: 1e-12 relative on I_a (the trapezoidal sum of sin² over whole periods is
//! exact); 1e-4 s on t₅, t₉₅ (linear interpolation of the sampled Husid curve, O(Δt²)).

use dcfm::motion::measures::{arias_intensity, significant_duration};
use dcfm::motion::units::STANDARD_GRAVITY;
use dcfm::Result;

use crate::record::{Check, CheckRow};

const SOURCE: &str = "docs/verification_references.md §W15 (Arias intensity of a sine)";

/// The time where the closed-form Husid curve of the sine reaches `level`.
fn husid_time(level: f64, period: f64, n: f64) -> f64 {
    let h = |t: f64| {
        (t / 2.0
            - period * (4.0 * std::f64::consts::PI * t / period).sin()
                / (8.0 * std::f64::consts::PI))
            / (n * period / 2.0)
    };
    let (mut lo, mut hi) = (0.0, n * period);
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if h(mid) < level {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// Run W15b.
pub fn run() -> Result<Vec<CheckRow>> {
    let (amp, period, n): (f64, f64, f64) = (3.0, 0.5, 10.0);
    let dt = period / 200.0;
    let samples = (n * period / dt).round() as usize + 1;
    let a: Vec<f64> = (0..samples)
        .map(|i| amp * (2.0 * std::f64::consts::PI * i as f64 * dt / period).sin())
        .collect();
    let mut check = Check::new("W15b Arias intensity of a sine");
    let reference = std::f64::consts::PI * amp * amp * n * period / (4.0 * STANDARD_GRAVITY);
    check.relative(
        "I_a (m/s)",
        reference,
        arias_intensity(&a, dt),
        1e-12,
        SOURCE,
    );
    let (t5, t95, _) =
        significant_duration(&a, dt, 0.05, 0.95).unwrap_or((f64::NAN, f64::NAN, f64::NAN));
    check.absolute(
        "t at 5 % of I_a (s)",
        husid_time(0.05, period, n),
        t5,
        1e-4,
        SOURCE,
    );
    check.absolute(
        "t at 95 % of I_a (s)",
        husid_time(0.95, period, n),
        t95,
        1e-4,
        SOURCE,
    );
    Ok(check.finish())
}
