//! Gmsh MSH 4.1 import (ASCII and binary).
//!
//! What becomes what:
//! - hex8 elements (Gmsh type 5) → [`Mesh::elements`] in file order; their node order is
//!   Gmsh's, which is VTK's and ours;
//! - nodes → [`Mesh::coords`], numbered `0..n` in file order; elements refer to them
//!   through the node tags exactly as the file writes them (blocks in any order, tags in
//!   any order); only the nodes of hex8 elements are kept (a node no hex8 uses would have
//!   no mass in an explicit run);
//! - 3D physical groups → regions (one per element: the first physical group of its
//!   volume entity) and element sets (every group). Names come from `$PhysicalNames`, else
//!   `volume_<tag>`; hex8 elements of a volume in no physical group form the region
//!   `unassigned_volume_<entity tag>`;
//! - 2D physical groups of 4-node quads (type 3) → face sets (each quad matched to the hex8
//!   face with the same four nodes) and node sets; unnamed ones are `surface_<tag>`;
//! - 1D groups (2-node lines, type 1) and 0D groups (points, type 15) → node sets, unnamed
//!   ones `curve_<tag>` / `point_<tag>`.
//!
//! A quad between two hex8 elements (an internal surface, e.g. the rock–lining interface)
//! matches a face of each; it is given to the element whose face has the quad's orientation
//! (the element the quad's right-hand normal points out of). Physical groups of the same
//! name are merged. Points, lines and quads outside physical groups are ignored; any other
//! element type is an error naming the type and the element tag.
//!
//! Refused with the tag named: a node tag or an element tag given twice, node tag 0, a
//! non-finite coordinate, an element referring to a node tag that `$Nodes` does not define.
//!
//! To duplicate the nodes between two regions (a contact interface), call
//! [`split_region_pairs`](crate::mesh::split::split_region_pairs) on the imported mesh.
//! [`crate::mesh::gmsh_write`] writes meshes that this reader reads back identically.

mod cursor;
mod msh41;

use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::Path;

use crate::error::{DcfmError, Result};
use crate::mesh::{Face, Mesh, HEX8_FACES};

use msh41::MshData;

/// Read a Gmsh MSH 4.1 file (ASCII or binary) into a validated [`Mesh`].
pub fn read_gmsh(path: &Path) -> Result<Mesh> {
    let label = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| DcfmError::io(label.clone(), e))?;
    parse_gmsh(&bytes, &label)
}

/// Parse the bytes of a Gmsh MSH 4.1 file (ASCII or binary) into a validated [`Mesh`];
/// `file_label` names the file in error messages.
pub fn parse_gmsh(bytes: &[u8], file_label: &str) -> Result<Mesh> {
    let data = msh41::parse(bytes).map_err(|message| DcfmError::Parse {
        file: file_label.to_string(),
        message,
    })?;
    Importer::new(file_label, &data).run()
}

/// Node tag → index in file order, and the coordinates in file order.
type NodeTable = (HashMap<u64, usize>, Vec<[f64; 3]>);

/// Elements of one lower-dimensional physical group: (gmsh element tag, node tags).
type GroupElements<'d> = Vec<(u64, &'d [u64])>;

struct Importer<'a> {
    file: &'a str,
    data: &'a MshData,
}

impl<'a> Importer<'a> {
    fn new(file: &'a str, data: &'a MshData) -> Self {
        Self { file, data }
    }

    fn group_name(&self, dim: i32, tag: i32) -> String {
        self.data
            .names
            .get(&(dim, tag))
            .cloned()
            .unwrap_or_else(|| {
                let kind = ["point", "curve", "surface", "volume"][dim.clamp(0, 3) as usize];
                format!("{kind}_{tag}")
            })
    }

    fn err(
        &self,
        field: impl Into<String>,
        value: impl std::fmt::Display,
        expected: &str,
    ) -> DcfmError {
        DcfmError::invalid(self.file, field, value, expected)
    }

