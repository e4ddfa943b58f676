//! W15f — the synthetic generator: bit-for-bit reproducibility and the Wolong-like preset.
//!
//! Goal: the same seed gives the same motion, bit for bit (same run, and the same bits as
//! the fingerprint recorded when the generator was written — the check that a change of
//! platform, compiler or dependency did not change the motion); the preset has the peaks,
//! the EW peak time and the two strong phases the issue specifies, and ends at rest.
//!
//! ```text
//!   seed 1, Wolong-like preset, 60 s at dt 0.005 s, x = EW, y = NS, z = UD
//!   PGA x 9.577, y 6.53, z 9.48 m/s²; EW peak at 13.01 s (33.01 s of the record)
//!   strong phases 2.6–20 s and 30–40 s: RMS acceleration in each ≥ 2 × that of 21–28 s
//!   and ≥ 2 × that of 0–2 s; ≥ 80 % of the Arias intensity inside the two phases
//!   final velocity and displacement 0 (|v| ≤ 1e-9 m/s, |u| ≤ 1e-9 m)
//! ```
//!
//! Reference: issue 8 / DESIGN.md §7 (the paper's Wolong input, Yang, Chen & Xiao 2014 §4).
//! The fingerprint is FNV-1a (64 bit) over the little-endian bytes of the three
//! acceleration series, recorded from the generator itself: it is a reproducibility
//! guard, not a reference for correctness (the other rows are).

use dcfm::motion::measures::peak;
use dcfm::motion::synthetic::wolong::{PEAK_TIME_EW, PGA_EW, PGA_NS, PGA_UD};
use dcfm::motion::{GroundMotion, MotionSpec, SyntheticSpec};
use dcfm::Result;

use crate::record::{Check, CheckRow};

const SOURCE: &str = "issue 8 (Wolong-like preset), DESIGN.md §7";

/// FNV-1a of the seed-1 preset's accelerations (x, y, z in order), recorded at the
/// generator's first version.
pub const FINGERPRINT_SEED_1: u64 = 0xa322_a6c5_c4c8_05e1;

/// The preset with `seed`, as a case would load it.
pub fn preset(seed: u64) -> Result<GroundMotion> {
    let spec = MotionSpec {
        synthetic: Some(SyntheticSpec {
            preset: Some("wolong".into()),
            seed: Some(seed),
            ..SyntheticSpec::default()
        }),
        ..MotionSpec::default()
    };
    spec.load("wolong", "w15_synthetic", std::path::Path::new(""))
}

/// FNV-1a (64 bit) over the bytes of the acceleration series.
pub fn fingerprint(m: &GroundMotion) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for c in &m.components {
        for v in &c.acceleration {
            for b in v.to_le_bytes() {
                h ^= u64::from(b);
                h = h.wrapping_mul(0x0000_0100_0000_01b3);
            }
        }
    }
    h
}

fn rms(a: &[f64], dt: f64, t0: f64, t1: f64) -> f64 {
    let (i0, i1) = (
        (t0 / dt).round() as usize,
        ((t1 / dt).round() as usize).min(a.len() - 1),
    );
    let s = &a[i0..=i1];
    (s.iter().map(|v| v * v).sum::<f64>() / s.len() as f64).sqrt()
}

/// Run W15f.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("W15f synthetic motion (Wolong-like preset)");
    let m = preset(1)?;
    let again = preset(1)?;
    let same = m.components.iter().zip(&again.components).all(|(a, b)| {
        a.acceleration
            .iter()
            .zip(&b.acceleration)
            .all(|(x, y)| x.to_bits() == y.to_bits())
    });
    check.absolute(
        "same seed twice: bit-identical (1 = yes)",
        1.0,
        f64::from(u8::from(same)),
        0.0,
        SOURCE,
    );
    let other = preset(2)?;
    let differs = m.components[0].acceleration != other.components[0].acceleration;
    check.absolute(
        "another seed: a different motion (1 = yes)",
        1.0,
        f64::from(u8::from(differs)),
        0.0,
        SOURCE,
    );
    check.absolute(
        "fingerprint of seed 1 equals the recorded one (1 = yes)",
        1.0,
        f64::from(u8::from(fingerprint(&m) == FINGERPRINT_SEED_1)),
        0.0,
        SOURCE,
    );
    for (axis, target) in [("x", PGA_EW), ("y", PGA_NS), ("z", PGA_UD)] {
        let c = m.component_named(axis).expect("preset has x, y, z");
        let p = peak(&c.acceleration, c.dt);
        check.relative(
            &format!("PGA {axis} (m/s²)"),
            target,
            p.value,
            1e-12,
            SOURCE,
        );
        if axis == "x" {
            check.absolute("EW peak time (s)", PEAK_TIME_EW, p.time, 0.5 * c.dt, SOURCE);
        }
        let quiet = rms(&c.acceleration, c.dt, 21.0, 28.0);
        let start = rms(&c.acceleration, c.dt, 0.0, 2.0);
        for (name, t0, t1) in [("2.6–20 s", 2.6, 20.0), ("30–40 s", 30.0, 40.0)] {
            let strong = rms(&c.acceleration, c.dt, t0, t1);
            check.within(
                &format!("{axis}: RMS in {name} / RMS in 21–28 s"),
                2.0,
                100.0,
                strong / quiet,
                SOURCE,
            );
            check.within(
                &format!("{axis}: RMS in {name} / RMS in 0–2 s"),
                2.0,
                100.0,
                strong / start,
                SOURCE,
            );
        }
        let h = dcfm::motion::measures::husid(&c.acceleration, c.dt);
        let at = |t: f64| h[((t / c.dt).round() as usize).min(h.len() - 1)];
        let inside = (at(20.0) - at(2.6)) + (at(40.0) - at(30.0));
        check.within(
            &format!("{axis}: share of Arias intensity in the two phases"),
            0.8,
            1.0,
            inside,
            SOURCE,
        );
        check.absolute(
            &format!("{axis}: final velocity (m/s)"),
            0.0,
            *c.velocity.last().unwrap_or(&f64::NAN),
            1e-9,
            SOURCE,
        );
        check.absolute(
            &format!("{axis}: final displacement (m)"),
            0.0,
            *c.displacement.last().unwrap_or(&f64::NAN),
            1e-9,
            SOURCE,
        );
    }
    Ok(check.finish())
}
