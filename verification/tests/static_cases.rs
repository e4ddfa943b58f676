//! Static-stage verification cases (W4 Kirsch, geostatic states, dynamic relaxation,
//! sequences / activation / hand-over): each registered case must pass every checked
//! quantity.
//! Requirement: the static stage reproduces the closed-form references of docs/verification_references.md
//! W4 and of the geostatic column, and its solvers agree (issue #7).

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
fn w04_kirsch() {
    run_case("W4");
}

#[test]
fn static_geostatic() {
    run_case("static-geo");
}

#[test]
fn static_relaxation() {
    run_case("static-DR");
}

#[test]
fn static_sequence() {
    run_case("static-seq");
}
