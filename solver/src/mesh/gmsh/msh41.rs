//! The sections of a Gmsh MSH 4.1 file (ASCII or binary) that dcfm reads, as the file gives
//! them: `$PhysicalNames`, `$Entities` (the physical groups of each entity), `$Nodes` (with
//! every node's tag) and `$Elements`; other sections are skipped.
//!
//! Written here rather than through a reader crate: the one available (mshio 0.4) drops
//! node tags when their range is dense, so a file whose node blocks hold tags out of global
//! order was read as another geometry, and malformed counts made it allocate without
//! bound or panic. Every count here is checked against the bytes left before anything is
//! allocated for it; tags are kept exactly as written.
//!
//! Format reference: Gmsh reference manual, §10.1 "MSH file format" (version 4.1).

use std::collections::HashMap;

use super::cursor::{Cursor, Encoding, Kind};

/// One block of nodes: the entity it belongs to, the tags and the coordinates.
#[derive(Clone, Debug, Default)]
pub(super) struct NodeBlock {
    pub tags: Vec<u64>,
    pub coords: Vec<[f64; 3]>,
}

/// One block of elements of one type on one entity.
#[derive(Clone, Debug)]
pub(super) struct ElementBlock {
    pub entity_dim: i32,
    pub entity_tag: i32,
    /// Gmsh element type (5 = hex8, 3 = quad4, 1 = line2, 15 = point).
    pub element_type: i32,
    pub nodes_per_element: usize,
    pub tags: Vec<u64>,
    /// `nodes_per_element` node tags per element.
    pub nodes: Vec<u64>,
}

/// The parts of an MSH 4.1 file that dcfm uses.
#[derive(Clone, Debug, Default)]
pub(super) struct MshData {
    /// (dim, physical tag) → name.
    pub names: HashMap<(i32, i32), String>,
    /// (dim, entity tag) → physical tags, in file order.
    pub entity_groups: HashMap<(i32, i32), Vec<i32>>,
    pub node_blocks: Vec<NodeBlock>,
    pub element_blocks: Vec<ElementBlock>,
    pub has_nodes: bool,
    pub has_elements: bool,
}

/// Nodes per element of the Gmsh types dcfm may meet (others are named as unsupported by
/// the importer, but their blocks must still be read past).
pub(super) fn nodes_per_element(element_type: i32) -> Option<usize> {
    Some(match element_type {
        1 => 2,   // 2-node line
        2 => 3,   // 3-node triangle
        3 => 4,   // 4-node quadrangle
        4 => 4,   // 4-node tetrahedron
        5 => 8,   // 8-node hexahedron
        6 => 6,   // 6-node prism
        7 => 5,   // 5-node pyramid
        8 => 3,   // 3-node line
        9 => 6,   // 6-node triangle
        10 => 9,  // 9-node quadrangle
        11 => 10, // 10-node tetrahedron
        12 => 27, // 27-node hexahedron
        13 => 18, // 18-node prism
        14 => 14, // 14-node pyramid
        15 => 1,  // point
        16 => 8,  // 8-node quadrangle
        17 => 20, // 20-node hexahedron
        18 => 15, // 15-node prism
        19 => 13, // 13-node pyramid
        _ => return None,
    })
}

/// Name of a Gmsh element type for messages.
pub(super) fn element_type_name(element_type: i32) -> &'static str {
    match element_type {
        1 => "Lin2",
        2 => "Tri3",
        3 => "Qua4",
        4 => "Tet4",
        5 => "Hex8",
        6 => "Pri6",
        7 => "Pyr5",
        8 => "Lin3",
        9 => "Tri6",
        10 => "Qua9",
        11 => "Tet10",
        12 => "Hex27",
        13 => "Pri18",
        14 => "Pyr14",
        15 => "Pnt",
        16 => "Qua8",
        17 => "Hex20",
        18 => "Pri15",
        19 => "Pyr13",
        _ => "unknown",
    }
}

