//! The boundaries of a model assembled per node: absorbing dashpots and springs, and the
//! seismic input and free-field tractions that drive them. Per boundary node b the force
//! on the body at tⁿ is
//!
//! ```text
//! F_b = S_b − K_b (Uⁿ) − C_b Vⁿ,    Vⁿ = ½(V^{n−½} + V^{n+½})   (dashpot centred)
//! S_b = K_b U_static + Σ_drives (K u_ff + C v_ff + A σ_ff·n)
//! ```
//!
//! where the sum runs over the boundary contributions driven by the free field: the
//! equivalent nodal forces of the seismic input F = A (K u_ff + C v_ff + σ_ff·n) at the
//! base (docs/verification_references.md §W2), the coupling of the side walls and of a
//! buried top face (dashpots on the velocity relative to the free field plus its
//! traction). U_static, the static stage's displacement, is what the springs are measured
//! from; the reactions of the static supports that the boundaries replace stay on as
//! constant loads (`static_stage::add_hand_over_loads`), so a model with zero input stays
//! at rest in its static state.

use std::collections::BTreeMap;

use nalgebra::Matrix3;
use rayon::prelude::*;

use crate::boundary::absorbing::{AbsorbingKind, AbsorbingSpec, FaceCoefficients};
use crate::boundary::centred_dashpot::CentredDashpotNode;
use crate::boundary::face_tensors::face_node_integrals;
use crate::boundary::free_field::column::{Column, ColumnBase, ColumnElement};
use crate::boundary::free_field::sides::{
    build_side, SideContext, Sides, WallDashpotDrive, WallTractionDrive,
};
use crate::boundary::free_field::wall::stress_dot;
use crate::boundary::free_field::{ColumnSpec, FreeField, FreeFieldSection};
use crate::boundary::per_slot::PerSlot;
use crate::boundary::seismic_input::{MotionDefinition, SeismicSection};
use crate::error::{DcfmError, Result};
use crate::material::{Elastic, Material};
use crate::mesh::vertical_profile::{face_centroid, vertical_profile};
use crate::mesh::{Face, Mesh};
use crate::model::Model;

/// Boundary nodes per parallel task in [`BoundarySystem::begin_step`].
const SLOT_CHUNK: usize = 256;

/// Which traction of the reference column a drive takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Traction {
    /// The ground below the level (a base face, n = −z).
    Below,
    /// The part of the column above the level (a buried top face): Column::force_from_above.
    Above,
}

/// One boundary contribution driven by the reference column at one level.
#[derive(Clone, Copy, Debug)]
struct ColumnDrive {
    slot: u32,
    level: u32,
    spring: Matrix3<f64>,
    dashpot: Matrix3<f64>,
    /// ∫φ dA of the node on these faces (m²).
    area: f64,
    traction: Traction,
}

/// What `dcfm check` prints about one boundary.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryReport {
    /// Field path of the boundary in the case file.
    pub field: String,
    pub description: String,
}

/// The boundaries of a model.
#[derive(Clone, Debug)]
pub struct BoundarySystem {
    /// Boundary nodes (main-grid ids), sorted.
    pub nodes: Vec<u32>,
    /// Total dashpot matrix C_b per node (N·s/m).
    pub dashpot: Vec<Matrix3<f64>>,
    /// Total spring matrix K_b per node (N/m).
    pub spring: Vec<Matrix3<f64>>,
    /// Static displacement the springs are measured from.
    u_static: Vec<[f64; 3]>,
    /// K U_static.
    constant_source: Vec<[f64; 3]>,
    /// S_b of the current step.
    source: Vec<[f64; 3]>,
    /// The centred-dashpot update of each node (after [`BoundarySystem::prepare`]).
    updates: Vec<CentredDashpotNode>,
    drives: Vec<ColumnDrive>,
    wall_dashpots: Vec<WallDashpotDrive>,
    wall_tractions: Vec<WallTractionDrive>,
    /// `drives`, `wall_dashpots` and `wall_tractions` grouped by the slot they add to.
    drives_of: PerSlot,
    wall_dashpots_of: PerSlot,
    wall_tractions_of: PerSlot,
    free_field: Option<FreeField>,
    /// What each boundary is, for reports.
    pub reports: Vec<BoundaryReport>,
}

