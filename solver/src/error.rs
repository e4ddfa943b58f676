//! Typed errors with context: the file, the field path, the value and what was expected;
//! the element, node or step where a run failed.

use thiserror::Error;

/// Every failure the solver reports. Bad input never panics: it ends here.
#[derive(Debug, Error)]
pub enum DcfmError {
    /// A field of the input has a value outside what the model accepts.
    #[error("{file}: {field} = {value}: {expected}")]
    InvalidInput {
        file: String,
        field: String,
        value: String,
        expected: String,
    },
    /// The input could not be parsed at all (syntax, unknown field, wrong type).
    #[error("{file}: {message}")]
    Parse { file: String, message: String },
    /// An I/O failure on a named file.
    #[error("{file}: {source}")]
    Io {
        file: String,
        #[source]
        source: std::io::Error,
    },
    /// An element whose geometry cannot be used (inverted, degenerate).
    #[error("element {element}: {reason}")]
    BadElement { element: usize, reason: String },
    /// A mesh-level inconsistency (unknown set, node index out of range, ...).
    #[error("mesh: {0}")]
    Mesh(String),
    /// The requested time step (`time.dt`) is above the stable one.
    #[error(
        "{file}: time.dt = {requested:.4e} s: exceeds the stable step {stable:.4e} s \
         (safety factor included), limited by element {element} \
         (characteristic length {length:.4e} m, wave speed {speed:.1} m/s)"
    )]
    TimeStepTooLarge {
        file: String,
        requested: f64,
        stable: f64,
        element: usize,
        length: f64,
        speed: f64,
    },
    /// The run went unstable; names the step, the place and the likely cause.
    #[error("run went unstable at step {step} (t = {time:.6e} s): {what} at node {node}; likely cause: {cause}")]
    Unstable {
        step: u64,
        time: f64,
        node: usize,
        what: String,
        cause: String,
    },
    /// A contact interface could not be set up or its solve did not settle.
    #[error("interface '{interface}': {message}")]
    Contact { interface: String, message: String },
    /// A material parameter set that the model cannot accept.
    #[error("material '{material}': {message}")]
    Material { material: String, message: String },
    /// A step of the static stage failed (did not converge, singular stiffness, an
    /// excavation or activation that the state does not allow); names the step and where.
    #[error("static stage, {step}: {message}")]
    Static { step: String, message: String },
}

/// Result alias used across the crate.
pub type Result<T> = std::result::Result<T, DcfmError>;

/// A value as given, except that a number of more than 20 digits (a float such as 1e300,
/// which `Display` writes out in full; no integer field holds one) is shown in
/// engineering notation.
fn readable_value(v: String) -> String {
    let plain = v.len() > 20
        && v.bytes()
            .all(|b| b.is_ascii_digit() || b == b'-' || b == b'.')
        && v.parse::<f64>().is_ok();
    if plain {
        crate::readable::engineering(v.parse().unwrap_or(f64::NAN))
    } else {
        v
    }
}

impl DcfmError {
    /// Shorthand for [`DcfmError::InvalidInput`].
    pub fn invalid(
        file: impl Into<String>,
        field: impl Into<String>,
        value: impl std::fmt::Display,
        expected: impl Into<String>,
    ) -> Self {
        DcfmError::InvalidInput {
            file: file.into(),
            field: field.into(),
            value: readable_value(value.to_string()),
            expected: expected.into(),
        }
    }

    /// The same error with `file` named where the error had no file yet (errors raised by
    /// the model, outside any case file).
    pub fn in_file(self, file: &str) -> Self {
        match self {
            DcfmError::TimeStepTooLarge {
                file: f,
                requested,
                stable,
                element,
                length,
                speed,
            } if f.is_empty() => DcfmError::TimeStepTooLarge {
                file: file.to_string(),
                requested,
                stable,
                element,
                length,
                speed,
            },
            DcfmError::InvalidInput {
                file: f,
                field,
                value,
                expected,
            } if f.is_empty() => DcfmError::InvalidInput {
                file: file.to_string(),
                field,
                value,
                expected,
            },
            other => other,
        }
    }

    /// Wrap an I/O error with the file it concerns.
    pub fn io(file: impl Into<String>, source: std::io::Error) -> Self {
        DcfmError::Io {
            file: file.into(),
            source,
        }
    }
}
