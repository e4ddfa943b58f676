//! `[static]`: the static stage's boundary conditions, loads, in-situ method and steps,
//! checked against the model (sets exist, the excavation / activation sequence is
//! possible, the numbers are in range) into a [`StaticPlan`].

use crate::boundary::Constraints;
use crate::case::schema::OutputSection;
use crate::case::static_schema::*;
use crate::case::DamagedVolumeMeasure;
use crate::error::{DcfmError, Result};
use crate::model::Model;
use crate::stage::static_stage::linear_solver::{LinearSettings, GIB};
use crate::stage::static_stage::{
    Convergence, ElementSet, InSitu, Layer, RelaxationSettings, StaticLoad, StaticPlan, StaticStep,
    StepSolver, StressProfile, TablePoint,
};

use super::checks::{dof_mask, finite_components, nodes_of};

fn tolerance(label: &str, field: &str, v: Option<f64>, default: f64) -> Result<f64> {
    let t = v.unwrap_or(default);
    if t.is_finite() && t > 0.0 && t < 1.0 {
        Ok(t)
    } else {
        Err(DcfmError::invalid(
            label,
            field,
            t,
            "must be in (0, 1) (out-of-balance ratio)",
        ))
    }
}

fn iterations(label: &str, field: &str, v: Option<usize>, default: usize) -> Result<usize> {
    let n = v.unwrap_or(default);
    if n >= 1 {
        Ok(n)
    } else {
        Err(DcfmError::invalid(label, field, n, "at least 1"))
    }
}

fn k0_pair(label: &str, field: &str, k: K0Value) -> Result<[f64; 2]> {
    let p = k.pair();
    if p.iter().all(|v| v.is_finite() && *v >= 0.0) {
        Ok(p)
    } else {
        Err(DcfmError::invalid(
            label,
            field,
            format!("{p:?}"),
            "finite values ≥ 0",
        ))
    }
}

/// The elements of an element set or region named `name`.
fn element_set(model: &Model, label: &str, field: &str, name: &str) -> Result<ElementSet> {
    let mesh = &model.mesh;
    let elements = if let Some(e) = mesh.element_sets.get(name) {
        let mut e = e.clone();
        e.sort_unstable();
        e.dedup();
        e
    } else if let Some(r) = mesh.region_index(name) {
        (0..mesh.n_elements() as u32)
            .filter(|&e| mesh.element_region[e as usize] as usize == r)
            .collect()
    } else {
        let mut known: Vec<&String> = mesh
            .element_sets
            .keys()
            .chain(mesh.region_names.iter())
            .collect();
        known.sort();
        known.dedup();
        return Err(DcfmError::invalid(
            label,
            field,
            format!("\"{name}\""),
            format!("an element set or region (known: {known:?})"),
        ));
    };
    if elements.is_empty() {
        return Err(DcfmError::invalid(
            label,
            field,
            format!("\"{name}\""),
            "a set with at least one element",
        ));
    }
    Ok(ElementSet {
        name: name.to_string(),
        elements,
    })
}

/// The static boundary conditions: `[[static.fixed]]`, or the DOFs the case constrains.
fn constraints(
    model: &Model,
    fixed: Option<&[crate::case::FixedSection]>,
    label: &str,
) -> Result<Constraints> {
    let n = model.mesh.n_nodes();
    let mut c = Constraints::new(n);
    match fixed {
        Some(list) => {
            for (k, f) in list.iter().enumerate() {
                let mask = dof_mask(label, &format!("static.fixed[{k}].dofs"), &f.dofs)?;
                let nodes = nodes_of(
                    &model.mesh,
                    label,
                    &format!("static.fixed[{k}].set"),
                    &f.set,
                )?;
                c.fix(&nodes, mask);
            }
        }
        None => {
            for mask in 1..8u8 {
                let nodes: Vec<u32> = (0..n as u32)
                    .filter(|&i| model.constraints.constrained[i as usize] == mask)
                    .collect();
                c.fix(&nodes, mask);
            }
        }
    }
    Ok(c)
}

