//! `[output]`: probes, damage measure and output intervals.

use crate::case::schema::OutputSection;
use crate::error::{DcfmError, Result};
use crate::model::Model;

/// Check `[output]` against the model (probe ids in range, threshold, intervals).
pub(super) fn check_output(model: &Model, section: &OutputSection, label: &str) -> Result<()> {
    for (k, &n) in section.nodes.iter().enumerate() {
        if n as usize >= model.mesh.n_nodes() {
            return Err(DcfmError::invalid(
                label,
                format!("output.nodes[{k}]"),
                n,
                format!("a node id below {}", model.mesh.n_nodes()),
            ));
        }
    }
    for (k, &e) in section.elements.iter().enumerate() {
        if e as usize >= model.n_elements() {
            return Err(DcfmError::invalid(
                label,
                format!("output.elements[{k}]"),
                e,
                format!("an element id below {}", model.n_elements()),
            ));
        }
    }
    let thr = section.damage_threshold;
    if !(thr.is_finite() && thr > 0.0 && thr < 1.0) {
        return Err(DcfmError::invalid(
            label,
            "output.damage_threshold",
            thr,
            "must be in (0, 1)",
        ));
    }
    // Compact frames (yingxiuwan branch): their sets must exist.
    if let Some(f) = &section.frames {
        if f.regions.is_empty() {
            return Err(DcfmError::invalid(
                label,
                "output.frames.regions",
                "[]",
                "at least one region or element set",
            ));
        }
        for (k, r) in f.regions.iter().enumerate() {
            if model.mesh.region_index(r).is_none() && !model.mesh.element_sets.contains_key(r) {
                return Err(DcfmError::invalid(
                    label,
                    format!("output.frames.regions[{k}]"),
                    r,
                    format!(
                        "a region or element set (regions: {:?})",
                        model.mesh.region_names
                    ),
                ));
            }
        }
    }
    if section.history_every == 0 {
        return Err(DcfmError::invalid(
            label,
            "output.history_every",
            0,
            "at least 1 (steps)",
        ));
    }
    Ok(())
}
