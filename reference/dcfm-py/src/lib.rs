//! Python bindings of the dcfm core (`import dcfm`).
//!
//! The module links the core library alone (no command line, no file output). What it
//! offers, each in its own file:
//!
//! - [`case`]: load and validate a case from a file, a TOML text or a Python dict (the
//!   dict is written as TOML and read by the same parser, so errors are identical);
//! - [`simulation`]: step a case, or run it with a progress callback, and read the
//!   histories and the final fields as numpy arrays;
//! - [`mesh`]: structured block meshes;
//! - [`material_point`]: one integration point of any material driven along a strain path;
//! - [`contact_pair`]: one contact pair, one step (the kernel of VERIFICATION W9);
//! - [`static_stage`]: `Case.static()`, the static stage's state;
//! - [`motion`]: ground motions — read, made from arrays (ObsPy traces), processed,
//!   integrated, measured (response spectrum), and given to cases;
//! - [`errors`]: the `DcfmError` exception, carrying the core's file/field/value message.
//!
//! Wrong Python types or shapes raise `TypeError` / `ValueError` naming the argument
//! ([`arrays`], [`toml_value`]).

use pyo3::prelude::*;

mod arrays;
mod case;
mod contact_pair;
mod errors;
mod material_point;
mod mesh;
mod motion;
mod simulation;
mod static_stage;
mod toml_value;

/// The `dcfm._dcfm` extension module (re-exported by the `dcfm` package).
#[pymodule]
#[pyo3(name = "_dcfm")]
fn dcfm_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("DcfmError", m.py().get_type::<errors::DcfmError>())?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add_class::<case::Case>()?;
    m.add_class::<simulation::Simulation>()?;
    m.add_class::<simulation::RunResult>()?;
    m.add_class::<mesh::Mesh>()?;
    m.add_function(wrap_pyfunction!(mesh::box_mesh, m)?)?;
    m.add_function(wrap_pyfunction!(material_point::material_point, m)?)?;
    m.add_function(wrap_pyfunction!(contact_pair::contact_pair_step, m)?)?;
    m.add_function(wrap_pyfunction!(toml_value::to_toml, m)?)?;
    m.add_class::<motion::Motion>()?;
    m.add_function(wrap_pyfunction!(motion::read_motion, m)?)?;
    m.add_function(wrap_pyfunction!(motion::synthetic_motion, m)?)?;
    m.add_function(wrap_pyfunction!(motion::response_spectrum, m)?)?;
    Ok(())
}