/// Parse the bytes of an MSH 4.1 file.
pub(super) fn parse(bytes: &[u8]) -> Result<MshData, String> {
    let (encoding, start) = mesh_format(bytes)?;
    let mut c = Cursor::new(bytes, start, encoding);
    let mut data = MshData::default();
    while let Some(name) = c.section()? {
        match name {
            "PhysicalNames" => {
                c.end_of_header_line();
                let text = c.text_until_end(name)?;
                data.names = physical_names(text)?;
            }
            "Entities" => {
                c.end_of_header_line();
                entities(&mut c, &mut data)?;
                c.expect_end(name)?;
            }
            "Nodes" => {
                if data.has_nodes {
                    return Err("two $Nodes sections".into());
                }
                c.end_of_header_line();
                nodes(&mut c, &mut data)?;
                c.expect_end(name)?;
                data.has_nodes = true;
            }
            "Elements" => {
                if data.has_elements {
                    return Err("two $Elements sections".into());
                }
                c.end_of_header_line();
                elements(&mut c, &mut data)?;
                c.expect_end(name)?;
                data.has_elements = true;
            }
            other if other.starts_with("End") => {
                return Err(format!(
                    "line {}: ${other} without its opening section",
                    c.line()
                ));
            }
            other => {
                let other = other.to_string();
                c.skip_section(&other)?;
            }
        }
    }
    Ok(data)
}

/// `$MeshFormat`: version 4.1, the encoding; returns the position after `$EndMeshFormat`.
fn mesh_format(bytes: &[u8]) -> Result<(Encoding, usize), String> {
    let head = &bytes[..bytes.len().min(256)];
    let text = String::from_utf8_lossy(head);
    let mut lines = text.lines().map(str::trim);
    if lines.next() != Some("$MeshFormat") {
        return Err("not a Gmsh mesh file (it must begin with $MeshFormat)".into());
    }
    let format = lines.next().unwrap_or("");
    let mut words = format.split_whitespace();
    let version = words.next().unwrap_or("");
    if version != "4.1" {
        return Err(format!(
            "MSH format version {version:?} is not supported: save the mesh as MSH 4.1 \
             (gmsh -format msh41, or Mesh.MshFileVersion = 4.1)"
        ));
    }
    let file_type = words.next().unwrap_or("");
    let data_size = words.next().unwrap_or("");
    let size_t: usize = match data_size {
        "4" => 4,
        "8" => 8,
        other => {
            return Err(format!(
                "$MeshFormat: data size {other:?}: expected 4 or 8 (bytes of size_t)"
            ))
        }
    };
    // Position just after the format line.
    let after_format = {
        let first = find(bytes, b"\n").ok_or("$MeshFormat: truncated")? + 1;
        first + find(&bytes[first..], b"\n").ok_or("$MeshFormat: truncated")? + 1
    };
    let (encoding, mut pos) = match file_type {
        "0" => (Encoding::Ascii, after_format),
        "1" => {
            let one = bytes
                .get(after_format..after_format + 4)
                .ok_or("$MeshFormat: truncated before the binary endianness word")?;
            match i32::from_le_bytes(one.try_into().expect("4 bytes")) {
                1 => {}
                _ if i32::from_be_bytes(one.try_into().expect("4 bytes")) == 1 => {
                    return Err("big-endian binary MSH files are not supported".into())
                }
                v => {
                    return Err(format!(
                        "$MeshFormat: binary endianness word is {v}, expected 1"
                    ))
                }
            }
            (Encoding::Binary { size_t }, after_format + 4)
        }
        other => {
            return Err(format!(
                "$MeshFormat: file type {other:?}: expected 0 (ASCII) or 1 (binary)"
            ))
        }
    };
    let mut c = Cursor::new(bytes, pos, Encoding::Ascii);
    c.expect_end("MeshFormat")?;
    pos = c.pos;
    Ok((encoding, pos))
}

fn find(hay: &[u8], needle: &[u8]) -> Option<usize> {
    hay.windows(needle.len()).position(|w| w == needle)
}

