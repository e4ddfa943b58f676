//! `[anchors]`: anchor bars given as lines (`[[anchors.bars]]`), as patterns over a face
//! set (`[[anchors.patterns]]`) or as reinforcement mats under one (`[[anchors.mats]]`),
//! superposed on their host elements; their steel mass goes
//! to the host nodes and their stiffness into the critical step.

use crate::element::anchor_bar::{AnchorBars, AnchorSection, BarNames, SteelSpec};
use crate::element::anchor_mat::mat_bars;
use crate::element::anchor_pattern::pattern_points;
use crate::element::host_locate::HostLocator;
use crate::error::{DcfmError, Result};
use crate::mesh::{Face, Mesh};
use crate::model::Model;

fn check_steel(steel: &SteelSpec, field: &str, label: &str) -> Result<()> {
    let positive = |name: &str, v: f64, unit: &str, hi: f64| {
        if !(v.is_finite() && v > 0.0 && v < hi) {
            Err(DcfmError::invalid(
                label,
                format!("{field}.{name}"),
                v,
                format!("must be > 0 and < {hi:e} ({unit})"),
            ))
        } else {
            Ok(())
        }
    };
    positive("diameter", steel.diameter, "m", 1.0)?;
    positive("young", steel.young, "Pa", 1e13)?;
    positive("yield_stress", steel.yield_stress, "Pa", 1e10)?;
    positive("density", steel.density, "kg/m³", 1e5)?;
    if !(steel.pretension.is_finite() && steel.pretension >= 0.0) {
        return Err(DcfmError::invalid(
            label,
            format!("{field}.pretension"),
            steel.pretension,
            "must be ≥ 0 (N)",
        ));
    }
    if let Some(k) = steel.bond_stiffness {
        positive("bond_stiffness", k, "N/m per m", 1e16)?;
    }
    if let Some(l) = steel.segment_length {
        positive("segment_length", l, "m", 1e4)?;
    }
    Ok(())
}

/// Every named length (m) finite, > 0 and < 10 km, or an error naming the field.
fn positive_lengths(lengths: &[(&str, f64)], field: &str, label: &str) -> Result<()> {
    for &(name, v) in lengths {
        if !(v.is_finite() && v > 0.0 && v < 1e4) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.{name}"),
                v,
                "must be > 0 (m)",
            ));
        }
    }
    Ok(())
}

/// The faces of `name`, or an error listing the mesh's face sets.
fn face_set<'m>(mesh: &'m Mesh, name: &str, field: &str, label: &str) -> Result<&'m [Face]> {
    mesh.face_sets.get(name).map(Vec::as_slice).ok_or_else(|| {
        DcfmError::invalid(
            label,
            format!("{field}.face_set"),
            name,
            format!(
                "a face set of the mesh (face sets: {:?})",
                mesh.face_sets.keys().collect::<Vec<_>>()
            ),
        )
    })
}

/// Build the bars of `[anchors]` into the model. `active`: the elements active when the
/// bars are installed (at the start of the seismic stage,
/// [`super::static_stage::active_at_installation`]); a bar point is hosted by the
/// lowest-numbered of them that holds it (docs/anchors.md, "Host elements").
pub(super) fn build_anchors(
    model: &mut Model,
    section: &AnchorSection,
    active: Vec<bool>,
    label: &str,
) -> Result<()> {
    if section.bars.is_empty() && section.patterns.is_empty() && section.mats.is_empty() {
        return Ok(());
    }
    let mesh = &model.mesh;
    let locator = HostLocator::with_eligible(mesh, active);
    let mut bars = AnchorBars::default();
    for (i, b) in section.bars.iter().enumerate() {
        let field = format!("anchors.bars[{i}]");
        check_steel(&b.steel, &field, label)?;
        if b.start.iter().chain(&b.end).any(|v| !v.is_finite()) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.start"),
                format!("{:?} → {:?}", b.start, b.end),
                "finite points (m)",
            ));
        }
        let name = b.name.clone().unwrap_or_else(|| format!("bar{i}"));
        let names = BarNames {
            name: name.clone(),
            group: name,
        };
        bars.add_bar(mesh, &locator, names, [b.start, b.end], &b.steel)
            .map_err(|msg| {
                DcfmError::invalid(label, field, format!("{:?} → {:?}", b.start, b.end), msg)
            })?;
    }
    for (i, p) in section.patterns.iter().enumerate() {
        let field = format!("anchors.patterns[{i}]");
        check_steel(&p.steel, &field, label)?;
        positive_lengths(
            &[("length", p.length), ("spacing", p.spacing)],
            &field,
            label,
        )?;
        if !(p.depth.is_finite() && p.depth >= 0.0) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.depth"),
                p.depth,
                "a depth ≥ 0 (m) of the bars' start below the face",
            ));
        }
        let faces = face_set(mesh, &p.face_set, &field, label)?;
        let group = p.name.clone().unwrap_or_else(|| format!("pattern{i}"));
        for (k, (face_point, dir)) in pattern_points(mesh, faces, p.spacing)
            .into_iter()
            .enumerate()
        {
            let start: [f64; 3] = std::array::from_fn(|d| face_point[d] + p.depth * dir[d]);
            let end: [f64; 3] = std::array::from_fn(|d| start[d] + p.length * dir[d]);
            let names = BarNames {
                name: format!("{group}.{k}"),
                group: group.clone(),
            };
            bars.add_bar(mesh, &locator, names, [start, end], &p.steel)
                .map_err(|msg| {
                    DcfmError::invalid(label, field.clone(), format!("bar {k} from {start:?}"), msg)
                })?;
        }
    }
    for (i, m) in section.mats.iter().enumerate() {
        let field = format!("anchors.mats[{i}]");
        check_steel(&m.steel, &field, label)?;
        positive_lengths(&[("cover", m.cover), ("spacing", m.spacing)], &field, label)?;
        let faces = face_set(mesh, &m.face_set, &field, label)?;
        let group = m.name.clone().unwrap_or_else(|| format!("mat{i}"));
        let lines = mat_bars(mesh, faces, m.cover, m.spacing).map_err(|msg| {
            DcfmError::invalid(label, format!("{field}.face_set"), &m.face_set, msg)
        })?;
        for (k, [start, end]) in lines.into_iter().enumerate() {
            let names = BarNames {
                name: format!("{group}.{k}"),
                group: group.clone(),
            };
            bars.add_bar(mesh, &locator, names, [start, end], &m.steel)
                .map_err(|msg| {
                    DcfmError::invalid(
                        label,
                        field.clone(),
                        format!("bar {k} from {start:?} to {end:?} (cover {} m)", m.cover),
                        msg,
                    )
                })?;
        }
    }
    bars.finish();
    bars.add_host_masses(&model.mesh, &mut model.mass);
    for (w, m) in model.inv_mass.iter_mut().zip(&model.mass) {
        *w = 1.0 / m;
    }
    let omega2 = bars.omega_squared_bound(&model.mesh, &model.mass);
    model.include_extra_stiffness(omega2);
    model.anchors = Some(bars);
    Ok(())
}
