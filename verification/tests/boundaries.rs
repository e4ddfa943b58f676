//! Boundary verification cases: absorbing boundaries, seismic input and the free field
//! reproduce their references (docs/verification_references.md §W2, W3, W14) within the stated tolerances.

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
fn w02_absorbing_boundaries() {
    run_case("W2");
}

#[test]
fn w03_site_response() {
    run_case("W3");
}

#[test]
fn w14_free_field() {
    run_case("W14");
}
