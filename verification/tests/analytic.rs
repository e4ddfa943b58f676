//! Analytic verification cases: each registered case must pass every checked quantity.
//! Requirement: the explicit core reproduces the closed-form references of
//! docs/verification_references.md within their stated tolerances.

use dcfm_verification::cases;
use dcfm_verification::record::failures;

fn run_case(id: &str) {
    let case = cases::all()
        .into_iter()
        .find(|c| c.info.id == id)
        .expect("registered case");
    let rows = (case.run)().unwrap_or_else(|e| panic!("{id}: {e}")).rows;
    assert!(!rows.is_empty(), "{id} checked nothing");
    let failed = failures(&rows);
    assert!(failed.is_empty(), "{id}:\n{}", failed.join("\n"));
}

#[test]
fn w01_wave_pulses() {
    run_case("W1");
}

#[test]
fn patch_test() {
    run_case("patch");
}

#[test]
fn energy_conservation() {
    run_case("energy");
}

#[test]
fn w10_plastic_damage() {
    run_case("W10");
}

#[test]
fn w10_one_point() {
    run_case("W10-1pt");
}

#[test]
fn w10_damaging_bar() {
    run_case("W10-bar");
}

#[test]
fn w11_rock_bolt() {
    run_case("W11");
}

#[test]
fn w13_stable_step() {
    run_case("W13");
}

#[test]
fn every_case_is_tested_here() {
    let ids: Vec<&str> = cases::all().iter().map(|c| c.info.id).collect();
    let covered = [
        "W1",
        "patch",
        "energy",
        "W10",
        "W10-1pt",
        "W10-bar",
        "W11",
        "W13",
        "W1-conv",
        "W5",
        "W6",
        "W7",
        "W8",
        "W9",
        "bonded",
        "drop",
        "W16",
        "W15a",
        "W15b",
        "W15c",
        "W15d",
        "W15e",
        "W15f", // boundaries.rs:
        "W2",
        "W3",
        "W14", // static_cases.rs:
        "W4",
        "static-geo",
        "static-DR",
        "static-seq",
    ];
    for id in ids {
        assert!(
            covered.contains(&id),
            "case {id} has no test in analytic.rs, convergence.rs, contact_cases.rs, boundaries.rs, motion.rs or static_cases.rs"
        );
    }
}
