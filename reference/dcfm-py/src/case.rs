//! `dcfm.Case`: a case loaded and validated from a file, a TOML text or a dict.

use std::path::{Path, PathBuf};

use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use dcfm::motion::Motions;

use crate::arrays::{index_vector, matrix, nodes3, vector};
use crate::errors::{to_py, IntoPy};
use crate::simulation::{RunOptions, Simulation};
use crate::toml_value::dict_to_toml;

/// A validated case: the model built from its text, and the text itself (every
/// simulation starts from a fresh build of it, so runs are repeatable), with the motions
/// the caller gave (`motions={"name": dcfm.Motion}`).
#[pyclass(module = "dcfm", name = "Case", frozen)]
pub struct Case {
    text: String,
    label: String,
    dir: PathBuf,
    motions: Motions,
    inner: dcfm::case::Case,
}

/// `motions`: a dict of name → `dcfm.Motion`, or None.
fn given_motions(motions: Option<&Bound<'_, PyAny>>) -> PyResult<Motions> {
    let mut out = Motions::new();
    let Some(obj) = motions else {
        return Ok(out);
    };
    let d = obj.cast::<PyDict>().map_err(|_| {
        PyTypeError::new_err("motions: expected a dict of name → dcfm.Motion, or None")
    })?;
    for (k, v) in d.iter() {
        let name: String = k
            .extract()
            .map_err(|_| PyTypeError::new_err("motions: keys must be str (the motion's name)"))?;
        let m = v.cast::<crate::motion::Motion>().map_err(|_| {
            PyTypeError::new_err(format!(
                "motions[{name:?}]: expected a dcfm.Motion (dcfm.read_motion, \
                 Motion.from_arrays, Motion.from_obspy)"
            ))
        })?;
        out.insert(name, m.get().inner.clone());
    }
    Ok(out)
}

impl Case {
    fn parse(
        text: String,
        label: String,
        dir: PathBuf,
        motions: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let motions = given_motions(motions)?;
        let inner = dcfm::case::parse_case_with_motions(&text, &label, &dir, &motions).py_err()?;
        Ok(Self {
            text,
            label,
            dir,
            motions,
            inner,
        })
    }

    /// A fresh build of the case (for a new simulation).
    pub fn rebuild(&self) -> PyResult<dcfm::case::Case> {
        dcfm::case::parse_case_with_motions(&self.text, &self.label, &self.dir, &self.motions)
            .py_err()
    }

    /// The case's label (file path or the label given).
    pub fn label(&self) -> &str {
        &self.label
    }
}

#[pymethods]
impl Case {
    /// Read, parse and validate a case file (relative paths inside it, such as a Gmsh
    /// mesh, are resolved against the file's folder). `motions` (name → `dcfm.Motion`)
    /// are available to the case's time functions (`{ type = "motion", motion = "name" }`)
    /// beside its own `[motions.NAME]`.
    #[staticmethod]
    #[pyo3(signature = (path, *, motions = None))]
    fn from_file(path: PathBuf, motions: Option<&Bound<'_, PyAny>>) -> PyResult<Self> {
        let label = path.display().to_string();
        let text =
            std::fs::read_to_string(&path).map_err(|e| to_py(dcfm::DcfmError::io(&label, e)))?;
        let dir = path.parent().unwrap_or(Path::new(".")).to_path_buf();
        Self::parse(text, label, dir, motions)
    }

