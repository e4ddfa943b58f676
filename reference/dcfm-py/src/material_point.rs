//! `dcfm.material_point`: one integration point of any material driven along a strain
//! path — the element kernels' `Material::update`, step by step.

use std::collections::BTreeMap;

use pyo3::prelude::*;
use pyo3::types::PyDict;

use crate::arrays::{f64_array, matrix, vector};
use crate::errors::{to_py, IntoPy};
use crate::toml_value::{dict_to_table, table_to_toml};

/// Drive one point of `material` (a dict with the keys of a `[materials.NAME]` table:
/// model, young, poisson, density and, for "plastic_damage", a `plastic_damage`
/// sub-dict) through the total strains `strain` ((k, 6), Voigt xx, yy, zz, xy, yz, zx,
/// engineering shear, tension positive), one update per row from the virgin state.
/// `char_length` is the element's characteristic length (m, crack band regularisation);
/// `dt` the time per increment (s, Duvaut–Lions viscosity; 0 = rate independent).
/// Errors name `materials.NAME.FIELD` in `<material_point>` as a case file would.
///
/// Returns a dict of arrays: stress (k, 6) in Pa; damage, damage_tension,
/// damage_compression, kappa_tension, kappa_compression (k,); plastic_strain (k, 6)
/// (zeros for a model without damage).
#[pyfunction]
#[pyo3(signature = (material, strain, *, char_length = 1.0, dt = 0.0, name = "material".to_string()))]
pub fn material_point<'py>(
    py: Python<'py>,
    material: &Bound<'py, PyAny>,
    strain: &Bound<'py, PyAny>,
    char_length: f64,
    dt: f64,
    name: String,
) -> PyResult<Bound<'py, PyDict>> {
    let label = "<material_point>";
    if !(char_length.is_finite() && char_length > 0.0) {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "char_length: {char_length} must be a finite length > 0 (m)"
        )));
    }
    if !(dt.is_finite() && dt >= 0.0) {
        return Err(pyo3::exceptions::PyValueError::new_err(format!(
            "dt: {dt} must be finite and ≥ 0 (s)"
        )));
    }
    let (eps, shape) = f64_array(strain, "strain", &[None, Some(6)])?;
    let mut materials = toml::Table::new();
    materials.insert(
        name.clone(),
        toml::Value::Table(dict_to_table(material, "material")?),
    );
    let mut doc = toml::Table::new();
    doc.insert("materials".into(), toml::Value::Table(materials));
    let text = table_to_toml(&doc, "material")?;
    #[derive(serde::Deserialize)]
    struct Doc {
        materials: BTreeMap<String, dcfm::case::MaterialSection>,
    }
    let doc: Doc = toml::from_str(&text).map_err(|e| {
        to_py(dcfm::DcfmError::Parse {
            file: label.into(),
            message: e.to_string().trim_end().to_string(),
        })
    })?;
    let materials = dcfm::case::build_materials(&doc.materials, label).py_err()?;
    let m = materials.get(&name).expect("the one material");
    if let dcfm::material::Material::PlasticDamage(p) = m {
        p.check_char_length(char_length).py_err()?;
    }
    let k = shape[0];
    let len = m.state_len();
    let mut old = vec![0.0; len];
    let mut new = vec![0.0; len];
    m.init_state(&mut old);
    // D is read from the state after each update (formed on demand under the consistent
    // rule: the same value as storing it).
    let ctx = dcfm::material::PointContext {
        char_length,
        dt,
        reads_damage: false,
    };
    let mut stress = Vec::with_capacity(6 * k);
    let mut dmg: [Vec<f64>; 5] = Default::default();
    let mut plastic = Vec::with_capacity(6 * k);
    for row in eps.chunks_exact(6) {
        let e: [f64; 6] = std::array::from_fn(|i| row[i]);
        new.copy_from_slice(&old);
        let s = m.update(&e, &old, &mut new, &ctx);
        std::mem::swap(&mut old, &mut new);
        stress.extend(s);
        let d = m.damage_state(&old).unwrap_or_default();
        for (v, x) in dmg.iter_mut().zip([d.d, d.dt, d.dc, d.kappa_t, d.kappa_c]) {
            v.push(x);
        }
        plastic.extend(d.plastic_strain);
    }
    let out = PyDict::new(py);
    out.set_item("stress", matrix(py, k, 6, stress))?;
    let [d, d_t, d_c, k_t, k_c] = dmg;
    out.set_item("damage", vector(py, d))?;
    out.set_item("damage_tension", vector(py, d_t))?;
    out.set_item("damage_compression", vector(py, d_c))?;
    out.set_item("kappa_tension", vector(py, k_t))?;
    out.set_item("kappa_compression", vector(py, k_c))?;
    out.set_item("plastic_strain", matrix(py, k, 6, plastic))?;
    Ok(out)
}
