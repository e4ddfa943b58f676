//! Gmsh MSH 4.1 export (ASCII), so that a mesh can be inspected and edited in Gmsh and read
//! back by [`crate::mesh::gmsh`] as the same mesh: same node coordinates and numbering,
//! same elements in the same order, same regions, element sets, face sets and node sets.
//!
//! What becomes what (the reader's conventions, in reverse):
//! - nodes → one node block, tags 1..n in mesh order (every node must belong to a hex8:
//!   the reader keeps only those);
//! - regions → 3D physical groups 1..R in region order; element sets → further 3D physical
//!   groups. Each maximal run of consecutive elements with the same region and the same
//!   element sets becomes one volume entity whose physical tags are the region's group
//!   first, then its sets' groups — so the element order is kept exactly. The reader makes
//!   an element set of every region; a mesh whose element set named like a region holds
//!   other elements cannot be written;
//! - face sets → one surface entity and 2D physical group each, of 4-node quads whose node
//!   order is the face's (counter-clockwise seen from outside its element: the reader gives
//!   a quad between two elements to the element its normal points out of);
//! - node sets → the same name as a face set must hold that face set's nodes (the reader
//!   makes a node set of every face set); nodes beyond those, and node sets with no face
//!   set, become point elements (type 15), one 0D entity per node, in a 0D group.
//!
//! Empty sets are not written (the reader cannot create them). Floats are written in
//! Rust's shortest round-trip form, so coordinates come back bit for bit.

use std::collections::BTreeMap;
use std::io::{self, Write};

use crate::error::{DcfmError, Result};
use crate::mesh::Mesh;

/// A mesh checked for export, with its entity layout.
pub struct GmshExport<'m> {
    mesh: &'m Mesh,
    /// Volume entities: (first element, end element, physical tags).
    volumes: Vec<(usize, usize, Vec<i32>)>,
    /// 3D physical groups: (tag, name).
    volume_groups: Vec<(i32, String)>,
    /// Face sets written: (physical tag, name).
    surface_groups: Vec<(i32, String)>,
    /// Point groups: (physical tag, name, nodes written as points).
    point_groups: Vec<(i32, String, Vec<u32>)>,
}

fn check_name(name: &str, what: &str) -> Result<()> {
    if name.is_empty() || name.contains('"') || name.contains('\n') || name.contains('\r') {
        return Err(DcfmError::Mesh(format!(
            "{what} {name:?} cannot be a Gmsh physical name (empty, or holds a quote or a line break)"
        )));
    }
    Ok(())
}

