//! Duplicated nodes between regions (where contact interfaces sit), all region pairs at
//! once, so that a node on several interfaces (a lining meeting the inner structure and
//! both meeting the rock) gets one copy per side and every interface keeps all its faces.
//!
//! Splitting pairs one after the other cannot do that: after `[rock, lining]` the lining
//! holds a copy of a node on the rock–lining–inner line, so a later `[lining, inner]` no
//! longer sees that node shared and drops the faces that touch the line.

use std::collections::HashMap;

use crate::mesh::{Face, Mesh, HEX8_FACES};

/// Why a split failed: the index of the pair in the list and the reason.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct SplitError {
    pub pair: usize,
    pub message: String,
}

/// Keep apart the regions of every pair `[a, b]`: at each node touched by both, the
/// elements of a and of b get different nodes (at the same place). Regions not split from
/// each other keep sharing their node. At every node the touching regions fall into groups
/// joined by "not split"; the group holding the lowest region index keeps the node, each
/// other group gets a new copy (so for one pair, `b` gets the copies, as before).
///
/// Creates, for every pair, the face sets `a-b` (faces of a that coincide with a face of b)
/// and `b-a`, with node sets of the same names; node sets named like a face set are rebuilt
/// from it. Errors: unknown or equal regions, a pair that shares no face, and a node where
/// a split pair is joined through a third region split from neither (name all three).
pub fn split_region_pairs(mesh: &mut Mesh, pairs: &[[String; 2]]) -> Result<(), SplitError> {
    split_regions(mesh, pairs, true)
}

/// As [`split_region_pairs`], but a pair that shares no face is no error: its regions are
/// kept apart where they touch along edges or at corners (a generator that lists every
/// pair of bodies that must not share a node, whichever of them happen to share faces);
/// its face sets are then empty.
pub fn split_region_pairs_touching(
    mesh: &mut Mesh,
    pairs: &[[String; 2]],
) -> Result<(), SplitError> {
    split_regions(mesh, pairs, false)
}

