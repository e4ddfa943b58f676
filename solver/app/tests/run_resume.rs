//! Runs of case files through the application's run driver: a run stopped at a checkpoint
//! and resumed ends bit-identical to an uninterrupted run.

use std::path::Path;

use dcfm::case::parse_case;
use dcfm_app::run::{run_case, RunOptions};

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

#[test]
fn resumed_run_matches_uninterrupted_run() {
    let dir = std::env::temp_dir().join(format!("dcfm-resume-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let full_dir = dir.join("full");
    let opts = |out: &Path, resume| RunOptions {
        out: out.to_path_buf(),
        resume,
        progress: false,
        ..Default::default()
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
        ..Default::default()
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
