//! From the lines and the geometry to the hex8 mesh: every cell of the line grid is
//! classified by what sits at its centroid (the arch band by its place between the bending
//! lines); the rock is meshed, the whole excavated volume (the air of the cavern, the pits,
//! the rooms and tunnels, and the space the concrete will fill) as rock of region
//! `excavated` grouped by bench, and the concrete (`lining`, `inner`) as its own elements
//! on the same cells (overlapping the excavated rock, which the static stage removes before
//! it places them). Then the named regions, element sets and face sets, and duplicated
//! nodes between every pair of bodies that must not share one: concrete and rock (the
//! contact interfaces), lining and inner structure (an interface), concrete and the
//! excavated rock it overlaps (never active together).

use std::collections::BTreeMap;

use crate::error::{DcfmError, Result};
use crate::mesh::split::split_region_pairs_touching;
use crate::mesh::{Face, Mesh};

use super::geometry::{ArchBand, CavernGeometry, Part};
use super::section::SectionLines;

/// The rock regions besides `rock`: the anti-seismic measures of paper §6 that change
/// the rock around the cavern.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct RockZones {
    /// Rock whose cell centroid lies within this distance (m) of the excavation, and every
    /// rock cell with a corner on the excavation, is region `rock_reinforced` (grouted and
    /// bolted rock: a stiffer, stronger material).
    pub reinforced: Option<f64>,
    /// Rock cells sharing a face with the inner structure are region `rock_isolation` (a
    /// soft layer between the lower structure and the rock).
    pub isolation: bool,
}

/// The concrete regions.
pub const CONCRETE: [&str; 2] = ["lining", "inner"];

/// Region of the excavated rock.
pub const EXCAVATED: &str = "excavated";

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

/// Excavation benches, from the crown down: a cell belongs to bench b when its centroid
/// lies at or above `levels[b]` (cavern frame) and below the previous level.
pub fn bench_of(levels: &[f64], z: f64) -> usize {
    levels
        .iter()
        .position(|&l| z >= l - 1e-9)
        .unwrap_or(levels.len() - 1)
}

/// The regions of a model with `zones`, in mesh order: the rock regions, the concrete,
/// the excavated rock.
pub fn region_names(zones: &RockZones) -> Vec<&'static str> {
    let mut r = vec!["rock"];
    if zones.reinforced.is_some() {
        r.push("rock_reinforced");
    }
    if zones.isolation {
        r.push("rock_isolation");
    }
    r.extend(CONCRETE);
    r.push(EXCAVATED);
    r
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

/// Offsets of the six face neighbours of a cell, in the order of `HEX8_FACES` (ζ−, ζ+,
/// η−, ξ+, η+, ξ−; ξ, η, ζ along x, y, z).
const NEIGHBOURS: [[i64; 3]; 6] = [
    [0, 0, -1],
    [0, 0, 1],
    [0, -1, 0],
    [1, 0, 0],
    [0, 1, 0],
    [-1, 0, 0],
];

/// One element to be: its region, bench, survey sets, grid cell and grid nodes.
struct Cell {
    key: (u16, u8, u32, usize),
    nodes: [usize; 8],
}

