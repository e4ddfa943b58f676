//! Gmsh MSH 4.1 import (ASCII and binary), through the `mshio` crate.
//!
//! What becomes what:
//! - hex8 elements (Gmsh type 5) → [`Mesh::elements`] in file order; their node order is
//!   Gmsh's, which is VTK's and ours;
//! - nodes → [`Mesh::coords`], renumbered `0..n` in file order; only the nodes of hex8
//!   elements are kept (a node no hex8 uses would have no mass in an explicit run);
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
//! To duplicate the nodes between two regions (a contact interface), call
//! [`split_between_regions`](crate::mesh::box_generator::split_between_regions) on the
//! imported mesh.
//!
//! mshio keeps node tags only when they are sparse; when they are dense (`max - min + 1 ==
//! count`, as Gmsh writes them) the i-th node in file order has tag `min + i`, which is what
//! Gmsh writes. mshio does not read `$PhysicalNames`, so that (always ASCII) section is
//! read here.

use std::collections::{BTreeMap, HashMap};
use std::path::Path;

use mshio::{ElementType, MshFile};

use crate::error::{DcfmError, Result};
use crate::mesh::{Face, Mesh, HEX8_FACES};

/// Read a Gmsh MSH 4.1 file (ASCII or binary) into a validated [`Mesh`].
pub fn read_gmsh(path: &Path) -> Result<Mesh> {
    let label = path.display().to_string();
    let bytes = std::fs::read(path).map_err(|e| DcfmError::io(label.clone(), e))?;
    parse_gmsh(&bytes, &label)
}

/// Parse the bytes of a Gmsh MSH 4.1 file (ASCII or binary) into a validated [`Mesh`];
/// `file_label` names the file in error messages.
pub fn parse_gmsh(bytes: &[u8], file_label: &str) -> Result<Mesh> {
    let parse_err = |message: String| DcfmError::Parse {
        file: file_label.to_string(),
        message,
    };
    check_version(bytes).map_err(parse_err)?;
    let names = physical_names(bytes).map_err(parse_err)?;
    let msh =
        mshio::parse_msh_bytes(bytes).map_err(|e| parse_err(describe_mshio_error(bytes, &e)))?;
    Importer::new(file_label, names).run(&msh)
}

/// Reject anything but MSH 4.1 with a hint (mshio's own message would be obscure).
fn check_version(bytes: &[u8]) -> std::result::Result<(), String> {
    let head = &bytes[..bytes.len().min(256)];
    let text = String::from_utf8_lossy(head);
    let mut lines = text.lines().map(str::trim);
    if lines.next() != Some("$MeshFormat") {
        return Err("not a Gmsh mesh file (it must begin with $MeshFormat)".into());
    }
    let version = lines
        .next()
        .and_then(|l| l.split_whitespace().next())
        .unwrap_or("");
    if version != "4.1" {
        return Err(format!(
            "MSH format version {version:?} is not supported: save the mesh as MSH 4.1 \
             (gmsh -format msh41, or Mesh.MshFileVersion = 4.1)"
        ));
    }
    Ok(())
}

/// A short mshio error: the chain of contexts, the byte offset and the line (no hex dump).
fn describe_mshio_error(bytes: &[u8], e: &mshio::MshParserError<&[u8]>) -> String {
    let trace = e.filtered_backtrace();
    let Some((rest, kind)) = trace.first() else {
        return "not a valid MSH 4.1 file".into();
    };
    let offset = bytes.len() - rest.len();
    let line = bytes[..offset].iter().filter(|&&b| b == b'\n').count() + 1;
    let contexts: Vec<String> = trace[1..]
        .iter()
        .rev()
        .map(|(_, k)| k.context().map_or_else(|| k.to_string(), str::to_string))
        .collect();
    format!(
        "not a valid MSH 4.1 file: {kind} (in {}; byte {offset}, line {line})",
        contexts.join(" > ")
    )
}

