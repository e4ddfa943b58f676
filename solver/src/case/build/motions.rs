//! `[motions.NAME]`: read or generate every ground motion, then resolve every time
//! function of the case that names one (`{ type = "motion", motion = "NAME", … }`).
//!
//! A new case section holding time functions adds its own to
//! [`resolve_time_functions`] so that they can use motions too.

use std::path::Path;

use crate::case::schema::CaseFile;
use crate::error::{DcfmError, Result};
use crate::motion::{load_motions, Motions};

/// Load the motions, add those the caller made (`given`; a name the case defines too is
/// an error), and resolve the time functions that use them.
pub(super) fn build_motions(
    file: &mut CaseFile,
    label: &str,
    dir: &Path,
    given: &Motions,
) -> Result<Motions> {
    let mut motions = load_motions(&file.motions, label, dir)?;
    for (name, m) in given {
        if motions.contains_key(name) {
            return Err(DcfmError::invalid(
                label,
                format!("motions.{name}"),
                "defined in the case",
                "a name not also given by the caller (rename one of the two motions)",
            ));
        }
        motions.insert(name.clone(), m.clone());
    }
    resolve_time_functions(file, &motions, label)?;
    Ok(motions)
}

/// Every time function of the case, with its field path, resolved against `motions`.
fn resolve_time_functions(file: &mut CaseFile, motions: &Motions, label: &str) -> Result<()> {
    for (k, p) in file.boundary.prescribed.iter_mut().enumerate() {
        p.history
            .resolve_motions(motions, label, &format!("boundary.prescribed[{k}].history"))?;
    }
    for (k, l) in file.loads.nodal.iter_mut().enumerate() {
        if let Some(h) = &mut l.history {
            h.resolve_motions(motions, label, &format!("loads.nodal[{k}].history"))?;
        }
    }
    if let Some(g) = &mut file.loads.gravity {
        if let Some(h) = &mut g.history {
            h.resolve_motions(motions, label, "loads.gravity.history")?;
        }
    }
    if let Some(s) = &mut file.seismic {
        for (axis, c) in [("x", &mut s.x), ("y", &mut s.y), ("z", &mut s.z)] {
            if let Some(h) = c {
                h.resolve_motions(motions, label, &format!("seismic.{axis}"))?;
            }
        }
    }
    Ok(())
}
