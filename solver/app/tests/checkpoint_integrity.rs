//! Trustworthy restarts (issue 13.5): a checkpoint carries a checksum and the hashes of
//! the case and mesh it was written for. A corrupted checkpoint, one of an older format,
//! or one of a case changed between the kill and the resume is refused, naming what is
//! wrong, unless the user asks to continue with the changed case.

use std::path::{Path, PathBuf};
use std::sync::LazyLock;

mod common;

use dcfm::case::parse_case;
use dcfm_app::run::{run_case, RunOptions, RunSummary};

/// A block on a base with a frictional interface (μs = 0.5), checkpoints every 10 steps.
static SLIDING: LazyLock<String> = LazyLock::new(|| common::sliding_block("0.004"));

/// The end of the "killed" first part: its last checkpoint is at step 10 or 20.
const SHORT_END: &str = "end = 0.0025";

fn dir(name: &str) -> PathBuf {
    common::fresh_dir("ckpt", name)
}

fn opts(out: &Path, resume: bool, changed: bool) -> RunOptions {
    RunOptions {
        resume,
        resume_with_changed_case: changed,
        ..common::options(out)
    }
}

fn run(text: &str, o: &RunOptions) -> dcfm::Result<RunSummary> {
    common::run_text("sliding.toml", text, o)
}

/// Run the first part of SLIDING into `out`, as if killed after its last checkpoint.
fn first_part(out: &Path) {
    run(
        &SLIDING.replace("end = 0.004", SHORT_END),
        &opts(out, false, false),
    )
    .unwrap();
    assert!(out.join("checkpoint.bin").exists());
}

#[test]
fn a_flipped_bit_is_refused_naming_the_checksum() {
    let out = dir("flip");
    first_part(&out);
    let path = out.join("checkpoint.bin");
    let mut bytes = std::fs::read(&path).unwrap();
    // A bit in the middle of the state (a displacement or an integration-point value).
    let k = bytes.len() / 2;
    bytes[k] ^= 0x10;
    std::fs::write(&path, &bytes).unwrap();
    let e = run(&SLIDING, &opts(&out, true, false))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("checkpoint.bin") && e.contains("checksum mismatch"),
        "{e}"
    );
    // Not even the flag that accepts a changed case takes a corrupted file.
    let e = run(&SLIDING, &opts(&out, true, true))
        .unwrap_err()
        .to_string();
    assert!(e.contains("checksum mismatch"), "{e}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_changed_friction_is_refused_naming_the_field_unless_asked() {
    let out = dir("mu");
    first_part(&out);
    let changed = SLIDING.replace("mu_s = 0.5", "mu_s = 0.45");
    let e = run(&changed, &opts(&out, true, false))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("checkpoint.bin")
            && e.contains("interfaces[0].mu_s changed")
            && e.contains("--resume-with-changed-case")
            && !e.contains("mesh"),
        "{e}"
    );
    // Asked to: the run resumes and says what changed, in summary.json too.
    let s = run(&changed, &opts(&out, true, true)).unwrap();
    assert!(s.resumed_from_step.is_some_and(|k| k > 0));
    assert_eq!(
        s.resumed_with_changes,
        vec!["case field interfaces[0].mu_s changed".to_string()]
    );
    let summary = std::fs::read_to_string(out.join("summary.json")).unwrap();
    assert!(summary.contains("interfaces[0].mu_s changed"), "{summary}");
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_case_with_only_its_end_time_and_title_changed_resumes() {
    let out = dir("same");
    first_part(&out);
    // Comments and number spelling do not count either.
    let text = SLIDING
        .replace("block sliding on a base", "the longer run")
        .replace("cohesion = 1e3", "cohesion = 1000.0 # Pa");
    let s = run(&text, &opts(&out, true, false)).unwrap();
    assert!(s.resumed_from_step.is_some_and(|k| k > 0));
    assert!(s.resumed_with_changes.is_empty());
    let _ = std::fs::remove_dir_all(&out);
}

/// The 2×2×2 cube of the Gmsh reader's fixtures: regions rock and lining, face set base.
fn gmsh_case(end: &str) -> String {
    format!(
        r#"
title = "gmsh cube"
[time]
end = {end}
[output]
checkpoint_every = 4
[mesh]
gmsh = "cube.msh"
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "rock"
material = "rock"
[[regions]]
name = "lining"
material = "rock"
[[boundary.fixed]]
set = "base"
dofs = "xyz"
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
"#
    )
}

