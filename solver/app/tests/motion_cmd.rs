//! `dcfm motion`: the summary and the files it writes, from a real record and from the
//! synthetic preset; bad flags are errors naming the flag.

use std::path::PathBuf;

use clap::Parser;

use dcfm_app::motion_cmd::{run, MotionArgs};

#[derive(Parser)]
struct Cli {
    #[command(flatten)]
    args: MotionArgs,
}

fn args(list: &[&str]) -> MotionArgs {
    Cli::parse_from(std::iter::once("dcfm-motion").chain(list.iter().copied())).args
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("dcfm-motion-cmd-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    d
}

#[test]
fn at2_record_summary_and_files() {
    let record = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../verification/fixtures/motions/NIS090.AT2");
    let out = scratch("at2");
    let lines = run(&args(&[
        record.to_str().unwrap(),
        "--highpass",
        "0.1",
        "--periods",
        "20",
        "--out",
        out.to_str().unwrap(),
        "--plot",
        "svg",
    ]))
    .unwrap();
    let text = lines.join("\n");
    assert!(
        text.contains("format     at2  station \"NISHI-AKASHI\""),
        "{text}"
    );
    assert!(text.contains("samples    4096 × dt 0.01 s"), "{text}");
    assert!(
        text.contains("band-pass: Butterworth order 4, high-pass 0.1 Hz"),
        "{text}"
    );
    let spectrum = std::fs::read_to_string(out.join("spectrum.csv")).unwrap();
    assert!(spectrum.starts_with("# dcfm motion: elastic response spectrum"));
    assert!(spectrum.contains("# band-pass: Butterworth"));
    assert_eq!(spectrum.lines().filter(|l| !l.starts_with('#')).count(), 21);
    let motion = std::fs::read_to_string(out.join("motion.csv")).unwrap();
    assert!(motion.contains("\nt,a_x,v_x,u_x\n"));
    assert_eq!(motion.lines().filter(|l| !l.starts_with('#')).count(), 4097);
    for f in ["husid.csv", "fourier.csv", "motion.svg"] {
        assert!(out.join(f).is_file(), "{f}");
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn synthetic_preset_summary() {
    let out = scratch("syn");
    let lines = run(&args(&[
        "--synthetic",
        "wolong",
        "--periods",
        "5",
        "--out",
        out.to_str().unwrap(),
    ]))
    .unwrap();
    let ew = lines.iter().find(|l| l.starts_with("EW ")).unwrap();
    // PGA 9.5770 m/s² at 13.010 s.
    assert!(ew.contains("9.5770") && ew.contains("13.010"), "{ew}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn bad_flags_are_errors_naming_them() {
    let e = run(&args(&["x.AT2", "--plot", "png"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("--plot = png"), "{e}");
    let e = run(&args(&["--synthetic", "wolong", "--lowpass", "150"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("lowpass = 150") && e.contains("Nyquist"), "{e}");
    let e = run(&args(&[])).unwrap_err().to_string();
    assert!(e.contains("FILE"), "{e}");
    let e = run(&args(&["no/such/file.txt", "--units", "g", "--dt", "0.01"]))
        .unwrap_err()
        .to_string();
    assert!(e.contains("no/such/file.txt"), "{e}");
}