/// The case sections the boundaries are built from.
pub struct BoundaryInputs<'a> {
    pub absorbing: &'a [AbsorbingSpec],
    pub free_field: Option<&'a FreeFieldSection>,
    pub seismic: Option<&'a SeismicSection>,
    /// The case's materials by name (for `material =` and the overburden).
    pub materials: &'a BTreeMap<String, Material>,
}

/// Faces of the named face sets, each checked to lie on the outside.
fn outside_faces(
    mesh: &Mesh,
    names: &[&str],
    outer: &std::collections::HashSet<Face>,
    label: &str,
    field: &str,
) -> Result<Vec<Face>> {
    let mut faces = Vec::new();
    for name in names {
        let Some(set) = mesh.face_sets.get(*name) else {
            let known: Vec<&String> = mesh.face_sets.keys().collect();
            return Err(DcfmError::invalid(
                label,
                field,
                format!("\"{name}\""),
                format!("a face set of the mesh (face sets: {known:?})"),
            ));
        };
        if set.is_empty() {
            return Err(DcfmError::invalid(
                label,
                field,
                format!("\"{name}\""),
                "a face set with at least one face",
            ));
        }
        for &f in set {
            if !outer.contains(&f) {
                return Err(DcfmError::invalid(
                    label,
                    field,
                    format!("\"{name}\""),
                    format!(
                        "faces on the model's outside; element {} face {} is covered by another \
                         element (an inner face or a contact interface)",
                        f.element, f.local
                    ),
                ));
            }
        }
        faces.extend_from_slice(set);
    }
    faces.sort_unstable();
    faces.dedup();
    Ok(faces)
}

/// The unit normal at a face's centre and whether the face is plane and horizontal with
/// its outward normal along `sign` · z (within 1e-6).
fn horizontal(mesh: &Mesh, f: Face, sign: f64) -> bool {
    let x = mesh.face_nodes(f).map(|n| mesh.coords[n as usize]);
    let Some(ints) = face_node_integrals(&x) else {
        return false;
    };
    let a: nalgebra::Vector3<f64> = ints.iter().map(|k| k.area_vector).sum();
    let area: f64 = ints.iter().map(|k| k.area).sum();
    a[2] * sign >= (1.0 - 1e-6) * area
}

/// Mesh bounding box.
fn bounding_box(mesh: &Mesh) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for x in &mesh.coords {
        for d in 0..3 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    (lo, hi)
}

