//! Case files: every example in cases/ loads; bad input of any kind gets an error naming
//! the file, the field path, the value and what was expected — never a panic (fuzzed).
//! (Runs and resumes are tested with the run driver in solver/app/tests.)

use std::path::{Path, PathBuf};

use proptest::prelude::*;

use dcfm::case::{load_case, parse_case};

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
    let e = err(&SMALL.replace("end = 0.002", "end = 0.002\nstable_step = \"global\""));
    assert!(
        e.contains("case.toml: time.stable_step = \"global\"") && e.contains("\"shared_mass\""),
        "{e}"
    );
    let e = err(&SMALL.replace(
        "end = 0.002",
        "end = 0.002\nstable_step = \"shared_mass\"\nsubcycling = { max_level = 2 }",
    ));
    assert!(
        e.contains("time.stable_step = \"shared_mass\"") && e.contains("time.subcycling"),
        "{e}"
    );
    // Accepted, and never a smaller step than the elements' own bound.
    let own = parse_case(SMALL, "case.toml", Path::new(".")).unwrap();
    let shared = parse_case(
        &SMALL.replace("end = 0.002", "end = 0.002\nstable_step = \"shared_mass\""),
        "case.toml",
        Path::new("."),
    )
    .unwrap();
    assert!(shared.dt >= own.dt, "{} < {}", shared.dt, own.dt);
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
    // Reinforcement mats: a good one loads; a bad cover, an unknown face set and a cover
    // that puts the bars outside the mesh (deeper than the 2 m block) are named.
    let mat = |face_set: &str, cover: &str| {
        format!(
            "{SMALL}\n[[anchors.mats]]\nname = \"m\"\nface_set = \"{face_set}\"\ncover = {cover}\n\
             spacing = 0.25\ndiameter = 0.02\nyield_stress = 400e6\n"
        )
    };
    parse_case(&mat("b.zmax", "0.05"), "case.toml", Path::new(".")).unwrap();
    let e = err(&mat("b.zmax", "-0.05"));
    assert!(
        e.contains("case.toml: anchors.mats[0].cover = -0.05: must be > 0 (m)"),
        "{e}"
    );
    let e = err(&mat("b.top", "0.05"));
    assert!(
        e.contains("anchors.mats[0].face_set = b.top") && e.contains("b.zmax"),
        "{e}"
    );
    let e = err(&mat("b.zmax", "2.5"));
    assert!(
        e.contains("anchors.mats[0]") && e.contains("cover 2.5 m") && e.contains("leaves the mesh"),
        "{e}"
    );
}

/// A pattern with `depth`: every bar runs along the inward normal of the 2 m block's top
/// (z = 2) from `depth` to `depth + length` below it (a tie between a wall's two mats);
/// without it from the face. A negative or non-finite depth is named.
#[test]
fn pattern_bars_start_at_their_depth_below_the_face() {
    let pattern = |depth: &str| {
        format!(
            "{SMALL}\n[[anchors.patterns]]\nname = \"t\"\nface_set = \"b.zmax\"\nlength = 0.5\n\
             spacing = 0.5\ndiameter = 0.012\nyield_stress = 300e6\n{depth}"
        )
    };
    for (line, top, bottom) in [("depth = 0.3\n", 1.7, 1.2), ("", 2.0, 1.5)] {
        let case = parse_case(&pattern(line), "case.toml", Path::new(".")).unwrap();
        let lines = case.model.anchors.as_ref().unwrap().lines();
        assert!(!lines.lines.is_empty());
        for [a, b] in &lines.lines {
            let (za, zb) = (lines.points[*a as usize][2], lines.points[*b as usize][2]);
            let (hi, lo) = (za.max(zb), za.min(zb));
            assert!(
                hi <= top + 1e-12 && lo >= bottom - 1e-12,
                "{line:?}: {za} → {zb}"
            );
            assert!((lines.points[*a as usize][0] - lines.points[*b as usize][0]).abs() < 1e-12);
        }
        let z = |k: usize| lines.points[k][2];
        let zs: Vec<f64> = (0..lines.points.len()).map(z).collect();
        let (max, min) = zs
            .iter()
            .fold((f64::MIN, f64::MAX), |(m, n), &v| (m.max(v), n.min(v)));
        assert!(
            (max - top).abs() < 1e-12 && (min - bottom).abs() < 1e-12,
            "{line:?}: {min} … {max}"
        );
    }
    for bad in ["-0.1", "nan"] {
        let e = err(&pattern(&format!("depth = {bad}\n")));
        assert!(
            e.contains("case.toml: anchors.patterns[0].depth") && e.contains("a depth ≥ 0 (m)"),
            "{e}"
        );
    }
}

/// `[output.frames]` intervals are written with the compact frames, every `vtu_every`
/// (5) steps: an interval that is not a multiple of it is rejected, naming the field, the
/// value and the expected multiple; a multiple and 0 load.
#[test]
fn frame_intervals_must_be_multiples_of_vtu_every() {
    let frames = |extra: &str| format!("{SMALL}\n[output.frames]\nregions = [\"b\"]\n{extra}\n");
    for good in [
        "anchors_every = 10",
        "anchors_every = 0",
        "full_every = 15\nanchors_every = 5",
    ] {
        parse_case(&frames(good), "case.toml", Path::new("."))
            .unwrap_or_else(|e| panic!("{good}: {e}"));
    }
    let e = err(&frames("anchors_every = 7"));
    assert!(
        e.contains("case.toml: output.frames.anchors_every = 7")
            && e.contains("a multiple of output.vtu_every = 5"),
        "{e}"
    );
    let e = err(&frames("full_every = 12"));
    assert!(
        e.contains("case.toml: output.frames.full_every = 12")
            && e.contains("a multiple of output.vtu_every = 5"),
        "{e}"
    );
    let e = err(&frames("anchors_every = 10").replace("vtu_every = 5", "vtu_every = 0"));
    assert!(
        e.contains("output.frames.anchors_every = 10") && e.contains("output.vtu_every = 0"),
        "{e}"
    );
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
