//! W15c — Butterworth filters: corner gain and zero phase.
//!
//! Goal: the filters applied to a record have the textbook magnitude, and the
//! forward–backward pass does not shift or distort a symmetric pulse.
//!
//! ```text
//!   (a) design: |H(f)| = 1/√(1 + (tan(πfΔt)/tan(πf_cΔt))^{±2n}) (bilinear, pre-warped),
//!       i.e. 1/√2 at f_c, for n = 1…8, low- and high-pass, at 7 frequencies
//!   (b) applied: a 20 s sine at f_c = 5 Hz (Δt = 1 ms) through one pass: steady amplitude
//!       1/√2 (−3.01 dB); forward-backward: 1/2 (−6.02 dB); orders 2, 4, 6
//!   (c) zero phase: a Gaussian pulse (σ = 0.05 s) at the centre of a 10 s record padded
//!       with 20 s of zeros each side, band-passed 0.5–10 Hz order 4 forward-backward:
//!       y(c + k) = y(c − k); the causal
//!       single pass is visibly asymmetric (checked so that this test can fail)
//! ```
//!
//! Reference: docs/verification_references.md §W15 (Oppenheim & Schafer §7.1). Tolerances: (a) 1e-12
//! (round-off); (b) 1e-3 relative (the amplitude is measured over whole periods after the
//! transients; the pads are not used); (c) 1e-9 of the peak.

use dcfm::motion::processing::butterworth::{Butterworth, Pass};
use dcfm::Result;

use crate::record::{Check, CheckRow};

const SOURCE: &str = "docs/verification_references.md §W15 (Butterworth corner gain, zero phase)";

/// Largest |design gain − textbook gain| over orders, sides and frequencies.
pub fn design_error() -> f64 {
    let (dt, fc) = (0.01, 4.0);
    let warp = |f: f64| (std::f64::consts::PI * f * dt).tan();
    let mut worst = 0.0f64;
    for order in 1..=8 {
        for pass in [Pass::Low, Pass::High] {
            let filt = Butterworth::new(pass, order, fc, dt);
            for f in [0.3, 1.0, 2.5, 4.0, 7.0, 15.0, 40.0] {
                let r = warp(f) / warp(fc);
                let x = match pass {
                    Pass::Low => r,
                    Pass::High => 1.0 / r,
                };
                let textbook = 1.0 / (1.0 + x.powi(2 * order as i32)).sqrt();
                worst = worst.max((filt.gain(f, dt) - textbook).abs());
            }
        }
    }
    worst
}

/// Steady amplitude of a unit sine at the corner after one pass or forward-backward.
pub fn applied_corner_gain(pass: Pass, order: usize, zero_phase: bool) -> f64 {
    let (dt, fc) = (0.001, 5.0);
    let n = 20_001;
    let mut x: Vec<f64> = (0..n)
        .map(|i| (2.0 * std::f64::consts::PI * fc * i as f64 * dt).sin())
        .collect();
    let filt = Butterworth::new(pass, order, fc, dt);
    if zero_phase {
        filt.forward_backward(&mut x);
    } else {
        filt.forward(&mut x);
    }
    // RMS over 50 whole periods in the middle (samples 7500 … 17500), times √2.
    let mid = &x[7_500..17_500];
    (2.0 * mid.iter().map(|v| v * v).sum::<f64>() / mid.len() as f64).sqrt()
}

/// Largest |y(c + k) − y(c − k)| / max|y| of a filtered symmetric pulse.
pub fn asymmetry(zero_phase: bool) -> f64 {
    // 10 s of record plus 20 s of zero pad on each side: the forward pass must have rung
    // out (e^(−ζωt) of the 0.5 Hz high-pass's slowest pole pair, ≈ e^(−30)) before the
    // backward pass starts, or the cut tail breaks the symmetry.
    let (dt, n) = (0.001, 50_001);
    let centre = n / 2;
    let mut x: Vec<f64> = (0..n)
        .map(|i| {
            let s = (i as f64 - centre as f64) * dt / 0.05;
            (-0.5 * s * s).exp()
        })
        .collect();
    let filters = [
        Butterworth::new(Pass::High, 4, 0.5, dt),
        Butterworth::new(Pass::Low, 4, 10.0, dt),
    ];
    for f in &filters {
        if zero_phase {
            f.forward_backward(&mut x);
        } else {
            f.forward(&mut x);
        }
    }
    let peak = x.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    (1..centre).fold(0.0f64, |m, k| m.max((x[centre + k] - x[centre - k]).abs())) / peak
}

/// Run W15c.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("W15c Butterworth filter");
    check.absolute(
        "design |H| vs 1/√(1 + (f/f_c)^2n) (warped), n = 1…8",
        0.0,
        design_error(),
        1e-12,
        SOURCE,
    );
    for order in [2, 4, 6] {
        for (pass, name) in [(Pass::Low, "low"), (Pass::High, "high")] {
            check.relative(
                &format!("{name}-pass order {order}, one pass: gain at f_c (−3.01 dB)"),
                std::f64::consts::FRAC_1_SQRT_2,
                applied_corner_gain(pass, order, false),
                1e-3,
                SOURCE,
            );
            check.relative(
                &format!("{name}-pass order {order}, forward-backward: gain at f_c (−6.02 dB)"),
                0.5,
                applied_corner_gain(pass, order, true),
                1e-3,
                SOURCE,
            );
        }
    }
    check.absolute(
        "forward-backward band-pass: asymmetry of a symmetric pulse",
        0.0,
        asymmetry(true),
        1e-9,
        SOURCE,
    );
    check.within(
        "causal single pass: asymmetry (must be visible, > 1e-2)",
        1e-2,
        10.0,
        asymmetry(false),
        SOURCE,
    );
    Ok(check.finish())
}