/// `$PhysicalNames` text: (dim, tag) → name.
pub(super) fn physical_names(text: &str) -> Result<HashMap<(i32, i32), String>, String> {
    let mut out = HashMap::new();
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

/// `$Entities`: the physical tags of every point, curve, surface and volume.
fn entities(c: &mut Cursor, data: &mut MshData) -> Result<(), String> {
    let per_entity = c.min_bytes(Kind::Int) + 3 * c.min_bytes(Kind::Float);
    let counts = [
        c.count("$Entities: number of points", per_entity)?,
        c.count("$Entities: number of curves", per_entity)?,
        c.count("$Entities: number of surfaces", per_entity)?,
        c.count("$Entities: number of volumes", per_entity)?,
    ];
    for (dim, &n) in counts.iter().enumerate() {
        let kind = ["point", "curve", "surface", "volume"][dim];
        for i in 0..n {
            let what = |f: &str| format!("$Entities: {kind} {} of {n}: {f}", i + 1);
            let tag = c.int(&what("tag"))?;
            let n_box = if dim == 0 { 3 } else { 6 };
            for _ in 0..n_box {
                c.float(&what("bounding box"))?;
            }
            let n_phys = c.count(&what("number of physical tags"), c.min_bytes(Kind::Int))?;
            let mut phys = Vec::with_capacity(n_phys);
            for _ in 0..n_phys {
                phys.push(c.int(&what("physical tag"))?);
            }
            if dim > 0 {
                let n_bound =
                    c.count(&what("number of bounding entities"), c.min_bytes(Kind::Int))?;
                for _ in 0..n_bound {
                    c.int(&what("bounding entity"))?;
                }
            }
            data.entity_groups.insert((dim as i32, tag), phys);
        }
    }
    Ok(())
}

/// `$Nodes`: every block with its tags and coordinates.
fn nodes(c: &mut Cursor, data: &mut MshData) -> Result<(), String> {
    let size = c.min_bytes(Kind::Size);
    let n_blocks = c.count("$Nodes: number of entity blocks", 4 * size)?;
    let n_nodes = c.size("$Nodes: number of nodes")?;
    c.size("$Nodes: minimum node tag")?;
    c.size("$Nodes: maximum node tag")?;
    let mut total = 0u64;
    for b in 0..n_blocks {
        let what = |f: &str| format!("$Nodes: block {} of {n_blocks}: {f}", b + 1);
        c.int(&what("entity dimension"))?;
        c.int(&what("entity tag"))?;
        let parametric = c.int(&what("parametric flag"))?;
        if parametric != 0 {
            return Err(what(
                "parametric nodes are not supported (save without Mesh.SaveParametric)",
            ));
        }
        let per_node = size + 3 * c.min_bytes(Kind::Float);
        let n = c.count(&what("number of nodes"), per_node)?;
        let mut block = NodeBlock {
            tags: Vec::with_capacity(n),
            coords: Vec::with_capacity(n),
        };
        for _ in 0..n {
            block.tags.push(c.size(&what("node tag"))?);
        }
        for &tag in &block.tags {
            let x = [
                c.float(&format!("$Nodes: x of node {tag}"))?,
                c.float(&format!("$Nodes: y of node {tag}"))?,
                c.float(&format!("$Nodes: z of node {tag}"))?,
            ];
            block.coords.push(x);
        }
        total += n as u64;
        data.node_blocks.push(block);
    }
    if total != n_nodes {
        return Err(format!(
            "$Nodes: the header says {n_nodes} nodes, the blocks hold {total}"
        ));
    }
    Ok(())
}

/// `$Elements`: every block with its element tags and node tags.
fn elements(c: &mut Cursor, data: &mut MshData) -> Result<(), String> {
    let size = c.min_bytes(Kind::Size);
    let n_blocks = c.count("$Elements: number of entity blocks", 4 * size)?;
    let n_elements = c.size("$Elements: number of elements")?;
    c.size("$Elements: minimum element tag")?;
    c.size("$Elements: maximum element tag")?;
    let mut total = 0u64;
    for b in 0..n_blocks {
        let what = |f: &str| format!("$Elements: block {} of {n_blocks}: {f}", b + 1);
        let entity_dim = c.int(&what("entity dimension"))?;
        let entity_tag = c.int(&what("entity tag"))?;
        let element_type = c.int(&what("element type"))?;
        let nodes_per_element = nodes_per_element(element_type).ok_or_else(|| {
            what(&format!(
                "element type {element_type} is not a Gmsh element type dcfm knows"
            ))
        })?;
        let n = c.count(&what("number of elements"), (1 + nodes_per_element) * size)?;
        let mut block = ElementBlock {
            entity_dim,
            entity_tag,
            element_type,
            nodes_per_element,
            tags: Vec::with_capacity(n),
            nodes: Vec::with_capacity(n * nodes_per_element),
        };
        for _ in 0..n {
            let tag = c.size(&what("element tag"))?;
            block.tags.push(tag);
            for _ in 0..nodes_per_element {
                block
                    .nodes
                    .push(c.size(&format!("$Elements: a node tag of element {tag}"))?);
            }
        }
        total += n as u64;
        data.element_blocks.push(block);
    }
    if total != n_elements {
        return Err(format!(
            "$Elements: the header says {n_elements} elements, the blocks hold {total}"
        ));
    }
    Ok(())
}
