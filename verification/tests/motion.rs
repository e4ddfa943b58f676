//! Ground-motion verification (docs/verification_references.md §W15): response spectrum, Arias intensity,
//! Butterworth filters, integration, real records, synthetic generator.
//! Requirement: the motion module reproduces closed forms and file headers within the
//! stated tolerances, and the synthetic default is reproducible bit for bit.

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
fn w15a_response_spectrum() {
    run_case("W15a");
}

#[test]
fn w15b_arias() {
    run_case("W15b");
}

#[test]
fn w15c_butterworth() {
    run_case("W15c");
}

#[test]
fn w15d_integration() {
    run_case("W15d");
}

#[test]
fn w15e_records() {
    run_case("W15e");
}

#[test]
fn w15f_synthetic() {
    run_case("W15f");
}
