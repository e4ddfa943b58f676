//! Convergence-rate checks. Requirement: the W1 P pulse error falls as h² at fixed Courant
//! number (fitted slope asserted); the (h, error) table is kept as a gold file so that a
//! change in accuracy shows up in review.

use dcfm_verification::analytic::PulseShape;
use dcfm_verification::cases::convergence_w01::{fitted_slope, table};

#[test]
fn w01_p_pulse_converges_at_second_order() {
    let t = table(PulseShape::SineSquared).unwrap();
    let slope = fitted_slope(&t);
    assert!(
        (slope - 2.0).abs() <= 0.25,
        "fitted slope {slope:.3}, table {t:?}"
    );
    let text: String = std::iter::once("h_m,rms_error_rel\n".to_string())
        .chain(t.iter().map(|(h, e)| format!("{h},{e:.3e}\n")))
        .collect();
    let gold_path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/gold/w01_convergence.csv"
    );
    match std::fs::read_to_string(gold_path) {
        Ok(gold) => assert_eq!(
            gold, text,
            "convergence table changed; if intended, update {gold_path}"
        ),
        Err(_) => {
            std::fs::write(gold_path, &text).unwrap();
            panic!("gold file {gold_path} was missing and has been written; rerun");
        }
    }
}
