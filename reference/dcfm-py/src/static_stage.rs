//! `Case.static()`: the static stage of a case (`[static]`, docs/static_stage.md) run on a
//! fresh build of the model, its state returned as numpy arrays — the displacements of the
//! direct solve (or the relaxation), the element stresses and strains, the reactions and
//! the per-step reports.

use std::time::Instant;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use dcfm::stage::static_stage::{self, StaticResult};

use crate::arrays::{matrix, nodes3, vector};
use crate::errors::to_py;

/// Run the static stage of `built` (without the GIL, on `threads` workers or all cores);
/// the model comes back in its post-static configuration with the stage's result.
pub fn run_stage(
    py: Python<'_>,
    built: dcfm::case::Case,
    label: &str,
    threads: Option<usize>,
) -> PyResult<(dcfm::case::Case, StaticResult, f64)> {
    let Some(plan) = built.static_plan.clone() else {
        return Err(PyValueError::new_err(format!(
            "{label}: the case has no [static] section (docs/static_stage.md)"
        )));
    };
    let dcfm::case::Case {
        file,
        title,
        model,
        dt,
        end,
        safety,
        subcycling,
        output,
        probes,
        motions,
        static_plan,
        max_steps,
        warnings,
        fingerprint,
    } = built;
    let pool = crate::simulation::thread_pool(threads)?;
    let t0 = Instant::now();
    let work = move || static_stage::run(model, &plan);
    let out = py.detach(|| match &pool {
        Some(p) => p.install(work),
        None => work(),
    });
    let wall = t0.elapsed().as_secs_f64();
    let (model, result) = out.map_err(|e| {
        to_py(match e {
            dcfm::DcfmError::Static { step, message } => dcfm::DcfmError::Static {
                step: format!("{label}: {step}"),
                message,
            },
            other => other,
        })
    })?;
    Ok((
        dcfm::case::Case {
            file,
            title,
            model,
            dt,
            end,
            safety,
            subcycling,
            output,
            probes,
            motions,
            static_plan,
            max_steps,
            warnings,
            fingerprint,
        },
        result,
        wall,
    ))
}

/// The static state as a dict of numpy arrays (see `Case.static` in the stubs).
pub fn result_dict<'py>(
    py: Python<'py>,
    model: &dcfm::model::Model,
    r: &StaticResult,
    wall_s: f64,
) -> PyResult<Bound<'py, PyDict>> {
    let n = model.mesh.n_nodes();
    let ne = model.n_elements();
    let d = PyDict::new(py);
    d.set_item("displacement", nodes3(py, &r.u))?;
    d.set_item("displacement_in_situ", nodes3(py, &r.u_in_situ))?;
    let f = dcfm::element::fields::ElementFields::of(model, &r.u);
    d.set_item("stress", matrix(py, ne, 6, f.stress))?;
    d.set_item("strain", matrix(py, ne, 6, f.strain))?;
    d.set_item("active", r.active.clone())?;
    let per_node = |list: &[(u32, [f64; 3])]| {
        let mut v = vec![[0.0; 3]; n];
        for (node, x) in list {
            for k in 0..3 {
                v[*node as usize][k] += x[k];
            }
        }
        v
    };
    d.set_item("reactions", nodes3(py, &per_node(&r.reactions)))?;
    d.set_item("static_loads", nodes3(py, &per_node(&r.static_loads)))?;
    d.set_item("out_of_balance", r.out_of_balance.ratio)?;
    d.set_item(
        "damaged_volume",
        vector(py, r.damaged_volume.to_vec()).into_any(),
    )?;
    let steps = PyList::empty(py);
    for s in &r.steps {
        let sd = PyDict::new(py);
        sd.set_item("name", &s.name)?;
        sd.set_item("solver", s.solver.name())?;
        sd.set_item("iterations", s.iterations)?;
        sd.set_item("initial_out_of_balance", s.initial.ratio)?;
        sd.set_item("out_of_balance", s.out_of_balance.ratio)?;
        sd.set_item("active_elements", s.active_elements)?;
        sd.set_item("equations", s.equations)?;
        sd.set_item("stiffness_nonzeros", s.stiffness_nonzeros)?;
        sd.set_item("factor_nonzeros", s.factor_nonzeros)?;
        let linear = match s.linear_solver {
            Some(dcfm::stage::static_stage::linear_solver::LinearSolverChoice::Cholesky) => {
                Some("cholesky")
            }
            Some(
                dcfm::stage::static_stage::linear_solver::LinearSolverChoice::ConjugateGradients,
            ) => Some("conjugate_gradients"),
            _ => None,
        };
        sd.set_item("linear_solver", linear)?;
        sd.set_item("seconds", s.seconds.to_vec())?;
        steps.append(sd)?;
    }
    d.set_item("steps", steps)?;
    d.set_item("wall_s", wall_s)?;
    Ok(d)
}
