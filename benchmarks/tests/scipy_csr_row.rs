//! The scipy CSR leapfrog row (issue 11): with a working Python the runner times
//! `benchmarks/python/csr_leapfrog.py` on the same cube right after `cube{n}_full` and
//! records dcfm's rate over it; with no Python, a Python that fails or one that prints
//! something else, the row is skipped with the reason and no ratio exists. Correctness
//! only: nothing is asserted on how fast either is.

use std::path::PathBuf;

use dcfm::element::Integration;
use dcfm_benchmarks::scipy_csr::{self, PYTHON_ENV};
use dcfm_benchmarks::{history, run_with_notes, targets, RunConfig, ScipyBaseline};

fn tiny(scipy: ScipyBaseline) -> RunConfig {
    RunConfig {
        sizes: vec![3],
        integrations: vec![Integration::Full],
        threads: vec![1, 2],
        min_wall_s: 0.0,
        min_steps: 4,
        max_steps: 8,
        history: None,
        plastic_damage: Vec::new(),
        large_one_point_sizes: Vec::new(),
        boundaries: false,
        interface_sizes: Vec::new(),
        static_sizes: Vec::new(),
        scipy,
        ..RunConfig::quick()
    }
}

/// Run `config`, returning the records and the notes.
fn run_noting(config: &RunConfig) -> (Vec<dcfm_benchmarks::ThroughputRecord>, Vec<String>) {
    let mut notes = Vec::new();
    let records = run_with_notes(config, |_| {}, |n| notes.push(n.to_string())).expect("run");
    (records, notes)
}

/// The Python the runner would find ($DCFM_BENCH_PYTHON, else the workspace's .venv).
fn python() -> Option<PathBuf> {
    scipy_csr::find_python(
        &ScipyBaseline::Auto,
        std::env::var_os(PYTHON_ENV),
        &history::workspace_root(),
    )
    .ok()
}

#[test]
fn row_and_ratio_with_a_working_python() {
    let Some(python) = python() else {
        // Without the project's environment (`scripts/setup.sh` not run) there is nothing
        // to compare with; with it, a Python that cannot be found is a failure.
        let venv = history::workspace_root().join(".venv");
        assert!(
            !venv.exists(),
            "{} exists but no Python was found in it",
            venv.display()
        );
        eprintln!("no .venv and no {PYTHON_ENV}: scipy row not run (run scripts/setup.sh)");
        return;
    };
    let (records, notes) = run_noting(&tiny(ScipyBaseline::Python(python)));
    assert!(notes.is_empty(), "{notes:?}");
    let names: Vec<(&str, usize)> = records
        .iter()
        .map(|r| (r.case.as_str(), r.threads))
        .collect();
    assert_eq!(
        names,
        [("cube3_full", 1), ("cube3_full", 2), ("cube3_scipy_csr", 1)]
    );
    let s = &records[2];
    let info = s.scipy_csr.as_ref().expect("scipy data on the row");
    // The same cube: 27 elements, 4³ nodes; the base's 16 nodes condensed out.
    assert_eq!((s.elements, s.nodes), (27, 64));
    assert_eq!((info.dofs, info.dofs_total), (3 * 48, 3 * 64));
    // Every free DOF couples to the 3 DOFs of at most 27 nodes.
    assert!(
        info.nnz > info.dofs && info.nnz <= 81 * info.dofs,
        "{}",
        info.nnz
    );
    // The same time step as dcfm's case, and at least min_steps timed steps.
    assert_eq!(s.dt_s, records[0].dt_s);
    assert!((4..=8).contains(&s.steps), "{}", s.steps);
    assert!(s.element_updates_per_s > 0.0);
    let rate = s.steps as f64 * 27.0 / s.wall_s;
    assert!((s.element_updates_per_s - rate).abs() <= 1e-9 * rate);
    // The recorded ratios are dcfm's rates over scipy's, per thread count ...
    let keys: Vec<usize> = info.dcfm_over_scipy.keys().copied().collect();
    assert_eq!(keys, [1, 2]);
    for r in &records[..2] {
        let want = r.element_updates_per_s / s.element_updates_per_s;
        assert!((info.dcfm_over_scipy[&r.threads] - want).abs() <= 1e-12 * want);
    }
    // ... and targets::scipy_ratios finds the same from the records.
    let q = targets::scipy_ratios(&records);
    assert_eq!(q.len(), 2);
    for q in &q {
        assert_eq!(q.case, "cube3_full");
        assert!((q.ratio - info.dcfm_over_scipy[&q.threads]).abs() <= 1e-12 * q.ratio);
    }
    // The 2x target names the 40³ cube only; the CSR bytes are not checked as dcfm's.
    let checks = targets::check(&records);
    assert!(!checks.iter().any(|c| c.target.contains("scipy")));
    assert!(!checks
        .iter()
        .any(|c| c.target.starts_with("cube3_scipy_csr")));
    // The record round-trips through JSON with its scipy data.
    let back: dcfm_benchmarks::ThroughputRecord = serde_json::from_str(&s.to_json_line()).unwrap();
    assert_eq!(back.scipy_csr.as_ref().unwrap().dcfm_over_scipy.len(), 2);
    assert_eq!(back.scipy_csr.unwrap().nnz, info.nnz);
}

/// A Python that cannot be started, one that fails and one that prints something else:
/// each is a "skipped" note naming why, the dcfm rows are there, and no ratio is.
#[cfg(unix)]
#[test]
fn broken_python_skips_the_row_with_the_reason() {
    for (python, why) in [
        (
            "/nonexistent/python3",
            "could not start /nonexistent/python3",
        ),
        ("/bin/false", "failed"),
        ("/bin/echo", "is not its JSON record"),
    ] {
        if !std::path::Path::new(python).exists() && python != "/nonexistent/python3" {
            continue;
        }
        let (records, notes) = run_noting(&tiny(ScipyBaseline::Python(python.into())));
        let names: Vec<&str> = records.iter().map(|r| r.case.as_str()).collect();
        assert_eq!(names, ["cube3_full", "cube3_full"], "{python}");
        assert_eq!(notes.len(), 1, "{python}: {notes:?}");
        assert!(
            notes[0].starts_with("cube3_scipy_csr skipped:") && notes[0].contains(why),
            "{python}: {}",
            notes[0]
        );
        assert!(targets::scipy_ratios(&records).is_empty());
    }
}

/// Off: no row and no note; and the rows come only with the elastic fully integrated cube.
#[test]
fn off_or_other_cases_give_no_row() {
    let (records, notes) = run_noting(&tiny(ScipyBaseline::Off));
    assert_eq!(records.len(), 2);
    assert!(notes.is_empty());
    let one_point = RunConfig {
        integrations: vec![Integration::OnePoint],
        threads: vec![1],
        ..tiny(ScipyBaseline::Python("/nonexistent/python3".into()))
    };
    let (records, notes) = run_noting(&one_point);
    assert_eq!(records.len(), 1);
    assert!(notes.is_empty(), "{notes:?}");
}
