//! Contact verification cases (W5–W9, W12 rows, bonded = monolithic, drop and bounce):
//! each registered case must pass every checked quantity.
//! Requirement: the dynamic contact force method reproduces the references of
//! docs/verification_references.md §W5–W9 and W12 within their stated tolerances.

use dcfm_verification::cases;
use dcfm_verification::record::failures;

fn run_case(id: &str) {
    let case = cases::all()
        .into_iter()
        .find(|c| c.info.id == id)
        .expect("registered case");
    let rows = (case.run)().unwrap_or_else(|e| panic!("{id}: {e}")).rows;
    assert!(!rows.is_empty(), "{id} checked nothing");
    for r in &rows {
        println!(
            "{} | {} | ref {:.6e} | got {:.6e} | err {:.3e} | tol {:.3e} | {}",
            r.case,
            r.quantity,
            r.reference,
            r.computed,
            r.rel_error,
            r.tolerance,
            if r.pass { "pass" } else { "FAIL" }
        );
    }
    let failed = failures(&rows);
    assert!(failed.is_empty(), "{id}:\n{}", failed.join("\n"));
}

#[test]
fn w05_bar_impact() {
    run_case("W5");
}

#[test]
fn w06_incline() {
    run_case("W6");
}

#[test]
fn w07_newmark_block() {
    run_case("W7");
}

#[test]
fn w16_stick_slip() {
    run_case("W16");
}

#[test]
fn w08_cohesive_bond() {
    run_case("W8");
}

#[test]
fn w09_pair_step() {
    run_case("W9");
}

#[test]
fn bonded_equals_monolithic() {
    run_case("bonded");
}

#[test]
fn drop_and_bounce() {
    run_case("drop");
}
