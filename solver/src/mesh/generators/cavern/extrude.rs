//! From the lines and the geometry to the hex8 mesh: every cell of the line grid is
//! classified by what sits at its centroid (the arch band by its place between the bending
//! lines), the air is left out, and the named regions, element sets and face sets are made;
//! then the concrete–rock and lining–inner-structure interfaces get duplicated nodes.

use std::collections::{BTreeMap, HashMap};

use crate::error::{DcfmError, Result};
use crate::mesh::split::split_region_pairs;
use crate::mesh::{Face, Mesh, HEX8_FACES};

use super::geometry::{ArchBand, CavernGeometry, Part};
use super::section::SectionLines;

/// Regions in mesh order.
pub const REGIONS: [&str; 3] = ["rock", "lining", "inner"];

/// The interfaces (region pairs split apart): concrete on rock, lining on inner structure.
pub const INTERFACES: [[&str; 2]; 3] = [["lining", "rock"], ["inner", "rock"], ["lining", "inner"]];

/// Element sets per survey region (paper §4.1 and §5.1) and per structural part.
pub const ELEMENT_SETS: [&str; 12] = [
    "arch",
    "upper_sidewalls",
    "crane_beam_corbels",
    "tunnel_lining",
    "junctions",
    "generator_floor",
    "turbine_floor",
    "mass_concrete",
    "turbine_layer_walls",
    "pedestals",
    "pedestal_inner_wall",
    "turbine_layer_columns",
];

/// Excavation benches, from the crown down: a rock face belongs to bench b when its
/// centroid lies at or above `levels[b]` (cavern frame) and below the previous level.
pub fn bench_of(levels: &[f64], z: f64) -> usize {
    levels
        .iter()
        .position(|&l| z >= l - 1e-9)
        .unwrap_or(levels.len() - 1)
}

/// Element sets a cell of `part` at centroid (x, y, z) belongs to (bits of ELEMENT_SETS).
fn sets_of(geo: &CavernGeometry, part: Part, c: [f64; 3]) -> u32 {
    let bit = |name: &str| {
        1u32 << ELEMENT_SETS
            .iter()
            .position(|s| *s == name)
            .expect("known set")
    };
    let mut b = match part {
        Part::ArchLining => bit("arch"),
        Part::WallLining => bit("upper_sidewalls"),
        Part::CraneCorbel => bit("crane_beam_corbels"),
        Part::TunnelLining => bit("tunnel_lining"),
        Part::GeneratorFloor => bit("generator_floor"),
        Part::TurbineFloor => bit("turbine_floor"),
        Part::MassConcrete => bit("mass_concrete"),
        Part::TurbineLayerWall => bit("turbine_layer_walls"),
        Part::Pedestal => bit("pedestals"),
        Part::Column => bit("turbine_layer_columns"),
        Part::Rock | Part::Void => 0,
    };
    if part == Part::Pedestal && geo.is_pedestal_inner_wall(c[0], c[1]) {
        b |= bit("pedestal_inner_wall");
    }
    if matches!(part, Part::WallLining | Part::TunnelLining)
        && geo.is_junction(c[0], c[1], c[2], geo.junction_reach())
    {
        b |= bit("junctions");
    }
    b
}