impl BoundarySystem {
    /// Build the boundaries of `model` from the case sections; `None` when the case has none.
    pub fn build(model: &Model, inputs: &BoundaryInputs, label: &str) -> Result<Option<Self>> {
        let has_top = inputs.free_field.is_some_and(|f| f.top.is_some());
        if inputs.absorbing.is_empty() && inputs.seismic.is_none() && !has_top {
            return Ok(None);
        }
        let mesh = &model.mesh;
        let outer: std::collections::HashSet<Face> = crate::mesh::outer_faces::outer_faces(mesh)
            .into_iter()
            .collect();
        let (lo, hi) = bounding_box(mesh);
        let size = (0..3)
            .map(|d| hi[d] - lo[d])
            .fold(0.0, f64::max)
            .max(1e-300);
        let centre: [f64; 3] = std::array::from_fn(|d| 0.5 * (lo[d] + hi[d]));
        let mut per_node: BTreeMap<u32, (Matrix3<f64>, Matrix3<f64>)> = BTreeMap::new();
        // Drives with the node id in `slot` until the boundary nodes are numbered.
        let mut drives: Vec<ColumnDrive> = Vec::new();
        let mut reports = Vec::new();
        let mut input_faces: Vec<Face> = Vec::new();
        for (k, spec) in inputs.absorbing.iter().enumerate() {
            let field = format!("boundary.absorbing[{k}]");
            let faces = outside_faces(
                mesh,
                &spec.set.names(),
                &outer,
                label,
                &format!("{field}.set"),
            )?;
            let far_field = match &spec.material {
                None => None,
                Some(name) => match inputs.materials.get(name) {
                    Some(m) => Some(*m.elastic()),
                    None => {
                        return Err(DcfmError::invalid(
                            label,
                            format!("{field}.material"),
                            format!("\"{name}\""),
                            format!(
                                "one of the [materials] tables: {:?}",
                                inputs.materials.keys().collect::<Vec<_>>()
                            ),
                        ))
                    }
                },
            };
            let springs = match spec.kind {
                AbsorbingKind::Dashpot => None,
                AbsorbingKind::ViscousSpring => {
                    for (name, v) in [("alpha_n", spec.alpha_n), ("alpha_t", spec.alpha_t)] {
                        if !(v.is_finite() && v > 0.0) {
                            return Err(DcfmError::invalid(
                                label,
                                format!("{field}.{name}"),
                                v,
                                "must be finite and > 0",
                            ));
                        }
                    }
                    if spec.distance.is_some() && spec.source.is_some() {
                        return Err(DcfmError::invalid(
                            label,
                            format!("{field}.distance"),
                            "given with source",
                            "either distance or source, not both",
                        ));
                    }
                    if let Some(r) = spec.distance {
                        if !(r.is_finite() && r > 0.0) {
                            return Err(DcfmError::invalid(
                                label,
                                format!("{field}.distance"),
                                r,
                                "must be finite and > 0 (m)",
                            ));
                        }
                    }
                    if let Some(s) = spec.source {
                        if !s.iter().all(|c| c.is_finite()) {
                            return Err(DcfmError::invalid(
                                label,
                                format!("{field}.source"),
                                format!("{s:?}"),
                                "finite coordinates (m)",
                            ));
                        }
                    }
                    Some((
                        spec.alpha_n,
                        spec.alpha_t,
                        spec.distance.unwrap_or(0.0),
                        spec.source.unwrap_or(centre),
                    ))
                }
            };
            for &f in &faces {
                let x = mesh.face_nodes(f).map(|n| mesh.coords[n as usize]);
                let Some(ints) = face_node_integrals(&x) else {
                    return Err(DcfmError::invalid(
                        label,
                        format!("{field}.set"),
                        format!("element {} face {}", f.element, f.local),
                        "a face of non-zero area",
                    ));
                };
                let material =
                    far_field.unwrap_or(*model.element_material(f.element as usize).elastic());
                let coef = FaceCoefficients::of(&material);
                for (j, &n) in mesh.face_nodes(f).iter().enumerate() {
                    let c = ints[j].matrix(coef.dashpot_normal, coef.dashpot_tangential);
                    let kmat = match springs {
                        None => Matrix3::zeros(),
                        Some((an, at, dist, src)) => {
                            let r = if dist > 0.0 {
                                dist
                            } else {
                                let p = mesh.coords[n as usize];
                                ((p[0] - src[0]).powi(2)
                                    + (p[1] - src[1]).powi(2)
                                    + (p[2] - src[2]).powi(2))
                                .sqrt()
                            };
                            if r <= 1e-9 * size {
                                return Err(DcfmError::invalid(
                                    label,
                                    format!("{field}.source"),
                                    format!("{:?}", src),
                                    format!("a point away from the boundary (node {n} lies on it)"),
                                ));
                            }
                            ints[j].matrix(an * coef.shear_modulus / r, at * coef.shear_modulus / r)
                        }
                    };
                    let e = per_node
                        .entry(n)
                        .or_insert((Matrix3::zeros(), Matrix3::zeros()));
                    e.0 += c;
                    e.1 += kmat;
                    if spec.input {
                        // The base's own K and C, driven by the free field at the base (level 0).
                        drives.push(ColumnDrive {
                            slot: n,
                            level: 0,
                            spring: kmat,
                            dashpot: c,
                            area: ints[j].area,
                            traction: Traction::Below,
                        });
                    }
                }
                if spec.input {
                    input_faces.push(f);
                }
            }
            if spec.input && inputs.seismic.is_none() {
                return Err(DcfmError::invalid(
                    label,
                    format!("{field}.input"),
                    true,
                    "a [seismic] section giving the input motion",
                ));
            }
            reports.push(BoundaryReport {
                field: field.clone(),
                description: format!(
                    "{} on {:?}: {} faces{}",
                    match spec.kind {
                        AbsorbingKind::Dashpot => "Lysmer dashpots",
                        AbsorbingKind::ViscousSpring => "viscous-spring boundary",
                    },
                    spec.set.names(),
                    faces.len(),
                    if spec.input { ", seismic input" } else { "" }
                ),
            });
        }
        // The free field (reference column, side walls and their columns) and the drives
        // of the seismic input.
        let mut free_field: Option<FreeField> = None;
        let mut sides = Sides::default();
        if let Some(seismic) = inputs.seismic {
            seismic.motion().validate(label, "seismic")?;
            if input_faces.is_empty() {
                return Err(DcfmError::invalid(
                    label,
                    "seismic",
                    "given",
                    "a [[boundary.absorbing]] with input = true (the model's base) to bring it in",
                ));
            }
            let tol = 1e-6 * size;
            for &f in &input_faces {
                if !horizontal(mesh, f, -1.0) {
                    return Err(DcfmError::invalid(
                        label,
                        "boundary.absorbing.input",
                        format!("element {} face {}", f.element, f.local),
                        "horizontal faces facing down (the model's base): the input is a \
                         vertically incident plane wave",
                    ));
                }
            }
            let z_base = face_centroid(mesh, input_faces[0])[2];
            if let Some(&f) = input_faces
                .iter()
                .find(|&&f| (face_centroid(mesh, f)[2] - z_base).abs() > tol)
            {
                return Err(DcfmError::invalid(
                    label,
                    "boundary.absorbing.input",
                    format!(
                        "element {} face {} at z = {}",
                        f.element,
                        f.local,
                        face_centroid(mesh, f)[2]
                    ),
                    format!("all input faces in one horizontal plane (first at z = {z_base})"),
                ));
            }
            let (spec, model_top_level, base) = reference_profile(
                model,
                seismic,
                &input_faces,
                lo,
                hi,
                inputs.materials,
                label,
            )?;
            // A buried top coupled to the free field.
            if let Some(top) = inputs.free_field.and_then(|f| f.top.as_ref()) {
                let field = "boundary.free_field.top";
                if seismic.overburden.is_empty() {
                    return Err(DcfmError::invalid(
                        label,
                        field,
                        format!("{:?}", top.names()),
                        "[[seismic.overburden]] layers up to the ground surface (a top coupled to \
                         the free field lies below the surface)",
                    ));
                }
                let faces = outside_faces(mesh, &top.names(), &outer, label, field)?;
                let z_top = spec.levels[model_top_level];
                for &f in &faces {
                    if !horizontal(mesh, f, 1.0) || (face_centroid(mesh, f)[2] - z_top).abs() > tol
                    {
                        return Err(DcfmError::invalid(
                            label,
                            field,
                            format!("element {} face {}", f.element, f.local),
                            format!("horizontal faces facing up at the model's top z = {z_top}"),
                        ));
                    }
                    let x = mesh.face_nodes(f).map(|n| mesh.coords[n as usize]);
                    let ints = face_node_integrals(&x).expect("horizontal face has an area");
                    let coef =
                        FaceCoefficients::of(model.element_material(f.element as usize).elastic());
                    for (j, &n) in mesh.face_nodes(f).iter().enumerate() {
                        let c = ints[j].matrix(coef.dashpot_normal, coef.dashpot_tangential);
                        per_node
                            .entry(n)
                            .or_insert((Matrix3::zeros(), Matrix3::zeros()))
                            .0 += c;
                        drives.push(ColumnDrive {
                            slot: n,
                            level: model_top_level as u32,
                            spring: Matrix3::zeros(),
                            dashpot: c,
                            area: ints[j].area,
                            traction: Traction::Above,
                        });
                    }
                }
                reports.push(BoundaryReport {
                    field: field.into(),
                    description: format!(
                        "buried top {:?} coupled to the free field ({} faces, {} m of overburden)",
                        top.names(),
                        faces.len(),
                        seismic.overburden.iter().map(|l| l.thickness).sum::<f64>()
                    ),
                });
            }
            reports.push(BoundaryReport {
                field: "seismic".into(),
                description: format!(
                    "{} {} motion, reference column of {} levels from z = {:.3} to {:.3} m",
                    match seismic.definition {
                        MotionDefinition::Incident => "incident",
                        MotionDefinition::Outcrop => "outcrop",
                        MotionDefinition::Within => "within",
                    },
                    match seismic.quantity {
                        crate::boundary::MotionKind::Velocity => "velocity",
                        _ => "acceleration",
                    },
                    spec.levels.len(),
                    spec.levels[0],
                    spec.levels[spec.levels.len() - 1]
                ),
            });
            // Free-field walls beside the vertical sides.
            let side_sets = inputs.free_field.map_or(&[][..], |f| &f.sides[..]);
            if !side_sets.is_empty() {
                type PerArea = (Matrix3<f64>, Matrix3<f64>, f64);
                let mut base_per_area: std::collections::HashMap<u32, PerArea> =
                    std::collections::HashMap::new();
                for d in drives.iter().filter(|d| d.traction == Traction::Below) {
                    let e = base_per_area.entry(d.slot).or_insert((
                        Matrix3::zeros(),
                        Matrix3::zeros(),
                        0.0,
                    ));
                    e.0 += d.spring;
                    e.1 += d.dashpot;
                    e.2 += d.area;
                }
                let base_per_area = base_per_area
                    .into_iter()
                    .map(|(n, (k, c, a))| (n, (k / a, c / a)))
                    .collect();
                let overburden: Vec<(f64, ColumnElement)> = spec.levels[model_top_level + 1..]
                    .iter()
                    .zip(&spec.elements[model_top_level..])
                    .map(|(&z, e)| (z, *e))
                    .collect();
                let ctx = SideContext {
                    base_per_area: &base_per_area,
                    overburden: &overburden,
                    z_base: spec.levels[0],
                    z_top: spec.levels[model_top_level],
                };
                let mut columns_at = BTreeMap::new();
                for (k, side) in side_sets.iter().enumerate() {
                    let field = format!("boundary.free_field.sides[{k}]");
                    let faces = outside_faces(mesh, &side.names(), &outer, label, &field)?;
                    build_side(
                        model,
                        &side.names().join("+"),
                        &faces,
                        &ctx,
                        &mut sides,
                        1,
                        &mut columns_at,
                        tol,
                    )
                    .map_err(|msg| {
                        DcfmError::invalid(label, &field, format!("{:?}", side.names()), msg)
                    })?;
                }
                for &(n, c) in &sides.node_dashpots {
                    per_node
                        .entry(n)
                        .or_insert((Matrix3::zeros(), Matrix3::zeros()))
                        .0 += c;
                }
                reports.push(BoundaryReport {
                    field: "boundary.free_field.sides".into(),
                    description: format!(
                        "{} free-field walls ({} wall elements), {} edge columns",
                        sides.walls.len(),
                        sides.walls.iter().map(|w| w.elements.len()).sum::<usize>(),
                        sides.columns.len()
                    ),
                });
            }
            let mut specs = vec![spec];
            specs.append(&mut sides.columns);
            free_field = Some(FreeField {
                specs,
                columns: Vec::new(),
                walls: std::mem::take(&mut sides.walls),
                motion: seismic.motion(),
                base,
                model_top_level,
            });
        } else if has_top || inputs.free_field.is_some_and(|f| !f.sides.is_empty()) {
            return Err(DcfmError::invalid(
                label,
                "boundary.free_field",
                "given",
                "a [seismic] section (the free field it couples to) with its input boundary",
            ));
        }
        let nodes: Vec<u32> = per_node.keys().copied().collect();
        let slot_of = |n: u32| {
            nodes
                .binary_search(&n)
                .expect("a drive's node is a boundary node") as u32
        };
        for d in drives.iter_mut() {
            d.slot = slot_of(d.slot);
        }
        for d in sides.dashpots.iter_mut() {
            d.main_node = slot_of(d.main_node);
        }
        for d in sides.tractions.iter_mut() {
            d.main_node = slot_of(d.main_node);
        }
        let (dashpot, spring): (Vec<_>, Vec<_>) = per_node.into_values().unzip();
        let nb = nodes.len();
        // Each list in slot order (stable: a slot's contributions keep their order), so
        // that the per-slot sums of `begin_step` read the lists front to back.
        drives.sort_by_key(|d| d.slot);
        sides.dashpots.sort_by_key(|d| d.main_node);
        sides.tractions.sort_by_key(|d| d.main_node);
        let drives_of = PerSlot::new(nb, drives.iter().map(|d| d.slot));
        let wall_dashpots_of = PerSlot::new(nb, sides.dashpots.iter().map(|d| d.main_node));
        let wall_tractions_of = PerSlot::new(nb, sides.tractions.iter().map(|d| d.main_node));
        Ok(Some(Self {
            nodes,
            dashpot,
            spring,
            u_static: vec![[0.0; 3]; nb],
            constant_source: vec![[0.0; 3]; nb],
            source: vec![[0.0; 3]; nb],
            updates: Vec::new(),
            drives,
            wall_dashpots: sides.dashpots,
            wall_tractions: sides.tractions,
            drives_of,
            wall_dashpots_of,
            wall_tractions_of,
            free_field,
            reports,
        }))
    }