/// `$PhysicalNames` (ASCII in ASCII and binary files alike): (dim, tag) → name.
fn physical_names(bytes: &[u8]) -> std::result::Result<HashMap<(i32, i32), String>, String> {
    let mut out = HashMap::new();
    let key = b"$PhysicalNames";
    // The section comes before $Entities / $Nodes, so search only up to there: binary
    // payloads could contain anything.
    let limit = find(bytes, b"$Nodes").unwrap_or(bytes.len());
    let Some(start) = find(&bytes[..limit], key) else {
        return Ok(out);
    };
    let body = &bytes[start + key.len()..];
    let end = find(body, b"$EndPhysicalNames").ok_or("$PhysicalNames without $EndPhysicalNames")?;
    let text =
        std::str::from_utf8(&body[..end]).map_err(|_| "$PhysicalNames is not valid UTF-8 text")?;
    let mut lines = text.lines().map(str::trim).filter(|l| !l.is_empty());
    let count: usize = lines
        .next()
        .and_then(|l| l.parse().ok())
        .ok_or("$PhysicalNames: first line must be the number of names")?;
    for i in 0..count {
        let line = lines
            .next()
            .ok_or_else(|| format!("$PhysicalNames: expected {count} names, found {i}"))?;
        let bad = || format!("$PhysicalNames: line '{line}' is not `dim tag \"name\"`");
        let (dim, rest) = line.split_once(char::is_whitespace).ok_or_else(bad)?;
        let (tag, name) = rest
            .trim_start()
            .split_once(char::is_whitespace)
            .ok_or_else(bad)?;
        let dim: i32 = dim.parse().map_err(|_| bad())?;
        let tag: i32 = tag.parse().map_err(|_| bad())?;
        let name = name.trim();
        let name = name
            .strip_prefix('"')
            .and_then(|n| n.strip_suffix('"'))
            .unwrap_or(name);
        out.insert((dim, tag), name.to_string());
    }
    Ok(out)
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// Elements of one lower-dimensional physical group: (gmsh element tag, node tags).
type GroupElements = Vec<(u64, Vec<u64>)>;

struct Importer<'a> {
    file: &'a str,
    names: HashMap<(i32, i32), String>,
}

impl<'a> Importer<'a> {
    fn new(file: &'a str, names: HashMap<(i32, i32), String>) -> Self {
        Self { file, names }
    }