/// Build the mesh (model coordinates: the model box's corner at the origin).
pub fn build_mesh(geo: &CavernGeometry, lines: &SectionLines, benches: &[f64]) -> Result<Mesh> {
    let (nx, ny, nz) = (lines.x.len(), lines.y.len(), lines.z.len());
    let grid = |i: usize, j: usize, k: usize| i + nx * (j + ny * k);
    // Node heights per (i, k) (the bending lines depend on x only).
    let zik: Vec<f64> = (0..nz)
        .flat_map(|k| (0..nx).map(move |i| (i, k)))
        .map(|(i, k)| lines.z_at(geo, i, k))
        .collect();
    let node_rel = |i: usize, j: usize, k: usize| [lines.x[i], lines.y[j], zik[i + nx * k]];

    struct Cell {
        key: (u16, u32, usize),
        nodes: [usize; 8],
    }
    let mut cells: Vec<Cell> = Vec::new();
    for k in 0..nz - 1 {
        let band = if k >= lines.k_inner && k < lines.k_outer {
            ArchBand::Lining
        } else if k >= lines.k_outer && k < lines.k_high {
            ArchBand::Above
        } else {
            ArchBand::None
        };
        for j in 0..ny - 1 {
            for i in 0..nx - 1 {
                let nodes = [
                    grid(i, j, k),
                    grid(i + 1, j, k),
                    grid(i + 1, j + 1, k),
                    grid(i, j + 1, k),
                    grid(i, j, k + 1),
                    grid(i + 1, j, k + 1),
                    grid(i + 1, j + 1, k + 1),
                    grid(i, j + 1, k + 1),
                ];
                let mut c = [0.0; 3];
                for &n in &nodes {
                    let (ii, jj, kk) = (n % nx, (n / nx) % ny, n / (nx * ny));
                    let p = node_rel(ii, jj, kk);
                    for d in 0..3 {
                        c[d] += 0.125 * p[d];
                    }
                }
                let part = geo.part_at(c[0], c[1], c[2], band);
                let Some(region) = part.region() else {
                    continue;
                };
                let r = REGIONS.iter().position(|&n| n == region).expect("region") as u16;
                cells.push(Cell {
                    key: (r, sets_of(geo, part, c), cells.len()),
                    nodes,
                });
            }
        }
    }
    // Elements grouped by region and set membership (few runs: few Gmsh entities), in
    // grid order within a group (compact blocks for the colouring).
    cells.sort_by_key(|c| c.key);
    let mut node_id = vec![u32::MAX; nx * ny * nz];
    for c in &cells {
        for &n in &c.nodes {
            node_id[n] = 0;
        }
    }
    let mut coords = Vec::new();
    for (n, id) in node_id.iter_mut().enumerate() {
        if *id == 0 {
            *id = coords.len() as u32;
            let (i, j, k) = (n % nx, (n / nx) % ny, n / (nx * ny));
            let p = node_rel(i, j, k);
            coords.push([
                p[0] + geo.origin[0],
                p[1] + geo.origin[1],
                p[2] + geo.origin[2],
            ]);
        }
    }
    let mut mesh = Mesh {
        coords,
        elements: cells.iter().map(|c| c.nodes.map(|n| node_id[n])).collect(),
        element_region: cells.iter().map(|c| c.key.0).collect(),
        region_names: REGIONS.iter().map(|s| s.to_string()).collect(),
        ..Default::default()
    };
    for (r, name) in REGIONS.iter().enumerate() {
        let set: Vec<u32> = (0..cells.len() as u32)
            .filter(|&e| cells[e as usize].key.0 == r as u16)
            .collect();
        if set.is_empty() {
            return Err(DcfmError::Mesh(format!(
                "the cavern model has no '{name}' element"
            )));
        }
        mesh.element_sets.insert(name.to_string(), set);
    }
    for (b, name) in ELEMENT_SETS.iter().enumerate() {
        let set: Vec<u32> = (0..cells.len() as u32)
            .filter(|&e| cells[e as usize].key.1 & (1 << b) != 0)
            .collect();
        if set.is_empty() {
            return Err(DcfmError::Mesh(format!(
                "the cavern model has no element in '{name}' (a dimension too small for the mesh?)"
            )));
        }
        mesh.element_sets.insert(name.to_string(), set);
    }
    add_face_sets(&mut mesh, geo, benches);
    let pairs: Vec<[String; 2]> = INTERFACES
        .iter()
        .map(|[a, b]| [a.to_string(), b.to_string()])
        .collect();
    split_region_pairs(&mut mesh, &pairs).map_err(|e| {
        DcfmError::Mesh(format!("interface {:?}: {}", INTERFACES[e.pair], e.message))
    })?;
    let node_sets: BTreeMap<String, Vec<u32>> = mesh
        .face_sets
        .iter()
        .map(|(n, f)| (n.clone(), mesh.face_set_nodes(f)))
        .collect();
    mesh.node_sets.extend(node_sets);
    mesh.validate()?;
    Ok(mesh)
}

/// Outer boundaries, the excavated rock surface per bench, the free concrete surfaces.
fn add_face_sets(mesh: &mut Mesh, geo: &CavernGeometry, benches: &[f64]) {
    let mut faces: HashMap<[u32; 4], Vec<Face>> = HashMap::new();
    for (e, conn) in mesh.elements.iter().enumerate() {
        for (l, local) in HEX8_FACES.iter().enumerate() {
            let mut key = local.map(|a| conn[a]);
            key.sort_unstable();
            faces.entry(key).or_default().push(Face {
                element: e as u32,
                local: l as u8,
            });
        }
    }
    let rock = 0u16;
    let mut sets: BTreeMap<String, Vec<Face>> = BTreeMap::new();
    let tol = 1e-6;
    for list in faces.values() {
        let centroid = |f: &Face| {
            let n = mesh.face_nodes(*f);
            let mut c = [0.0; 3];
            for &a in &n {
                for d in 0..3 {
                    c[d] += 0.25 * mesh.coords[a as usize][d];
                }
            }
            c
        };
        let region = |f: &Face| mesh.element_region[f.element as usize];
        match list.as_slice() {
            [f] => {
                let n = mesh.face_nodes(*f);
                let on = |d: usize, v: f64| {
                    n.iter()
                        .all(|&a| (mesh.coords[a as usize][d] - v).abs() < tol)
                };
                let mut boundary = None;
                for (d, axis) in ["x", "y", "z"].iter().enumerate() {
                    if on(d, 0.0) {
                        boundary = Some(format!("{axis}min"));
                    } else if on(d, geo.model[d]) {
                        boundary = Some(format!("{axis}max"));
                    }
                }
                let name = match boundary {
                    Some(b) => b,
                    None if region(f) == rock => {
                        let z = centroid(f)[2] - geo.origin[2];
                        sets.entry("excavation".into()).or_default().push(*f);
                        format!("excavation_{}", bench_of(benches, z) + 1)
                    }
                    None if region(f) == 1 => "lining_surface".into(),
                    None => "inner_surface".into(),
                };
                sets.entry(name).or_default().push(*f);
            }
            [f, g] => {
                let (r, c) = match (region(f) == rock, region(g) == rock) {
                    (true, false) => (f, g),
                    (false, true) => (g, f),
                    _ => continue,
                };
                let z = centroid(c)[2] - geo.origin[2];
                sets.entry("excavation".into()).or_default().push(*r);
                sets.entry(format!("excavation_{}", bench_of(benches, z) + 1))
                    .or_default()
                    .push(*r);
            }
            _ => {}
        }
    }
    for (name, mut f) in sets {
        f.sort_unstable();
        mesh.face_sets.insert(name, f);
    }
}
