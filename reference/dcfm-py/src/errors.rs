//! The `DcfmError` Python exception: the core's typed error, its message unchanged
//! (`cases/x.toml: materials.rock.poisson = 0.7: must be in (-1, 0.5)`), with the parts
//! as attributes (`file`, `field`, `value`, `expected`; `None` where the error has none).

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

create_exception!(
    dcfm,
    DcfmError,
    PyException,
    "An error of the dcfm core: bad input (file, field path, value, expectation), an \
     unstable run, a bad element or mesh, a contact or material failure."
);

/// The Python exception for a core error.
pub fn to_py(err: dcfm::DcfmError) -> PyErr {
    use dcfm::DcfmError as E;
    let message = err.to_string();
    let (kind, file, field, value, expected): (&str, Option<String>, _, _, _) = match &err {
        E::InvalidInput {
            file,
            field,
            value,
            expected,
        } => (
            "invalid_input",
            Some(file.clone()),
            Some(field.clone()),
            Some(value.clone()),
            Some(expected.clone()),
        ),
        E::Parse { file, .. } => ("parse", Some(file.clone()), None, None, None),
        E::Io { file, .. } => ("io", Some(file.clone()), None, None, None),
        E::BadElement { .. } => ("bad_element", None, None, None, None),
        E::Mesh(_) => ("mesh", None, None, None, None),
        E::TimeStepTooLarge {
            file, requested, ..
        } => (
            "time_step_too_large",
            Some(file.clone()),
            Some("time.dt".to_string()),
            Some(format!("{requested:e}")),
            None,
        ),
        E::Unstable { .. } => ("unstable", None, None, None, None),
        E::Contact { .. } => ("contact", None, None, None, None),
        E::Material { .. } => ("material", None, None, None, None),
        E::Static { .. } => ("static", None, None, None, None),
    };
    Python::attach(|py| {
        let e = DcfmError::new_err(message);
        let obj = e.value(py);
        for (name, v) in [
            ("file", file),
            ("field", field),
            ("value", value),
            ("expected", expected),
        ] {
            // Setting an attribute on a fresh exception instance cannot fail.
            let _ = obj.setattr(name, v);
        }
        let _ = obj.setattr("kind", kind);
        e
    })
}

/// `Result` of the core → `PyResult`.
pub trait IntoPy<T> {
    /// Map the core's error to [`DcfmError`].
    fn py_err(self) -> PyResult<T>;
}

impl<T> IntoPy<T> for dcfm::Result<T> {
    fn py_err(self) -> PyResult<T> {
        self.map_err(to_py)
    }
}
