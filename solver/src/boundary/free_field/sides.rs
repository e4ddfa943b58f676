//! Building the free-field walls of the model's vertical sides, the columns at their
//! vertical ends, and the coupling of the main grid's side nodes to the walls.
//!
//! A side must be plane and vertical, and a rectangle in its plane: its outline runs
//! along its base, its top and two vertical ends. Its wall has one element per side face
//! (the same nodes, so every side node has its free-field partner), extended through the
//! overburden with the reference column's levels. At each vertical end a 1D column takes
//! the layering of the wall elements along that end; walls meeting at an edge of the model
//! share it. A wall's base takes the seismic input with the per-area springs and dashpots
//! of the main grid's base under it.

use std::collections::{BTreeMap, HashMap};

use nalgebra::Matrix3;

use crate::boundary::face_tensors::face_node_integrals;
use crate::boundary::free_field::column::ColumnElement;
use crate::boundary::free_field::wall::{ColumnLink, LinkTraction, Wall, WallPoint};
use crate::boundary::free_field::ColumnSpec;
use crate::material::Elastic;
use crate::mesh::{Face, Mesh};
use crate::model::Model;

/// The main grid's coupling to one wall node: C (v_wall) on the relative velocity.
#[derive(Clone, Copy, Debug)]
pub struct WallDashpotDrive {
    pub main_node: u32,
    pub wall: u32,
    pub wall_node: u32,
    pub dashpot: Matrix3<f64>,
}

/// The traction of one wall element on one main-grid node of its face:
/// Σ_q N_j(q) w_q σ_q·n.
#[derive(Clone, Copy, Debug)]
pub struct WallTractionDrive {
    pub main_node: u32,
    pub wall: u32,
    pub element: u32,
    /// N_j(q) w_q n at the four Gauss points (m² × unit normal).
    pub weights: [[f64; 3]; 4],
}

/// Everything the sides add.
#[derive(Debug, Default)]
pub struct Sides {
    pub walls: Vec<Wall>,
    /// Edge columns (to be numbered after the reference column).
    pub columns: Vec<ColumnSpec>,
    pub dashpots: Vec<WallDashpotDrive>,
    pub tractions: Vec<WallTractionDrive>,
    /// Dashpot matrix each main-grid side node receives (to add to its total).
    pub node_dashpots: Vec<(u32, Matrix3<f64>)>,
}

/// Per-unit-area spring and dashpot of the main grid's base at a node, and the level
/// structure of the reference column above the model's top.
pub struct SideContext<'a> {
    pub base_per_area: &'a HashMap<u32, (Matrix3<f64>, Matrix3<f64>)>,
    /// (z, element) of the reference column's elements above the model's top: each the
    /// element between the previous level and z.
    pub overburden: &'a [(f64, ColumnElement)],
    /// Height of the model's base and top.
    pub z_base: f64,
    pub z_top: f64,
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Lysmer dashpot matrix per unit length or area with normal `n` for material `m`.
fn lysmer(m: &Elastic, n: [f64; 3], measure: f64) -> Matrix3<f64> {
    let nv = nalgebra::Vector3::from(n);
    let (cp, cs) = (m.density * m.p_wave_speed(), m.density * m.s_wave_speed());
    (Matrix3::identity() * cs + nv * nv.transpose() * (cp - cs)) * measure
}

