//! `dcfm.box_mesh`: structured hex8 blocks (the case file's `[[mesh.blocks]]`) as a
//! `dcfm.Mesh` with numpy coordinates, connectivity and sets.

use std::collections::BTreeMap;

use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};

use crate::arrays::{index_vector, matrix, nodes3};
use crate::case::connectivity;
use crate::errors::{to_py, IntoPy};
use crate::toml_value::to_value;

const LABEL: &str = "<box_mesh>";

/// A hex8 mesh: coordinates, connectivity, regions and named sets.
#[pyclass(module = "dcfm", name = "Mesh", frozen)]
pub struct Mesh {
    inner: dcfm::mesh::Mesh,
}

#[pymethods]
impl Mesh {
    #[getter]
    fn n_nodes(&self) -> usize {
        self.inner.n_nodes()
    }

    #[getter]
    fn n_elements(&self) -> usize {
        self.inner.n_elements()
    }

    /// Node coordinates, (n_nodes, 3) (m).
    #[getter]
    fn coords<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        nodes3(py, &self.inner.coords).into_any()
    }

    /// Connectivity, (n_elements, 8), VTK/Gmsh hex8 order.
    #[getter]
    fn elements<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        connectivity(py, &self.inner.elements)
    }

    /// Region index of every element.
    #[getter]
    fn element_region<'py>(&self, py: Python<'py>) -> Bound<'py, PyAny> {
        index_vector(
            py,
            self.inner
                .element_region
                .iter()
                .map(|&r| r as i64)
                .collect(),
        )
        .into_any()
    }

    #[getter]
    fn region_names(&self) -> Vec<String> {
        self.inner.region_names.clone()
    }

    /// Node sets: name → node ids.
    #[getter]
    fn node_sets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        ids_dict(py, &self.inner.node_sets)
    }

    /// Element sets: name → element ids.
    #[getter]
    fn element_sets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        ids_dict(py, &self.inner.element_sets)
    }

    /// Face sets: name → (k, 2) array of (element, local face 0–5).
    #[getter]
    fn face_sets<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (name, faces) in &self.inner.face_sets {
            let flat: Vec<i64> = faces
                .iter()
                .flat_map(|f| [f.element as i64, f.local as i64])
                .collect();
            d.set_item(name, matrix(py, faces.len(), 2, flat))?;
        }
        Ok(d)
    }

    fn __repr__(&self) -> String {
        format!(
            "Mesh({} nodes, {} hex8 elements, regions {:?})",
            self.inner.n_nodes(),
            self.inner.n_elements(),
            self.inner.region_names
        )
    }
}

fn ids_dict<'py>(
    py: Python<'py>,
    sets: &BTreeMap<String, Vec<u32>>,
) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    for (name, ids) in sets {
        d.set_item(
            name,
            index_vector(py, ids.iter().map(|&i| i as i64).collect()),
        )?;
    }
    Ok(d)
}

/// Structured hex8 blocks merged into one mesh, as `[[mesh.blocks]]` of a case file:
/// `blocks` is a list of dicts (name, origin, size, divisions, and optionally region,
/// grading); `split` lists region pairs whose shared nodes are duplicated (contact
/// surfaces); `merge_tolerance` is relative to the smallest element length.
#[pyfunction]
#[pyo3(signature = (blocks, split = None, merge_tolerance = None))]
pub fn box_mesh(
    blocks: &Bound<'_, PyAny>,
    split: Option<&Bound<'_, PyAny>>,
    merge_tolerance: Option<f64>,
) -> PyResult<Mesh> {
    if blocks.cast::<PyList>().is_err() && blocks.cast::<pyo3::types::PyTuple>().is_err() {
        return Err(pyo3::exceptions::PyTypeError::new_err(
            "blocks: expected a list of dicts (name, origin, size, divisions[, region, grading])",
        ));
    }
    let mut table = toml::Table::new();
    table.insert("blocks".into(), to_value(blocks, "blocks")?);
    if let Some(s) = split {
        table.insert("split".into(), to_value(s, "split")?);
    }
    if let Some(t) = merge_tolerance {
        table.insert("merge_tolerance".into(), toml::Value::Float(t));
    }
    let text = toml::to_string(&table)
        .map_err(|e| pyo3::exceptions::PyTypeError::new_err(format!("blocks: {e}")))?;
    let spec: dcfm::mesh::BoxMeshSpec = toml::from_str(&text).map_err(|e| {
        to_py(dcfm::DcfmError::Parse {
            file: LABEL.into(),
            message: e.to_string().trim_end().to_string(),
        })
    })?;
    let inner = spec.build(LABEL).py_err()?;
    Ok(Mesh { inner })
}
