//! Runs of case files through the application's run driver: a run stopped at a checkpoint
//! and resumed ends bit-identical to an uninterrupted run.

use std::path::Path;
use std::sync::LazyLock;

mod common;

use dcfm::case::parse_case;
use dcfm_app::run::{run_case, RunOptions};

/// The 2 m block pushed on its top, lightly damped, with fields every 5 steps, node and
/// element 0 in the histories and a checkpoint every 4 steps.
static SMALL: LazyLock<String> = LazyLock::new(|| {
    common::elastic_block(
        "small",
        "0.002",
        2.0,
        &format!(
            "{}[damping]\nbeta = 1e-6\n[output]\nvtu_every = 5\nnodes = [0]\nelements = [0]\n\
             checkpoint_every = 4\n",
            common::TOP_RAMP
        ),
    )
});

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
    let case = parse_case(&SMALL, "small.toml", Path::new(".")).unwrap();
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
        parse_case(&SMALL, "small.toml", Path::new(".")).unwrap(),
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

static SLIDING: LazyLock<String> = LazyLock::new(|| common::sliding_block("0.01"));

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
        parse_case(&SLIDING, "s.toml", Path::new(".")).unwrap(),
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
        parse_case(&SLIDING, "s.toml", Path::new(".")).unwrap(),
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
