//! A Python dict as a TOML document: the dict form of a case goes through TOML text and
//! the core's own parser, so that its errors are exactly those of a case file.

use pyo3::exceptions::PyTypeError;
use pyo3::prelude::*;
use pyo3::types::{PyBool, PyDict, PyFloat, PyInt, PyList, PyString, PyTuple};

/// Convert `obj` (at `path`, for messages) into a TOML value. Accepted: bool, int, float,
/// str, dict with str keys, list/tuple, numpy scalars and arrays (through `tolist()`).
pub fn to_value(obj: &Bound<'_, PyAny>, path: &str) -> PyResult<toml::Value> {
    if obj.is_instance_of::<PyBool>() {
        return Ok(toml::Value::Boolean(obj.extract()?));
    }
    if obj.is_instance_of::<PyInt>() {
        let v: i64 = obj.extract().map_err(|_| {
            PyTypeError::new_err(format!("{path}: integer {obj} does not fit in 64 bits"))
        })?;
        return Ok(toml::Value::Integer(v));
    }
    if obj.is_instance_of::<PyFloat>() {
        return Ok(toml::Value::Float(obj.extract()?));
    }
    if obj.is_instance_of::<PyString>() {
        return Ok(toml::Value::String(obj.extract()?));
    }
    if let Ok(d) = obj.cast::<PyDict>() {
        let mut table = toml::Table::new();
        for (k, v) in d.iter() {
            let key: String = k.extract().map_err(|_| {
                PyTypeError::new_err(format!(
                    "{path}: key {} is a {}, expected str",
                    k.repr().map(|r| r.to_string()).unwrap_or_default(),
                    type_name(&k)
                ))
            })?;
            let child = if path.is_empty() {
                key.clone()
            } else {
                format!("{path}.{key}")
            };
            if v.is_none() {
                // TOML has no null: a key set to None is left out (its default applies).
                continue;
            }
            table.insert(key, to_value(&v, &child)?);
        }
        return Ok(toml::Value::Table(table));
    }
    if obj.is_instance_of::<PyList>() || obj.is_instance_of::<PyTuple>() {
        let mut items = Vec::new();
        for (i, v) in obj.try_iter()?.enumerate() {
            items.push(to_value(&v?, &format!("{path}[{i}]"))?);
        }
        return Ok(toml::Value::Array(items));
    }
    // numpy scalars and arrays: their Python equivalents.
    if obj.hasattr("tolist")? && obj.hasattr("dtype")? {
        let plain = obj.call_method0("tolist")?;
        return to_value(&plain, path);
    }
    Err(PyTypeError::new_err(format!(
        "{path}: a {} cannot be written to a case (expected bool, int, float, str, dict, list \
         or a numpy value)",
        type_name(obj)
    )))
}

fn type_name(obj: &Bound<'_, PyAny>) -> String {
    obj.get_type()
        .name()
        .map(|n| n.to_string())
        .unwrap_or_else(|_| "?".into())
}

/// A dict as a TOML table (`argument` names the Python argument in messages).
pub fn dict_to_table(obj: &Bound<'_, PyAny>, argument: &str) -> PyResult<toml::Table> {
    if obj.cast::<PyDict>().is_err() {
        return Err(PyTypeError::new_err(format!(
            "{argument}: expected a dict, got a {}",
            type_name(obj)
        )));
    }
    let value = to_value(obj, "")
        .map_err(|e| PyTypeError::new_err(format!("{argument}: {}", e.value(obj.py()))))?;
    let toml::Value::Table(table) = value else {
        unreachable!("a dict converts to a table")
    };
    Ok(table)
}

/// The TOML text of a table.
pub fn table_to_toml(table: &toml::Table, argument: &str) -> PyResult<String> {
    toml::to_string(table)
        .map_err(|e| PyTypeError::new_err(format!("{argument}: not expressible as TOML: {e}")))
}

/// The TOML text of a dict (`argument` names the Python argument in messages).
pub fn dict_to_toml(obj: &Bound<'_, PyAny>, argument: &str) -> PyResult<String> {
    table_to_toml(&dict_to_table(obj, argument)?, argument)
}

/// The TOML text the dict form of a case is read through (to see what the parser sees).
#[pyfunction]
pub fn to_toml(case: &Bound<'_, PyAny>) -> PyResult<String> {
    dict_to_toml(case, "case")
}