fn load(model: &Model, l: &StaticLoadSection, k: usize, label: &str) -> Result<StaticLoad> {
    let field = format!("static.loads[{k}]");
    let given = [
        l.force.is_some(),
        l.pressure.is_some(),
        l.traction.is_some(),
    ];
    if given.iter().filter(|&&g| g).count() != 1 {
        return Err(DcfmError::invalid(
            label,
            &field,
            format!(
                "force {:?}, pressure {:?}, traction {:?}",
                l.force, l.pressure, l.traction
            ),
            "exactly one of force (N per node), pressure (Pa) or traction (Pa)",
        ));
    }
    if let Some(f) = l.force {
        finite_components(label, &format!("{field}.force"), &f, "N")?;
        let nodes = nodes_of(&model.mesh, label, &format!("{field}.set"), &l.set)?;
        return Ok(StaticLoad::Nodal { nodes, force: f });
    }
    let Some(faces) = model.mesh.face_sets.get(&l.set).filter(|f| !f.is_empty()) else {
        return Err(DcfmError::invalid(
            label,
            format!("{field}.set"),
            format!("\"{}\"", l.set),
            format!(
                "a face set (pressure and traction act on faces; face sets: {:?})",
                model.mesh.face_sets.keys().collect::<Vec<_>>()
            ),
        ));
    };
    if let Some(p) = l.pressure {
        if !p.is_finite() {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.pressure"),
                p,
                "finite (Pa)",
            ));
        }
        return Ok(StaticLoad::Pressure {
            faces: faces.clone(),
            pressure: p,
        });
    }
    let t = l.traction.expect("one of the three");
    finite_components(label, &format!("{field}.traction"), &t, "Pa")?;
    Ok(StaticLoad::Traction {
        faces: faces.clone(),
        traction: t,
    })
}

