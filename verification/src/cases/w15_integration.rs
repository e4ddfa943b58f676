//! W15d — integration of an analytic motion after baseline correction.
//!
//! Goal: the processing chain (mean baseline, integration) gives the analytic velocity and
//! displacement of a motion with a baseline offset.
//!
//! ```text
//!   a(t) = c + A sin(2πt/T), c = 0.2 m/s² (the offset), A = 2 m/s², T = 0.8 s,
//!   4 whole periods, Δt = T/4000, read as a one-column text record (m/s²)
//!   after removing the mean: v = A T/(2π)(1 − cos(2πt/T)), u = A T/(2π)(t − T/(2π) sin(2πt/T))
//! ```
//!
//! Reference: docs/verification_references.md §W15 (integration of an analytic motion). Tolerance 1e-6 of
//! the peak (the trapezoidal rule on a sine: (ωΔt)²/12 ≈ 2e-7).

use dcfm::motion::{process, read_str, AccelUnits, ProcessingOptions, ReadOptions};
use dcfm::Result;

use crate::record::{Check, CheckRow};

const SOURCE: &str = "docs/verification_references.md §W15 (integration of an analytic motion)";

/// (max |v − v_exact| / max |v|, max |u − u_exact| / max |u|, mean removed − c).
pub fn errors() -> Result<(f64, f64, f64)> {
    let (c, amp, period) = (0.2, 2.0, 0.8);
    let dt = period / 4000.0;
    let n = 4 * 4000 + 1;
    let w = 2.0 * std::f64::consts::PI / period;
    let text: String = (0..n)
        .map(|i| format!("{:.17e}\n", c + amp * (w * i as f64 * dt).sin()))
        .collect();
    let options = ReadOptions {
        format: None,
        units: Some(AccelUnits::MetrePerSecond2),
        dt: Some(dt),
    };
    let record = read_str(&text, "analytic.txt", &options)?;
    let motion = process(
        &record,
        "analytic",
        &ProcessingOptions::default(),
        "analytic.txt",
        "processing",
    )?;
    let comp = &motion.components[0];
    let (mut ev, mut eu, mut pv, mut pu) = (0.0f64, 0.0f64, 0.0f64, 0.0f64);
    for i in 0..n {
        let t = i as f64 * dt;
        let v = amp / w * (1.0 - (w * t).cos());
        let u = amp / w * (t - (w * t).sin() / w);
        ev = ev.max((comp.velocity[i] - v).abs());
        eu = eu.max((comp.displacement[i] - u).abs());
        pv = pv.max(v.abs());
        pu = pu.max(u.abs());
    }
    let k = n / 3;
    let mean_removed = c + amp * (w * k as f64 * dt).sin() - comp.acceleration[k];
    Ok((ev / pv, eu / pu, mean_removed - c))
}

/// Run W15d.
pub fn run() -> Result<Vec<CheckRow>> {
    let (ev, eu, offset) = errors()?;
    let mut check = Check::new("W15d integration after baseline correction");
    check.absolute("velocity: max |v − exact| / max |v|", 0.0, ev, 1e-6, SOURCE);
    check.absolute(
        "displacement: max |u − exact| / max |u|",
        0.0,
        eu,
        1e-6,
        SOURCE,
    );
    check.absolute("mean removed − offset c (m/s²)", 0.0, offset, 1e-12, SOURCE);
    Ok(check.finish())
}
