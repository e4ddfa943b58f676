//! One row per checked quantity: the reference, the computed value, the error and the
//! tolerance with its source.

use serde::Serialize;

/// A checked quantity (row of `results.json`).
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct CheckRow {
    pub case: String,
    pub quantity: String,
    pub reference: f64,
    pub computed: f64,
    /// |computed − reference| / |reference| (or the absolute error when `absolute`).
    pub rel_error: f64,
    pub tolerance: f64,
    pub pass: bool,
    pub source: String,
}

/// Builder of rows for one case.
pub struct Check {
    case: String,
    rows: Vec<CheckRow>,
}

impl Check {
    /// Rows of case `case`.
    pub fn new(case: &str) -> Self {
        Self {
            case: case.to_string(),
            rows: Vec::new(),
        }
    }

    /// Relative check |c − r|/|r| ≤ tol.
    pub fn relative(
        &mut self,
        quantity: &str,
        reference: f64,
        computed: f64,
        tol: f64,
        source: &str,
    ) -> &mut Self {
        let err = (computed - reference).abs() / reference.abs();
        self.push(quantity, reference, computed, err, tol, source)
    }

    /// Absolute check |c − r| ≤ tol (reported in `rel_error` as the absolute error).
    pub fn absolute(
        &mut self,
        quantity: &str,
        reference: f64,
        computed: f64,
        tol: f64,
        source: &str,
    ) -> &mut Self {
        let err = (computed - reference).abs();
        self.push(quantity, reference, computed, err, tol, source)
    }

    /// Range check lo ≤ computed ≤ hi (reference = centre, tolerance = half-width).
    pub fn within(
        &mut self,
        quantity: &str,
        lo: f64,
        hi: f64,
        computed: f64,
        source: &str,
    ) -> &mut Self {
        let centre = 0.5 * (lo + hi);
        let half = 0.5 * (hi - lo);
        let err = (computed - centre).abs();
        self.push(quantity, centre, computed, err, half, source)
    }

    fn push(
        &mut self,
        quantity: &str,
        reference: f64,
        computed: f64,
        err: f64,
        tol: f64,
        source: &str,
    ) -> &mut Self {
        self.rows.push(CheckRow {
            case: self.case.clone(),
            quantity: quantity.to_string(),
            reference,
            computed,
            rel_error: err,
            tolerance: tol,
            pass: err.is_finite() && err <= tol,
            source: source.to_string(),
        });
        self
    }

    /// The rows.
    pub fn finish(self) -> Vec<CheckRow> {
        self.rows
    }
}

/// Failed rows as readable lines (for test assertions).
pub fn failures(rows: &[CheckRow]) -> Vec<String> {
    rows.iter()
        .filter(|r| !r.pass)
        .map(|r| {
            format!(
                "{} / {}: computed {:.6e}, reference {:.6e}, error {:.3e} > tolerance {:.3e} ({})",
                r.case, r.quantity, r.computed, r.reference, r.rel_error, r.tolerance, r.source
            )
        })
        .collect()
}