/// Check that `mesh` can be written so that it reads back identically, and lay out its
/// entities and physical groups.
pub fn prepare_gmsh_export(mesh: &Mesh) -> Result<GmshExport<'_>> {
    mesh.validate()?;
    let mut used = vec![false; mesh.n_nodes()];
    for conn in &mesh.elements {
        for &a in conn {
            used[a as usize] = true;
        }
    }
    if let Some(n) = used.iter().position(|u| !u) {
        return Err(DcfmError::Mesh(format!(
            "node {n} belongs to no element: Gmsh export keeps only element nodes"
        )));
    }
    let n_regions = mesh.region_names.len();
    let mut volume_groups: Vec<(i32, String)> = Vec::new();
    for (r, name) in mesh.region_names.iter().enumerate() {
        check_name(name, "region")?;
        volume_groups.push((r as i32 + 1, name.clone()));
    }
    // Element sets other than the regions' own.
    let mut set_tags: Vec<(i32, &Vec<u32>)> = Vec::new();
    for (name, elements) in &mesh.element_sets {
        check_name(name, "element set")?;
        if let Some(r) = mesh.region_index(name) {
            let region: Vec<u32> = (0..mesh.n_elements() as u32)
                .filter(|&e| mesh.element_region[e as usize] as usize == r)
                .collect();
            if *elements != region {
                return Err(DcfmError::Mesh(format!(
                    "element set '{name}' is named like a region but holds other elements: \
                     Gmsh would read it back as the region"
                )));
            }
            continue;
        }
        if elements.is_empty() {
            continue;
        }
        if elements.windows(2).any(|w| w[0] >= w[1]) {
            return Err(DcfmError::Mesh(format!(
                "element set '{name}' is not sorted and unique"
            )));
        }
        let tag = (n_regions + set_tags.len() + 1) as i32;
        volume_groups.push((tag, name.clone()));
        set_tags.push((tag, elements));
    }
    // Signature of every element: its sets' tags.
    let mut member: Vec<Vec<i32>> = vec![Vec::new(); mesh.n_elements()];
    for (tag, elements) in &set_tags {
        for &e in elements.iter() {
            member[e as usize].push(*tag);
        }
    }
    let mut volumes: Vec<(usize, usize, Vec<i32>)> = Vec::new();
    for e in 0..mesh.n_elements() {
        let mut phys = vec![mesh.element_region[e] as i32 + 1];
        phys.extend(&member[e]);
        match volumes.last_mut() {
            Some((_, end, p)) if *p == phys => *end = e + 1,
            _ => volumes.push((e, e + 1, phys)),
        }
    }
    // Face sets and the node sets that go with them.
    let mut surface_groups = Vec::new();
    let mut point_groups = Vec::new();
    let mut next_tag = 1i32;
    for (name, faces) in &mesh.face_sets {
        check_name(name, "face set")?;
        if faces.is_empty() {
            continue;
        }
        if faces.windows(2).any(|w| w[0] >= w[1]) {
            return Err(DcfmError::Mesh(format!(
                "face set '{name}' is not sorted and unique"
            )));
        }
        surface_groups.push((next_tag, name.clone()));
        next_tag += 1;
    }
    for (name, nodes) in &mesh.node_sets {
        check_name(name, "node set")?;
        if nodes.is_empty() {
            continue;
        }
        if nodes.windows(2).any(|w| w[0] >= w[1]) {
            return Err(DcfmError::Mesh(format!(
                "node set '{name}' is not sorted and unique"
            )));
        }
        let extra: Vec<u32> = match mesh.face_sets.get(name).filter(|f| !f.is_empty()) {
            Some(faces) => {
                let of_faces = mesh.face_set_nodes(faces);
                if let Some(missing) = of_faces.iter().find(|n| nodes.binary_search(n).is_err()) {
                    return Err(DcfmError::Mesh(format!(
                        "node set '{name}' lacks node {missing} of the face set of the same \
                         name: Gmsh would read it back with the face set's nodes"
                    )));
                }
                nodes
                    .iter()
                    .copied()
                    .filter(|n| of_faces.binary_search(n).is_err())
                    .collect()
            }
            None => nodes.clone(),
        };
        if !extra.is_empty() {
            point_groups.push((0, name.clone(), extra));
        }
    }
    for (i, g) in point_groups.iter_mut().enumerate() {
        g.0 = i as i32 + 1;
    }
    Ok(GmshExport {
        mesh,
        volumes,
        volume_groups,
        surface_groups,
        point_groups,
    })
}

/// Bounding box of some nodes.
fn bbox(mesh: &Mesh, nodes: impl Iterator<Item = u32>) -> [f64; 6] {
    let mut b = [
        f64::INFINITY,
        f64::INFINITY,
        f64::INFINITY,
        -f64::INFINITY,
        -f64::INFINITY,
        -f64::INFINITY,
    ];
    for n in nodes {
        let x = mesh.coords[n as usize];
        for d in 0..3 {
            b[d] = b[d].min(x[d]);
            b[d + 3] = b[d + 3].max(x[d]);
        }
    }
    b
}