    fn groups_of(&self, dim: i32, tag: i32) -> &'a [i32] {
        self.data
            .entity_groups
            .get(&(dim, tag))
            .map_or(&[], Vec::as_slice)
    }

    /// Every node tag → index in file order; duplicates, tag 0 and non-finite
    /// coordinates refused with the tag named.
    fn node_index(&self) -> Result<NodeTable> {
        let data = self.data;
        if !data.has_nodes {
            return Err(self.err("$Nodes", "missing", "a $Nodes section"));
        }
        let n: usize = data.node_blocks.iter().map(|b| b.tags.len()).sum();
        let mut index: HashMap<u64, usize> = HashMap::with_capacity(n);
        let mut coords = Vec::with_capacity(n);
        for block in &data.node_blocks {
            for (&tag, x) in block.tags.iter().zip(&block.coords) {
                if tag == 0 {
                    return Err(self.err("$Nodes", "node tag 0", "tags from 1 (0 is reserved)"));
                }
                if let Some(d) = x.iter().position(|c| !c.is_finite()) {
                    return Err(self.err(
                        format!("$Nodes: node {tag}"),
                        format!("{} = {}", ["x", "y", "z"][d], x[d]),
                        "finite coordinates",
                    ));
                }
                if index.insert(tag, coords.len()).is_some() {
                    return Err(self.err(
                        "$Nodes",
                        format!("node tag {tag} given twice"),
                        "each node tag once",
                    ));
                }
                coords.push(*x);
            }
        }
        Ok((index, coords))
    }

    fn run(&self) -> Result<Mesh> {
        let (node_index, all_coords) = self.node_index()?;
        if !self.data.has_elements {
            return Err(self.err("$Elements", "missing", "an $Elements section"));
        }

        // Elements: hex8 into the mesh, points / lines / quads of physical groups aside.
        let mut hex_nodes: Vec<[usize; 8]> = Vec::new(); // indices into all_coords
        let mut hex_tags: Vec<u64> = Vec::new();
        let mut hex_entity: Vec<i32> = Vec::new();
        let mut lower: BTreeMap<(i32, i32), GroupElements> = BTreeMap::new();
        let mut seen_tags: HashSet<u64> = HashSet::new();
        for block in &self.data.element_blocks {
            for &tag in &block.tags {
                if !seen_tags.insert(tag) {
                    return Err(self.err(
                        "$Elements",
                        format!("element tag {tag} given twice"),
                        "each element tag once",
                    ));
                }
            }
        }
        for block in &self.data.element_blocks {
            let Some(&first) = block.tags.first() else {
                continue;
            };
            let k = block.nodes_per_element;
            match block.element_type {
                5 => {
                    for (el, nodes) in block.tags.iter().zip(block.nodes.chunks_exact(k)) {
                        let mut conn = [0usize; 8];
                        for (c, tag) in conn.iter_mut().zip(nodes) {
                            *c = *node_index.get(tag).ok_or_else(|| {
                                self.err(
                                    format!("$Elements: element {el}"),
                                    format!("node tag {tag}"),
                                    "a node tag defined in $Nodes",
                                )
                            })?;
                        }
                        hex_nodes.push(conn);
                        hex_tags.push(*el);
                        hex_entity.push(block.entity_tag);
                    }
                }
                15 | 1 | 3 => {
                    let dim = block.entity_dim;
                    for &phys in self.groups_of(dim, block.entity_tag) {
                        let list = lower.entry((dim, phys)).or_default();
                        for (el, nodes) in block.tags.iter().zip(block.nodes.chunks_exact(k)) {
                            list.push((*el, nodes));
                        }
                    }
                }
                other => return Err(self.err(
                    format!("$Elements: element {first}"),
                    format!(
                        "type {} (Gmsh type {other})",
                        msh41::element_type_name(other)
                    ),
                    "not supported: dcfm reads hex8 (Gmsh type 5) volume elements, and points, \
                         2-node lines and 4-node quads only as members of physical groups",
                )),
            }
        }
        if hex_nodes.is_empty() {
            return Err(self.err(
                "$Elements",
                "no hex8 element",
                "a hexahedral volume mesh (Gmsh type 5; recombine the volume mesh, e.g. transfinite volumes with Recombine, or Mesh.SubdivisionAlgorithm = 2)",
            ));
        }

        // Keep the nodes of hex8 elements, numbered 0..n in file order.
        let mut used = vec![false; all_coords.len()];
        for conn in &hex_nodes {
            for &a in conn {
                used[a] = true;
            }
        }
        let mut new_index = vec![u32::MAX; all_coords.len()];
        let mut coords = Vec::new();
        for (old, _) in used.iter().enumerate().filter(|(_, &u)| u) {
            new_index[old] = coords.len() as u32;
            coords.push(all_coords[old]);
        }
        let mesh_node = |tag: u64, el: u64, group: &str| -> Result<u32> {
            node_index
                .get(&tag)
                .map(|&i| new_index[i])
                .filter(|&i| i != u32::MAX)
                .ok_or_else(|| {
                    self.err(
                        format!("physical group '{group}': element {el}"),
                        format!("node tag {tag}"),
                        "a node of some hex8 element",
                    )
                })
        };

        let mut mesh = Mesh {
            coords,
            elements: hex_nodes.iter().map(|c| c.map(|a| new_index[a])).collect(),
            ..Default::default()
        };

        // Regions and element sets from 3D physical groups.
        let mut region_of_name: HashMap<String, u16> = HashMap::new();
        let mut region_keys: Vec<(i32, i32, String)> = Vec::new(); // (0 physical / 1 unassigned, tag, name)
        let mut seen = HashSet::new();
        for &entity in &hex_entity {
            if !seen.insert(entity) {
                continue;
            }
            match self.groups_of(3, entity).first() {
                Some(&phys) => region_keys.push((0, phys, self.group_name(3, phys))),
                None => region_keys.push((1, entity, format!("unassigned_volume_{entity}"))),
            }
        }
        region_keys.sort();
        for (_, _, name) in region_keys {
            if !region_of_name.contains_key(&name) {
                if mesh.region_names.len() > u16::MAX as usize {
                    return Err(self.err(
                        "physical volumes",
                        mesh.region_names.len() + 1,
                        "at most 65536 regions",
                    ));
                }
                region_of_name.insert(name.clone(), mesh.region_names.len() as u16);
                mesh.region_names.push(name);
            }
        }
        for (e, &entity) in hex_entity.iter().enumerate() {
            let groups = self.groups_of(3, entity);
            let name = match groups.first() {
                Some(&phys) => self.group_name(3, phys),
                None => format!("unassigned_volume_{entity}"),
            };
            mesh.element_region.push(region_of_name[&name]);
            for &phys in groups {
                mesh.element_sets
                    .entry(self.group_name(3, phys))
                    .or_default()
                    .push(e as u32);
            }
        }
        for set in mesh.element_sets.values_mut() {
            set.sort_unstable();
            set.dedup();
        }

        // Geometry first (an inverted element would also confuse the face matching below),
        // naming the element by its Gmsh tag.
        mesh.validate().map_err(|e| match e {
            DcfmError::BadElement { element, reason } => self.err(
                format!("$Elements: element {}", hex_tags[element]),
                format!(
                    "hex8 with node tags {:?}",
                    self.element_node_tags(hex_tags[element])
                ),
                &format!("{reason} (mesh element {element})"),
            ),
            other => other,
        })?;

        // Node sets (dims 0, 1, 2) and face sets (dim 2).
        let quads_exist = lower.keys().any(|&(dim, _)| dim == 2);
        let face_lookup = if quads_exist {
            Some(self.face_lookup(&mesh, &lower, &mesh_node)?)
        } else {
            None
        };
        for (&(dim, phys), list) in &lower {
            let name = self.group_name(dim, phys);
            let mut nodes = Vec::new();
            for (el, tags) in list {
                for &t in tags.iter() {
                    nodes.push(mesh_node(t, *el, &name)?);
                }
            }
            let set = mesh.node_sets.entry(name.clone()).or_default();
            set.extend(nodes);
            set.sort_unstable();
            set.dedup();
            if dim != 2 {
                continue;
            }
            let lookup = face_lookup.as_ref().expect("built when quads exist");
            let mut faces = Vec::with_capacity(list.len());
            for (el, tags) in list {
                if tags.len() != 4 {
                    return Err(self.err(
                        format!("physical group '{name}': element {el}"),
                        format!("{} nodes", tags.len()),
                        "4-node quads in surface groups",
                    ));
                }
                let q: Vec<u32> = tags
                    .iter()
                    .map(|&t| mesh_node(t, *el, &name))
                    .collect::<Result<_>>()?;
                let quad = [q[0], q[1], q[2], q[3]];
                faces.push(self.match_quad(&mesh, lookup, &quad, *el, &name)?);
            }
            let set = mesh.face_sets.entry(name).or_default();
            set.extend(faces);
            set.sort_unstable();
            set.dedup();
        }

        Ok(mesh)
    }

    /// Node tags of the element with gmsh tag `tag` (for error messages).
    fn element_node_tags(&self, tag: u64) -> Vec<u64> {
        for b in &self.data.element_blocks {
            if let Some(i) = b.tags.iter().position(|&t| t == tag) {
                let k = b.nodes_per_element;
                return b.nodes[i * k..(i + 1) * k].to_vec();
            }
        }
        Vec::new()
    }

    /// Hex8 faces whose four nodes all lie on some physical quad, keyed by sorted nodes.
    fn face_lookup(
        &self,
        mesh: &Mesh,
        lower: &BTreeMap<(i32, i32), GroupElements>,
        mesh_node: &dyn Fn(u64, u64, &str) -> Result<u32>,
    ) -> Result<HashMap<[u32; 4], Vec<Face>>> {
        let mut on_quad = vec![false; mesh.n_nodes()];
        for (&(dim, phys), list) in lower {
            if dim != 2 {
                continue;
            }
            let name = self.group_name(dim, phys);
            for (el, tags) in list {
                for &t in tags.iter() {
                    on_quad[mesh_node(t, *el, &name)? as usize] = true;
                }
            }
        }
        let mut lookup: HashMap<[u32; 4], Vec<Face>> = HashMap::new();
        for (e, conn) in mesh.elements.iter().enumerate() {
            for (l, local) in HEX8_FACES.iter().enumerate() {
                let nodes = local.map(|a| conn[a]);
                if nodes.iter().all(|&n| on_quad[n as usize]) {
                    let mut key = nodes;
                    key.sort_unstable();
                    lookup.entry(key).or_default().push(Face {
                        element: e as u32,
                        local: l as u8,
                    });
                }
            }
        }
        Ok(lookup)
    }

    /// The hex8 face with the quad's four nodes; between two elements, the one whose face
    /// has the quad's orientation.
    fn match_quad(
        &self,
        mesh: &Mesh,
        lookup: &HashMap<[u32; 4], Vec<Face>>,
        quad: &[u32; 4],
        el: u64,
        group: &str,
    ) -> Result<Face> {
        let mut key = *quad;
        key.sort_unstable();
        let field = || format!("physical group '{group}': element {el}");
        let candidates = lookup.get(&key).map(Vec::as_slice).unwrap_or(&[]);
        match candidates {
            [] => Err(self.err(
                field(),
                format!("quad with mesh nodes {quad:?}"),
                "a face of some hex8 element",
            )),
            [one] => Ok(*one),
            [_, _] => {
                let same_orientation = |f: &Face| {
                    let n = mesh.face_nodes(*f);
                    (0..4).any(|s| (0..4).all(|i| n[(s + i) % 4] == quad[i]))
                };
                candidates
                    .iter()
                    .copied()
                    .find(same_orientation)
                    .ok_or_else(|| {
                        self.err(
                            field(),
                            format!("quad with mesh nodes {quad:?}"),
                            "nodes in cyclic order around the face",
                        )
                    })
            }
            _ => Err(self.err(
                field(),
                format!("quad with mesh nodes {quad:?}"),
                &format!(
                    "a face shared by at most two hex8 elements, not {}",
                    candidates.len()
                ),
            )),
        }
    }
}

#[cfg(test)]
mod tests;