    fn group_name(&self, dim: i32, tag: i32) -> String {
        self.names.get(&(dim, tag)).cloned().unwrap_or_else(|| {
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

    fn run(&self, msh: &MshFile<u64, i32, f64>) -> Result<Mesh> {
        // Physical tags of every entity: (dim, entity tag) → physical tags, in file order.
        let mut entity_groups: HashMap<(i32, i32), Vec<i32>> = HashMap::new();
        if let Some(ent) = &msh.data.entities {
            for p in &ent.points {
                entity_groups.insert((0, p.tag), p.physical_tags.clone());
            }
            for c in &ent.curves {
                entity_groups.insert((1, c.tag), c.physical_tags.clone());
            }
            for s in &ent.surfaces {
                entity_groups.insert((2, s.tag), s.physical_tags.clone());
            }
            for v in &ent.volumes {
                entity_groups.insert((3, v.tag), v.physical_tags.clone());
            }
        }
        let no_groups = Vec::new();
        let groups_of = |dim: i32, tag: i32| entity_groups.get(&(dim, tag)).unwrap_or(&no_groups);

        // All nodes by tag, in file order.
        let nodes = msh
            .data
            .nodes
            .as_ref()
            .ok_or_else(|| self.err("$Nodes", "missing", "a $Nodes section"))?;
        let mut node_index: HashMap<u64, usize> =
            HashMap::with_capacity(nodes.node_blocks.iter().map(|b| b.nodes.len()).sum());
        let mut all_coords: Vec<[f64; 3]> = Vec::with_capacity(node_index.capacity());
        let mut dense_tag = nodes.min_node_tag;
        for block in &nodes.node_blocks {
            let tags: Vec<u64> = match &block.node_tags {
                Some(map) => {
                    let mut t = vec![0u64; block.nodes.len()];
                    for (&tag, &i) in map {
                        t[i] = tag;
                    }
                    t
                }
                None => {
                    let t = (dense_tag..dense_tag + block.nodes.len() as u64).collect();
                    dense_tag += block.nodes.len() as u64;
                    t
                }
            };
            for (tag, n) in tags.into_iter().zip(&block.nodes) {
                if node_index.insert(tag, all_coords.len()).is_some() {
                    return Err(self.err(
                        "$Nodes",
                        format!("node tag {tag}"),
                        "each node tag once",
                    ));
                }
                all_coords.push([n.x, n.y, n.z]);
            }
        }

        // Elements: hex8 into the mesh, points / lines / quads of physical groups aside.
        let elements = msh
            .data
            .elements
            .as_ref()
            .ok_or_else(|| self.err("$Elements", "missing", "an $Elements section"))?;
        let mut hex_nodes: Vec<[usize; 8]> = Vec::new(); // indices into all_coords
        let mut hex_tags: Vec<u64> = Vec::new();
        let mut hex_entity: Vec<i32> = Vec::new();
        let mut lower: BTreeMap<(i32, i32), GroupElements> = BTreeMap::new();
        for block in &elements.element_blocks {
            let ty = block.element_type;
            let Some(first) = block.elements.first() else {
                continue;
            };
            match ty {
                ElementType::Hex8 => {
                    for el in &block.elements {
                        let mut conn = [0usize; 8];
                        for (c, tag) in conn.iter_mut().zip(&el.nodes) {
                            *c = *node_index.get(tag).ok_or_else(|| {
                                self.err(
                                    format!("$Elements: element {}", el.element_tag),
                                    format!("node tag {tag}"),
                                    "a node tag defined in $Nodes",
                                )
                            })?;
                        }
                        hex_nodes.push(conn);
                        hex_tags.push(el.element_tag);
                        hex_entity.push(block.entity_tag);
                    }
                }
                ElementType::Pnt | ElementType::Lin2 | ElementType::Qua4 => {
                    let dim = block.entity_dim;
                    for &phys in groups_of(dim, block.entity_tag) {
                        let list = lower.entry((dim, phys)).or_default();
                        for el in &block.elements {
                            list.push((el.element_tag, el.nodes.clone()));
                        }
                    }
                }
                other => return Err(self.err(
                    format!("$Elements: element {}", first.element_tag),
                    format!("type {other:?} (Gmsh type {})", other as i32),
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

        // Keep the nodes of hex8 elements, renumbered 0..n in file order.
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
        let mut seen = std::collections::HashSet::new();
        for &entity in &hex_entity {
            if !seen.insert(entity) {
                continue;
            }
            match groups_of(3, entity).first() {
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
            let groups = groups_of(3, entity);
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
                    elements_node_tags(msh, hex_tags[element])
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
                for &t in tags {
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
                for &t in tags {
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

/// Node tags of the element with gmsh tag `tag` (for error messages).
fn elements_node_tags(msh: &MshFile<u64, i32, f64>, tag: u64) -> Vec<u64> {
    msh.data
        .elements
        .iter()
        .flat_map(|e| &e.element_blocks)
        .flat_map(|b| &b.elements)
        .find(|e| e.element_tag == tag)
        .map(|e| e.nodes.clone())
        .unwrap_or_default()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::box_generator::split_between_regions;

    fn fixture(name: &str) -> std::path::PathBuf {
        Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("tests/fixtures")
            .join(name)
    }

    fn ascii_text() -> String {
        std::fs::read_to_string(fixture("cube_2x2x2.msh")).unwrap()
    }

    /// Replace the `n`-th line after the line equal to `header` with `f(line)`.
    fn edit_after(text: &str, header: &str, n: usize, f: impl Fn(&str) -> String) -> String {
        let lines: Vec<&str> = text.lines().collect();
        let at = lines
            .iter()
            .position(|l| *l == header)
            .expect("header line")
            + n;
        let mut out: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
        out[at] = f(lines[at]);
        out.join("\n") + "\n"
    }

    /// The fixture: a 2 m cube of 2×2×2 hex8, "rock" below z = 1, "lining" above (both
    /// also in "all"), quads "base" (z = 0, normal −z) and "interface" (z = 1, normal +z),
    /// lines "edge" (y = z = 0) and an unnamed point group at the origin.
    fn check_cube(m: &Mesh) {
        assert_eq!(m.n_nodes(), 27);
        assert_eq!(m.n_elements(), 8);
        // Nodes were written in grid order, so renumbering gives node i + 3j + 9k.
        for (n, c) in m.coords.iter().enumerate() {
            assert_eq!(*c, [(n % 3) as f64, ((n / 3) % 3) as f64, (n / 9) as f64]);
        }
        assert_eq!(m.elements[0], [0, 1, 4, 3, 9, 10, 13, 12]);
        assert_eq!(
            m.region_names,
            vec!["rock".to_string(), "lining".to_string()]
        );
        assert_eq!(m.element_region, vec![0, 0, 0, 0, 1, 1, 1, 1]);
        assert_eq!(m.element_sets["rock"], vec![0, 1, 2, 3]);
        assert_eq!(m.element_sets["lining"], vec![4, 5, 6, 7]);
        assert_eq!(m.element_sets["all"], (0..8).collect::<Vec<u32>>());
        // Base: the ζ− faces of the four rock elements.
        let base = &m.face_sets["base"];
        assert_eq!(base.len(), 4);
        assert!(
            base.iter().all(|f| f.local == 0 && f.element < 4),
            "{base:?}"
        );
        // Interface: both rock (ζ+) and lining (ζ−) faces match; the quad's +z normal
        // points out of the rock.
        let iface = &m.face_sets["interface"];
        assert_eq!(iface.len(), 4);
        assert!(
            iface.iter().all(|f| f.local == 1 && f.element < 4),
            "{iface:?}"
        );
        for f in base.iter().chain(iface) {
            let z = if f.local == 0 { 0.0 } else { 1.0 };
            assert!(m
                .face_nodes(*f)
                .iter()
                .all(|&n| m.coords[n as usize][2] == z));
        }
        assert_eq!(m.node_sets["base"], (0..9).collect::<Vec<u32>>());
        assert_eq!(m.node_sets["interface"], (9..18).collect::<Vec<u32>>());
        assert_eq!(m.node_sets["edge"], vec![0, 1, 2]);
        assert_eq!(m.node_sets["point_4"], vec![0]);
        assert!(!m.node_sets.contains_key("rock"));
    }

    #[test]
    fn ascii_sparse_tags_counts_regions_and_sets() {
        let m = read_gmsh(&fixture("cube_2x2x2.msh")).unwrap();
        check_cube(&m);
    }

    #[test]
    fn binary_dense_tags_same_mesh() {
        let b = read_gmsh(&fixture("cube_2x2x2_binary.msh")).unwrap();
        check_cube(&b);
        let a = read_gmsh(&fixture("cube_2x2x2.msh")).unwrap();
        assert_eq!(a.coords, b.coords);
        assert_eq!(a.elements, b.elements);
        assert_eq!(a.face_sets, b.face_sets);
        assert_eq!(a.node_sets, b.node_sets);
    }

    /// `gmsh_stack*.msh` were written by Gmsh 4.15 itself (OpenCASCADE boxes 3×3×2 "rock"
    /// under 3×3×1 "lining", fragmented, transfinite with 3 points per curve, recombined;
    /// physical surfaces "base" (z = 0) and "interface" (z = 2), an unnamed physical point
    /// 31 at the origin), as ASCII and as binary MSH 4.1.
    fn check_gmsh_stack(m: &Mesh) {
        assert_eq!(m.n_elements(), 16);
        assert_eq!(m.n_nodes(), 45);
        assert_eq!(
            m.region_names,
            vec!["rock".to_string(), "lining".to_string()]
        );
        let z = |n: u32| m.coords[n as usize][2];
        for (e, conn) in m.elements.iter().enumerate() {
            let zc: f64 = conn.iter().map(|&n| z(n)).sum::<f64>() / 8.0;
            let expect = if zc < 2.0 { 0 } else { 1 };
            assert_eq!(m.element_region[e], expect, "element {e} at z = {zc}");
        }
        assert_eq!(m.element_sets["rock"].len(), 8);
        assert_eq!(m.element_sets["lining"].len(), 8);
        for (name, level) in [("base", 0.0), ("interface", 2.0)] {
            let faces = &m.face_sets[name];
            assert_eq!(faces.len(), 4, "{name}");
            for f in faces {
                assert!(
                    m.face_nodes(*f).iter().all(|&n| z(n) == level),
                    "{name} {f:?}"
                );
            }
            assert_eq!(m.node_sets[name].len(), 9);
        }
        assert!(m.face_sets["base"]
            .iter()
            .all(|f| m.element_region[f.element as usize] == 0));
        let origin = &m.node_sets["point_31"];
        assert_eq!(origin.len(), 1);
        assert_eq!(m.coords[origin[0] as usize], [0.0; 3]);
    }

    #[test]
    fn files_written_by_gmsh_itself() {
        let a = read_gmsh(&fixture("gmsh_stack.msh")).unwrap();
        check_gmsh_stack(&a);
        let b = read_gmsh(&fixture("gmsh_stack_binary.msh")).unwrap();
        check_gmsh_stack(&b);
        assert_eq!(a.coords, b.coords);
        assert_eq!(a.elements, b.elements);
        assert_eq!(a.face_sets, b.face_sets);
        let mut m = a;
        split_between_regions(&mut m, "rock", "lining").unwrap();
        m.validate().unwrap();
        assert_eq!(m.n_nodes(), 45 + 9);
        assert_eq!(m.face_sets["rock-lining"].len(), 4);
    }

    #[test]
    fn unnamed_and_unassigned_volumes() {
        // Physical volume 2 ("lining") without a name: region and set `volume_2`.
        let text = ascii_text().replace("6\n3 1 \"rock\"\n3 2 \"lining\"\n", "5\n3 1 \"rock\"\n");
        let named = parse_gmsh(text.as_bytes(), "a.msh").unwrap();
        assert_eq!(
            named.region_names,
            vec!["rock".to_string(), "volume_2".to_string()]
        );
        assert_eq!(named.element_sets["volume_2"], vec![4, 5, 6, 7]);
        // Volume entity 2 in no physical group at all: region `unassigned_volume_2`.
        let text = text.replace("2.0 2.0 2.0 2 2 6 1 2", "2.0 2.0 2.0 0 1 2");
        let m = parse_gmsh(text.as_bytes(), "b.msh").unwrap();
        assert_eq!(
            m.region_names,
            vec!["rock".to_string(), "unassigned_volume_2".to_string()]
        );
        assert_eq!(m.element_region, vec![0, 0, 0, 0, 1, 1, 1, 1]);
        assert_eq!(m.element_sets["all"], vec![0, 1, 2, 3]);
        assert!(!m.element_sets.contains_key("volume_2"));
    }

    #[test]
    fn physical_names_with_spaces() {
        let names = physical_names(b"$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$PhysicalNames\n2\n3  7   \"upper lining\"\n2 1 base\n$EndPhysicalNames\n$Nodes\n").unwrap();
        assert_eq!(names[&(3, 7)], "upper lining");
        assert_eq!(names[&(2, 1)], "base");
        assert!(physical_names(b"$PhysicalNames\n1\n3 x \"a\"\n$EndPhysicalNames\n").is_err());
    }

    #[test]
    fn split_between_imported_regions() {
        let mut m = read_gmsh(&fixture("cube_2x2x2.msh")).unwrap();
        split_between_regions(&mut m, "rock", "lining").unwrap();
        m.validate().unwrap();
        assert_eq!(m.n_nodes(), 27 + 9);
        assert_eq!(m.face_sets["rock-lining"].len(), 4);
        assert_eq!(m.face_sets["lining-rock"].len(), 4);
        let rock: Vec<u32> = m.nodes_of("rock").unwrap();
        let lining: Vec<u32> = m.nodes_of("lining").unwrap();
        assert!(
            lining.iter().all(|n| !rock.contains(n)),
            "no node shared after the split"
        );
        // The copies sit where the originals are.
        let a = &m.node_sets["rock-lining"];
        let b = &m.node_sets["lining-rock"];
        let za: Vec<f64> = a.iter().map(|&n| m.coords[n as usize][2]).collect();
        let zb: Vec<f64> = b.iter().map(|&n| m.coords[n as usize][2]).collect();
        assert!(za.iter().chain(&zb).all(|&z| z == 1.0));
        // The imported interface face set (rock faces) still names the rock side.
        assert_eq!(m.face_set_nodes(&m.face_sets["interface"]), *a);
    }

    #[test]
    fn missing_file_and_garbage_name_the_file() {
        let msg = read_gmsh(Path::new("/no/such/mesh.msh"))
            .unwrap_err()
            .to_string();
        assert!(msg.contains("/no/such/mesh.msh"), "{msg}");
        let msg = parse_gmsh(b"hello", "junk.msh").unwrap_err().to_string();
        assert!(
            msg.starts_with("junk.msh: ") && msg.contains("$MeshFormat"),
            "{msg}"
        );
        let v2 = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n";
        let msg = parse_gmsh(v2.as_bytes(), "old.msh")
            .unwrap_err()
            .to_string();
        assert!(msg.contains("old.msh") && msg.contains("4.1"), "{msg}");
    }

    #[test]
    fn truncated_file_names_file_and_line() {
        let text = ascii_text();
        let cut = &text[..text.find("$Elements").unwrap() + 40];
        let msg = parse_gmsh(cut.as_bytes(), "cut.msh")
            .unwrap_err()
            .to_string();
        assert!(
            msg.starts_with("cut.msh: ") && msg.contains("line"),
            "{msg}"
        );
        assert!(msg.len() < 600, "no hex dump: {msg}");
        let bin = std::fs::read(fixture("cube_2x2x2_binary.msh")).unwrap();
        let msg = parse_gmsh(&bin[..bin.len() - 100], "cut_bin.msh")
            .unwrap_err()
            .to_string();
        assert!(msg.starts_with("cut_bin.msh: "), "{msg}");
    }

    #[test]
    fn inverted_element_is_named_by_its_gmsh_tag() {
        // First rock hex: swap its bottom and top node quadruples.
        let text = edit_after(&ascii_text(), "3 1 5 4", 1, |l| {
            let t: Vec<&str> = l.split_whitespace().collect();
            format!("{} {} {}", t[0], t[5..9].join(" "), t[1..5].join(" "))
        });
        let tag = text.lines().skip_while(|l| *l != "3 1 5 4").nth(1).unwrap();
        let tag = tag.split_whitespace().next().unwrap();
        let msg = parse_gmsh(text.as_bytes(), "inv.msh")
            .unwrap_err()
            .to_string();
        assert!(msg.starts_with("inv.msh: "), "{msg}");
        assert!(
            msg.contains(&format!("element {tag}")) && msg.contains("inverted"),
            "{msg}"
        );
    }

    #[test]
    fn other_element_types_are_named() {
        // Turn the lining block into 4-node tetrahedra.
        let mut text = ascii_text().replace("\n3 2 5 4\n", "\n3 2 4 4\n");
        for i in 1..=4 {
            text = edit_after(&text, "3 2 4 4", i, |l| {
                l.split_whitespace().take(5).collect::<Vec<_>>().join(" ")
            });
        }
        let tag = text.lines().skip_while(|l| *l != "3 2 4 4").nth(1).unwrap();
        let tag = tag.split_whitespace().next().unwrap();
        let msg = parse_gmsh(text.as_bytes(), "tet.msh")
            .unwrap_err()
            .to_string();
        assert!(msg.starts_with("tet.msh: "), "{msg}");
        assert!(
            msg.contains("Tet4") && msg.contains(&format!("element {tag}")),
            "{msg}"
        );
    }

    #[test]
    fn unknown_node_and_stray_quad_are_errors() {
        let text = edit_after(&ascii_text(), "3 2 5 4", 1, |l| {
            let mut t: Vec<String> = l.split_whitespace().map(String::from).collect();
            t[3] = "999999".into();
            t.join(" ")
        });
        let msg = parse_gmsh(text.as_bytes(), "n.msh")
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("n.msh") && msg.contains("node tag 999999"),
            "{msg}"
        );
        // A base quad whose nodes are not one hex face (two of them swapped with the top).
        let text = edit_after(&ascii_text(), "2 1 3 4", 1, |l| {
            let t: Vec<&str> = l.split_whitespace().collect();
            let hex = ascii_text();
            let top = hex
                .lines()
                .skip_while(|l| *l != "3 2 5 4")
                .nth(1)
                .unwrap()
                .to_string();
            let top: Vec<&str> = top.split_whitespace().collect();
            format!("{} {} {} {} {}", t[0], t[1], t[2], top[7], top[8])
        });
        let msg = parse_gmsh(text.as_bytes(), "q.msh")
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("q.msh") && msg.contains("'base'") && msg.contains("face"),
            "{msg}"
        );
    }

    #[test]
    fn no_hex8_is_an_error() {
        let text = ascii_text()
            .replace("\n3 1 5 4\n", "\n3 1 4 0\n")
            .replace("\n3 2 5 4\n", "\n3 2 4 0\n");
        // Drop the eight hex lines that now follow empty blocks: simplest is to rebuild.
        let lines: Vec<&str> = text.lines().collect();
        let at = lines.iter().position(|l| *l == "3 1 4 0").unwrap();
        let mut kept: Vec<&str> = lines[..=at].to_vec();
        kept.push("3 2 4 0");
        kept.extend(&lines[at + 10..]);
        let text = kept.join("\n") + "\n";
        let text = text.replacen("6 19 1000 1054", "6 11 1000 1030", 1);
        let msg = parse_gmsh(text.as_bytes(), "empty.msh")
            .unwrap_err()
            .to_string();
        assert!(
            msg.contains("empty.msh: $Elements = no hex8 element"),
            "{msg}"
        );
    }
}