    /// Precompute the per-node updates for time step `dt` (masses and constrained DOFs
    /// final) and build the free-field column.
    pub fn prepare(&mut self, dt: f64, mass: &[f64], constrained: &[u8]) {
        self.updates = self
            .nodes
            .iter()
            .zip(&self.dashpot)
            .map(|(&n, c)| {
                CentredDashpotNode::new(mass[n as usize], *c, constrained[n as usize] & 0b111, dt)
            })
            .collect();
        if let Some(ff) = self.free_field.as_mut() {
            ff.prepare(dt);
        }
        self.refresh_constant_source();
    }

    fn refresh_constant_source(&mut self) {
        for b in 0..self.nodes.len() {
            let ku = self.spring[b] * nalgebra::Vector3::from(self.u_static[b]);
            self.constant_source[b] = [ku[0], ku[1], ku[2]];
        }
    }

    /// The static displacement `u` (all nodes) the springs are measured from: the model
    /// stays at rest in its static state (the static supports' reactions that the
    /// boundaries replace are constant loads, `static_stage::add_hand_over_loads`).
    pub fn set_static_displacement(&mut self, u: &[[f64; 3]]) {
        for (b, &n) in self.nodes.iter().enumerate() {
            self.u_static[b] = u[n as usize];
        }
        self.refresh_constant_source();
    }

