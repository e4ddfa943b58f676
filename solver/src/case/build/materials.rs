//! `[materials]` and `[[regions]]`: the constitutive models and how each mesh region is
//! discretised; the plastic-damage element-size limit.

use std::collections::BTreeMap;

use crate::case::schema::{MaterialSection, ModelKind, RegionSection};
use crate::element::Integration;
use crate::error::{DcfmError, Result};
use crate::material::{Elastic, Material, PlasticDamage};
use crate::model::{Model, RegionSetup};

/// Every `[materials.NAME]` table as a validated [`Material`]; errors name
/// `materials.NAME.FIELD` in file `label` (also what the Python module's material-point
/// driver calls, so its errors read as the case file's).
pub fn build_materials(
    section: &BTreeMap<String, MaterialSection>,
    label: &str,
) -> Result<BTreeMap<String, Material>> {
    let mut materials = BTreeMap::new();
    for (name, m) in section {
        let field = format!("materials.{name}");
        super::plausibility::check_material_limits(name, m, label)?;
        let elastic = Elastic::new(name, m.young, m.poisson, m.density).map_err(|e| match e {
            DcfmError::Material { message, .. } => {
                let (key, rest) = message.split_once(" = ").unwrap_or(("", &message));
                let (value, expected) = rest.split_once(": ").unwrap_or((rest, ""));
                DcfmError::invalid(label, format!("{field}.{key}"), value, expected)
            }
            other => other,
        })?;
        let material = match m.model {
            ModelKind::Elastic => {
                if m.plastic_damage.is_some() {
                    return Err(DcfmError::invalid(
                        label,
                        format!("{field}.plastic_damage"),
                        "given",
                        "only with model = \"plastic_damage\"",
                    ));
                }
                Material::Elastic(elastic)
            }
            ModelKind::PlasticDamage => {
                let Some(p) = &m.plastic_damage else {
                    return Err(DcfmError::invalid(
                        label,
                        format!("{field}.plastic_damage"),
                        "missing",
                        "a [materials.NAME.plastic_damage] table",
                    ));
                };
                Material::PlasticDamage(Box::new(PlasticDamage::new(name, elastic, p).map_err(
                    |e| match e {
                        DcfmError::Material { material, message } => DcfmError::invalid(
                            label,
                            format!("materials.{material}.plastic_damage"),
                            "",
                            message,
                        ),
                        other => other,
                    },
                )?))
            }
        };
        materials.insert(name.clone(), material);
    }
    Ok(materials)
}

/// Every `[[regions]]` entry with its material resolved.
pub(super) fn build_regions(
    section: &[RegionSection],
    materials: &BTreeMap<String, Material>,
    label: &str,
) -> Result<Vec<RegionSetup>> {
    let mut setups = Vec::new();
    for (ri, r) in section.iter().enumerate() {
        if let Some(first) = section[..ri].iter().position(|q| q.name == r.name) {
            return Err(DcfmError::invalid(
                label,
                format!("regions[{ri}].name"),
                format!("\"{}\"", r.name),
                format!("a region named once (regions[{first}] has that name already)"),
            ));
        }
        let Some(material) = materials.get(&r.material) else {
            return Err(DcfmError::invalid(
                label,
                format!("regions[{ri}].material"),
                format!("\"{}\"", r.material),
                format!(
                    "one of the [materials] tables: {:?}",
                    materials.keys().collect::<Vec<_>>()
                ),
            ));
        };
        if r.integration == Integration::OnePoint
            && !(r.hourglass.is_finite() && (0.0..=0.5).contains(&r.hourglass))
        {
            return Err(DcfmError::invalid(
                label,
                format!("regions[{ri}].hourglass"),
                r.hourglass,
                "must be in [0, 0.5]",
            ));
        }
        setups.push(RegionSetup {
            region: r.name.clone(),
            material: material.clone(),
            integration: r.integration,
            hourglass: r.hourglass,
        });
    }
    Ok(setups)
}

/// Plastic-damage regions: no element larger than the material's fracture energy allows
/// (snap-back).
pub(super) fn check_element_sizes(model: &Model, label: &str) -> Result<()> {
    for g in &model.groups {
        if let Material::PlasticDamage(p) = &g.material {
            let limit = p.max_element_size();
            if let Some((le, &l)) = g.char_length.iter().enumerate().find(|(_, &l)| l > limit) {
                return Err(DcfmError::invalid(
                    label,
                    format!("regions.{}", g.name),
                    format!("element {} of size {l:.3} m", g.elements[le]),
                    format!("the material's fracture energy allows elements up to {limit:.3} m (snap-back); refine the mesh or raise the fracture energy"),
                ));
            }
        }
    }
    Ok(())
}