/// Build the mesh (model coordinates: the model box's corner at the origin).
pub fn build_mesh(
    geo: &CavernGeometry,
    lines: &SectionLines,
    benches: &[f64],
    zones: &RockZones,
) -> Result<Mesh> {
    let (nx, ny, nz) = (lines.x.len(), lines.y.len(), lines.z.len());
    let (cx, cy, cz) = (nx - 1, ny - 1, nz - 1);
    let grid = |i: usize, j: usize, k: usize| i + nx * (j + ny * k);
    let cell_index = |i: usize, j: usize, k: usize| i + cx * (j + cy * k);
    // Node heights per (i, k) (the bending lines depend on x only).
    let zik: Vec<f64> = (0..nz)
        .flat_map(|k| (0..nx).map(move |i| (i, k)))
        .map(|(i, k)| lines.z_at(geo, i, k))
        .collect();
    let node_rel = |n: usize| {
        let (i, j, k) = (n % nx, (n / nx) % ny, n / (nx * ny));
        [lines.x[i], lines.y[j], zik[i + nx * k]]
    };
    let cell_nodes = |i: usize, j: usize, k: usize| {
        [
            grid(i, j, k),
            grid(i + 1, j, k),
            grid(i + 1, j + 1, k),
            grid(i, j + 1, k),
            grid(i, j, k + 1),
            grid(i + 1, j, k + 1),
            grid(i + 1, j + 1, k + 1),
            grid(i, j + 1, k + 1),
        ]
    };
    // 1. What sits in every cell, and its centroid (cavern frame).
    let n_cells = cx * cy * cz;
    let mut parts = vec![Part::Void; n_cells];
    let mut centroids = vec![[0.0; 3]; n_cells];
    for k in 0..cz {
        let band = if k >= lines.k_inner && k < lines.k_outer {
            ArchBand::Lining
        } else if k >= lines.k_outer && k < lines.k_high {
            ArchBand::Above
        } else {
            ArchBand::None
        };
        for j in 0..cy {
            for i in 0..cx {
                let mut c = [0.0; 3];
                for n in cell_nodes(i, j, k) {
                    let p = node_rel(n);
                    for d in 0..3 {
                        c[d] += 0.125 * p[d];
                    }
                }
                let ci = cell_index(i, j, k);
                parts[ci] = geo.part_at(c[0], c[1], c[2], band);
                centroids[ci] = c;
            }
        }
    }
    let neighbour = |ci: usize, dir: usize| -> Option<usize> {
        let (i, j, k) = (ci % cx, (ci / cx) % cy, ci / (cx * cy));
        let o = NEIGHBOURS[dir];
        let (a, b, c) = (i as i64 + o[0], j as i64 + o[1], k as i64 + o[2]);
        if a < 0 || b < 0 || c < 0 || a >= cx as i64 || b >= cy as i64 || c >= cz as i64 {
            None
        } else {
            Some(cell_index(a as usize, b as usize, c as usize))
        }
    };
    // 2. Elements: one of the rock or of the excavated rock in every cell, and one of the
    // concrete where the concrete will be.
    let regions = region_names(zones);
    let region = |name: &str| regions.iter().position(|&r| r == name).expect("region") as u16;
    let (r_excavated, r_lining, r_inner) = (region(EXCAVATED), region("lining"), region("inner"));
    let mut cells: Vec<Cell> = Vec::with_capacity(n_cells + n_cells / 8);
    for ci in 0..n_cells {
        let (i, j, k) = (ci % cx, (ci / cx) % cy, ci / (cx * cy));
        let part = parts[ci];
        let c = centroids[ci];
        let bench = bench_of(benches, c[2]) as u8;
        if part == Part::Rock {
            let isolation = zones.isolation
                && (0..6)
                    .any(|d| neighbour(ci, d).is_some_and(|n| parts[n].region() == Some("inner")));
            let name = if isolation {
                "rock_isolation"
            } else if zones.reinforced.is_some_and(|t| {
                // Its centre within t of the excavation, or a corner on it (a coarse
                // cell whose centre lies farther: the zone wraps the whole excavation).
                geo.distance_to_excavation(c[0], c[1], c[2]) < t
                    || cell_nodes(i, j, k).iter().any(|&n| {
                        let p = node_rel(n);
                        geo.distance_to_excavation(p[0], p[1], p[2]) < 1e-9
                    })
            }) {
                "rock_reinforced"
            } else {
                "rock"
            };
            cells.push(Cell {
                key: (region(name), 0, 0, ci),
                nodes: cell_nodes(i, j, k),
            });
            continue;
        }
        cells.push(Cell {
            key: (r_excavated, bench, 0, ci),
            nodes: cell_nodes(i, j, k),
        });
        if let Some(concrete) = part.region() {
            cells.push(Cell {
                key: (region(concrete), bench, sets_of(geo, part, c), ci),
                nodes: cell_nodes(i, j, k),
            });
        }
    }
    // Elements grouped by region, bench and set membership (few runs: few Gmsh entities),
    // in grid order within a group (compact blocks for the colouring).
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
            let p = node_rel(n);
            coords.push(std::array::from_fn(|d| p[d] + geo.origin[d]));
        }
    }
    let mut mesh = Mesh {
        coords,
        elements: cells.iter().map(|c| c.nodes.map(|n| node_id[n])).collect(),
        element_region: cells.iter().map(|c| c.key.0).collect(),
        region_names: regions.iter().map(|s| s.to_string()).collect(),
        ..Default::default()
    };
    // 3. Element sets: regions, survey sets, benches.
    let collect = |pred: &dyn Fn(&Cell) -> bool| -> Vec<u32> {
        (0..cells.len() as u32)
            .filter(|&e| pred(&cells[e as usize]))
            .collect()
    };
    for (r, name) in regions.iter().enumerate() {
        let set = collect(&|c| c.key.0 == r as u16);
        if set.is_empty() {
            return Err(DcfmError::Mesh(format!(
                "the cavern model has no '{name}' element"
            )));
        }
        mesh.element_sets.insert(name.to_string(), set);
    }
    for (b, name) in ELEMENT_SETS.iter().enumerate() {
        let set = collect(&|c| c.key.2 & (1 << b) != 0);
        if set.is_empty() {
            return Err(DcfmError::Mesh(format!(
                "the cavern model has no element in '{name}' (a dimension too small for the mesh?)"
            )));
        }
        mesh.element_sets.insert(name.to_string(), set);
    }
    let concrete = |c: &Cell| c.key.0 == r_lining || c.key.0 == r_inner;
    for b in 0..benches.len() {
        for (name, pred) in [
            (
                format!("excavation_{}", b + 1),
                &(|c: &Cell| c.key.0 == r_excavated) as &dyn Fn(&Cell) -> bool,
            ),
            (format!("concrete_{}", b + 1), &concrete),
        ] {
            let set = collect(&|c| pred(c) && c.key.1 as usize == b);
            if !set.is_empty() {
                mesh.element_sets.insert(name, set);
            }
        }
    }
    // 4. Face sets from the grid: the faces of a cell towards a neighbour of another kind.
    let mut solid_of = vec![u32::MAX; n_cells];
    let mut concrete_of = vec![u32::MAX; n_cells];
    for (e, c) in cells.iter().enumerate() {
        if concrete(c) {
            concrete_of[c.key.3] = e as u32;
        } else {
            solid_of[c.key.3] = e as u32;
        }
    }
    let mut sets: BTreeMap<String, Vec<Face>> = BTreeMap::new();
    let mut add = |name: &str, element: u32, dir: usize| {
        sets.entry(name.to_string()).or_default().push(Face {
            element,
            local: dir as u8,
        });
    };
    for ci in 0..n_cells {
        let part = parts[ci];
        for dir in 0..6 {
            let other = neighbour(ci, dir).map(|n| parts[n]);
            if part == Part::Rock {
                let Some(o) = other else {
                    let axis = ["z", "z", "y", "x", "y", "x"][dir];
                    let end = ["min", "max", "min", "max", "max", "min"][dir];
                    add(&format!("{axis}{end}"), solid_of[ci], dir);
                    continue;
                };
                if o != Part::Rock {
                    add("excavation", solid_of[ci], dir);
                    match o {
                        Part::ArchLining => add("bolts_arch", solid_of[ci], dir),
                        Part::WallLining => add("bolts_upper_sidewalls", solid_of[ci], dir),
                        _ => {}
                    }
                }
            } else if let Some(name) = part.region() {
                if other == Some(Part::Void) {
                    add(&format!("{name}_surface"), concrete_of[ci], dir);
                    match part {
                        Part::ArchLining => add("lining_face_arch", concrete_of[ci], dir),
                        Part::WallLining => {
                            add("lining_face_upper_sidewalls", concrete_of[ci], dir)
                        }
                        // The crane beam's vertical face towards the cavern (x faces: the
                        // corbels run along y), from which the beam's rock anchors start.
                        Part::CraneCorbel if dir == 3 || dir == 5 => {
                            add("crane_beam_face", concrete_of[ci], dir)
                        }
                        _ => {}
                    }
                }
            }
        }
    }
    for (name, mut f) in sets {
        f.sort_unstable();
        mesh.face_sets.insert(name, f);
    }
    // 5. Duplicated nodes: concrete from every rock region and from the excavated rock,
    // lining from inner; then one interface surface per concrete region against all the
    // rock (`lining-rock` / `rock-lining`, `inner-rock` / `rock-inner`).
    let rock_regions: Vec<&str> = regions
        .iter()
        .copied()
        .filter(|r| r.starts_with("rock"))
        .collect();
    let mut pairs: Vec<[String; 2]> = Vec::new();
    for c in CONCRETE {
        for r in rock_regions.iter().chain(&[EXCAVATED]) {
            pairs.push([c.to_string(), r.to_string()]);
        }
    }
    pairs.push(["lining".into(), "inner".into()]);
    split_region_pairs_touching(&mut mesh, &pairs)
        .map_err(|e| DcfmError::Mesh(format!("interface {:?}: {}", pairs[e.pair], e.message)))?;
    for c in CONCRETE {
        let (mut a, mut b) = (Vec::new(), Vec::new());
        for r in rock_regions.iter().chain(&[EXCAVATED]) {
            let fa = mesh
                .face_sets
                .remove(&format!("{c}-{r}"))
                .unwrap_or_default();
            let fb = mesh
                .face_sets
                .remove(&format!("{r}-{c}"))
                .unwrap_or_default();
            mesh.node_sets.remove(&format!("{c}-{r}"));
            mesh.node_sets.remove(&format!("{r}-{c}"));
            if *r != EXCAVATED {
                a.extend(fa);
                b.extend(fb);
            }
        }
        a.sort_unstable();
        b.sort_unstable();
        if a.is_empty() {
            return Err(DcfmError::Mesh(format!(
                "the cavern model's '{c}' touches no rock"
            )));
        }
        mesh.face_sets.insert(format!("{c}-rock"), a);
        mesh.face_sets.insert(format!("rock-{c}"), b);
    }
    let node_sets: BTreeMap<String, Vec<u32>> = mesh
        .face_sets
        .iter()
        .map(|(n, f)| (n.clone(), mesh.face_set_nodes(f)))
        .collect();
    mesh.node_sets.extend(node_sets);
    mesh.validate()?;
    Ok(mesh)
}
