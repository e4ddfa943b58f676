//! Ground motions (issue 8): read a 3 × 60 000-sample record from a text file, process it
//! (mean baseline, 1 s tapers, zero-phase Butterworth 0.1–25 Hz order 4 with pads, end
//! correction, integration) and compute its 5 % response spectrum at 200 periods for the
//! three components. Target: ≤ 0.2 s on the 2-core machine. Also each part alone.

use std::fmt::Write as _;
use std::hint::black_box;
use std::path::PathBuf;

use criterion::{criterion_group, criterion_main, Criterion};
use dcfm::motion::measures::response_spectrum;
use dcfm::motion::measures::spectrum::log_periods;
use dcfm::motion::{
    process, read_file, AccelUnits, GroundMotion, MotionSpec, ProcessingOptions, ReadOptions,
    Record, SyntheticSpec,
};

/// A 60 s, 3-component record at dt = 0.001 s (60 001 samples per component) written as
/// a four-column text file (t, EW, NS, UD in g), from the synthetic generator.
fn record_file() -> PathBuf {
    let spec = MotionSpec {
        synthetic: Some(SyntheticSpec {
            preset: Some("wolong".into()),
            dt: Some(0.001),
            ..SyntheticSpec::default()
        }),
        ..MotionSpec::default()
    };
    let m = spec
        .load("bench", "bench", std::path::Path::new(""))
        .expect("preset");
    let mut text = String::from("t,EW,NS,UD\n");
    for i in 0..m.npts() {
        let _ = write!(text, "{:.3}", i as f64 * m.dt);
        for c in &m.components {
            let _ = write!(text, ",{:.7e}", c.acceleration[i] / 9.80665);
        }
        text.push('\n');
    }
    let path = std::env::temp_dir().join(format!("dcfm-bench-motion-{}.csv", std::process::id()));
    std::fs::write(&path, text).expect("temp file");
    path
}

fn options() -> ProcessingOptions {
    ProcessingOptions {
        taper: 1.0,
        highpass: Some(0.1),
        lowpass: Some(25.0),
        zero_end: true,
        ..ProcessingOptions::default()
    }
}

fn read(path: &std::path::Path) -> Record {
    let opts = ReadOptions {
        units: Some(AccelUnits::G),
        ..ReadOptions::default()
    };
    read_file(path, &opts).expect("record")
}

fn spectra(m: &GroundMotion, periods: &[f64]) -> f64 {
    m.components
        .iter()
        .map(|c| {
            response_spectrum(&c.acceleration, c.dt, periods, 0.05)
                .iter()
                .map(|p| p.sa)
                .sum::<f64>()
        })
        .sum()
}

fn motion(c: &mut Criterion) {
    let path = record_file();
    let periods = log_periods(0.01, 10.0, 200);
    let rec = read(&path);
    assert_eq!((rec.npts(), rec.components.len()), (60_001, 3));
    let mut g = c.benchmark_group("motion");
    g.sample_size(10);
    g.bench_function(
        "read + process + spectrum (3 × 60 000 samples, 200 periods)",
        |b| {
            b.iter(|| {
                let r = read(&path);
                let m =
                    process(&r, "bench", &options(), "bench", "processing").expect("processing");
                black_box(spectra(&m, &periods))
            })
        },
    );
    g.bench_function("read 3 × 60 000 samples (CSV)", |b| {
        b.iter(|| black_box(read(&path)))
    });
    g.bench_function("process 3 × 60 000 samples", |b| {
        b.iter(|| {
            black_box(
                process(&rec, "bench", &options(), "bench", "processing").expect("processing"),
            )
        })
    });
    let m = process(&rec, "bench", &options(), "bench", "processing").expect("processing");
    g.bench_function("response spectra 3 × 200 periods", |b| {
        b.iter(|| black_box(spectra(&m, &periods)))
    });
    g.finish();
    let _ = std::fs::remove_file(&path);
}

criterion_group!(benches, motion);
criterion_main!(benches);
