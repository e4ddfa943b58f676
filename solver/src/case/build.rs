//! From the parsed case file to a validated [`Model`], with field paths in every error.

use std::path::{Path, PathBuf};

use crate::boundary::Prescribed;
use crate::case::schema::*;
use crate::element::Integration;
use crate::error::{DcfmError, Result};
use crate::load::{Gravity, NodalLoad, TimeFunction};
use crate::material::{Elastic, Material, PlasticDamage};
use crate::mesh::Mesh;
use crate::model::{Model, Rayleigh, RegionSetup};

/// A loaded case: the model and the run settings.
#[derive(Debug)]
pub struct Case {
    /// Path of the case file.
    pub file: PathBuf,
    pub title: String,
    pub model: Model,
    /// Time step (s), checked against the stable step.
    pub dt: f64,
    /// End time (s).
    pub end: f64,
    pub safety: f64,
    pub output: OutputSection,
}

/// Read, parse and build a case file.
pub fn load_case(path: &Path) -> Result<Case> {
    let label = path.display().to_string();
    let text = std::fs::read_to_string(path).map_err(|e| DcfmError::io(&label, e))?;
    parse_case(&text, &label, path.parent().unwrap_or(Path::new(".")))
}

/// Parse and build a case from its text; `label` names it in errors, `dir` resolves
/// relative paths (the Gmsh file).
pub fn parse_case(text: &str, label: &str, dir: &Path) -> Result<Case> {
    let file: CaseFile = toml::from_str(text).map_err(|e| DcfmError::Parse {
        file: label.to_string(),
        message: e.to_string().trim_end().to_string(),
    })?;
    build(file, label, dir)
}

