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

    /// The case title the rows carry.
    pub fn case(&self) -> &str {
        &self.case
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

/// A curve a case computed, with the reference curve where the case has one, for the
/// report's plots (`series.json`). Long curves are thinned to at most
/// [`Series::MAX_POINTS`] points when they are added.
#[derive(Clone, Debug, Serialize, PartialEq)]
pub struct Series {
    /// Case title (the `case` of its rows).
    pub case: String,
    /// What the curve shows (plot title).
    pub name: String,
    /// Axis labels with units.
    pub x_label: String,
    pub y_label: String,
    /// Abscissae of the computed curve.
    pub x: Vec<f64>,
    /// Computed values.
    pub computed: Vec<f64>,
    /// Reference values at the same abscissae (closed form), if the case has a curve.
    pub reference: Option<Vec<f64>>,
    /// Plot both axes logarithmically (convergence).
    pub log_log: bool,
}

impl Series {
    /// Most points kept per curve.
    pub const MAX_POINTS: usize = 600;

    /// A curve of `case`; `reference` has the length of `x` when given.
    pub fn new(
        case: &str,
        name: &str,
        (x_label, y_label): (&str, &str),
        x: Vec<f64>,
        computed: Vec<f64>,
        reference: Option<Vec<f64>>,
    ) -> Self {
        assert_eq!(
            x.len(),
            computed.len(),
            "{name}: x and computed differ in length"
        );
        if let Some(r) = &reference {
            assert_eq!(x.len(), r.len(), "{name}: x and reference differ in length");
        }
        let stride = x.len().div_ceil(Self::MAX_POINTS).max(1);
        let thin = |v: Vec<f64>| -> Vec<f64> {
            let last = v.len().saturating_sub(1);
            v.iter()
                .enumerate()
                .filter(|(i, _)| i % stride == 0 || *i == last)
                .map(|(_, &x)| x)
                .collect()
        };
        Self {
            case: case.to_string(),
            name: name.to_string(),
            x_label: x_label.to_string(),
            y_label: y_label.to_string(),
            x: thin(x),
            computed: thin(computed),
            reference: reference.map(thin),
            log_log: false,
        }
    }

    /// The same curve on log–log axes.
    pub fn log_log(mut self) -> Self {
        self.log_log = true;
        self
    }
}

/// What a case returns: its checked rows and the curves its report section plots.
#[derive(Clone, Debug, Default)]
pub struct CaseOutput {
    pub rows: Vec<CheckRow>,
    pub series: Vec<Series>,
}

impl From<Vec<CheckRow>> for CaseOutput {
    fn from(rows: Vec<CheckRow>) -> Self {
        Self {
            rows,
            series: Vec::new(),
        }
    }
}