impl GmshExport<'_> {
    /// Write the mesh as ASCII MSH 4.1.
    pub fn write<W: Write>(&self, w: &mut W) -> io::Result<()> {
        let m = self.mesh;
        writeln!(w, "$MeshFormat\n4.1 0 8\n$EndMeshFormat")?;
        let n_names =
            self.volume_groups.len() + self.surface_groups.len() + self.point_groups.len();
        writeln!(w, "$PhysicalNames\n{n_names}")?;
        for (tag, name) in &self
            .point_groups
            .iter()
            .map(|g| (g.0, g.1.clone()))
            .collect::<Vec<_>>()
        {
            writeln!(w, "0 {tag} \"{name}\"")?;
        }
        for (tag, name) in &self.surface_groups {
            writeln!(w, "2 {tag} \"{name}\"")?;
        }
        for (tag, name) in &self.volume_groups {
            writeln!(w, "3 {tag} \"{name}\"")?;
        }
        writeln!(w, "$EndPhysicalNames")?;

        // Entities: one point per node of a point group, one surface per face set, the
        // volume runs.
        let n_points: usize = self.point_groups.iter().map(|g| g.2.len()).sum();
        writeln!(w, "$Entities")?;
        writeln!(
            w,
            "{n_points} 0 {} {}",
            self.surface_groups.len(),
            self.volumes.len()
        )?;
        let mut point_tag = 0;
        for (tag, _, nodes) in &self.point_groups {
            for &n in nodes {
                point_tag += 1;
                let x = m.coords[n as usize];
                writeln!(w, "{point_tag} {} {} {} 1 {tag}", x[0], x[1], x[2])?;
            }
        }
        for (i, (tag, name)) in self.surface_groups.iter().enumerate() {
            let faces = &m.face_sets[name];
            let b = bbox(m, faces.iter().flat_map(|f| m.face_nodes(*f)));
            writeln!(
                w,
                "{} {} {} {} {} {} {} 1 {tag} 0",
                i + 1,
                b[0],
                b[1],
                b[2],
                b[3],
                b[4],
                b[5]
            )?;
        }
        for (i, (start, end, phys)) in self.volumes.iter().enumerate() {
            let b = bbox(m, (*start..*end).flat_map(|e| m.elements[e]));
            write!(
                w,
                "{} {} {} {} {} {} {} {}",
                i + 1,
                b[0],
                b[1],
                b[2],
                b[3],
                b[4],
                b[5],
                phys.len()
            )?;
            for p in phys {
                write!(w, " {p}")?;
            }
            writeln!(w, " 0")?;
        }
        writeln!(w, "$EndEntities")?;

        // Nodes: one block on volume 1, tags 1..n.
        let n = m.n_nodes();
        writeln!(w, "$Nodes\n1 {n} 1 {n}\n3 1 0 {n}")?;
        for i in 1..=n {
            writeln!(w, "{i}")?;
        }
        for x in &m.coords {
            writeln!(w, "{} {} {}", x[0], x[1], x[2])?;
        }
        writeln!(w, "$EndNodes")?;

        // Elements: hex8 by volume run, then quads by face set, then points.
        let n_quads: usize = self
            .surface_groups
            .iter()
            .map(|(_, name)| m.face_sets[name].len())
            .sum();
        let n_blocks = self.volumes.len() + self.surface_groups.len() + n_points;
        let total = m.n_elements() + n_quads + n_points;
        writeln!(w, "$Elements\n{n_blocks} {total} 1 {total}")?;
        for (i, (start, end, _)) in self.volumes.iter().enumerate() {
            writeln!(w, "3 {} 5 {}", i + 1, end - start)?;
            for e in *start..*end {
                let c = m.elements[e];
                writeln!(
                    w,
                    "{} {} {} {} {} {} {} {} {}",
                    e + 1,
                    c[0] + 1,
                    c[1] + 1,
                    c[2] + 1,
                    c[3] + 1,
                    c[4] + 1,
                    c[5] + 1,
                    c[6] + 1,
                    c[7] + 1
                )?;
            }
        }
        let mut tag = m.n_elements();
        for (i, (_, name)) in self.surface_groups.iter().enumerate() {
            let faces = &m.face_sets[name];
            writeln!(w, "2 {} 3 {}", i + 1, faces.len())?;
            for f in faces {
                tag += 1;
                let q = m.face_nodes(*f);
                writeln!(
                    w,
                    "{tag} {} {} {} {}",
                    q[0] + 1,
                    q[1] + 1,
                    q[2] + 1,
                    q[3] + 1
                )?;
            }
        }
        let mut point_tag = 0;
        for (_, _, nodes) in &self.point_groups {
            for &node in nodes {
                point_tag += 1;
                tag += 1;
                writeln!(w, "0 {point_tag} 15 1\n{tag} {}", node + 1)?;
            }
        }
        writeln!(w, "$EndElements")?;
        Ok(())
    }

    /// The whole file as bytes.
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out = Vec::new();
        self.write(&mut out).expect("writing to memory");
        out
    }
}