fn split_regions(
    mesh: &mut Mesh,
    pairs: &[[String; 2]],
    require_shared_face: bool,
) -> Result<(), SplitError> {
    let err = |pair: usize, message: String| SplitError { pair, message };
    let mut idx: Vec<[u16; 2]> = Vec::with_capacity(pairs.len());
    for (p, [a, b]) in pairs.iter().enumerate() {
        let find = |name: &str| {
            mesh.region_index(name).map(|r| r as u16).ok_or_else(|| {
                err(
                    p,
                    format!("unknown region '{name}' (regions: {:?})", mesh.region_names),
                )
            })
        };
        let (ra, rb) = (find(a)?, find(b)?);
        if ra == rb {
            return Err(err(p, "the two regions must differ".into()));
        }
        idx.push([ra, rb]);
    }
    let is_split = |r: u16, s: u16| {
        idx.iter()
            .any(|&[a, b]| (a == r && b == s) || (a == s && b == r))
    };

    // Faces of each pair on the shared surface, from the unsplit topology.
    let mut face_of: HashMap<[u32; 4], Vec<Face>> = HashMap::new();
    for (e, conn) in mesh.elements.iter().enumerate() {
        for (l, local) in HEX8_FACES.iter().enumerate() {
            let mut key = local.map(|a| conn[a]);
            key.sort_unstable();
            face_of.entry(key).or_default().push(Face {
                element: e as u32,
                local: l as u8,
            });
        }
    }
    let mut pair_faces: Vec<(Vec<Face>, Vec<Face>)> = vec![(Vec::new(), Vec::new()); idx.len()];
    // A face shared by more than two elements (bodies that overlap in volume, e.g. a
    // lining placed where rock is excavated) belongs to every pair among them.
    let mut keys: Vec<&[u32; 4]> = face_of.keys().collect();
    keys.sort_unstable();
    for faces in keys.into_iter().map(|k| &face_of[k]) {
        for (i, &f) in faces.iter().enumerate() {
            for &g in &faces[i + 1..] {
                let (rf, rg) = (
                    mesh.element_region[f.element as usize],
                    mesh.element_region[g.element as usize],
                );
                for (p, &[a, b]) in idx.iter().enumerate() {
                    if rf == a && rg == b {
                        pair_faces[p].0.push(f);
                        pair_faces[p].1.push(g);
                    } else if rf == b && rg == a {
                        pair_faces[p].0.push(g);
                        pair_faces[p].1.push(f);
                    }
                }
            }
        }
    }
    for (p, (fa, _)) in pair_faces.iter_mut().enumerate() {
        if fa.is_empty() && require_shared_face {
            return Err(err(
                p,
                format!(
                    "regions '{}' and '{}' share no face",
                    pairs[p][0], pairs[p][1]
                ),
            ));
        }
    }
    for (fa, fb) in pair_faces.iter_mut() {
        fa.sort_unstable();
        fb.sort_unstable();
    }

    // Regions touching each node (few per node).
    let n = mesh.n_nodes();
    let mut touching: Vec<Vec<u16>> = vec![Vec::new(); n];
    for (e, conn) in mesh.elements.iter().enumerate() {
        let r = mesh.element_region[e];
        for &a in conn {
            let t = &mut touching[a as usize];
            if !t.contains(&r) {
                t.push(r);
            }
        }
    }
    // New node per (node, region) where the region's group does not keep the original.
    let mut copy_of: HashMap<(u32, u16), u32> = HashMap::new();
    for (node, regions) in touching.iter_mut().enumerate() {
        if regions.len() < 2
            || !regions
                .iter()
                .any(|&r| regions.iter().any(|&s| is_split(r, s)))
        {
            continue;
        }
        regions.sort_unstable();
        // Groups by union-find over "not split".
        let k = regions.len();
        let mut parent: Vec<usize> = (0..k).collect();
        fn root(parent: &mut [usize], mut i: usize) -> usize {
            while parent[i] != i {
                parent[i] = parent[parent[i]];
                i = parent[i];
            }
            i
        }
        for i in 0..k {
            for j in i + 1..k {
                if !is_split(regions[i], regions[j]) {
                    let (ri, rj) = (root(&mut parent, i), root(&mut parent, j));
                    parent[ri.max(rj)] = ri.min(rj);
                }
            }
        }
        for i in 0..k {
            for j in i + 1..k {
                if is_split(regions[i], regions[j]) && root(&mut parent, i) == root(&mut parent, j)
                {
                    let name = |r: u16| mesh.region_names[r as usize].clone();
                    let p = idx
                        .iter()
                        .position(|&[a, b]| {
                            (a == regions[i] && b == regions[j])
                                || (a == regions[j] && b == regions[i])
                        })
                        .expect("a split pair");
                    let others: Vec<String> = regions
                        .iter()
                        .filter(|&&r| r != regions[i] && r != regions[j])
                        .map(|&r| name(r))
                        .collect();
                    return Err(err(
                        p,
                        format!(
                            "at node {node} ({:?}) regions '{}' and '{}' must be kept apart but \
                             both share it with {:?}, which is split from neither: split that \
                             region from one of them too",
                            mesh.coords[node],
                            name(regions[i]),
                            name(regions[j]),
                            others
                        ),
                    ));
                }
            }
        }
        // The group of the lowest region (regions[0]) keeps the node; each other group
        // gets one copy shared by its regions.
        let keep = root(&mut parent, 0);
        let mut group_copy: HashMap<usize, u32> = HashMap::new();
        for i in 0..k {
            let g = root(&mut parent, i);
            if g == keep {
                continue;
            }
            let c = *group_copy.entry(g).or_insert_with(|| {
                mesh.coords.push(mesh.coords[node]);
                (mesh.coords.len() - 1) as u32
            });
            copy_of.insert((node as u32, regions[i]), c);
        }
    }
    for (e, conn) in mesh.elements.iter_mut().enumerate() {
        let r = mesh.element_region[e];
        for a in conn.iter_mut() {
            if let Some(&c) = copy_of.get(&(*a, r)) {
                *a = c;
            }
        }
    }
    // Node sets derived from face sets follow their faces.
    let rebuilt: Vec<(String, Vec<u32>)> = mesh
        .face_sets
        .iter()
        .filter(|(name, _)| mesh.node_sets.contains_key(*name))
        .map(|(name, f)| (name.clone(), mesh.face_set_nodes(f)))
        .collect();
    mesh.node_sets.extend(rebuilt);
    for ([a, b], (fa, fb)) in pairs.iter().zip(pair_faces) {
        let (ab, ba) = (format!("{a}-{b}"), format!("{b}-{a}"));
        mesh.node_sets.insert(ab.clone(), mesh.face_set_nodes(&fa));
        mesh.node_sets.insert(ba.clone(), mesh.face_set_nodes(&fb));
        mesh.face_sets.insert(ab, fa);
        mesh.face_sets.insert(ba, fb);
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::{BlockSpec, BoxMeshSpec};

    /// Rock below z = 1; lining (x < 1) and inner (x > 1) side by side above it: the line
    /// x = 1, z = 1 touches all three regions.
    fn three_regions() -> Mesh {
        let block = |name: &str, origin: [f64; 3], size: [f64; 3]| BlockSpec {
            name: name.into(),
            region: None,
            origin,
            size,
            divisions: [2 * size[0] as usize, 2, 2],
            grading: [1.0; 3],
        };
        BoxMeshSpec {
            blocks: vec![
                block("rock", [0.0; 3], [2.0, 1.0, 1.0]),
                block("lining", [0.0, 0.0, 1.0], [1.0, 1.0, 1.0]),
                block("inner", [1.0, 0.0, 1.0], [1.0, 1.0, 1.0]),
            ],
            split: vec![],
            merge_tolerance: 1e-6,
        }
        .build("t")
        .unwrap()
    }

    fn pairs(p: &[[&str; 2]]) -> Vec<[String; 2]> {
        p.iter()
            .map(|[a, b]| [a.to_string(), b.to_string()])
            .collect()
    }

    #[test]
    fn node_on_three_interfaces_gets_three_copies_and_every_face_is_kept() {
        let mut m = three_regions();
        let n0 = m.n_nodes();
        split_region_pairs(
            &mut m,
            &pairs(&[["rock", "lining"], ["rock", "inner"], ["lining", "inner"]]),
        )
        .unwrap();
        m.validate().unwrap();
        // Each of the three interfaces keeps all its faces: 2×2 under the lining and under
        // the inner block, 2×2 between them.
        for (name, n) in [
            ("rock-lining", 4),
            ("lining-rock", 4),
            ("rock-inner", 4),
            ("inner-rock", 4),
            ("lining-inner", 4),
            ("inner-lining", 4),
        ] {
            assert_eq!(m.face_sets[name].len(), n, "{name}");
        }
        // The 3 nodes on the triple line (x = 1, z = 1) exist three times, the 12 other
        // nodes of the rock top twice, and the 6 other nodes of the lining–inner face twice.
        assert_eq!(m.n_nodes(), n0 + 3 * 2 + 12 + 6);
        let rock = m.nodes_of("rock").unwrap();
        let lining = m.nodes_of("lining").unwrap();
        let inner = m.nodes_of("inner").unwrap();
        assert!(lining
            .iter()
            .all(|n| !rock.contains(n) && !inner.contains(n)));
        assert!(inner.iter().all(|n| !rock.contains(n)));
    }

    #[test]
    fn regions_not_split_keep_sharing() {
        let mut m = three_regions();
        let n0 = m.n_nodes();
        split_region_pairs(&mut m, &pairs(&[["rock", "lining"], ["rock", "inner"]])).unwrap();
        // Lining and inner share their copies: the rock top (3 × 5 nodes) is doubled once.
        assert_eq!(m.n_nodes(), n0 + 15);
        let lining = m.nodes_of("lining").unwrap();
        let inner = m.nodes_of("inner").unwrap();
        assert_eq!(lining.iter().filter(|n| inner.contains(n)).count(), 9);
    }

    #[test]
    fn a_split_pair_joined_through_a_third_region_is_an_error() {
        let mut m = three_regions();
        let e = split_region_pairs(&mut m, &pairs(&[["lining", "inner"]])).unwrap_err();
        assert_eq!(e.pair, 0);
        assert!(
            e.message.contains("'lining' and 'inner'") && e.message.contains("rock"),
            "{e:?}"
        );
        let e = split_region_pairs(&mut three_regions(), &pairs(&[["rock", "nope"]])).unwrap_err();
        assert!(e.message.contains("unknown region 'nope'"), "{e:?}");
    }
}