fn in_situ(
    model: &Model,
    s: &InSituSection,
    default_solver: StepSolver,
    default_conv: Convergence,
    label: &str,
) -> Result<InSitu> {
    let f = |name: &str| format!("static.in_situ.{name}");
    let solver = s.solver.unwrap_or(default_solver);
    let convergence = Convergence {
        tolerance: tolerance(label, &f("tolerance"), s.tolerance, default_conv.tolerance)?,
        max_iterations: iterations(
            label,
            &f("max_iterations"),
            s.max_iterations,
            default_conv.max_iterations,
        )?,
    };
    let unused = |name: &str, given: bool| -> Result<()> {
        if given {
            Err(DcfmError::invalid(
                label,
                f(name),
                "given",
                format!(
                    "only with method = \"k0\" or \"table\" as documented (method = {:?})",
                    s.method
                ),
            ))
        } else {
            Ok(())
        }
    };
    let has_gravity = model.gravity.is_some();
    match s.method {
        InSituMethod::None | InSituMethod::Gravity => {
            unused("ground_surface", s.ground_surface.is_some())?;
            unused("k0", s.k0.is_some())?;
            unused("unit_weight", s.unit_weight.is_some())?;
            unused("layers", !s.layers.is_empty())?;
            unused("table", !s.table.is_empty())?;
            unused("surface_pressure", s.surface_pressure != 0.0)?;
            if s.method == InSituMethod::None {
                return Ok(InSitu::None);
            }
            if !has_gravity {
                return Err(DcfmError::invalid(
                    label,
                    f("method"),
                    "\"gravity\"",
                    "needs [loads.gravity] (the body force the in-situ step solves for)",
                ));
            }
            Ok(InSitu::Gravity {
                solver,
                convergence,
            })
        }
        InSituMethod::K0 => {
            unused("table", !s.table.is_empty())?;
            let Some(zs) = s.ground_surface else {
                return Err(DcfmError::invalid(
                    label,
                    f("ground_surface"),
                    "missing",
                    "z of the ground surface (m)",
                ));
            };
            let ztop = model
                .mesh
                .coords
                .iter()
                .map(|x| x[2])
                .fold(f64::NEG_INFINITY, f64::max);
            if !(zs.is_finite() && zs >= ztop - 1e-9 * ztop.abs().max(1.0)) {
                return Err(DcfmError::invalid(
                    label,
                    f("ground_surface"),
                    zs,
                    format!("at or above the model's top (z = {ztop})"),
                ));
            }
            if !(s.surface_pressure.is_finite() && s.surface_pressure >= 0.0) {
                return Err(DcfmError::invalid(
                    label,
                    f("surface_pressure"),
                    s.surface_pressure,
                    "finite and ≥ 0 (Pa, compression positive)",
                ));
            }
            if let Some(g) = s.unit_weight {
                if !(g.is_finite() && g >= 0.0) {
                    return Err(DcfmError::invalid(
                        label,
                        f("unit_weight"),
                        g,
                        "finite and ≥ 0 (N/m³)",
                    ));
                }
            }
            let default_k0 = s.k0.map(|k| k0_pair(label, &f("k0"), k)).transpose()?;
            let mut layers = Vec::new();
            if s.layers.is_empty() {
                let Some(k0) = default_k0 else {
                    return Err(DcfmError::invalid(
                        label,
                        f("k0"),
                        "missing",
                        "σ_h/σ_v (a value or [x, y])",
                    ));
                };
                layers.push(Layer {
                    bottom: f64::NEG_INFINITY,
                    unit_weight: s.unit_weight,
                    k0,
                });
            }
            let mut top = zs;
            for (k, l) in s.layers.iter().enumerate() {
                let lf = |name: &str| f(&format!("layers[{k}].{name}"));
                let last = k + 1 == s.layers.len();
                let bottom = match l.bottom {
                    Some(b) if b.is_finite() && b < top => b,
                    Some(b) => {
                        return Err(DcfmError::invalid(
                            label,
                            lf("bottom"),
                            b,
                            format!("below the layer's top z = {top} (layers from the top down)"),
                        ))
                    }
                    None if last => f64::NEG_INFINITY,
                    None => {
                        return Err(DcfmError::invalid(
                            label,
                            lf("bottom"),
                            "missing",
                            "z of the layer's base (only the last layer may omit it)",
                        ))
                    }
                };
                let k0 = match (l.k0, default_k0) {
                    (Some(k), _) => k0_pair(label, &lf("k0"), k)?,
                    (None, Some(k)) => k,
                    (None, None) => {
                        return Err(DcfmError::invalid(
                            label,
                            lf("k0"),
                            "missing",
                            "σ_h/σ_v of the layer (or static.in_situ.k0)",
                        ))
                    }
                };
                let unit_weight = l.unit_weight.or(s.unit_weight);
                if let Some(g) = unit_weight {
                    if !(g.is_finite() && g >= 0.0) {
                        return Err(DcfmError::invalid(
                            label,
                            lf("unit_weight"),
                            g,
                            "finite and ≥ 0 (N/m³)",
                        ));
                    }
                }
                layers.push(Layer {
                    bottom,
                    unit_weight,
                    k0,
                });
                top = bottom;
            }
            if !has_gravity && layers.iter().any(|l| l.unit_weight.is_none()) {
                return Err(DcfmError::invalid(
                    label,
                    f("unit_weight"),
                    "missing",
                    "a unit weight (N/m³), or [loads.gravity] to take ρ|g| of the materials",
                ));
            }
            Ok(InSitu::Field {
                profile: StressProfile::Layers {
                    ground_surface: zs,
                    surface_pressure: s.surface_pressure,
                    layers,
                },
                solver,
                convergence,
            })
        }
        InSituMethod::Table => {
            unused("ground_surface", s.ground_surface.is_some())?;
            unused("k0", s.k0.is_some())?;
            unused("unit_weight", s.unit_weight.is_some())?;
            unused("layers", !s.layers.is_empty())?;
            unused("surface_pressure", s.surface_pressure != 0.0)?;
            if s.table.is_empty() {
                return Err(DcfmError::invalid(
                    label,
                    f("table"),
                    "[]",
                    "rows [z, σ_v, K0] or [z, σ_v, K0_x, K0_y]",
                ));
            }
            let mut points: Vec<TablePoint> = Vec::new();
            for (k, row) in s.table.iter().enumerate() {
                let rf = f(&format!("table[{k}]"));
                let ok = (row.len() == 3 || row.len() == 4) && row.iter().all(|v| v.is_finite());
                if !ok {
                    return Err(DcfmError::invalid(
                        label,
                        rf,
                        format!("{row:?}"),
                        "3 or 4 finite numbers: [z, σ_v, K0] or [z, σ_v, K0_x, K0_y]",
                    ));
                }
                let k0 = if row.len() == 3 {
                    [row[2], row[2]]
                } else {
                    [row[2], row[3]]
                };
                if row[1] < 0.0 || k0.iter().any(|&v| v < 0.0) {
                    return Err(DcfmError::invalid(
                        label,
                        rf,
                        format!("{row:?}"),
                        "σ_v ≥ 0 (compression positive) and K0 ≥ 0",
                    ));
                }
                if let Some(prev) = points.last() {
                    if row[0] >= prev.z {
                        return Err(DcfmError::invalid(
                            label,
                            rf,
                            format!("{row:?}"),
                            format!(
                                "z below the previous row's {} (rows from the top down)",
                                prev.z
                            ),
                        ));
                    }
                }
                points.push(TablePoint {
                    z: row[0],
                    sigma_v: row[1],
                    k0,
                });
            }
            Ok(InSitu::Field {
                profile: StressProfile::Table { points },
                solver,
                convergence,
            })
        }
    }
}