#[test]
fn an_edited_mesh_file_is_refused_naming_the_mesh() {
    let root = dir("mesh");
    let out = root.join("out");
    std::fs::create_dir_all(&root).unwrap();
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("../tests/fixtures/cube_2x2x2.msh");
    let msh = std::fs::read_to_string(fixture).unwrap();
    std::fs::write(root.join("cube.msh"), &msh).unwrap();
    let go = |end: &str, resume: bool| {
        run_case(
            parse_case(&gmsh_case(end), "cube.toml", &root).unwrap(),
            &opts(&out, resume, false),
        )
    };
    go("0.0015", false).unwrap();
    // The case text is the same; one node of the mesh file moved by 0.1 m.
    assert_eq!(msh.matches("\n2.0 2.0 2.0\n").count(), 1);
    std::fs::write(
        root.join("cube.msh"),
        msh.replace("\n2.0 2.0 2.0\n", "\n2.0 2.0 2.1\n"),
    )
    .unwrap();
    let e = go("0.003", true).unwrap_err().to_string();
    assert!(
        e.contains("the mesh changed") && !e.contains("case field"),
        "{e}"
    );
    // Restored, the file resumes.
    std::fs::write(root.join("cube.msh"), &msh).unwrap();
    assert!(go("0.003", true).unwrap().resumed_from_step.is_some());
    let _ = std::fs::remove_dir_all(&root);
}

#[test]
fn a_checkpoint_of_the_older_format_is_refused_naming_it() {
    let out = dir("old");
    first_part(&out);
    let path = out.join("checkpoint.bin");
    let mut bytes = b"DCFMCKP4".to_vec();
    bytes.extend(vec![0u8; 256]);
    std::fs::write(&path, bytes).unwrap();
    let e = run(&SLIDING, &opts(&out, true, true))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("older dcfm") && e.contains("DCFMCKP4") && e.contains("without --resume"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_resume_removes_the_temporary_files_of_a_killed_checkpoint_write() {
    let out = dir("tmp");
    first_part(&out);
    // What a process killed while writing its checkpoint leaves (another pid).
    let killed = out.join(".checkpoint.bin.4000000.3.tmp");
    std::fs::write(&killed, b"half a checkpoint").unwrap();
    run(&SLIDING, &opts(&out, true, false)).unwrap();
    assert!(!killed.exists(), "temporary file of a killed write kept");
    let _ = std::fs::remove_dir_all(&out);
}

/// The cube of SLIDING's base shaken at its base by a one-column record file `acc.txt`.
fn shaken_case(end: &str) -> String {
    format!(
        r#"
title = "shaken cube"
[time]
end = {end}
[output]
checkpoint_every = 4
[mesh]
[[mesh.blocks]]
name = "b"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 1.0]
divisions = [2, 2, 2]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "b"
material = "rock"
[motions.rec]
file = "acc.txt"
units = "m/s2"
dt = 0.0005
[[boundary.prescribed]]
set = "b.zmin"
dof = "x"
kind = "acceleration"
history = {{ type = "motion", motion = "rec", component = "a" }}
"#
    )
}

#[test]
fn an_edited_motion_record_is_refused_naming_the_motion() {
    let root = dir("motion");
    let out = root.join("out");
    std::fs::create_dir_all(&root).unwrap();
    let record = "0.0\n0.5\n1.0\n0.5\n0.0\n-0.5\n-1.0\n-0.5\n0.0\n";
    std::fs::write(root.join("acc.txt"), record).unwrap();
    let go = |end: &str, resume: bool| {
        run_case(
            parse_case(&shaken_case(end), "shaken.toml", &root).unwrap(),
            &opts(&out, resume, false),
        )
    };
    go("0.0015", false).unwrap();
    // Same path, same case text; one sample of the record changed.
    std::fs::write(root.join("acc.txt"), record.replace("\n1.0\n", "\n1.2\n")).unwrap();
    let e = go("0.003", true).unwrap_err().to_string();
    assert!(
        e.contains("the record of ground motion rec changed")
            && !e.contains("case field")
            && !e.contains("mesh"),
        "{e}"
    );
    // Restored, the file resumes.
    std::fs::write(root.join("acc.txt"), record).unwrap();
    assert!(go("0.003", true).unwrap().resumed_from_step.is_some());
    let _ = std::fs::remove_dir_all(&root);
}
