//! Small validators shared by the section builders: every failure names the file, the
//! field path, the value and what was expected.

use crate::error::{DcfmError, Result};
use crate::mesh::Mesh;

/// `v` must be finite and > 0.
pub(super) fn finite_positive(label: &str, field: &str, v: f64, what: &str) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(DcfmError::invalid(
            label,
            field,
            v,
            format!("must be finite and > 0 ({what})"),
        ))
    }
}

/// Every component of `v` must be finite.
pub(super) fn finite_components(label: &str, field: &str, v: &[f64; 3], unit: &str) -> Result<()> {
    if v.iter().all(|x| x.is_finite()) {
        Ok(())
    } else {
        Err(DcfmError::invalid(
            label,
            field,
            format!("{v:?}"),
            format!("finite components ({unit})"),
        ))
    }
}

/// DOF letters ("x", "yz", "xyz") as a bit mask x = 1, y = 2, z = 4.
pub(super) fn dof_mask(label: &str, field: &str, dofs: &str) -> Result<u8> {
    let mut mask = 0u8;
    if dofs.is_empty() {
        return Err(DcfmError::invalid(
            label,
            field,
            "\"\"",
            "one or more of x, y, z (e.g. \"xyz\")",
        ));
    }
    for ch in dofs.chars() {
        mask |= match ch {
            'x' => 1,
            'y' => 2,
            'z' => 4,
            _ => {
                return Err(DcfmError::invalid(
                    label,
                    field,
                    format!("\"{dofs}\""),
                    "only the letters x, y, z",
                ))
            }
        };
    }
    Ok(mask)
}

/// The nodes of a node, face or element set or a region; at least one.
pub(super) fn nodes_of(mesh: &Mesh, label: &str, field: &str, set: &str) -> Result<Vec<u32>> {
    match mesh.nodes_of(set) {
        Some(n) if !n.is_empty() => Ok(n),
        Some(_) => Err(DcfmError::invalid(
            label,
            field,
            format!("\"{set}\""),
            "a set with at least one node",
        )),
        None => Err(DcfmError::invalid(
            label,
            field,
            format!("\"{set}\""),
            format!(
                "a node, face or element set or a region; known: {}",
                mesh.set_names().join(", ")
            ),
        )),
    }
}
