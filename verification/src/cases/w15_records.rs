//! W15e — real records that packages ship, read by the Rust readers, against their own
//! headers.
//!
//! Goal: each reader gets npts, dt, units and the peak of a real file right.
//!
//! ```text
//!   NIS090.AT2  (PEER NGA, old header)  npts 4096, dt 0.01 s (header line 4); PGA 0.503 g
//!   2516b_a.smc (USGS SMC)              npts 41200 (int header #17), dt 1/200 s (real #2),
//!                                       PGA 3.91E+1 cm/s² ("pk acc" of text line 7)
//!   test.knet   (K-NET ASCII)           5900 samples = 59 s × 100 Hz (header), dt 0.01 s,
//!                                       PGA after removing the mean = Max. Acc. 4.383 gal
//!   hand_made.v2 (COSMOS V2, by hand)   npts 400, dt 10 ms (real header #62), orientation
//!                                       90° → x, PGA = max |100 sin(4πt) sin(πt/4)| cm/s²
//! ```
//!
//! Reference: the files' headers (fixtures and provenance in
//! `verification/fixtures/motions/PROVENANCE.md`); the AT2 PGA 0.503 g is docs/verification_references.md
//! W15's. Tolerances: npts exact; dt 1e-12; PGA to the header's last printed digit (half a
//! unit of it: 0.0005 g, 0.05 cm/s², 0.0005 gal), the COSMOS one to its 5 printed decimals.

use std::path::{Path, PathBuf};

use dcfm::motion::measures::peak;
use dcfm::motion::units::{AccelUnits, STANDARD_GRAVITY};
use dcfm::motion::{process, read_file, Axis, ProcessingOptions, ReadOptions};
use dcfm::Result;

use crate::record::{Check, CheckRow};

const SOURCE: &str =
    "file headers (verification/fixtures/motions/PROVENANCE.md), docs/verification_references.md §W15";

/// The fixture directory.
pub fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fixtures")
        .join("motions")
}

/// Run W15e.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("W15e real records vs their headers");
    let dir = fixtures();
    let auto = ReadOptions::default();

    let at2 = read_file(&dir.join("NIS090.AT2"), &auto)?;
    let a = &at2.components[0].acceleration;
    check.absolute("NIS090.AT2 npts", 4096.0, a.len() as f64, 0.0, SOURCE);
    check.absolute("NIS090.AT2 dt (s)", 0.01, at2.dt, 1e-12, SOURCE);
    check.absolute(
        "NIS090.AT2 PGA (g)",
        0.503,
        peak(a, at2.dt).value / STANDARD_GRAVITY,
        5e-4,
        SOURCE,
    );
    check.absolute(
        "NIS090.AT2 units g (1 = yes)",
        1.0,
        f64::from(u8::from(at2.units == AccelUnits::G)),
        0.0,
        SOURCE,
    );

    let smc = read_file(&dir.join("2516b_a.smc"), &auto)?;
    let a = &smc.components[0].acceleration;
    check.absolute("2516b_a.smc npts", 41200.0, a.len() as f64, 0.0, SOURCE);
    check.absolute("2516b_a.smc dt (s)", 0.005, smc.dt, 1e-12, SOURCE);
    check.absolute(
        "2516b_a.smc PGA (cm/s²)",
        39.1,
        peak(a, smc.dt).value * 100.0,
        0.05,
        SOURCE,
    );
    check.absolute(
        "2516b_a.smc header peak read (cm/s²)",
        39.1,
        smc.components[0].header_peak.unwrap_or(f64::NAN) * 100.0,
        1e-9,
        SOURCE,
    );

    let knet = read_file(&dir.join("test.knet"), &auto)?;
    check.absolute(
        "test.knet npts (59 s × 100 Hz)",
        5900.0,
        knet.npts() as f64,
        0.0,
        SOURCE,
    );
    check.absolute("test.knet dt (s)", 0.01, knet.dt, 1e-12, SOURCE);
    let motion = process(
        &knet,
        "knet",
        &ProcessingOptions::default(),
        "test.knet",
        "processing",
    )?;
    let c = &motion.components[0];
    check.absolute(
        "test.knet PGA after mean removal (gal)",
        4.383,
        peak(&c.acceleration, c.dt).value * 100.0,
        5e-4,
        SOURCE,
    );
    check.absolute(
        "test.knet component E-W on x (1 = yes)",
        1.0,
        f64::from(u8::from(c.axis == Some(Axis::X))),
        0.0,
        SOURCE,
    );

    let cosmos = read_file(&dir.join("hand_made.v2"), &auto)?;
    let a = &cosmos.components[0].acceleration;
    let reference = (0..400)
        .map(|i| {
            let t = i as f64 * 0.01;
            (100.0
                * (4.0 * std::f64::consts::PI * t).sin()
                * (std::f64::consts::PI * t / 4.0).sin())
            .abs()
        })
        .fold(0.0f64, f64::max);
    check.absolute("hand_made.v2 npts", 400.0, a.len() as f64, 0.0, SOURCE);
    check.absolute("hand_made.v2 dt (s)", 0.01, cosmos.dt, 1e-12, SOURCE);
    check.absolute(
        "hand_made.v2 PGA (cm/s²)",
        reference,
        peak(a, cosmos.dt).value * 100.0,
        5e-6,
        SOURCE,
    );
    check.absolute(
        "hand_made.v2 orientation 90° on x (1 = yes)",
        1.0,
        f64::from(u8::from(cosmos.components[0].axis == Some(Axis::X))),
        0.0,
        SOURCE,
    );
    Ok(check.finish())
}
