//! Whole runs of a case file as throughput rows (`case_run`): every thread count runs the
//! same steps, the records land in the history file, and a resumed stretch counts only
//! the steps it ran.

use std::path::{Path, PathBuf};

use dcfm_benchmarks::case_run::{run_case_timed, CaseRunConfig};
use dcfm_benchmarks::{history, BenchError};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("dcfm-case-run-test-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// W1's P pulse (cases/w01_p_pulse.toml) with another end time and a checkpoint every 50
/// steps, written into `dir`.
fn w01_case(dir: &Path, end: &str) -> PathBuf {
    let root = history::workspace_root();
    let text = std::fs::read_to_string(root.join("cases/w01_p_pulse.toml")).unwrap();
    assert!(text.contains("end = 0.14") && text.contains("[output]\n"));
    let text = text
        .replace("end = 0.14", &format!("end = {end}"))
        .replace("[output]\n", "[output]\ncheckpoint_every = 50\n");
    let path = dir.join("pulse.toml");
    std::fs::write(&path, text).unwrap();
    path
}

fn config(case: PathBuf, dir: &Path) -> CaseRunConfig {
    CaseRunConfig {
        name: Some("pulse".to_string()),
        history: Some(dir.join("history.jsonl")),
        scratch: dir.to_path_buf(),
        ..CaseRunConfig::new(case)
    }
}

#[test]
fn fresh_runs_on_each_thread_count_are_recorded() {
    let dir = scratch("fresh");
    let cfg = config(w01_case(&dir, "0.14"), &dir);
    let mut summaries = Vec::new();
    let records = run_case_timed(&cfg, |_, s| summaries.push(s.clone())).unwrap();
    assert_eq!(records.len(), 2);
    for (r, threads) in records.iter().zip([1, 2]) {
        assert_eq!(r.case, "run_pulse");
        assert_eq!(r.threads, threads);
        assert_eq!(r.elements, 200);
        assert_eq!(r.mode, "case");
        assert!(r.steps > 100 && r.steps_per_s > 0.0 && r.element_updates_per_s > 0.0);
    }
    assert_eq!(records[0].steps, records[1].steps);
    // The two runs end in the same state (results independent of the thread count).
    assert_eq!(
        summaries[0].energies.kinetic.to_bits(),
        summaries[1].energies.kinetic.to_bits()
    );
    let saved = history::read(&dir.join("history.jsonl")).unwrap();
    let key = |r: &dcfm_benchmarks::ThroughputRecord| (r.case.clone(), r.threads, r.steps);
    assert_eq!(
        saved.iter().map(key).collect::<Vec<_>>(),
        records.iter().map(key).collect::<Vec<_>>()
    );
    // The scratch folders are removed.
    let left: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| {
            e.file_name()
                .to_string_lossy()
                .starts_with("dcfm-case-run-")
        })
        .collect();
    assert!(left.is_empty(), "{left:?}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn a_resumed_stretch_counts_its_own_steps() {
    let dir = scratch("resume");
    // The first half, run as `dcfm run` would, leaves its checkpoint in `first`.
    let half = w01_case(&dir, "0.07");
    let first = dir.join("first");
    let case = dcfm::case::load_case(&half).unwrap();
    let options = dcfm_app::run::RunOptions {
        out: first.clone(),
        resume: false,
        resume_with_changed_case: false,
        allow_long: false,
        progress: false,
    };
    let done = dcfm_app::run::run_case(case, &options).unwrap();
    // The whole pulse from it: only the second half's steps are timed and counted.
    let whole = w01_case(&dir, "0.14");
    let cfg = CaseRunConfig {
        resume_from: Some(first.clone()),
        threads: vec![1],
        ..config(whole, &dir)
    };
    let mut summaries = Vec::new();
    let records = run_case_timed(&cfg, |_, s| summaries.push(s.clone())).unwrap();
    let s = &summaries[0];
    // From the first half's last checkpoint (every 50 steps, and at its end).
    let from = s.resumed_from_step.expect("resumed");
    assert!(from > 0 && from <= done.steps, "{from}");
    assert_eq!(records[0].steps, s.steps - from);
    assert!(s.steps > done.steps);
    assert_eq!(records[0].mode, "case_resumed");
    // The folder resumed from is left as it was.
    assert!(first.join("checkpoint.bin").is_file());
    // A folder without a checkpoint is refused by name.
    let cfg = CaseRunConfig {
        resume_from: Some(dir.join("nowhere")),
        ..cfg
    };
    match run_case_timed(&cfg, |_, _| {}) {
        Err(BenchError::Config(msg)) => assert!(msg.contains("checkpoint.bin"), "{msg}"),
        other => panic!("expected a configuration error, got {other:?}"),
    }
    let _ = std::fs::remove_dir_all(&dir);
}
