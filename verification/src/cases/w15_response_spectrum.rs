//! W15a — the Nigam–Jennings recursion against closed-form SDOF responses.
//!
//! Goal: the response-spectrum oscillator is exact for piecewise-linear input, so with a
//! fine step it reproduces the analytic responses to 1e-6.
//!
//! ```text
//!   (a) undamped: ü + ω_n²u = A sin ωt from rest, T_n = 1 s, ω/ω_n = 0.6, A = 1,
//!       Δt = 1e-4 s, 5 s:  u = A/(ω_n² − ω²)(sin ωt − (ω/ω_n) sin ω_n t)
//!       and the spectrum's SD of a_g = −A sin ωt = max|u| over the same samples
//!   (b) damped impulse: ü + 2ξω_nu̇ + ω_n²u = δ(t), ξ = 0.05, T_n = 0.5 s:
//!       u = e^(−ξω_n t) sin(ω_d t)/ω_d; δ(t) imposed as u̇(0⁺) = 1, then free vibration,
//!       at Δt = 0.01 s and 0.05 s (the recursion is exact at any step)
//! ```
//!
//! Reference: docs/verification_references.md §W15 (Chopra, Dynamics of Structures, eqs. 3.1.3 and 4.1.6).
//! Tolerance: 1e-6 of the peak response (the brief's figure; what is left in (a) is the
//! linear interpolation of the sine between samples, O((ωΔt)²/12) ≈ 1e-8).

use dcfm::motion::measures::{response_spectrum, sdof_response};
use dcfm::Result;

use crate::record::{Check, CheckRow};

const SOURCE: &str = "docs/verification_references.md §W15 (Chopra eqs. 3.1.3, 4.1.6)";
const TOL: f64 = 1e-6;

/// max |u − u_exact| / max |u_exact| of the undamped harmonic case, and the relative error
/// of the spectrum's SD.
pub fn undamped_harmonic() -> (f64, f64) {
    let two_pi = 2.0 * std::f64::consts::PI;
    let (wn, w, amp, dt) = (two_pi, 0.6 * two_pi, 1.0, 1e-4);
    let n = 50_001;
    let p: Vec<f64> = (0..n).map(|i| amp * (w * i as f64 * dt).sin()).collect();
    let exact: Vec<f64> = (0..n)
        .map(|i| {
            let t = i as f64 * dt;
            amp / (wn * wn - w * w) * ((w * t).sin() - w / wn * (wn * t).sin())
        })
        .collect();
    let (u, _) = sdof_response(&p, dt, wn, 0.0, 0.0, 0.0);
    let peak = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let err = u
        .iter()
        .zip(&exact)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
    let ag: Vec<f64> = p.iter().map(|x| -x).collect();
    let sd = response_spectrum(&ag, dt, &[1.0], 0.0)[0].sd;
    (err / peak, (sd - peak).abs() / peak)
}

/// max |u − u_exact| / max |u_exact| of the damped impulse response at step `dt`.
pub fn damped_impulse(dt: f64) -> f64 {
    let (xi, wn): (f64, f64) = (0.05, 2.0 * std::f64::consts::PI / 0.5);
    let wd = wn * (1.0 - xi * xi).sqrt();
    let n = (10.0 / dt) as usize + 1;
    let p = vec![0.0; n];
    let (u, _) = sdof_response(&p, dt, wn, xi, 0.0, 1.0);
    let mut peak = 0.0f64;
    let mut err = 0.0f64;
    for (i, ui) in u.iter().enumerate() {
        let t = i as f64 * dt;
        let e = (-xi * wn * t).exp() * (wd * t).sin() / wd;
        peak = peak.max(e.abs());
        err = err.max((ui - e).abs());
    }
    err / peak
}

/// Run W15a.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("W15a response spectrum (Nigam–Jennings)");
    let (history, sd) = undamped_harmonic();
    check.absolute(
        "undamped harmonic: max |u − exact| / max |u|",
        0.0,
        history,
        TOL,
        SOURCE,
    );
    check.absolute(
        "undamped harmonic: spectral SD vs max |u exact| (relative)",
        0.0,
        sd,
        TOL,
        SOURCE,
    );
    for dt in [0.01, 0.05] {
        check.absolute(
            &format!("damped impulse ξ = 0.05, Δt = {dt} s: max |u − exact| / max |u|"),
            0.0,
            damped_impulse(dt),
            TOL,
            SOURCE,
        );
    }
    Ok(check.finish())
}