    /// Step the free field to tⁿ⁺¹ and compute the sources S_b at tⁿ: each node's sum on
    /// its own (in parallel), its contributions in list order — the drives, then the
    /// walls' dashpots, then the walls' tractions — so the sums do not depend on the
    /// thread count.
    pub fn begin_step(&mut self, t: f64, dt: f64) {
        let Some(ff) = self.free_field.as_mut() else {
            self.source.copy_from_slice(&self.constant_source);
            return;
        };
        ff.step(t, dt);
        let ff = &*ff;
        let col = &ff.columns[0];
        let (drives, dashpots, tractions) =
            (&self.drives, &self.wall_dashpots, &self.wall_tractions);
        let (drives_of, dashpots_of, tractions_of) = (
            &self.drives_of,
            &self.wall_dashpots_of,
            &self.wall_tractions_of,
        );
        let constant = &self.constant_source;
        self.source
            .par_chunks_mut(SLOT_CHUNK)
            .enumerate()
            .for_each(|(c, chunk)| {
                for (k, s) in chunk.iter_mut().enumerate() {
                    let b = c * SLOT_CHUNK + k;
                    *s = constant[b];
                    for &j in drives_of.of(b) {
                        let d = &drives[j as usize];
                        let l = d.level as usize;
                        let u = nalgebra::Vector3::from(col.displacement(l));
                        let v = nalgebra::Vector3::from(col.velocity(l));
                        let t = match d.traction {
                            Traction::Below if l == 0 => col.base_traction(),
                            Traction::Below => {
                                let s = col.stress(l - 1);
                                [-s[5], -s[4], -s[2]]
                            }
                            Traction::Above => col.force_from_above(l),
                        };
                        let f = d.spring * u + d.dashpot * v;
                        for k in 0..3 {
                            s[k] += f[k] + d.area * t[k];
                        }
                    }
                    for &j in dashpots_of.of(b) {
                        let d = &dashpots[j as usize];
                        let v = ff.walls[d.wall as usize].velocity(d.wall_node as usize);
                        let f = d.dashpot * nalgebra::Vector3::from(v);
                        for k in 0..3 {
                            s[k] += f[k];
                        }
                    }
                    for &j in tractions_of.of(b) {
                        let d = &tractions[j as usize];
                        let w = &ff.walls[d.wall as usize];
                        for (q, a) in d.weights.iter().enumerate() {
                            let t = stress_dot(&w.stress(d.element as usize, q), a);
                            for k in 0..3 {
                                s[k] += t[k];
                            }
                        }
                    }
                }
            });
    }