fn finite_positive(label: &str, field: &str, v: f64, what: &str) -> Result<()> {
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

fn dof_mask(label: &str, field: &str, dofs: &str) -> Result<u8> {
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

fn nodes_of(mesh: &Mesh, label: &str, field: &str, set: &str) -> Result<Vec<u32>> {
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

fn build(file: CaseFile, label: &str, dir: &Path) -> Result<Case> {
    // Time.
    finite_positive(label, "time.end", file.time.end, "s")?;
    if !(file.time.safety.is_finite() && file.time.safety > 0.0 && file.time.safety <= 1.0) {
        return Err(DcfmError::invalid(
            label,
            "time.safety",
            file.time.safety,
            "must be in (0, 1]",
        ));
    }
    if let Some(dt) = file.time.dt {
        finite_positive(label, "time.dt", dt, "s")?;
    }
    // Mesh.
    let mut mesh = match (&file.mesh.gmsh, file.mesh.blocks.is_empty()) {
        (Some(_), false) => {
            return Err(DcfmError::invalid(
                label,
                "mesh",
                "gmsh and blocks",
                "either a gmsh file or blocks, not both",
            ))
        }
        (None, true) => {
            return Err(DcfmError::invalid(
                label,
                "mesh",
                "{}",
                "a gmsh file (mesh.gmsh) or [[mesh.blocks]]",
            ))
        }
        (Some(g), true) => {
            let path = dir.join(g);
            let mut mesh = crate::mesh::gmsh::read_gmsh(&path)?;
            for (si, [a, b]) in file.mesh.split.iter().enumerate() {
                crate::mesh::box_generator::split_between_regions(&mut mesh, a, b).map_err(
                    |msg| {
                        DcfmError::invalid(
                            label,
                            format!("mesh.split[{si}]"),
                            format!("[{a}, {b}]"),
                            msg,
                        )
                    },
                )?;
            }
            mesh
        }
        (None, false) => file.mesh.box_spec().build(label)?,
    };
    // Extra node sets.
    for (name, s) in &file.node_sets {
        let field = format!("node_sets.{name}");
        let mut nodes = s.nodes.clone();
        if let Some(&bad) = nodes.iter().find(|&&n| n as usize >= mesh.n_nodes()) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.nodes"),
                bad,
                format!("node ids below {}", mesh.n_nodes()),
            ));
        }
        if let Some([lo, hi]) = s.bounds {
            for d in 0..3 {
                if !(lo[d].is_finite() && hi[d].is_finite() && lo[d] <= hi[d]) {
                    return Err(DcfmError::invalid(
                        label,
                        format!("{field}.box"),
                        format!("{lo:?}..{hi:?}"),
                        "finite corners with min ≤ max",
                    ));
                }
            }
            let slack = 1e-9;
            for (i, x) in mesh.coords.iter().enumerate() {
                if (0..3).all(|d| x[d] >= lo[d] - slack && x[d] <= hi[d] + slack) {
                    nodes.push(i as u32);
                }
            }
        }
        nodes.sort_unstable();
        nodes.dedup();
        if nodes.is_empty() {
            return Err(DcfmError::invalid(
                label,
                field,
                "[]",
                "at least one node (nodes = [...] or box = [[..],[..]])",
            ));
        }
        mesh.node_sets.insert(name.clone(), nodes);
    }
    // Materials.
    let mut materials = std::collections::BTreeMap::new();
    for (name, m) in &file.materials {
        let field = format!("materials.{name}");
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
    // Regions.
    let mut setups = Vec::new();
    for (ri, r) in file.regions.iter().enumerate() {
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
    let mut model = Model::new(mesh, &setups, label)?;
    // Plastic-damage snap-back limit per element.
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
    // Contact interfaces.
    if !file.interfaces.is_empty() {
        let system = crate::contact::ContactSystem::new(&model.mesh, &file.interfaces, label)?;
        model.contact = Some(system);
    }
    // Boundary conditions.
    for (k, f) in file.boundary.fixed.iter().enumerate() {
        let mask = dof_mask(label, &format!("boundary.fixed[{k}].dofs"), &f.dofs)?;
        let nodes = nodes_of(
            &model.mesh,
            label,
            &format!("boundary.fixed[{k}].set"),
            &f.set,
        )?;
        model.constraints.fix(&nodes, mask);
    }
    for (k, p) in file.boundary.prescribed.iter().enumerate() {
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
    // Loads.
    let unit = TimeFunction::Constant { value: 1.0 };
    for (k, l) in file.loads.nodal.iter().enumerate() {
        let field = format!("loads.nodal[{k}]");
        if !l.force.iter().all(|f| f.is_finite()) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.force"),
                format!("{:?}", l.force),
                "finite components (N)",
            ));
        }
        let history = l.history.clone().unwrap_or(unit.clone());
        history.validate(label, &format!("{field}.history"))?;
        let nodes = nodes_of(&model.mesh, label, &format!("{field}.set"), &l.set)?;
        model.nodal_loads.push(NodalLoad {
            nodes,
            force: l.force,
            history,
        });
    }
    if let Some(g) = &file.loads.gravity {
        if !g.acceleration.iter().all(|a| a.is_finite()) {
            return Err(DcfmError::invalid(
                label,
                "loads.gravity.acceleration",
                format!("{:?}", g.acceleration),
                "finite components (m/s²)",
            ));
        }
        let history = g.history.clone().unwrap_or(unit.clone());
        history.validate(label, "loads.gravity.history")?;
        model.gravity = Some(Gravity {
            acceleration: g.acceleration,
            history,
        });
    }
    // Damping.
    for (name, v) in [("alpha", file.damping.alpha), ("beta", file.damping.beta)] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(DcfmError::invalid(
                label,
                format!("damping.{name}"),
                v,
                "must be finite and ≥ 0",
            ));
        }
    }
    model.damping = Rayleigh {
        alpha: file.damping.alpha,
        beta: file.damping.beta,
    };
    // Initial velocities.
    for (k, iv) in file.initial.velocity.iter().enumerate() {
        if !iv.value.iter().all(|v| v.is_finite()) {
            return Err(DcfmError::invalid(
                label,
                format!("initial.velocity[{k}].value"),
                format!("{:?}", iv.value),
                "finite components (m/s)",
            ));
        }
        let nodes = nodes_of(
            &model.mesh,
            label,
            &format!("initial.velocity[{k}].set"),
            &iv.set,
        )?;
        model.initial_velocity.push((nodes, iv.value));
    }
    // Outputs.
    for (k, &n) in file.output.nodes.iter().enumerate() {
        if n as usize >= model.mesh.n_nodes() {
            return Err(DcfmError::invalid(
                label,
                format!("output.nodes[{k}]"),
                n,
                format!("a node id below {}", model.mesh.n_nodes()),
            ));
        }
    }
    for (k, &e) in file.output.elements.iter().enumerate() {
        if e as usize >= model.n_elements() {
            return Err(DcfmError::invalid(
                label,
                format!("output.elements[{k}]"),
                e,
                format!("an element id below {}", model.n_elements()),
            ));
        }
    }
    let thr = file.output.damage_threshold;
    if !(thr.is_finite() && thr > 0.0 && thr < 1.0) {
        return Err(DcfmError::invalid(
            label,
            "output.damage_threshold",
            thr,
            "must be in (0, 1)",
        ));
    }
    if file.output.history_every == 0 {
        return Err(DcfmError::invalid(
            label,
            "output.history_every",
            0,
            "at least 1 (steps)",
        ));
    }
    // Time step.
    let stable = file.time.safety * model.critical_step_with_damping();
    let dt = file.time.dt.unwrap_or(stable);
    if dt > stable * (1.0 + 1e-12) {
        return Err(DcfmError::TimeStepTooLarge {
            requested: dt,
            stable,
            element: model.stable.element,
            length: model.stable.length,
            speed: model.stable.speed,
        });
    }
    Ok(Case {
        file: PathBuf::from(label),
        title: file.title,
        model,
        dt,
        end: file.time.end,
        safety: file.time.safety,
        output: file.output,
    })
}
