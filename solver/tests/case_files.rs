//! Case files: every example in cases/ loads; bad input of any kind gets an error naming
//! the file, the field path, the value and what was expected — never a panic (fuzzed);
//! a run stopped at a checkpoint and resumed ends bit-identical to an uninterrupted run.

use std::path::{Path, PathBuf};

use proptest::prelude::*;

use dcfm::case::{load_case, parse_case};
use dcfm::stage::run::{run_case, RunOptions};

fn cases_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../cases")
}

const SMALL: &str = r#"
title = "small"
[time]
end = 0.002
[output]
vtu_every = 5
nodes = [0]
elements = [0]
checkpoint_every = 4
[mesh]
[[mesh.blocks]]
name = "b"
origin = [0.0, 0.0, 0.0]
size = [2.0, 2.0, 2.0]
divisions = [2, 2, 2]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "b"
material = "rock"
[[boundary.fixed]]
set = "b.zmin"
dofs = "xyz"
[[loads.nodal]]
set = "b.zmax"
force = [1e5, 0.0, -1e5]
history = { type = "ramp", rate = 1000.0 }
[damping]
beta = 1e-6
"#;

fn err(text: &str) -> String {
    parse_case(text, "case.toml", Path::new("."))
        .unwrap_err()
        .to_string()
}

#[test]
fn every_example_case_loads() {
    let mut n = 0;
    for entry in std::fs::read_dir(cases_dir()).unwrap() {
        let p = entry.unwrap().path();
        if p.extension().is_some_and(|e| e == "toml") {
            load_case(&p).unwrap_or_else(|e| panic!("{}: {e}", p.display()));
            n += 1;
        }
    }
    assert!(n > 0);
}

#[test]
fn errors_name_file_field_value_and_expectation() {
    let e = err(&SMALL.replace("poisson = 0.25", "poisson = 0.7"));
    assert!(
        e.contains("case.toml: materials.rock.poisson = 0.7: must be in (-1, 0.5)"),
        "{e}"
    );
    let e = err(&SMALL.replace("dofs = \"xyz\"", "dofs = \"xq\""));
    assert!(
        e.contains("case.toml: boundary.fixed[0].dofs = \"xq\""),
        "{e}"
    );
    let e = err(&SMALL.replace("set = \"b.zmin\"", "set = \"nowhere\""));
    assert!(
        e.contains("boundary.fixed[0].set = \"nowhere\"") && e.contains("b.zmin"),
        "{e}"
    );
    let e = err(&SMALL.replace("end = 0.002", "end = 0.002\ndt = 1.0"));
    assert!(
        e.contains("exceeds the stable step") && e.contains("element"),
        "{e}"
    );
    let e = err(&SMALL.replace("material = \"rock\"", "material = \"granite\""));
    assert!(e.contains("regions[0].material = \"granite\""), "{e}");
    let e = err(&SMALL.replace("young = 20e9", "youngs = 20e9"));
    assert!(e.contains("case.toml") && e.contains("youngs"), "{e}");
    let e = err(&SMALL.replace("divisions = [2, 2, 2]", "divisions = [2, 0, 2]"));
    assert!(e.contains("mesh.blocks[0].divisions[1] = 0"), "{e}");
    let e = err(&SMALL.replace("nodes = [0]", "nodes = [99999]"));
    assert!(e.contains("output.nodes[0] = 99999"), "{e}");
    let e = err(&SMALL.replace("rate = 1000.0", "rate = nan"));
    assert!(e.contains("loads.nodal[0].history.rate = NaN"), "{e}");
}