    /// S_b of the current step.
    #[inline]
    pub fn source(&self, b: usize) -> [f64; 3] {
        self.source[b]
    }

    /// The centred-dashpot update of boundary node `b`.
    #[inline]
    pub fn update(&self, b: usize) -> &CentredDashpotNode {
        &self.updates[b]
    }

    /// Largest ω² the springs add to a node: max_b λ_max(K_b)/M_b. With the element bound
    /// ω² ≤ max_e ω_e², the Rayleigh quotient of K + K_s gives ω² ≤ max_e ω_e² + this
    /// (docs/boundaries.md §3).
    pub fn spring_omega_squared(&self, mass: &[f64]) -> f64 {
        self.nodes
            .iter()
            .zip(&self.spring)
            .map(|(&n, k)| {
                let ev = k.symmetric_eigenvalues();
                ev.max() / mass[n as usize]
            })
            .fold(0.0, f64::max)
    }

    /// Critical step of the free-field grids (columns: min h/c_p; walls: 2/ω_max), if any.
    pub fn free_field_critical_step(&self) -> Option<f64> {
        self.free_field.as_ref().map(FreeField::critical_step)
    }

    /// Velocity of the reference free-field column at the ground surface (its top) at tⁿ
    /// of the last step, if there is one.
    pub fn free_field_surface_velocity(&self) -> Option<[f64; 3]> {
        let c = self.reference_column()?;
        Some(c.velocity(c.n_levels() - 1))
    }

