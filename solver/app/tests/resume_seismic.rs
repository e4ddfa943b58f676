//! A seismic run — static stage, viscous-spring base with the input, free-field walls and
//! edge columns, a buried top coupled to the free field through the overburden — stopped
//! at a checkpoint and resumed ends bit-identical to an uninterrupted run: the checkpoint
//! carries the free-field grids, the springs' static reference and the static result.

use std::path::Path;

use dcfm::case::parse_case;
use dcfm_app::run::{run_case, RunOptions};

const CASE: &str = r#"
title = "seismic resume"
[time]
end = 0.08
[output]
vtu_every = 20
nodes = [0, 40]
checkpoint_every = 10
[mesh]
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, 0.0]
size = [20.0, 20.0, 20.0]
divisions = [2, 2, 4]
[materials.rock]
model = "elastic"
young = 10e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "rock"
material = "rock"
integration = "full"
damping = { alpha = 0.5, beta = 1e-4 }
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[[boundary.absorbing]]
set = "outer.zmin"
kind = "viscous_spring"
input = true
[boundary.free_field]
sides = ["outer.xmin", "outer.xmax", "outer.ymin", "outer.ymax"]
top = "outer.zmax"
[seismic]
quantity = "acceleration"
definition = "outcrop"
x = { type = "sine", amplitude = 2.0, frequency = 8.0 }
z = { type = "ricker", amplitude = 1.0, frequency = 12.0 }
[[seismic.overburden]]
thickness = 20.0
material = "rock"
[static]
solver = "direct"
[[static.fixed]]
set = "outer.zmin"
dofs = "xyz"
[[static.fixed]]
set = "outer.xmin"
dofs = "x"
[[static.fixed]]
set = "outer.xmax"
dofs = "x"
[[static.fixed]]
set = "outer.ymin"
dofs = "y"
[[static.fixed]]
set = "outer.ymax"
dofs = "y"
[[static.loads]]
set = "outer.zmax"
pressure = 5.3e5
[static.in_situ]
method = "gravity"
"#;

#[test]
fn resumed_seismic_run_matches_uninterrupted_run() {
    let dir = std::env::temp_dir().join(format!("dcfm-resume-seismic-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let opts = |out: &Path, resume| RunOptions {
        out: out.to_path_buf(),
        resume,
        progress: false,
        ..Default::default()
    };
    let text = CASE.to_string();
    let full_dir = dir.join("full");
    let full = run_case(
        parse_case(&text, "seismic.toml", Path::new(".")).unwrap(),
        &opts(&full_dir, false),
    )
    .unwrap();
    let part_dir = dir.join("part");
    let short = text.replace("end = 0.08", "end = 0.045");
    run_case(
        parse_case(&short, "seismic.toml", Path::new(".")).unwrap(),
        &opts(&part_dir, false),
    )
    .unwrap();
    let resumed = run_case(
        parse_case(&text, "seismic.toml", Path::new(".")).unwrap(),
        &opts(&part_dir, true),
    )
    .unwrap();
    assert!(resumed.resumed_from_step.is_some());
    assert_eq!(full.steps, resumed.steps);
    for (a, b) in [
        (full.energies.input, resumed.energies.input),
        (full.energies.boundary, resumed.energies.boundary),
        (full.energies.internal, resumed.energies.internal),
    ] {
        assert_eq!(a.to_bits(), b.to_bits(), "{a} vs {b}");
    }
    let a = std::fs::read_to_string(full_dir.join("histories.csv")).unwrap();
    let b = std::fs::read_to_string(part_dir.join("histories.csv")).unwrap();
    assert_eq!(a, b, "histories differ after resume");
    // The input did move the model (the test is not about a model at rest).
    assert!(full.energies.input.abs() > 0.0);
    let _ = std::fs::remove_dir_all(&dir);
}