#[test]
fn resumed_run_matches_uninterrupted_run() {
    let dir = std::env::temp_dir().join(format!("dcfm-resume-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let full_dir = dir.join("full");
    let opts = |out: &Path, resume| RunOptions {
        out: out.to_path_buf(),
        resume,
        progress: false,
    };
    let case = parse_case(SMALL, "small.toml", Path::new(".")).unwrap();
    let full = run_case(case, &opts(&full_dir, false)).unwrap();
    // Interrupted: run to a shorter end (its last checkpoint is at a step multiple of 4),
    // then resume with the full end time.
    let part_dir = dir.join("part");
    let short = SMALL.replace("end = 0.002", "end = 0.0012");
    run_case(
        parse_case(&short, "small.toml", Path::new(".")).unwrap(),
        &opts(&part_dir, false),
    )
    .unwrap();
    let resumed = run_case(
        parse_case(SMALL, "small.toml", Path::new(".")).unwrap(),
        &opts(&part_dir, true),
    )
    .unwrap();
    assert!(resumed.resumed_from_step.is_some());
    assert_eq!(full.steps, resumed.steps);
    assert_eq!(
        full.energies.internal.to_bits(),
        resumed.energies.internal.to_bits()
    );
    assert_eq!(
        full.energies.external.to_bits(),
        resumed.energies.external.to_bits()
    );
    let a = std::fs::read_to_string(full_dir.join("histories.csv")).unwrap();
    let b = std::fs::read_to_string(part_dir.join("histories.csv")).unwrap();
    assert_eq!(a, b, "histories differ after resume");
    let _ = std::fs::remove_dir_all(&dir);
}

const SLIDING: &str = r#"
title = "block sliding on a base"
[time]
end = 0.01
[output]
history_every = 2
checkpoint_every = 10
[mesh]
split = [["base", "block"]]
[[mesh.blocks]]
name = "base"
origin = [0.0, 0.0, 0.0]
size = [4.0, 2.0, 1.0]
divisions = [4, 2, 1]
[[mesh.blocks]]
name = "block"
origin = [1.0, 0.0, 1.0]
size = [1.0, 2.0, 1.0]
divisions = [1, 2, 1]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "base"
material = "rock"
[[regions]]
name = "block"
material = "rock"
[[boundary.fixed]]
set = "base"
dofs = "xyz"
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[[loads.nodal]]
set = "block"
force = [8000.0, 0.0, 0.0]
[[interfaces]]
name = "slip"
surface_a = "block-base"
surface_b = "base-block"
mu_s = 0.5
mu_d = 0.4
cohesion = 1e3
b_may_extend = true
"#;

#[test]
fn resumed_contact_run_matches_uninterrupted_run() {
    let dir = std::env::temp_dir().join(format!("dcfm-resume-contact-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let opts = |out: &Path, resume| RunOptions {
        out: out.to_path_buf(),
        resume,
        progress: false,
    };
    let full = run_case(
        parse_case(SLIDING, "s.toml", Path::new(".")).unwrap(),
        &opts(&dir.join("full"), false),
    )
    .unwrap();
    let short = SLIDING.replace("end = 0.01", "end = 0.006");
    run_case(
        parse_case(&short, "s.toml", Path::new(".")).unwrap(),
        &opts(&dir.join("part"), false),
    )
    .unwrap();
    let resumed = run_case(
        parse_case(SLIDING, "s.toml", Path::new(".")).unwrap(),
        &opts(&dir.join("part"), true),
    )
    .unwrap();
    assert!(resumed.resumed_from_step.is_some());
    assert!(
        full.energies.contact > 0.0,
        "the block must slide (friction work {})",
        full.energies.contact
    );
    let a = std::fs::read_to_string(dir.join("full/histories.csv")).unwrap();
    let b = std::fs::read_to_string(dir.join("part/histories.csv")).unwrap();
    assert_eq!(a, b, "histories differ after resuming a run with contact");
    let _ = std::fs::remove_dir_all(&dir);
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    /// Random edits of a valid case never panic: they parse, or fail with a message that
    /// names the file.
    #[test]
    fn fuzzed_case_never_panics(pos in 0usize..SMALL.len(), cut in 0usize..40, insert in "[ -~]{0,12}") {
        let mut text = SMALL.to_string();
        let pos = (0..=pos).rev().find(|&p| text.is_char_boundary(p)).unwrap_or(0);
        let end = (pos + cut).min(text.len());
        let end = (end..=text.len()).find(|&p| text.is_char_boundary(p)).unwrap_or(text.len());
        text.replace_range(pos..end, &insert);
        if let Err(e) = parse_case(&text, "fuzz.toml", Path::new(".")) {
            prop_assert!(e.to_string().contains("fuzz.toml") || e.to_string().starts_with("element") || e.to_string().starts_with("mesh"), "{}", e);
        }
    }

    /// Random numbers in every numeric field never panic.
    #[test]
    fn fuzzed_numbers_never_panic(young in prop_oneof![Just(f64::NAN), Just(f64::INFINITY), -1e12f64..1e12],
                                  poisson in -2.0f64..2.0, density in -10.0f64..1e4,
                                  size in -1.0f64..10.0, end in -1.0f64..0.01) {
        let text = SMALL
            .replace("young = 20e9", &format!("young = {young:?}"))
            .replace("poisson = 0.25", &format!("poisson = {poisson:?}"))
            .replace("density = 2700.0", &format!("density = {density:?}"))
            .replace("size = [2.0, 2.0, 2.0]", &format!("size = [{size:?}, 2.0, 2.0]"))
            .replace("end = 0.002", &format!("end = {end:?}"));
        let _ = parse_case(&text, "fuzz.toml", Path::new("."));
    }
}
