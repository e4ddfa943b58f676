//! `[boundary]` and `[seismic]`: fixed DOFs, prescribed motions, absorbing and free-field
//! boundaries and the seismic input through them.

use std::collections::BTreeMap;

use crate::boundary::{BoundaryInputs, BoundarySystem, Prescribed};
use crate::case::schema::{BoundarySection, CaseFile};
use crate::error::{DcfmError, Result};
use crate::material::Material;
use crate::model::Model;

use super::checks::{dof_mask, nodes_of};

/// Fixed DOFs and prescribed motions of `[boundary]` into the model's constraints.
pub(super) fn build_boundary(
    model: &mut Model,
    section: &BoundarySection,
    label: &str,
) -> Result<()> {
    for (k, f) in section.fixed.iter().enumerate() {
        let mask = dof_mask(label, &format!("boundary.fixed[{k}].dofs"), &f.dofs)?;
        let nodes = nodes_of(
            &model.mesh,
            label,
            &format!("boundary.fixed[{k}].set"),
            &f.set,
        )?;
        model.constraints.fix(&nodes, mask);
    }
    for (k, p) in section.prescribed.iter().enumerate() {
        let field = format!("boundary.prescribed[{k}]");
        let mask = dof_mask(label, &format!("{field}.dof"), &p.dof)?;
        if mask.count_ones() != 1 {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.dof"),
                format!("\"{}\"", p.dof),
                "exactly one of x, y, z",
            ));
        }
        p.history.validate(label, &format!("{field}.history"))?;
        let nodes = nodes_of(&model.mesh, label, &format!("{field}.set"), &p.set)?;
        model
            .constraints
            .prescribe(Prescribed {
                nodes,
                dof: mask.trailing_zeros() as usize,
                kind: p.kind,
                history: p.history.clone(),
            })
            .map_err(|n| {
                DcfmError::invalid(
                    label,
                    format!("{field}.set"),
                    &p.set,
                    format!("node {n} already has this DOF fixed or prescribed"),
                )
            })?;
    }
    Ok(())
}

/// Absorbing and free-field boundaries and the seismic input (after the constraints and
/// the damping, which the boundaries' per-node updates use).
pub(super) fn build_absorbing(
    model: &mut Model,
    file: &CaseFile,
    materials: &BTreeMap<String, Material>,
    label: &str,
) -> Result<()> {
    let inputs = BoundaryInputs {
        absorbing: &file.boundary.absorbing,
        free_field: file.boundary.free_field.as_ref(),
        seismic: file.seismic.as_ref(),
        materials,
    };
    model.boundaries = BoundarySystem::build(model, &inputs, label)?;
    Ok(())
}