    /// The reference free-field column (after [`BoundarySystem::prepare`]).
    pub fn reference_column(&self) -> Option<&Column> {
        self.free_field.as_ref()?.reference()
    }

    /// The free field, if any.
    pub fn free_field(&self) -> Option<&FreeField> {
        self.free_field.as_ref()
    }

    /// State for checkpoints.
    pub fn state_values(&self) -> Vec<f64> {
        let mut out = Vec::new();
        for x in &self.u_static {
            out.extend(x);
        }
        if let Some(ff) = &self.free_field {
            ff.state_values(&mut out);
        }
        out
    }

    /// Restore what [`BoundarySystem::state_values`] wrote.
    pub fn restore_state(&mut self, values: &[f64]) -> std::result::Result<(), String> {
        let nb = self.nodes.len();
        if values.len() < 3 * nb {
            return Err(format!(
                "boundary state has {} values, the case's boundaries need at least {}",
                values.len(),
                3 * nb
            ));
        }
        for (b, x) in self.u_static.iter_mut().enumerate() {
            *x = std::array::from_fn(|d| values[3 * b + d]);
        }
        self.refresh_constant_source();
        let rest = &values[3 * nb..];
        match self.free_field.as_mut() {
            Some(ff) => {
                let used = ff.restore_state(rest)?;
                if used != rest.len() {
                    return Err(format!(
                        "boundary state has {} values too many for the case's free field",
                        rest.len() - used
                    ));
                }
            }
            None if !rest.is_empty() => {
                return Err("boundary state has a free field the case does not have".into())
            }
            None => {}
        }
        Ok(())
    }
}