    /// Parse and validate a case from its TOML text; `label` names it in errors and
    /// `base_dir` resolves relative paths; `motions` as for `from_file`.
    #[staticmethod]
    #[pyo3(signature = (text, label = "<toml>".to_string(), base_dir = PathBuf::from("."), *,
        motions = None))]
    fn from_toml(
        text: String,
        label: String,
        base_dir: PathBuf,
        motions: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        Self::parse(text, label, base_dir, motions)
    }

    /// Parse and validate a case given as a dict with the case file's structure. The dict
    /// is written as TOML and read by the same parser as a file, so every error names the
    /// same field path; `None` values are left out (their default applies). `motions` as
    /// for `from_file`.
    #[staticmethod]
    #[pyo3(signature = (case, label = "<dict>".to_string(), base_dir = PathBuf::from("."), *,
        motions = None))]
    fn from_dict(
        case: &Bound<'_, PyAny>,
        label: String,
        base_dir: PathBuf,
        motions: Option<&Bound<'_, PyAny>>,
    ) -> PyResult<Self> {
        let text = dict_to_toml(case, "case")?;
        Self::parse(text, label, base_dir, motions)
    }

    /// Whether the case has a static stage (`[static]`).
    #[getter]
    fn has_static(&self) -> bool {
        self.inner.static_plan.is_some()
    }

    /// Names of the motions the case can use (its `[motions.NAME]` and those given).
    #[getter]
    fn motion_names(&self) -> Vec<String> {
        self.inner.motions.keys().cloned().collect()
    }

    /// The static stage (`[static]`, docs/static_stage.md) on a fresh build of the model:
    /// a dict with displacement and displacement_in_situ (n, 3), stress and strain
    /// (e, 6; element means at the end of the stage, zero for inactive elements), active
    /// (e,), reactions and static_loads (n, 3), out_of_balance (the final ratio),
    /// damaged_volume (3,), steps (one dict per step: name, solver, iterations,
    /// out-of-balance before and after, equations, nonzeros, seconds) and wall_s.
    #[pyo3(signature = (*, threads = None))]
    fn r#static<'py>(
        &self,
        py: Python<'py>,
        threads: Option<usize>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let built = self.rebuild()?;
        let (built, result, wall) =
            crate::static_stage::run_stage(py, built, &self.label, threads)?;
        crate::static_stage::result_dict(py, &built.model, &result, wall)
    }

    /// The TOML text the case was read from.
    #[getter]
    fn toml(&self) -> &str {
        &self.text
    }

    /// File path or label used in messages.
    #[getter(label)]
    fn label_py(&self) -> &str {
        &self.label
    }

    #[getter]
    fn title(&self) -> &str {
        &self.inner.title
    }

    /// Time step of a run (s): `time.dt`, or `safety` × the critical step.
    #[getter]
    fn dt(&self) -> f64 {
        self.inner.dt
    }

    /// End time (s).
    #[getter]
    fn end(&self) -> f64 {
        self.inner.end
    }

    /// Safety factor on the critical step.
    #[getter]
    fn safety(&self) -> f64 {
        self.inner.safety
    }

    /// Critical step with damping, before the safety factor (s).
    #[getter]
    fn critical_dt(&self) -> f64 {
        self.inner.model.critical_step_with_damping()
    }

    /// The element that limits the stable step.
    #[getter]
    fn limiting_element(&self) -> usize {
        self.inner.model.stable.element
    }

    /// Steps a run to `end` takes.
    #[getter]
    fn n_steps(&self) -> u64 {
        (self.inner.end / self.inner.dt).ceil() as u64
    }

    #[getter]
    fn n_nodes(&self) -> usize {
        self.inner.model.mesh.n_nodes()
    }

    #[getter]
    fn n_elements(&self) -> usize {
        self.inner.model.n_elements()
    }

    /// Node coordinates, (n_nodes, 3) (m).
    #[getter]
    fn coords<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        nodes3(py, &self.inner.model.mesh.coords).into_any()
    }

    /// Hex8 connectivity, (n_elements, 8), VTK/Gmsh node order.
    #[getter]
    fn elements<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        connectivity(py, &self.inner.model.mesh.elements)
    }

    /// Region index of every element (into `region_names`).
    #[getter]
    fn element_region<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        let r = &self.inner.model.mesh.element_region;
        index_vector(py, r.iter().map(|&x| x as i64).collect()).into_any()
    }

    #[getter]
    fn region_names(&self) -> Vec<String> {
        self.inner.model.mesh.region_names.clone()
    }

    /// Lumped nodal masses (kg).
    #[getter]
    fn mass<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        vector(py, self.inner.model.mass.clone()).into_any()
    }

    /// Names of every node, face and element set and region.
    #[getter]
    fn set_names(&self) -> Vec<String> {
        self.inner.model.mesh.set_names()
    }

    /// Nodes of a node set, face set, element set or region.
    fn nodes_of<'py>(&self, py: Python<'py>, set: &str) -> PyResult<Bound<'py, PyAny>> {
        let mesh = &self.inner.model.mesh;
        let nodes = mesh.nodes_of(set).ok_or_else(|| {
            PyValueError::new_err(format!(
                "set: no set or region named {set:?} (have {:?})",
                mesh.set_names()
            ))
        })?;
        Ok(index_vector(py, nodes.iter().map(|&n| n as i64).collect()).into_any())
    }

    /// Nodes listed in `[output] nodes` (the default nodes of a run's histories).
    #[getter]
    fn output_nodes(&self) -> Vec<u32> {
        self.inner.output.nodes.clone()
    }

    /// Elements listed in `[output] elements`.
    #[getter]
    fn output_elements(&self) -> Vec<u32> {
        self.inner.output.elements.clone()
    }

    /// A simulation of this case at t = 0 (a fresh build of the model), with the case's
    /// time step or `dt` (checked against the stable step). A case with a static stage
    /// starts from its static state, as `dcfm run` does (the stage's supports' reactions
    /// and static loads stay on as constant loads, absorbing springs measured from it).
    #[pyo3(signature = (dt = None))]
    fn start(&self, py: Python<'_>, dt: Option<f64>) -> PyResult<Simulation> {
        Simulation::from_case(py, self, dt)
    }

    /// Run the case from t = 0: `start(dt).run(...)`; see `Simulation.run`.
    #[pyo3(signature = (*, end = None, steps = None, record_every = 1, nodes = None,
        elements = None, callback = None, callback_every = 100, threads = None, dt = None, free_field = false))]
    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        py: Python<'_>,
        end: Option<f64>,
        steps: Option<u64>,
        record_every: u64,
        nodes: Option<Vec<i64>>,
        elements: Option<Vec<i64>>,
        callback: Option<Bound<'_, PyAny>>,
        callback_every: u64,
        threads: Option<usize>,
        dt: Option<f64>,
        free_field: bool,
    ) -> PyResult<crate::simulation::RunResult> {
        let mut sim = Simulation::from_case(py, self, dt)?;
        sim.run_with(
            py,
            RunOptions {
                end,
                steps,
                record_every,
                nodes,
                elements,
                callback,
                callback_every,
                threads,
                free_field,
            },
        )
    }

    fn __repr__(&self) -> String {
        format!(
            "Case({:?}: {} nodes, {} elements, dt = {:.4e} s, end = {} s)",
            self.label,
            self.inner.model.mesh.n_nodes(),
            self.inner.model.n_elements(),
            self.inner.dt,
            self.inner.end
        )
    }

    /// The case's `[output]` settings as a dict (nodes, elements, ...).
    #[getter]
    fn output<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let o = &self.inner.output;
        let d = PyDict::new(py);
        d.set_item("nodes", o.nodes.clone())?;
        d.set_item("elements", o.elements.clone())?;
        d.set_item("history_every", o.history_every)?;
        d.set_item("vtu_every", o.vtu_every)?;
        d.set_item("damage_threshold", o.damage_threshold)?;
        Ok(d)
    }
}

impl Case {
    /// The built case (model, settings).
    pub fn inner(&self) -> &dcfm::case::Case {
        &self.inner
    }
}

/// (n, 8) integer connectivity.
pub fn connectivity<'py>(py: Python<'py>, elements: &[[u32; 8]]) -> Bound<'py, PyAny> {
    let flat: Vec<i64> = elements.iter().flatten().map(|&n| n as i64).collect();
    matrix(py, elements.len(), 8, flat).into_any()
}
