//! numpy in and out: arrays from the core's vectors, and Python arguments checked into
//! `f64` arrays of a given shape (a wrong type is a `TypeError`, a wrong shape a
//! `ValueError`, both naming the argument).

use numpy::ndarray::{Array1, Array2, Array3};
use numpy::{
    IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayDyn, PyArrayMethods, PyUntypedArrayMethods,
};
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;

/// (n, 3) array of node vectors.
pub fn nodes3<'py>(py: Python<'py>, v: &[[f64; 3]]) -> Bound<'py, PyArray2<f64>> {
    let flat: Vec<f64> = v.iter().flatten().copied().collect();
    Array2::from_shape_vec((v.len(), 3), flat)
        .expect("n × 3")
        .into_pyarray(py)
}

/// (rows, cols) array from row-major data (floats or indices).
pub fn matrix<'py, T: numpy::Element>(
    py: Python<'py>,
    rows: usize,
    cols: usize,
    data: Vec<T>,
) -> Bound<'py, PyArray2<T>> {
    Array2::from_shape_vec((rows, cols), data)
        .expect("rows × cols")
        .into_pyarray(py)
}

/// (a, b, c) array from row-major data.
pub fn cube<'py>(
    py: Python<'py>,
    shape: (usize, usize, usize),
    data: Vec<f64>,
) -> Bound<'py, PyArray3<f64>> {
    Array3::from_shape_vec(shape, data)
        .expect("a × b × c")
        .into_pyarray(py)
}

/// 1-D array.
pub fn vector<'py>(py: Python<'py>, data: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    Array1::from_vec(data).into_pyarray(py)
}

/// 1-D integer array.
pub fn index_vector<'py>(py: Python<'py>, data: Vec<i64>) -> Bound<'py, PyArray1<i64>> {
    Array1::from_vec(data).into_pyarray(py)
}

/// `obj` as a float64 array whose shape matches `shape` (`None`: any length on that
/// axis); returns the row-major data and the shape. `name` is the argument's name.
pub fn f64_array(
    obj: &Bound<'_, PyAny>,
    name: &str,
    shape: &[Option<usize>],
) -> PyResult<(Vec<f64>, Vec<usize>)> {
    let py = obj.py();
    let np = py.import("numpy")?;
    let arr = np.call_method1("asarray", (obj, "float64")).map_err(|e| {
        PyTypeError::new_err(format!(
            "{name}: expected an array of numbers ({})",
            e.value(py)
        ))
    })?;
    let arr = arr
        .cast::<PyArrayDyn<f64>>()
        .map_err(|_| PyTypeError::new_err(format!("{name}: expected an array of numbers")))?;
    let got: Vec<usize> = arr.shape().to_vec();
    let fits = got.len() == shape.len()
        && got
            .iter()
            .zip(shape)
            .all(|(g, s)| s.is_none_or(|s| s == *g));
    if !fits {
        let want: Vec<String> = shape
            .iter()
            .map(|s| s.map_or("n".to_string(), |s| s.to_string()))
            .collect();
        return Err(PyValueError::new_err(format!(
            "{name}: expected shape ({}), got {:?}",
            want.join(", "),
            got
        )));
    }
    let data: Vec<f64> = arr.to_vec().or_else(|_| {
        // Not contiguous: copy through numpy.
        np.call_method1("ascontiguousarray", (arr,))?
            .cast::<PyArrayDyn<f64>>()
            .map_err(|_| PyTypeError::new_err(format!("{name}: expected an array of numbers")))?
            .to_vec()
            .map_err(|e| PyValueError::new_err(format!("{name}: {e}")))
    })?;
    if let Some(i) = data.iter().position(|x| !x.is_finite()) {
        return Err(PyValueError::new_err(format!(
            "{name}: value {} at flat index {i} is not finite",
            data[i]
        )));
    }
    Ok((data, got))
}

/// `obj` as a 3-vector (`name` names the argument).
pub fn vec3(obj: &Bound<'_, PyAny>, name: &str) -> PyResult<[f64; 3]> {
    let (d, _) = f64_array(obj, name, &[Some(3)])?;
    Ok([d[0], d[1], d[2]])
}
