//! `[output]`: probes (by id, by place, by set, with names), damage measure and output
//! steps.

use std::collections::BTreeMap;

use crate::case::probes::{ElementProbe, NodeProbe, Probes};
use crate::case::schema::{OutputSection, ProbeReduce};
use crate::element::host_locate::HostLocator;
use crate::error::{DcfmError, Result};
use crate::model::Model;

use super::checks::{finite_components, near_names};

/// Check `[output]` against the model and resolve its probes.
pub(super) fn build_output(model: &Model, section: &OutputSection, label: &str) -> Result<Probes> {
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
        frame_interval(label, "full_every", f.full_every, section.vtu_every)?;
        frame_interval(label, "anchors_every", f.anchors_every, section.vtu_every)?;
    }
    if section.history_every == 0 {
        return Err(DcfmError::invalid(
            label,
            "output.history_every",
            0,
            "at least 1 (steps)",
        ));
    }
    resolve_probes(model, section, label)
}

/// `output.frames.<key>` (steps between two whole-mesh or anchor frames) must be a multiple
/// of `output.vtu_every`: those frames are written with the compact frames (docs/outputs.md),
/// so any other interval would silently give the least common multiple. 0 is always
/// allowed (`full_every`: first and last only; `anchors_every`: with every frame).
fn frame_interval(label: &str, key: &str, every: u64, vtu_every: u64) -> Result<()> {
    if every == 0 || (vtu_every > 0 && every.is_multiple_of(vtu_every)) {
        return Ok(());
    }
    let expected = if vtu_every == 0 {
        "0 (output.vtu_every = 0: frames at the first and the last step only)".to_string()
    } else {
        format!("0 or a multiple of output.vtu_every = {vtu_every} (steps)")
    };
    Err(DcfmError::invalid(
        label,
        format!("output.frames.{key}"),
        every,
        expected,
    ))
}

