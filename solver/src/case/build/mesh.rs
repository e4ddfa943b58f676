//! `[mesh]` and `[node_sets]`: the mesh from a Gmsh file or structured blocks, the region
//! splits, and the extra node sets.

use std::path::Path;

use crate::case::schema::{MeshSection, NodeSetSection};
use crate::error::{DcfmError, Result};
use crate::mesh::Mesh;

/// The mesh of `[mesh]`, split between the region pairs of `mesh.split`.
pub(super) fn build_mesh(section: &MeshSection, label: &str, dir: &Path) -> Result<Mesh> {
    if let Some(spec) = &section.plate_with_hole {
        if section.gmsh.is_some() || !section.blocks.is_empty() {
            return Err(DcfmError::invalid(
                label,
                "mesh",
                "plate_with_hole with gmsh or blocks",
                "one mesh source: a gmsh file, blocks or a plate_with_hole",
            ));
        }
        return spec.build(label);
    }
    match (&section.gmsh, section.blocks.is_empty()) {
        (Some(_), false) => Err(DcfmError::invalid(
            label,
            "mesh",
            "gmsh and blocks",
            "either a gmsh file or blocks, not both",
        )),
        (None, true) => Err(DcfmError::invalid(
            label,
            "mesh",
            "{}",
            "a gmsh file (mesh.gmsh), [[mesh.blocks]] or [mesh.plate_with_hole]",
        )),
        (Some(g), true) => {
            let path = dir.join(g);
            let mut mesh = crate::mesh::gmsh::read_gmsh(&path)?;
            crate::mesh::split::split_region_pairs(&mut mesh, &section.split).map_err(|e| {
                let [a, b] = &section.split[e.pair];
                DcfmError::invalid(
                    label,
                    format!("mesh.split[{}]", e.pair),
                    format!("[{a}, {b}]"),
                    e.message,
                )
            })?;
            Ok(mesh)
        }
        (None, false) => section.box_spec().build(label),
    }
}

/// Add the `[node_sets]` of the case to the mesh: explicit node lists and boxes.
pub(super) fn add_node_sets(
    mesh: &mut Mesh,
    sets: &std::collections::BTreeMap<String, NodeSetSection>,
    label: &str,
) -> Result<()> {
    for (name, s) in sets {
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
    Ok(())
}