/// Names of the physical groups of each kind written (for a summary).
pub fn group_counts(export: &GmshExport) -> BTreeMap<&'static str, usize> {
    BTreeMap::from([
        ("volume groups", export.volume_groups.len()),
        ("surface groups", export.surface_groups.len()),
        ("point groups", export.point_groups.len()),
        ("volume entities", export.volumes.len()),
    ])
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::gmsh::parse_gmsh;
    use crate::mesh::{BlockSpec, BoxMeshSpec};

    /// Two regions split apart, overlapping element sets, face and node sets of every
    /// kind: written and read back, the mesh is the same in every field.
    #[test]
    fn written_mesh_reads_back_identically() {
        let block = |name: &str, origin: [f64; 3], divisions: [usize; 3]| BlockSpec {
            name: name.into(),
            region: None,
            origin,
            size: [1.0, 1.0, 1.0],
            divisions,
            grading: [1.3, 1.0, 0.7],
        };
        let mut m = BoxMeshSpec {
            blocks: vec![
                block("rock", [0.1, -0.2, 0.0], [3, 2, 2]),
                block("lining", [0.1, -0.2, 1.0], [3, 2, 1]),
            ],
            split: vec![["rock".into(), "lining".into()]],
            merge_tolerance: 1e-6,
        }
        .build("t")
        .unwrap();
        // Awkward coordinates.
        for (i, x) in m.coords.iter_mut().enumerate() {
            x[0] += 1e-9 * (i as f64).sin();
            x[2] *= std::f64::consts::PI / 3.0;
        }
        // Element sets cutting across regions and each other, in no run order.
        m.element_sets.insert(
            "odd".into(),
            (0..m.n_elements() as u32).filter(|e| e % 2 == 1).collect(),
        );
        m.element_sets.insert("low".into(), (0..7).collect());
        // A node set with a face set of its name plus an extra node, and a pure node set.
        let mut base = m.node_sets["rock.zmin"].clone();
        base.push(m.n_nodes() as u32 - 1);
        base.sort_unstable();
        m.node_sets.insert("rock.zmin".into(), base);
        m.node_sets.insert("probe".into(), vec![3, 17]);
        let export = prepare_gmsh_export(&m).unwrap();
        let bytes = export.to_bytes();
        let back = parse_gmsh(&bytes, "round.msh").unwrap();
        assert_eq!(back.coords, m.coords);
        assert_eq!(back.elements, m.elements);
        assert_eq!(back.region_names, m.region_names);
        assert_eq!(back.element_region, m.element_region);
        assert_eq!(back.element_sets, m.element_sets);
        assert_eq!(back.face_sets, m.face_sets);
        assert_eq!(back.node_sets, m.node_sets);
        assert!(m.face_sets.contains_key("lining-rock") && m.face_sets.contains_key("rock-lining"));
    }

    #[test]
    fn unrepresentable_meshes_are_refused_with_the_set_named() {
        let mut m = BoxMeshSpec::single("rock", [0.0; 3], [1.0; 3], [2, 2, 2])
            .build("t")
            .unwrap();
        m.element_sets.insert("rock".into(), vec![0, 1]);
        let e = prepare_gmsh_export(&m).err().unwrap().to_string();
        assert!(e.contains("element set 'rock'"), "{e}");
        let mut m = BoxMeshSpec::single("rock", [0.0; 3], [1.0; 3], [2, 2, 2])
            .build("t")
            .unwrap();
        m.node_sets.insert("rock.zmin".into(), vec![0]);
        let e = prepare_gmsh_export(&m).err().unwrap().to_string();
        assert!(e.contains("node set 'rock.zmin'"), "{e}");
        let mut m = BoxMeshSpec::single("rock", [0.0; 3], [1.0; 3], [2, 2, 2])
            .build("t")
            .unwrap();
        m.element_sets.insert("bad\"name".into(), vec![0]);
        assert!(prepare_gmsh_export(&m).is_err());
    }
}