/// Which elements are active at the end of the static stage — when the seismic stage
/// starts and the anchor bars are installed: those active from the start (every element
/// but those whose first appearance in the steps is in an `activate` list, as
/// [`StaticPlan::derive_initially_inactive`]), then the steps' `excavate` (removed) and
/// `activate` (placed) lists in order. Every element without a static stage. The
/// sequence's consistency is checked by [`build_static`].
pub(super) fn active_at_installation(
    model: &Model,
    section: Option<&StaticSection>,
    label: &str,
) -> Result<Vec<bool>> {
    let n = model.n_elements();
    let mut active = vec![true; n];
    let Some(s) = section else {
        return Ok(active);
    };
    let mut steps = Vec::with_capacity(s.steps.len());
    for (k, st) in s.steps.iter().enumerate() {
        let f = |kind: &str, j: usize| format!("static.steps[{k}].{kind}[{j}]");
        let sets = |names: &[String], kind: &str| -> Result<Vec<ElementSet>> {
            names
                .iter()
                .enumerate()
                .map(|(j, name)| element_set(model, label, &f(kind, j), name))
                .collect()
        };
        steps.push((
            sets(&st.excavate, "excavate")?,
            sets(&st.activate, "activate")?,
        ));
    }
    let mut seen = vec![false; n];
    for (excavate, activate) in &steps {
        for &e in excavate.iter().flat_map(|set| &set.elements) {
            seen[e as usize] = true;
        }
        for &e in activate.iter().flat_map(|set| &set.elements) {
            if !seen[e as usize] {
                active[e as usize] = false;
            }
            seen[e as usize] = true;
        }
    }
    for (excavate, activate) in &steps {
        for &e in excavate.iter().flat_map(|set| &set.elements) {
            active[e as usize] = false;
        }
        for &e in activate.iter().flat_map(|set| &set.elements) {
            active[e as usize] = true;
        }
    }
    Ok(active)
}

/// The index of the contact interface `name` named by `field` (a static step's `bond`).
fn bonded_interface(model: &Model, label: &str, field: &str, name: &str) -> Result<usize> {
    let contact = model.contact.as_ref();
    contact
        .and_then(|c| c.interface_index(name))
        .ok_or_else(|| {
            let known = contact.map(|c| c.interface_names()).unwrap_or_default();
            DcfmError::invalid(
                label,
                field,
                format!("\"{name}\""),
                if known.is_empty() {
                    "the name of a contact interface (the case has none)".to_string()
                } else {
                    format!("the name of a contact interface: {}", known.join(", "))
                },
            )
        })
}

/// `linear_solver`, `factor_memory_limit`, `cg_tolerance`, `cg_max_iterations`.
fn linear_settings(s: &StaticSection, label: &str) -> Result<LinearSettings> {
    let mut linear = LinearSettings::default();
    if let Some(c) = s.linear_solver {
        linear.choice = c;
    }
    if let Some(g) = s.factor_memory_limit {
        if !(g.is_finite() && g > 0.0) {
            return Err(DcfmError::invalid(
                label,
                "static.factor_memory_limit",
                g,
                "a size in GiB > 0",
            ));
        }
        linear.factor_memory_limit = g * GIB;
    }
    if let Some(t) = s.cg_tolerance {
        if !(t.is_finite() && t > 0.0 && t < 1.0) {
            return Err(DcfmError::invalid(
                label,
                "static.cg_tolerance",
                t,
                "a relative residual in (0, 1)",
            ));
        }
        linear.cg.tolerance = t;
    }
    linear.cg.max_iterations = iterations(
        label,
        "static.cg_max_iterations",
        s.cg_max_iterations,
        linear.cg.max_iterations,
    )?;
    Ok(linear)
}