/// Node and element probes in column order: `nodes`, `probes`, `elements`,
/// `element_probes`. Errors: an id out of range, a point outside the model, an unknown or
/// empty set, a probe without or with more than one of `at`/`node`/`set`, a name used
/// twice, the same node (element) probed twice.
fn resolve_probes(model: &Model, section: &OutputSection, label: &str) -> Result<Probes> {
    let mesh = &model.mesh;
    let mut probes = Probes::default();
    // Which field first asked for a single node / element, and which names are taken.
    let mut single_nodes: BTreeMap<u32, String> = BTreeMap::new();
    let mut single_elements: BTreeMap<u32, String> = BTreeMap::new();
    let mut names: BTreeMap<String, String> = BTreeMap::new();
    let mut claim_name = |name: &str, field: &str| -> Result<()> {
        if let Some(first) = names.get(name) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.name"),
                format!("\"{name}\""),
                format!("a name no other probe uses ({first} has it)"),
            ));
        }
        names.insert(name.to_string(), field.to_string());
        Ok(())
    };
    let twice = |field: &str, what: &str, id: u32, first: &str| {
        DcfmError::invalid(
            label,
            field,
            format!("{what} {id}"),
            format!("a {what} no other probe reads ({first} already probes it)"),
        )
    };
    for (k, &n) in section.nodes.iter().enumerate() {
        let field = format!("output.nodes[{k}]");
        if n as usize >= mesh.n_nodes() {
            return Err(DcfmError::invalid(
                label,
                &field,
                n,
                format!("a node id below {}", mesh.n_nodes()),
            ));
        }
        if let Some(first) = single_nodes.get(&n) {
            return Err(twice(&field, "node", n, first));
        }
        single_nodes.insert(n, field.clone());
        claim_name(&format!("node{n}"), &field)?;
        probes.nodes.push(NodeProbe {
            label: format!("node{n}"),
            nodes: vec![n],
            mean: false,
            found: format!("node {n} at {}", point(&mesh.coords[n as usize])),
            field,
        });
    }
    let locator = (section.probes.iter().any(|p| p.at.is_some())
        || section.element_probes.iter().any(|p| p.at.is_some()))
    .then(|| HostLocator::new(mesh, |e| model.element_location.get(e).is_some()));
    for (k, p) in section.probes.iter().enumerate() {
        let field = format!("output.probes[{k}]");
        check_name(&p.name, &field, label)?;
        claim_name(&p.name, &field)?;
        let given = [p.at.is_some(), p.node.is_some(), p.set.is_some()];
        check_probe_form(label, &field, &p.name, given, "node", p.reduce)?;
        let single = |node: u32, found: String| NodeProbe {
            label: p.name.clone(),
            nodes: vec![node],
            mean: false,
            found,
            field: field.clone(),
        };
        let probe = if let Some(at) = p.at {
            let f = format!("{field}.at");
            finite_components(label, &f, &at, "m")?;
            let loc = locator.as_ref().expect("built when a probe has a point");
            let (node, dist) = nearest_node(mesh, &at);
            if loc.locate(mesh, &at).is_none() && !within_element(mesh, node, dist) {
                return Err(DcfmError::invalid(
                    label,
                    f,
                    point(&at),
                    format!(
                        "a point inside the model (no element holds it; the nearest node, \
                         {node}, is {dist:.4e} m away)"
                    ),
                ));
            }
            single(
                node,
                format!(
                    "node {node} at {}, {dist:.4e} m from {}",
                    point(&mesh.coords[node as usize]),
                    point(&at)
                ),
            )
        } else if let Some(n) = p.node {
            if n as usize >= mesh.n_nodes() {
                return Err(DcfmError::invalid(
                    label,
                    format!("{field}.node"),
                    n,
                    format!("a node id below {}", mesh.n_nodes()),
                ));
            }
            single(
                n,
                format!("node {n} at {}", point(&mesh.coords[n as usize])),
            )
        } else {
            let set = p.set.as_deref().unwrap_or_default();
            let f = format!("{field}.set");
            let nodes = match mesh.nodes_of(set) {
                Some(n) if !n.is_empty() => n,
                Some(_) => {
                    return Err(DcfmError::invalid(
                        label,
                        f,
                        format!("\"{set}\""),
                        "a set with at least one node (this one is empty)",
                    ))
                }
                None => {
                    return Err(DcfmError::invalid(
                        label,
                        f,
                        format!("\"{set}\""),
                        format!(
                            "a node, face or element set or a region{}",
                            near_names(set, &mesh.set_names())
                        ),
                    ))
                }
            };
            let mean = p.reduce == ProbeReduce::Mean;
            if !mean {
                for (j, &n) in nodes.iter().enumerate() {
                    probes.nodes.push(NodeProbe {
                        label: format!("{}_n{n}", p.name),
                        nodes: vec![n],
                        mean: false,
                        found: format!(
                            "node {n} at {} ({} of {} in set '{set}')",
                            point(&mesh.coords[n as usize]),
                            j + 1,
                            nodes.len()
                        ),
                        field: field.clone(),
                    });
                }
                continue;
            }
            NodeProbe {
                label: p.name.clone(),
                found: format!("mean of the {} nodes of set '{set}'", nodes.len()),
                nodes,
                mean: true,
                field: field.clone(),
            }
        };
        if !probe.mean {
            let n = probe.nodes[0];
            if let Some(first) = single_nodes.get(&n) {
                return Err(twice(&field, "node", n, first));
            }
            single_nodes.insert(n, field.clone());
        }
        probes.nodes.push(probe);
    }
    for (k, &e) in section.elements.iter().enumerate() {
        let field = format!("output.elements[{k}]");
        if e as usize >= model.n_elements() {
            return Err(DcfmError::invalid(
                label,
                &field,
                e,
                format!("an element id below {}", model.n_elements()),
            ));
        }
        if let Some(first) = single_elements.get(&e) {
            return Err(twice(&field, "element", e, first));
        }
        single_elements.insert(e, field.clone());
        claim_name(&format!("elem{e}"), &field)?;
        probes.elements.push(ElementProbe {
            label: format!("elem{e}"),
            elements: vec![e],
            mean: false,
            found: format!("element {e} (region '{}')", region_of(model, e)),
            field,
        });
    }
    for (k, p) in section.element_probes.iter().enumerate() {
        let field = format!("output.element_probes[{k}]");
        check_name(&p.name, &field, label)?;
        claim_name(&p.name, &field)?;
        let given = [p.at.is_some(), p.element.is_some(), p.set.is_some()];
        check_probe_form(label, &field, &p.name, given, "element", p.reduce)?;
        let (elements, mean, found) = if let Some(at) = p.at {
            let f = format!("{field}.at");
            finite_components(label, &f, &at, "m")?;
            let loc = locator.as_ref().expect("built when a probe has a point");
            let Some(host) = loc.locate(mesh, &at) else {
                return Err(DcfmError::invalid(
                    label,
                    f,
                    point(&at),
                    "a point inside the model (no element holds it)",
                ));
            };
            let e = host.element;
            (
                vec![e],
                false,
                format!(
                    "element {e} (region '{}') holds {}",
                    region_of(model, e),
                    point(&at)
                ),
            )
        } else if let Some(e) = p.element {
            if e as usize >= model.n_elements() {
                return Err(DcfmError::invalid(
                    label,
                    format!("{field}.element"),
                    e,
                    format!("an element id below {}", model.n_elements()),
                ));
            }
            (
                vec![e],
                false,
                format!("element {e} (region '{}')", region_of(model, e)),
            )
        } else {
            let set = p.set.as_deref().unwrap_or_default();
            let f = format!("{field}.set");
            let elements: Vec<u32> = if let Some(r) = mesh.region_index(set) {
                (0..mesh.n_elements() as u32)
                    .filter(|&e| mesh.element_region[e as usize] as usize == r)
                    .collect()
            } else if let Some(s) = mesh.element_sets.get(set) {
                s.clone()
            } else {
                let mut known: Vec<String> = mesh.region_names.clone();
                known.extend(mesh.element_sets.keys().cloned());
                return Err(DcfmError::invalid(
                    label,
                    f,
                    format!("\"{set}\""),
                    format!("an element set or a region{}", near_names(set, &known)),
                ));
            };
            if elements.is_empty() {
                return Err(DcfmError::invalid(
                    label,
                    f,
                    format!("\"{set}\""),
                    "a set with at least one element (this one is empty)",
                ));
            }
            if p.reduce == ProbeReduce::Each {
                for (j, &e) in elements.iter().enumerate() {
                    probes.elements.push(ElementProbe {
                        label: format!("{}_e{e}", p.name),
                        elements: vec![e],
                        mean: false,
                        found: format!(
                            "element {e} ({} of {} in set '{set}')",
                            j + 1,
                            elements.len()
                        ),
                        field: field.clone(),
                    });
                }
                continue;
            }
            let n = elements.len();
            (
                elements,
                true,
                format!("volume mean of the {n} elements of set '{set}'"),
            )
        };
        if !mean {
            let e = elements[0];
            if let Some(first) = single_elements.get(&e) {
                return Err(twice(&field, "element", e, first));
            }
            single_elements.insert(e, field.clone());
        }
        probes.elements.push(ElementProbe {
            label: p.name.clone(),
            elements,
            mean,
            found,
            field,
        });
    }
    Ok(probes)
}

