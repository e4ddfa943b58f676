//! `dcfm.contact_pair_step`: one contact pair, one step — the point-to-point kernel of
//! the dynamic contact force method (eqs. 5–15, `dcfm::contact::solve_pair`).

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

use dcfm::contact::{solve_pair, PairInput, PairParams, PairState};

use crate::arrays::{vec3, vector};

fn state_from(name: &str) -> PyResult<PairState> {
    Ok(match name {
        "bonded" => PairState::Bonded,
        "stick" => PairState::Stick,
        "sliding" => PairState::Sliding,
        "separated" => PairState::Separated,
        other => {
            return Err(PyValueError::new_err(format!(
                "state: {other:?} is not one of \"bonded\", \"stick\", \"sliding\", \"separated\""
            )))
        }
    })
}

fn state_name(s: PairState) -> &'static str {
    match s {
        PairState::Bonded => "bonded",
        PairState::Stick => "stick",
        PairState::Sliding => "sliding",
        PairState::Separated => "separated",
    }
}

/// Solve one pair (node a on surface a, node b on surface b) for one step.
///
/// `normal`: unit normal of surface a at a (from a towards b); `w_sum`: 1/M_a + 1/M_b
/// (> 0); `dt`: time step; `rel_pred`: predicted relative displacement Ū_b − Ū_a;
/// `rel_old`: U_b − U_a at the start of the step; `mu_s` ≥ `mu_d` ≥ 0 the friction
/// coefficients; `shear_capacity` cA and `tensile_capacity` σ_t A (N) count only while
/// bonded. Returns a dict: force (3,) on node a (b gets −force), state, normal (λ,
/// compression positive), tangential (3,).
#[pyfunction]
#[pyo3(signature = (*, state, normal, w_sum, dt, rel_pred, rel_old, mu_s, mu_d,
    shear_capacity = 0.0, tensile_capacity = 0.0))]
#[allow(clippy::too_many_arguments)]
pub fn contact_pair_step<'py>(
    py: Python<'py>,
    state: &str,
    normal: &Bound<'py, PyAny>,
    w_sum: f64,
    dt: f64,
    rel_pred: &Bound<'py, PyAny>,
    rel_old: &Bound<'py, PyAny>,
    mu_s: f64,
    mu_d: f64,
    shear_capacity: f64,
    tensile_capacity: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let state = state_from(state)?;
    let n = vec3(normal, "normal")?;
    let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
    if (len - 1.0).abs() > 1e-9 {
        return Err(PyValueError::new_err(format!(
            "normal: length {len} is not 1"
        )));
    }
    let positive = |name: &str, v: f64| -> PyResult<()> {
        if v.is_finite() && v > 0.0 {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "{name}: {v} must be finite and > 0"
            )))
        }
    };
    let non_negative = |name: &str, v: f64| -> PyResult<()> {
        if v.is_finite() && v >= 0.0 {
            Ok(())
        } else {
            Err(PyValueError::new_err(format!(
                "{name}: {v} must be finite and ≥ 0"
            )))
        }
    };
    positive("w_sum", w_sum)?;
    positive("dt", dt)?;
    non_negative("mu_s", mu_s)?;
    non_negative("mu_d", mu_d)?;
    non_negative("shear_capacity", shear_capacity)?;
    non_negative("tensile_capacity", tensile_capacity)?;
    if mu_d > mu_s {
        return Err(PyValueError::new_err(format!(
            "mu_d: {mu_d} must not exceed mu_s = {mu_s}"
        )));
    }
    let out = solve_pair(
        state,
        &PairParams {
            mu_s,
            mu_d,
            shear_capacity,
            tensile_capacity,
        },
        &PairInput {
            n,
            w_sum,
            dt,
            rel_pred: vec3(rel_pred, "rel_pred")?,
            rel_old: vec3(rel_old, "rel_old")?,
        },
    );
    let d = PyDict::new(py);
    d.set_item("force", vector(py, out.r.to_vec()))?;
    d.set_item("state", state_name(out.state))?;
    d.set_item("normal", out.normal)?;
    d.set_item("tangential", vector(py, out.tangential.to_vec()))?;
    Ok(d)
}