/// Build the wall of one side (faces already checked to be outside). `first_column` is
/// the index the next new edge column will get; `columns_at` maps the plan position of
/// an edge (rounded) to its column index, shared between walls.
#[allow(clippy::too_many_arguments)]
pub fn build_side(
    model: &Model,
    name: &str,
    faces: &[Face],
    ctx: &SideContext,
    sides: &mut Sides,
    first_column: usize,
    columns_at: &mut BTreeMap<(i64, i64), usize>,
    tol: f64,
) -> Result<(), String> {
    let mesh: &Mesh = &model.mesh;
    // Plane and vertical.
    let corners = |f: Face| mesh.face_nodes(f).map(|n| mesh.coords[n as usize]);
    let area_vector = |f: Face| -> Option<[f64; 3]> {
        let ints = face_node_integrals(&corners(f))?;
        let a: nalgebra::Vector3<f64> = ints.iter().map(|k| k.area_vector).sum();
        Some([a[0], a[1], a[2]])
    };
    let a0 = area_vector(faces[0]).ok_or("a degenerate face")?;
    let l0 = dot(a0, a0).sqrt();
    let n = [a0[0] / l0, a0[1] / l0, 0.0];
    if a0[2].abs() > 1e-6 * l0 {
        return Err(format!(
            "side '{name}' is not vertical (element {} face {} has normal {:?})",
            faces[0].element,
            faces[0].local,
            a0.map(|c| c / l0)
        ));
    }
    let nh = (n[0] * n[0] + n[1] * n[1]).sqrt();
    let n = [n[0] / nh, n[1] / nh, 0.0];
    let offset = dot(n, corners(faces[0])[0]);
    for &f in faces {
        let a = area_vector(f).ok_or("a degenerate face")?;
        let l = dot(a, a).sqrt();
        let off_plane = corners(f).iter().any(|x| (dot(n, *x) - offset).abs() > tol);
        if dot(a, n) < (1.0 - 1e-6) * l || off_plane {
            return Err(format!(
                "side '{name}' is not one vertical plane: element {} face {} leaves the plane \
                 of element {} face {}",
                f.element, f.local, faces[0].element, faces[0].local
            ));
        }
    }
    let es = [-n[1], n[0], 0.0]; // e_z × n
    let s_of = |x: [f64; 3]| dot(es, x);
    // Wall nodes of the side.
    let mut main_node: Vec<u32> = faces.iter().flat_map(|&f| mesh.face_nodes(f)).collect();
    main_node.sort_unstable();
    main_node.dedup();
    let index: HashMap<u32, u32> = main_node
        .iter()
        .enumerate()
        .map(|(i, &n)| (n, i as u32))
        .collect();
    let mut elements: Vec<[u32; 4]> = Vec::new();
    let mut points = Vec::new();
    let mut materials = Vec::new();
    let mut damping = Vec::new();
    for &f in faces {
        let x = corners(f);
        let pts = WallPoint::of_quad(&x, es).ok_or_else(|| {
            format!(
                "element {} face {} is degenerate in the side's plane",
                f.element, f.local
            )
        })?;
        elements.push(mesh.face_nodes(f).map(|n| index[&n]));
        points.push(pts);
        materials.push(*model.element_material(f.element as usize).elastic());
        let d = model.element_damping(f.element as usize);
        damping.push((d.alpha, d.beta));
    }
    let mut coords: Vec<[f64; 3]> = main_node.iter().map(|&n| mesh.coords[n as usize]).collect();
    // Outline: edges used by one element must run along the base, the top or an end.
    let (mut s_min, mut s_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for x in &coords {
        s_min = s_min.min(s_of(*x));
        s_max = s_max.max(s_of(*x));
    }
    let mut edge_count: HashMap<(u32, u32), u32> = HashMap::new();
    for e in &elements {
        for k in 0..4 {
            let (a, b) = (e[k], e[(k + 1) % 4]);
            *edge_count.entry((a.min(b), a.max(b))).or_default() += 1;
        }
    }
    for (&(a, b), &count) in &edge_count {
        if count != 1 {
            continue;
        }
        let (xa, xb) = (coords[a as usize], coords[b as usize]);
        let on = |f: &dyn Fn([f64; 3]) -> bool| f(xa) && f(xb);
        let ok = on(&|x| (x[2] - ctx.z_base).abs() <= tol)
            || on(&|x| (x[2] - ctx.z_top).abs() <= tol)
            || on(&|x| (s_of(x) - s_min).abs() <= tol)
            || on(&|x| (s_of(x) - s_max).abs() <= tol);
        if !ok {
            return Err(format!(
                "side '{name}' is not a rectangle in its plane: its outline passes through \
                 node {} at {:?} (the outline must follow the base z = {}, the top z = {} and \
                 two vertical ends)",
                main_node[a as usize], xa, ctx.z_base, ctx.z_top
            ));
        }
    }
    // Extension through the overburden: rows above the top edge.
    let mut top_edge: Vec<u32> = (0..coords.len() as u32)
        .filter(|&i| (coords[i as usize][2] - ctx.z_top).abs() <= tol)
        .collect();
    top_edge.sort_by(|&a, &b| s_of(coords[a as usize]).total_cmp(&s_of(coords[b as usize])));
    let mut row = top_edge.clone();
    for &(z, layer) in ctx.overburden {
        let next: Vec<u32> = row
            .iter()
            .map(|&i| {
                let x = coords[i as usize];
                coords.push([x[0], x[1], z]);
                main_node.push(u32::MAX);
                (coords.len() - 1) as u32
            })
            .collect();
        for k in 0..row.len().saturating_sub(1) {
            let conn = [row[k], row[k + 1], next[k + 1], next[k]];
            let x = conn.map(|i| coords[i as usize]);
            let pts = WallPoint::of_quad(&x, es)
                .ok_or_else(|| format!("degenerate overburden element above side '{name}'"))?;
            elements.push(conn);
            points.push(pts);
            materials.push(layer.material);
            damping.push((layer.alpha, layer.beta));
        }
        row = next;
    }
    // Ends: a column at each, links of the end nodes.
    let mut links = Vec::new();
    for (s_end, sign) in [(s_min, -1.0), (s_max, 1.0)] {
        let mut end_nodes: Vec<u32> = (0..coords.len() as u32)
            .filter(|&i| (s_of(coords[i as usize]) - s_end).abs() <= tol)
            .collect();
        end_nodes.sort_by(|&a, &b| coords[a as usize][2].total_cmp(&coords[b as usize][2]));
        let levels: Vec<f64> = end_nodes.iter().map(|&i| coords[i as usize][2]).collect();
        // The wall element along each end segment gives the segment's material.
        let mut seg_material = Vec::new();
        for w in end_nodes.windows(2) {
            let e = elements
                .iter()
                .position(|e| e.contains(&w[0]) && e.contains(&w[1]))
                .ok_or_else(|| format!("side '{name}': no element along its end at s = {s_end}"))?;
            seg_material.push((materials[e], damping[e]));
        }
        let spec = ColumnSpec {
            at: [
                coords[end_nodes[0] as usize][0],
                coords[end_nodes[0] as usize][1],
            ],
            levels: levels.clone(),
            elements: levels
                .windows(2)
                .zip(&seg_material)
                .map(|(w, (m, d))| ColumnElement {
                    height: w[1] - w[0],
                    material: *m,
                    alpha: d.0,
                    beta: d.1,
                })
                .collect(),
        };
        let key = (
            (spec.at[0] / tol).round() as i64,
            (spec.at[1] / tol).round() as i64,
        );
        let column = match columns_at.get(&key) {
            Some(&c) => {
                let existing = &sides.columns[c - first_column];
                let same = existing.levels.len() == spec.levels.len()
                    && existing
                        .levels
                        .iter()
                        .zip(&spec.levels)
                        .all(|(a, b)| (a - b).abs() <= tol);
                if !same {
                    return Err(format!(
                        "the free-field sides meeting at ({:.3}, {:.3}) have different vertical \
                         node levels along their common edge",
                        spec.at[0], spec.at[1]
                    ));
                }
                c
            }
            None => {
                let c = first_column + sides.columns.len();
                columns_at.insert(key, c);
                sides.columns.push(spec);
                c
            }
        };
        let normal = [sign * es[0], sign * es[1], 0.0];
        for (l, &i) in end_nodes.iter().enumerate() {
            let below = if l > 0 {
                levels[l] - levels[l - 1]
            } else {
                0.0
            };
            let above = if l + 1 < levels.len() {
                levels[l + 1] - levels[l]
            } else {
                0.0
            };
            let mut dashpot = Matrix3::zeros();
            if l > 0 {
                dashpot += lysmer(&seg_material[l - 1].0, normal, 0.5 * below);
            }
            if l + 1 < levels.len() {
                dashpot += lysmer(&seg_material[l].0, normal, 0.5 * above);
            }
            links.push(ColumnLink {
                node: i,
                column: column as u32,
                level: l as u32,
                dashpot,
                spring: Matrix3::zeros(),
                traction: LinkTraction::Lateral {
                    below: normal.map(|c| 0.5 * below * c),
                    above: normal.map(|c| 0.5 * above * c),
                },
            });
        }
    }
    // Base: the seismic input with the main base's per-area springs and dashpots.
    let mut base_nodes: Vec<u32> = (0..coords.len() as u32)
        .filter(|&i| (coords[i as usize][2] - ctx.z_base).abs() <= tol)
        .collect();
    base_nodes.sort_by(|&a, &b| s_of(coords[a as usize]).total_cmp(&s_of(coords[b as usize])));
    for (k, &i) in base_nodes.iter().enumerate() {
        let s = s_of(coords[i as usize]);
        let left = if k > 0 {
            s - s_of(coords[base_nodes[k - 1] as usize])
        } else {
            0.0
        };
        let right = if k + 1 < base_nodes.len() {
            s_of(coords[base_nodes[k + 1] as usize]) - s
        } else {
            0.0
        };
        let length = 0.5 * (left + right);
        let Some(&(spring, dashpot)) = ctx.base_per_area.get(&main_node[i as usize]) else {
            return Err(format!(
                "side '{name}': its base node {} is not on the base that takes the seismic input",
                main_node[i as usize]
            ));
        };
        links.push(ColumnLink {
            node: i,
            column: 0,
            level: 0,
            dashpot: dashpot * length,
            spring: spring * length,
            traction: LinkTraction::Base { length },
        });
    }
    // The main grid's coupling: dashpots on the velocity relative to the wall, and the
    // wall's traction σ·n over each face.
    let wall_index = sides.walls.len() as u32;
    for (e, &f) in faces.iter().enumerate() {
        let x = corners(f);
        let ints = face_node_integrals(&x).ok_or("a degenerate face")?;
        let m = model.element_material(f.element as usize).elastic();
        let (cp, cs) = (m.density * m.p_wave_speed(), m.density * m.s_wave_speed());
        for (j, &node) in mesh.face_nodes(f).iter().enumerate() {
            let c = ints[j].matrix(cp, cs);
            sides.node_dashpots.push((node, c));
            sides.dashpots.push(WallDashpotDrive {
                main_node: node,
                wall: wall_index,
                wall_node: index[&node],
                dashpot: c,
            });
            let weights = std::array::from_fn(|q| {
                let p = &points[e][q];
                n.map(|c| c * p.shape[j] * p.weight)
            });
            sides.tractions.push(WallTractionDrive {
                main_node: node,
                wall: wall_index,
                element: e as u32,
                weights,
            });
        }
    }
    let mut wall = Wall::new(
        name.to_string(),
        n,
        main_node,
        elements,
        points,
        materials,
        damping,
    );
    wall.set_links(links);
    sides.walls.push(wall);
    Ok(())
}
