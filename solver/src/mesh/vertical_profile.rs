//! The column of elements above a base face: walking up from an element through the face
//! opposite its base to the element that shares it — or, across a split (a contact
//! interface), the element whose face lies at the same place — until the top of the mesh.
//! The free field takes its layering from such a profile.

use std::collections::HashMap;

use crate::mesh::{Face, Mesh};

/// Local face opposite each local face of a hex8 ([`crate::mesh::HEX8_FACES`] order:
/// ζ−, ζ+, η−, ξ+, η+, ξ−).
pub const OPPOSITE_FACE: [u8; 6] = [1, 0, 4, 5, 2, 3];

/// One element of a profile: its id and the heights of the centroids of its bottom and
/// top faces.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileElement {
    pub element: u32,
    pub z_bottom: f64,
    pub z_top: f64,
}

/// Height of a face's centroid (mean of its corners).
pub fn face_centroid(mesh: &Mesh, f: Face) -> [f64; 3] {
    let mut c = [0.0; 3];
    for n in mesh.face_nodes(f) {
        for d in 0..3 {
            c[d] += 0.25 * mesh.coords[n as usize][d];
        }
    }
    c
}

/// The elements stacked above `base` (a face on the bottom of the mesh), bottom to top.
/// Stops at the first face that no other element shares. Errors (as text) when the walk
/// goes down or sideways (the mesh is not layered there).
pub fn vertical_profile(mesh: &Mesh, base: Face) -> Result<Vec<ProfileElement>, String> {
    let tol = crate::mesh::outer_faces::place_tolerance(mesh);
    let mut by_nodes: HashMap<[u32; 4], Vec<Face>> = HashMap::new();
    let mut by_place: HashMap<[i64; 12], Vec<Face>> = HashMap::new();
    for element in 0..mesh.n_elements() as u32 {
        for local in 0..6u8 {
            let f = Face { element, local };
            let mut key = mesh.face_nodes(f);
            key.sort_unstable();
            by_nodes.entry(key).or_default().push(f);
            by_place
                .entry(crate::mesh::outer_faces::place_key(mesh, f, tol))
                .or_default()
                .push(f);
        }
    }
    let mut out = Vec::new();
    let mut bottom = base;
    loop {
        let top = Face {
            element: bottom.element,
            local: OPPOSITE_FACE[bottom.local as usize],
        };
        let (zb, zt) = (face_centroid(mesh, bottom)[2], face_centroid(mesh, top)[2]);
        if zt <= zb {
            return Err(format!(
                "element {} does not rise from face {} (z {zb:.4} → {zt:.4}); the mesh is not \
                 stacked in layers above the chosen base face",
                bottom.element, bottom.local
            ));
        }
        out.push(ProfileElement {
            element: bottom.element,
            z_bottom: zb,
            z_top: zt,
        });
        let mut key = mesh.face_nodes(top);
        key.sort_unstable();
        let other = |fs: &Vec<Face>| fs.iter().copied().find(|f| f.element != top.element);
        let next = by_nodes.get(&key).and_then(other).or_else(|| {
            by_place
                .get(&crate::mesh::outer_faces::place_key(mesh, top, tol))
                .and_then(other)
        });
        match next {
            Some(next) => bottom = next,
            None => return Ok(out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::BoxMeshSpec;

    #[test]
    fn walks_a_block_from_bottom_to_top() {
        let m = BoxMeshSpec::single("b", [0.0; 3], [2.0, 2.0, 6.0], [2, 2, 3])
            .build("t")
            .unwrap();
        let base = m.face_sets["b.zmin"][0];
        let p = vertical_profile(&m, base).unwrap();
        assert_eq!(p.len(), 3);
        assert_eq!(p[0].z_bottom, 0.0);
        assert_eq!(p[2].z_top, 6.0);
        for w in p.windows(2) {
            assert_eq!(w[0].z_top, w[1].z_bottom);
        }
    }
}