/// The plan of `[static]`, or `None` when the case has no static stage.
pub(super) fn build_static(
    model: &Model,
    section: Option<&StaticSection>,
    output: &OutputSection,
    label: &str,
) -> Result<Option<StaticPlan>> {
    let Some(s) = section else {
        return Ok(None);
    };
    let solver = s.solver.unwrap_or(StepSolver::Direct);
    let conv = Convergence {
        tolerance: tolerance(label, "static.tolerance", s.tolerance, 1e-5)?,
        max_iterations: iterations(label, "static.max_iterations", s.max_iterations, 200_000)?,
    };
    let mut relaxation = RelaxationSettings::default();
    if let Some(d) = s.damping {
        relaxation.damping = d;
    }
    if let Some(m) = s.mass_scaling {
        relaxation.mass_scaling = m;
    }
    if let Some(p) = s.predictor {
        relaxation.predictor = p;
    }
    relaxation.history_every = iterations(label, "static.history_every", s.history_every, 10)?;
    let mut plan = StaticPlan::new(constraints(model, s.fixed.as_deref(), label)?);
    plan.relaxation = relaxation;
    plan.linear = linear_settings(s, label)?;
    plan.damage_threshold = output.damage_threshold;
    plan.damage_per_element = output.damaged_volume == DamagedVolumeMeasure::Element;
    for (k, l) in s.loads.iter().enumerate() {
        plan.loads.push(load(model, l, k, label)?);
    }
    if let Some(is) = &s.in_situ {
        plan.in_situ = in_situ(model, is, solver, conv, label)?;
    }
    for (k, st) in s.steps.iter().enumerate() {
        let f = |name: &str| format!("static.steps[{k}].{name}");
        let excavate = st
            .excavate
            .iter()
            .enumerate()
            .map(|(j, n)| element_set(model, label, &f(&format!("excavate[{j}]")), n))
            .collect::<Result<Vec<_>>>()?;
        let activate = st
            .activate
            .iter()
            .enumerate()
            .map(|(j, n)| element_set(model, label, &f(&format!("activate[{j}]")), n))
            .collect::<Result<Vec<_>>>()?;
        let substeps = iterations(label, &f("substeps"), st.substeps, 1)?;
        let bond = st
            .bond
            .iter()
            .enumerate()
            .map(|(j, n)| {
                bonded_interface(model, label, &f(&format!("bond[{j}]")), n).map(|i| (i, n.clone()))
            })
            .collect::<Result<Vec<_>>>()?;
        plan.steps.push(StaticStep {
            name: st.name.clone().unwrap_or_else(|| format!("step {}", k + 1)),
            excavate,
            activate,
            bond,
            solver: st.solver.unwrap_or(solver),
            substeps,
            convergence: Convergence {
                tolerance: tolerance(label, &f("tolerance"), st.tolerance, conv.tolerance)?,
                max_iterations: iterations(
                    label,
                    &f("max_iterations"),
                    st.max_iterations,
                    conv.max_iterations,
                )?,
            },
        });
    }
    // The step that bonds each interface (bonded_interface resolved every index).
    let mut bonded_at: Vec<Option<usize>> =
        vec![None; model.contact.as_ref().map_or(0, |c| c.len())];
    for (k, st) in plan.steps.iter().enumerate() {
        for (j, &(i, _)) in st.bond.iter().enumerate() {
            if let Some(first) = bonded_at[i] {
                return Err(DcfmError::invalid(
                    label,
                    format!("static.steps[{k}].bond[{j}]"),
                    format!("\"{}\"", s.steps[k].bond[j]),
                    format!(
                        "an interface bonded once (it is already bonded by static.steps[{first}])"
                    ),
                ));
            }
            bonded_at[i] = Some(k);
        }
    }
    plan.derive_initially_inactive(model.n_elements());
    // Play the sequence: every excavated element active, every placed element inactive.
    let mut active = vec![true; model.n_elements()];
    for &e in &plan.initially_inactive {
        active[e as usize] = false;
    }
    for (k, st) in plan.steps.iter().enumerate() {
        for (j, set) in st.excavate.iter().enumerate() {
            if let Some(&e) = set.elements.iter().find(|&&e| !active[e as usize]) {
                return Err(DcfmError::invalid(
                    label,
                    format!("static.steps[{k}].excavate[{j}]"),
                    format!("\"{}\"", set.name),
                    format!("a set whose elements are all active at that step (element {e} is already removed or not yet placed)"),
                ));
            }
            for &e in &set.elements {
                active[e as usize] = false;
            }
        }
        for (j, set) in st.activate.iter().enumerate() {
            if let Some(&e) = set.elements.iter().find(|&&e| active[e as usize]) {
                return Err(DcfmError::invalid(
                    label,
                    format!("static.steps[{k}].activate[{j}]"),
                    format!("\"{}\"", set.name),
                    format!("a set whose elements are all inactive at that step (element {e} is already active: a set is placed once, after its excavation if it was there before)"),
                ));
            }
            for &e in &set.elements {
                active[e as usize] = true;
            }
        }
    }
    for (k, &e) in output.elements.iter().enumerate() {
        if !active.get(e as usize).copied().unwrap_or(true) {
            return Err(DcfmError::invalid(
                label,
                format!("output.elements[{k}]"),
                e,
                "an element that is active after the static stage (this one is excavated)",
            ));
        }
    }
    Ok(Some(plan))
}
