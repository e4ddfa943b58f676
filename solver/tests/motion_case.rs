//! Motions as case items: `[motions.NAME]` resolved into time functions at case build,
//! the example case loads, and bad references are errors naming the field.

use std::path::Path;

use dcfm::case::{load_case, parse_case};
use dcfm::motion::{Axis, Format};

const BASE: &str = r#"
[time]
end = 0.01
[mesh]
[[mesh.blocks]]
name = "b"
origin = [0.0, 0.0, 0.0]
size = [2.0, 2.0, 2.0]
divisions = [1, 1, 1]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "b"
material = "rock"
"#;

fn case(extra: &str) -> String {
    format!("{BASE}{extra}")
}

const SYNTHETIC: &str = r#"
[motions.quake]
synthetic = { preset = "wolong", seed = 3, duration = 8.0, phases = [{ rise = 0.2, start = 1.0, end = 4.0, decay = 1.0 }], fade = 1.0, components = { x = { pga = 2.0, ground_frequency = 2.0, ground_damping = 0.6, highpass_frequency = 0.5, highpass_damping = 0.7, peak_time = 2.0 } } }
[[boundary.prescribed]]
set = "b.zmin"
dof = "x"
kind = "acceleration"
history = { type = "motion", motion = "quake", component = "x", scale = 2.0, start = 0.5 }
"#;

#[test]
fn a_motion_time_function_follows_the_motion() {
    let c = parse_case(&case(SYNTHETIC), "m.toml", Path::new(".")).unwrap();
    let m = &c.motions["quake"];
    assert_eq!((m.format, m.components.len()), (Format::Synthetic, 1));
    let comp = m.component(Axis::X).unwrap();
    let peak = comp.acceleration.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    assert!((peak - 2.0).abs() < 1e-12);
    let h = &c.model.constraints.prescribed[0].history;
    for t in [0.0, 0.3, 0.51, 1.234, 2.5, 7.0, 9.0, 20.0] {
        let k = comp.at(t - 0.5);
        assert!((h.value(t) - 2.0 * k.a).abs() < 1e-12, "t {t}");
        // ∫₀ᵗ a = v (the motion starts at rest at t = start).
        assert!((h.integral(t) - 2.0 * k.v).abs() < 1e-12, "t {t}");
    }
    assert_eq!(h.value(0.2), 0.0);
}

#[test]
fn the_example_case_loads_with_its_preset() {
    let c =
        load_case(&Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases/motion_synthetic.toml"))
            .unwrap();
    let m = &c.motions["wolong"];
    assert_eq!(m.npts(), 12001);
    assert_eq!(c.model.constraints.prescribed.len(), 3);
    // component = "UD" (the record's own name) is the z component.
    let z = m.component(Axis::Z).unwrap();
    assert_eq!(
        c.model.constraints.prescribed[2].history.value(13.0),
        z.at(13.0).a
    );
}

#[test]
fn bad_references_name_the_field_and_the_choices() {
    let e = parse_case(
        &case(&SYNTHETIC.replace("motion = \"quake\"", "motion = \"kobe\"")),
        "m.toml",
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        e,
        "m.toml: boundary.prescribed[0].history.motion = \"kobe\": a motion defined in [motions.NAME]: quake"
    );
    let e = parse_case(
        &case(&SYNTHETIC.replace("component = \"x\"", "component = \"NS\"")),
        "m.toml",
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("m.toml: boundary.prescribed[0].history.component = \"NS\": a component of motion \"quake\": x"), "{e}");
    let e = parse_case(
        &case("[motions.q]\nfile = \"nowhere.at2\"\n"),
        "m.toml",
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("nowhere.at2"), "{e}");
    let e = parse_case(
        &case("[motions.q]\nsynthetic = { preset = \"kobe\" }\n"),
        "m.toml",
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        e,
        "m.toml: motions.q.synthetic.preset = \"kobe\": a known preset: wolong"
    );
    let e = parse_case(
        &case("[motions.q]\nsynthetic = { preset = \"wolong\" }\n[motions.q.processing]\nlowpass = 150.0\n"),
        "m.toml",
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert!(e.starts_with("m.toml: motions.q.processing.lowpass = 150: a corner below the Nyquist frequency 100 Hz"), "{e}");
    let e = parse_case(
        &case("[motions.q]\nfile = \"a\"\nsynthetic = { preset = \"wolong\" }\n"),
        "m.toml",
        Path::new("."),
    )
    .unwrap_err()
    .to_string();
    assert_eq!(
        e,
        "m.toml: motions.q = 2 sources: exactly one of file, files, synthetic"
    );
}

#[test]
fn a_record_file_motion_from_the_fixtures() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../verification/fixtures/motions");
    let text = case(
        r#"
[motions.kobe]
file = "NIS090.AT2"
[motions.kobe.processing]
window = [2.0, 30.0]
taper = 1.0
highpass = 0.1
lowpass = 25.0
zero_end = true
resample_dt = 0.005
[[boundary.prescribed]]
set = "b.zmin"
dof = "x"
kind = "velocity"
history = { type = "motion", motion = "kobe", component = "090", quantity = "velocity" }
"#,
    );
    let c = parse_case(&text, "k.toml", &dir).unwrap();
    let m = &c.motions["kobe"];
    assert_eq!(m.dt, 0.005);
    assert_eq!(m.npts(), 5601);
    let x = m.component(Axis::X).unwrap();
    assert!(
        x.velocity.last().unwrap().abs() < 1e-12 && x.displacement.last().unwrap().abs() < 1e-12
    );
    // Every step is in the provenance: read, window, baseline, taper, band-pass,
    // resampling, end correction, integration.
    let p = m.provenance.join("\n");
    for word in [
        "read",
        "window 2–30 s",
        "baseline: mean",
        "taper",
        "Butterworth order 4",
        "resampled",
        "end correction",
        "integrated",
    ] {
        assert!(p.contains(word), "{word} missing from\n{p}");
    }
}