/// The layering of the reference free-field column: the elements stacked above the input
/// face nearest `profile_at`, then the overburden layers.
fn reference_profile(
    model: &Model,
    seismic: &SeismicSection,
    input_faces: &[Face],
    lo: [f64; 3],
    hi: [f64; 3],
    materials: &BTreeMap<String, Material>,
    label: &str,
) -> Result<(ColumnSpec, usize, ColumnBase)> {
    let mesh = &model.mesh;
    let at = seismic.profile_at.unwrap_or([lo[0], lo[1]]);
    if !at.iter().all(|c| c.is_finite()) {
        return Err(DcfmError::invalid(
            label,
            "seismic.profile_at",
            format!("{at:?}"),
            "finite plan coordinates [x, y] (m)",
        ));
    }
    let start = *input_faces
        .iter()
        .min_by(|&&a, &&b| {
            let d = |f: Face| {
                let c = face_centroid(mesh, f);
                (c[0] - at[0]).powi(2) + (c[1] - at[1]).powi(2)
            };
            d(a).total_cmp(&d(b))
        })
        .expect("at least one input face");
    let [profile_x, profile_y, _] = face_centroid(mesh, start);
    let profile = vertical_profile(mesh, start)
        .map_err(|msg| DcfmError::invalid(label, "seismic.profile_at", format!("{at:?}"), msg))?;
    let top_reached = profile.last().map_or(lo[2], |p| p.z_top);
    let tol = 1e-6 * (hi[2] - lo[2]).max(1e-300);
    if (top_reached - hi[2]).abs() > tol {
        return Err(DcfmError::invalid(
            label,
            "seismic.profile_at",
            format!("{at:?}"),
            format!(
                "a vertical line through rock from the base to the model's top (z = {}); the \
                 elements above the base face there end at z = {top_reached} (an opening?) — \
                 give profile_at away from the cavern",
                hi[2]
            ),
        ));
    }
    let mut levels = vec![profile[0].z_bottom];
    let mut elements = Vec::new();
    for p in &profile {
        levels.push(p.z_top);
        let d = model.element_damping(p.element as usize);
        elements.push(ColumnElement {
            height: p.z_top - p.z_bottom,
            material: *model.element_material(p.element as usize).elastic(),
            alpha: d.alpha,
            beta: d.beta,
        });
    }
    let model_top_level = levels.len() - 1;
    let h_top = elements.last().map_or(1.0, |e| e.height);
    for (k, layer) in seismic.overburden.iter().enumerate() {
        let field = format!("seismic.overburden[{k}]");
        if !(layer.thickness.is_finite() && layer.thickness > 0.0) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.thickness"),
                layer.thickness,
                "must be finite and > 0 (m)",
            ));
        }
        let Some(m) = materials.get(&layer.material) else {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.material"),
                format!("\"{}\"", layer.material),
                format!(
                    "one of the [materials] tables: {:?}",
                    materials.keys().collect::<Vec<_>>()
                ),
            ));
        };
        let n = match layer.divisions {
            Some(0) => {
                return Err(DcfmError::invalid(
                    label,
                    format!("{field}.divisions"),
                    0,
                    "at least 1",
                ))
            }
            Some(n) => n,
            None => (layer.thickness / h_top).ceil().max(1.0) as usize,
        };
        let h = layer.thickness / n as f64;
        let material: Elastic = *m.elastic();
        for _ in 0..n {
            let z = levels[levels.len() - 1] + h;
            levels.push(z);
            elements.push(ColumnElement {
                height: h,
                material,
                alpha: model.damping.alpha,
                beta: model.damping.beta,
            });
        }
    }
    let base = match seismic.definition {
        MotionDefinition::Within => ColumnBase::Rigid,
        MotionDefinition::Incident | MotionDefinition::Outcrop => ColumnBase::Transmitting,
    };
    let spec = ColumnSpec {
        at: [profile_x, profile_y],
        levels,
        elements,
    };
    Ok((spec, model_top_level, base))
}