/// A probe names exactly one of `at`, `<id_key>` (`node` or `element`) and `set` (`given`,
/// in that order), and asks for `reduce = "mean"` only with a set.
fn check_probe_form(
    label: &str,
    field: &str,
    name: &str,
    given: [bool; 3],
    id_key: &str,
    reduce: ProbeReduce,
) -> Result<()> {
    if given.iter().filter(|&&g| g).count() != 1 {
        return Err(DcfmError::invalid(
            label,
            field,
            format!("\"{name}\""),
            format!("exactly one of at = [x, y, z], {id_key} = ID, set = \"NAME\""),
        ));
    }
    if reduce == ProbeReduce::Mean && !given[2] {
        return Err(DcfmError::invalid(
            label,
            format!("{field}.reduce"),
            "\"mean\"",
            "only with set = \"NAME\"",
        ));
    }
    Ok(())
}

/// A probe name must make a plain column name.
fn check_name(name: &str, field: &str, label: &str) -> Result<()> {
    let ok = !name.is_empty()
        && name
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-' || c == '.');
    if ok {
        Ok(())
    } else {
        Err(DcfmError::invalid(
            label,
            format!("{field}.name"),
            format!("\"{name}\""),
            "a non-empty name of letters, digits, '_', '-' or '.' (it starts column names)",
        ))
    }
}

fn point(p: &[f64; 3]) -> String {
    format!("({}, {}, {})", p[0], p[1], p[2])
}

fn region_of(model: &Model, e: u32) -> &str {
    let r = model.mesh.element_region[e as usize] as usize;
    model
        .mesh
        .region_names
        .get(r)
        .map(String::as_str)
        .unwrap_or("?")
}

/// The node nearest to `p` (lowest id among equals) and its distance.
fn nearest_node(mesh: &crate::mesh::Mesh, p: &[f64; 3]) -> (u32, f64) {
    let mut best = (0u32, f64::INFINITY);
    for (i, x) in mesh.coords.iter().enumerate() {
        let d2: f64 = (0..3).map(|d| (x[d] - p[d]).powi(2)).sum();
        if d2 < best.1 {
            best = (i as u32, d2);
        }
    }
    (best.0, best.1.sqrt())
}

/// `dist` is within the longest edge of an element around `node` (a point on the model's
/// surface, just outside by round-off, still finds its node).
fn within_element(mesh: &crate::mesh::Mesh, node: u32, dist: f64) -> bool {
    const EDGES: [(usize, usize); 12] = [
        (0, 1),
        (1, 2),
        (2, 3),
        (3, 0),
        (4, 5),
        (5, 6),
        (6, 7),
        (7, 4),
        (0, 4),
        (1, 5),
        (2, 6),
        (3, 7),
    ];
    let mut longest: f64 = 0.0;
    for (e, conn) in mesh.elements.iter().enumerate() {
        if conn.contains(&node) {
            let x = mesh.element_coords(e);
            for (a, b) in EDGES {
                let l: f64 = (0..3).map(|d| (x[a][d] - x[b][d]).powi(2)).sum();
                longest = longest.max(l.sqrt());
            }
        }
    }
    dist <= 1e-6 * longest
}
