//! The outside of a mesh: element faces that no other element face covers, neither
//! topologically (a face shared by two elements) nor geometrically (a face of the other
//! side of a split, i.e. of a contact interface, whose nodes are duplicates at the same
//! place). Absorbing and free-field boundaries may only sit on such faces.

use std::collections::{HashMap, HashSet};

use crate::mesh::{Face, Mesh, HEX8_FACES};

/// Faces of the mesh that lie on its outside, in element order.
pub fn outer_faces(mesh: &Mesh) -> Vec<Face> {
    let covered = covered_faces(mesh);
    all_faces(mesh).filter(|f| !covered.contains(f)).collect()
}

/// Add the face sets `outer.xmin`, `outer.xmax`, … `outer.zmax`: the outside faces lying
/// on each plane of the mesh's bounding box (corners within 1e-6 of the box size), with
/// node sets of the same names. Sets the mesh already has keep their own definition.
pub fn add_bounding_box_face_sets(mesh: &mut Mesh) {
    if mesh.n_nodes() == 0 {
        return;
    }
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for x in &mesh.coords {
        for d in 0..3 {
            lo[d] = lo[d].min(x[d]);
            hi[d] = hi[d].max(x[d]);
        }
    }
    let size = (0..3).map(|d| hi[d] - lo[d]).fold(0.0, f64::max);
    let tol = 1e-6 * size;
    let outer = outer_faces(mesh);
    for (d, axis) in ["x", "y", "z"].iter().enumerate() {
        for (end, plane) in [("min", lo[d]), ("max", hi[d])] {
            let name = format!("outer.{axis}{end}");
            if mesh.face_sets.contains_key(&name) || mesh.node_sets.contains_key(&name) {
                continue;
            }
            let faces: Vec<Face> = outer
                .iter()
                .copied()
                .filter(|&f| {
                    mesh.face_nodes(f)
                        .iter()
                        .all(|&n| (mesh.coords[n as usize][d] - plane).abs() <= tol)
                })
                .collect();
            if faces.is_empty() {
                continue;
            }
            let nodes = mesh.face_set_nodes(&faces);
            mesh.face_sets.insert(name.clone(), faces);
            mesh.node_sets.insert(name, nodes);
        }
    }
}

/// Every face of every element.
fn all_faces(mesh: &Mesh) -> impl Iterator<Item = Face> + '_ {
    (0..mesh.n_elements() as u32)
        .flat_map(|element| (0..6u8).map(move |local| Face { element, local }))
}

/// Faces that another element's face covers: the same four nodes, or four nodes at the
/// same places (coordinates rounded to a tolerance of the face's size).
pub fn covered_faces(mesh: &Mesh) -> HashSet<Face> {
    let mut by_nodes: HashMap<[u32; 4], Vec<Face>> = HashMap::new();
    let mut by_place: HashMap<[i64; 12], Vec<Face>> = HashMap::new();
    let tol = place_tolerance(mesh);
    for f in all_faces(mesh) {
        let mut key = mesh.face_nodes(f);
        key.sort_unstable();
        by_nodes.entry(key).or_default().push(f);
        by_place.entry(place_key(mesh, f, tol)).or_default().push(f);
    }
    let mut covered = HashSet::new();
    for group in by_nodes.values().chain(by_place.values()) {
        if group.len() > 1 {
            covered.extend(group.iter().copied());
        }
    }
    covered
}

/// Rounding length for geometric face matching: 1e-6 of the smallest element edge.
pub(crate) fn place_tolerance(mesh: &Mesh) -> f64 {
    let mut h = f64::INFINITY;
    for e in 0..mesh.n_elements() {
        let x = mesh.element_coords(e);
        for face in HEX8_FACES {
            for k in 0..4 {
                let (a, b) = (x[face[k]], x[face[(k + 1) % 4]]);
                let d =
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                if d > 0.0 {
                    h = h.min(d);
                }
            }
        }
    }
    if h.is_finite() {
        1e-6 * h
    } else {
        1e-9
    }
}

/// The face's corner coordinates, rounded to `tol` and sorted (so that the two sides of
/// an interface, whose node orders differ, give the same key).
pub(crate) fn place_key(mesh: &Mesh, f: Face, tol: f64) -> [i64; 12] {
    let mut corners: [[i64; 3]; 4] = mesh
        .face_nodes(f)
        .map(|n| mesh.coords[n as usize].map(|c| (c / tol).round() as i64));
    corners.sort_unstable();
    let mut key = [0i64; 12];
    for (k, c) in corners.iter().enumerate() {
        key[3 * k..3 * k + 3].copy_from_slice(c);
    }
    key
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::BoxMeshSpec;

    #[test]
    fn a_block_has_its_six_sides_outside() {
        let m = BoxMeshSpec::single("b", [0.0; 3], [2.0, 3.0, 4.0], [2, 3, 4])
            .build("t")
            .unwrap();
        let outer = outer_faces(&m);
        assert_eq!(outer.len(), 2 * (2 * 3 + 3 * 4 + 2 * 4));
    }

    #[test]
    fn bounding_box_face_sets_cover_the_outer_planes() {
        let mut m = BoxMeshSpec::single("b", [0.0; 3], [2.0, 3.0, 4.0], [2, 3, 4])
            .build("t")
            .unwrap();
        add_bounding_box_face_sets(&mut m);
        assert_eq!(m.face_sets["outer.zmin"].len(), 6);
        assert_eq!(m.face_sets["outer.xmax"].len(), 12);
        assert_eq!(m.face_sets["outer.zmin"], m.face_sets["b.zmin"]);
    }

    #[test]
    fn faces_of_a_split_interface_are_not_outside() {
        use crate::mesh::BlockSpec;
        let spec = BoxMeshSpec {
            blocks: vec![
                BlockSpec {
                    name: "a".into(),
                    region: None,
                    origin: [0.0; 3],
                    size: [1.0, 1.0, 1.0],
                    divisions: [1, 1, 1],
                    grading: [1.0; 3],
                },
                BlockSpec {
                    name: "b".into(),
                    region: None,
                    origin: [0.0, 0.0, 1.0],
                    size: [1.0, 1.0, 1.0],
                    divisions: [1, 1, 1],
                    grading: [1.0; 3],
                },
            ],
            split: vec![["a".into(), "b".into()]],
            merge_tolerance: 1e-6,
        };
        let m = spec.build("t").unwrap();
        assert_eq!(outer_faces(&m).len(), 10);
    }
}
