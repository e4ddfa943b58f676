//! The Wolong-like preset: the default input of every example and of the Yingxiuwan case.
//!
//! The paper (Yang, Chen & Xiao 2014, §4) drives its model with 60 s (the 20–80 s window)
//! of the three-component Wolong record (station 051WCW, Wenchuan 2008): EW PGA
//! 957.7 cm/s² at 33.01 s of the record, NS ≈ 653 and UD ≈ 948 cm/s², with damage growing
//! in two strong phases, 2.6–20 s and 30–40 s of the window. The real record is not
//! shipped; this preset makes a stochastic motion with those features:
//!
//! - 60 s at dt = 0.005 s (200 samples/s, the rate of the Chinese strong-motion network);
//! - envelope: phase 1 rises from 0.3 s to 2.6 s, plateau to 20 s, decays with τ = 2.5 s;
//!   phase 2 rises from 26 s to 30 s, plateau (level 0.8) to 40 s, decays with τ = 4 s;
//!   3 s fade to zero at the end;
//! - spectral shape (not fitted to the record; typical of a near-fault rock site):
//!   horizontals f_g = 3 Hz, ζ_g = 0.6; vertical f_g = 6 Hz, ζ_g = 0.6; high-pass
//!   f_f = 0.5 Hz (0.6 Hz vertical), ζ_f = 0.7, which keeps the peak ground velocity
//!   and displacement near 1 m/s and 0.5 m (the displacement variance of the
//!   Clough–Penzien spectrum grows as f_f^−3);
//! - peaks: x (EW) 9.577 m/s², y (NS) 6.53 m/s², z (UD) 9.48 m/s²;
//! - the EW peak is placed at 13.01 s of the window — 33.01 s of the original record —
//!   to the sample; the NS and UD peaks fall where their noise puts them;
//! - final velocity and displacement zero (baseline corrected).
//!
//! Seed 1 unless the case sets another.

use super::envelope::Phase;
use super::{ComponentShape, GeneratorParameters};
use crate::motion::record::Axis;

/// EW peak (m/s²): 957.7 cm/s².
pub const PGA_EW: f64 = 9.577;
/// NS peak (m/s²): ≈ 653 cm/s².
pub const PGA_NS: f64 = 6.53;
/// UD peak (m/s²): ≈ 948 cm/s².
pub const PGA_UD: f64 = 9.48;
/// Time of the EW peak in the 60 s window (s): 33.01 s of the record − 20 s.
pub const PEAK_TIME_EW: f64 = 13.01;

/// The preset's parameters.
pub fn parameters() -> GeneratorParameters {
    let horizontal = |name: &str, pga: f64, peak_time: Option<f64>| ComponentShape {
        name: Some(name.to_string()),
        pga,
        ground_frequency: 3.0,
        ground_damping: 0.6,
        highpass_frequency: 0.5,
        highpass_damping: 0.7,
        peak_time,
    };
    GeneratorParameters {
        seed: 1,
        duration: 60.0,
        dt: 0.005,
        phases: vec![
            Phase {
                rise: 0.3,
                start: 2.6,
                end: 20.0,
                decay: 2.5,
                level: 1.0,
            },
            Phase {
                rise: 26.0,
                start: 30.0,
                end: 40.0,
                decay: 4.0,
                level: 0.8,
            },
        ],
        fade: 3.0,
        components: vec![
            (Axis::X, horizontal("EW", PGA_EW, Some(PEAK_TIME_EW))),
            (Axis::Y, horizontal("NS", PGA_NS, None)),
            (
                Axis::Z,
                ComponentShape {
                    name: Some("UD".to_string()),
                    pga: PGA_UD,
                    ground_frequency: 6.0,
                    ground_damping: 0.6,
                    highpass_frequency: 0.6,
                    highpass_damping: 0.7,
                    peak_time: None,
                },
            ),
        ],
        label: "Wolong-like preset".into(),
    }
}
