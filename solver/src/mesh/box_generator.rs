//! Structured hex8 blocks with graded spacing, merged into one mesh; optional duplicated
//! nodes along the surfaces between two regions (where a contact interface will sit).

use std::collections::BTreeMap;

use serde::Deserialize;

use crate::error::{DcfmError, Result};
use crate::mesh::split::split_region_pairs;
use crate::mesh::{merge_coincident_nodes, Face, Mesh};

/// One structured block: an axis-aligned box divided into `divisions` hex8 elements.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BlockSpec {
    /// Block name: prefixes its sets (`NAME.xmin`, ..., `NAME.zmax`) and names its element set.
    pub name: String,
    /// Region (and so material) of the block's elements; defaults to the block name.
    #[serde(default)]
    pub region: Option<String>,
    /// Lower corner (m).
    pub origin: [f64; 3],
    /// Edge lengths (m).
    pub size: [f64; 3],
    /// Number of elements along x, y, z.
    pub divisions: [usize; 3],
    /// Ratio of the last to the first element length along each axis (1 = uniform).
    #[serde(default = "unit_grading")]
    pub grading: [f64; 3],
}

fn unit_grading() -> [f64; 3] {
    [1.0; 3]
}

/// A mesh made of blocks. Coincident nodes of different blocks are merged (within
/// `merge_tolerance` × the smallest element length) and then split again between each
/// region pair of `split`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BoxMeshSpec {
    pub blocks: Vec<BlockSpec>,
    /// Region pairs `[a, b]` to keep apart: the nodes they share are duplicated, face sets
    /// `a-b` (faces of region a on the shared surface) and `b-a` are created.
    #[serde(default)]
    pub split: Vec<[String; 2]>,
    /// Relative merge tolerance (fraction of the smallest element length).
    #[serde(default = "default_merge_tolerance")]
    pub merge_tolerance: f64,
}

fn default_merge_tolerance() -> f64 {
    1e-6
}

/// Largest grading (and smallest, its inverse) of a block axis: a million-fold ratio of
/// the last to the first element length, far beyond any graded mesh (≈ 20); at 1e200 the
/// geometric series overflows and the elements degenerate.
const MAX_GRADING: f64 = 1e6;

/// Shortest block edge (m): 1 nm is atomic scale, where no continuum model holds (and
/// 1e-300 m gives elements whose stiffness underflows into a "degenerate" element).
const MIN_LENGTH: f64 = 1e-9;
/// Longest block edge and largest coordinate (m): a hundred Earth diameters (1.3e7 m).
const MAX_LENGTH: f64 = 1e9;

const AXES: [&str; 3] = ["x", "y", "z"];

/// Node coordinates along one axis: `n` intervals over `length`, geometric grading so
/// that the last interval is `grading` times the first.
fn axis_points(origin: f64, length: f64, n: usize, grading: f64) -> Vec<f64> {
    let mut pts = Vec::with_capacity(n + 1);
    if (grading - 1.0).abs() < 1e-12 || n == 1 {
        for i in 0..=n {
            pts.push(origin + length * i as f64 / n as f64);
        }
    } else {
        let r = grading.powf(1.0 / (n as f64 - 1.0));
        let first = length * (r - 1.0) / (r.powi(n as i32) - 1.0);
        let mut x = origin;
        pts.push(x);
        let mut h = first;
        for _ in 0..n {
            x += h;
            pts.push(x);
            h *= r;
        }
        pts[n] = origin + length;
    }
    pts
}

impl BlockSpec {
    fn validate(&self, field: &str, file: &str) -> Result<()> {
        for d in 0..3 {
            if !(self.size[d].is_finite() && self.size[d] > 0.0) {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.size[{d}]"),
                    self.size[d],
                    "must be a finite length > 0 (m)",
                ));
            }
            if !(MIN_LENGTH..=MAX_LENGTH).contains(&self.size[d]) {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.size[{d}]"),
                    format!("{:e}", self.size[d]),
                    format!(
                        "a length from {MIN_LENGTH:e} m (atoms, not a continuum) to \
                         {MAX_LENGTH:e} m (a hundred Earth diameters); a units slip?"
                    ),
                ));
            }
            if !(self.origin[d].is_finite() && self.origin[d].abs() <= MAX_LENGTH) {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.origin[{d}]"),
                    format!("{:e}", self.origin[d]),
                    format!("a finite coordinate within ±{MAX_LENGTH:e} m"),
                ));
            }
            if self.divisions[d] == 0 || self.divisions[d] > 100_000 {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.divisions[{d}]"),
                    self.divisions[d],
                    "must be between 1 and 100000",
                ));
            }
            let g = self.grading[d];
            if !(g.is_finite() && (1.0 / MAX_GRADING..=MAX_GRADING).contains(&g)) {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.grading[{d}]"),
                    format!("{g:e}"),
                    format!(
                        "a finite ratio of the last to the first element length from 1e-6 \
                         to {} (a million-fold ratio in one block; beyond it the smallest \
                         elements vanish into the round-off of the coordinates)",
                        crate::readable::engineering(MAX_GRADING)
                    ),
                ));
            }
        }
        Ok(())
    }
}

impl BoxMeshSpec {
    /// Two blocks whose boxes share a volume (not just a face) would be merged into a mesh
    /// with interpenetrating elements and nodes merged at random: an error naming both,
    /// unless their regions are kept apart by a `split` pair (then the overlap is the
    /// user's intent, e.g. an initial interpenetration a contact test sets up).
    fn check_overlaps(&self, file: &str) -> Result<()> {
        let region = |b: &BlockSpec| b.region.clone().unwrap_or_else(|| b.name.clone());
        for (i, a) in self.blocks.iter().enumerate() {
            for (j, b) in self.blocks.iter().enumerate().skip(i + 1) {
                let mut overlap = [0.0; 3];
                for d in 0..3 {
                    let lo = a.origin[d].max(b.origin[d]);
                    let hi = (a.origin[d] + a.size[d]).min(b.origin[d] + b.size[d]);
                    // Touching within the merge tolerance is not overlapping.
                    let h =
                        (a.size[d] / a.divisions[d] as f64).min(b.size[d] / b.divisions[d] as f64);
                    overlap[d] = hi - lo;
                    if overlap[d] <= self.merge_tolerance * h {
                        overlap[d] = 0.0;
                    }
                }
                if overlap.iter().all(|&o| o > 0.0) {
                    let (ra, rb) = (region(a), region(b));
                    let split = self
                        .split
                        .iter()
                        .any(|[p, q]| (*p == ra && *q == rb) || (*p == rb && *q == ra));
                    if !split {
                        return Err(DcfmError::invalid(
                            file,
                            format!("mesh.blocks[{j}]"),
                            format!("'{}'", b.name),
                            format!(
                                "overlaps block '{}' (mesh.blocks[{i}]) over {:.4} × {:.4} × {:.4} m: \
                                 blocks may share faces, not volume (or split their regions \
                                 [{ra}, {rb}] to keep two overlapping bodies apart)",
                                a.name, overlap[0], overlap[1], overlap[2]
                            ),
                        ));
                    }
                }
            }
        }
        Ok(())
    }

    /// A single uniform block named `name` (region `name`).
    pub fn single(name: &str, origin: [f64; 3], size: [f64; 3], divisions: [usize; 3]) -> Self {
        Self {
            blocks: vec![BlockSpec {
                name: name.to_string(),
                region: None,
                origin,
                size,
                divisions,
                grading: [1.0; 3],
            }],
            split: Vec::new(),
            merge_tolerance: default_merge_tolerance(),
        }
    }

    /// Build the mesh. `file` names the case file for error messages.
    pub fn build(&self, file: &str) -> Result<Mesh> {
        if self.blocks.is_empty() {
            return Err(DcfmError::invalid(
                file,
                "mesh.blocks",
                "[]",
                "at least one block",
            ));
        }
        let total: usize = self
            .blocks
            .iter()
            .map(|b| b.divisions.iter().product::<usize>())
            .sum();
        if total > 50_000_000 {
            return Err(DcfmError::invalid(
                file,
                "mesh.blocks",
                total,
                "at most 50 million elements in all",
            ));
        }
        if !(self.merge_tolerance.is_finite()
            && self.merge_tolerance > 0.0
            && self.merge_tolerance < 0.1)
        {
            return Err(DcfmError::invalid(
                file,
                "mesh.merge_tolerance",
                self.merge_tolerance,
                "must be in (0, 0.1)",
            ));
        }
        for (bi, block) in self.blocks.iter().enumerate() {
            block.validate(&format!("mesh.blocks[{bi}]"), file)?;
        }
        self.check_overlaps(file)?;
        let mut mesh = Mesh::default();
        let mut block_names = std::collections::BTreeSet::new();
        let mut min_h = f64::INFINITY;
        for (bi, block) in self.blocks.iter().enumerate() {
            let field = format!("mesh.blocks[{bi}]");
            block.validate(&field, file)?;
            if !block_names.insert(block.name.clone()) {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.name"),
                    &block.name,
                    "block names must be unique",
                ));
            }
            let region_name = block.region.clone().unwrap_or_else(|| block.name.clone());
            let region = match mesh.region_index(&region_name) {
                Some(r) => r,
                None => {
                    mesh.region_names.push(region_name);
                    mesh.region_names.len() - 1
                }
            } as u16;
            let pts: Vec<Vec<f64>> = (0..3)
                .map(|d| {
                    axis_points(
                        block.origin[d],
                        block.size[d],
                        block.divisions[d],
                        block.grading[d],
                    )
                })
                .collect();
            for p in &pts {
                for w in p.windows(2) {
                    min_h = min_h.min(w[1] - w[0]);
                }
            }
            let [nx, ny, nz] = block.divisions;
            let node0 = mesh.coords.len() as u32;
            let nid =
                |i: usize, j: usize, k: usize| node0 + (i + (nx + 1) * (j + (ny + 1) * k)) as u32;
            for k in 0..=nz {
                for j in 0..=ny {
                    for i in 0..=nx {
                        mesh.coords.push([pts[0][i], pts[1][j], pts[2][k]]);
                    }
                }
            }
            let elem0 = mesh.elements.len() as u32;
            let mut faces: [Vec<Face>; 6] = Default::default();
            for k in 0..nz {
                for j in 0..ny {
                    for i in 0..nx {
                        let e = mesh.elements.len() as u32;
                        mesh.elements.push([
                            nid(i, j, k),
                            nid(i + 1, j, k),
                            nid(i + 1, j + 1, k),
                            nid(i, j + 1, k),
                            nid(i, j, k + 1),
                            nid(i + 1, j, k + 1),
                            nid(i + 1, j + 1, k + 1),
                            nid(i, j + 1, k + 1),
                        ]);
                        mesh.element_region.push(region);
                        // Local faces: 0 ζ−, 1 ζ+, 2 η−, 3 ξ+, 4 η+, 5 ξ−.
                        if i == 0 {
                            faces[0].push(Face {
                                element: e,
                                local: 5,
                            });
                        }
                        if i == nx - 1 {
                            faces[1].push(Face {
                                element: e,
                                local: 3,
                            });
                        }
                        if j == 0 {
                            faces[2].push(Face {
                                element: e,
                                local: 2,
                            });
                        }
                        if j == ny - 1 {
                            faces[3].push(Face {
                                element: e,
                                local: 4,
                            });
                        }
                        if k == 0 {
                            faces[4].push(Face {
                                element: e,
                                local: 0,
                            });
                        }
                        if k == nz - 1 {
                            faces[5].push(Face {
                                element: e,
                                local: 1,
                            });
                        }
                    }
                }
            }
            mesh.element_sets.insert(
                block.name.clone(),
                (elem0..mesh.elements.len() as u32).collect(),
            );
            for (s, f) in faces.into_iter().enumerate() {
                let name = format!(
                    "{}.{}{}",
                    block.name,
                    AXES[s / 2],
                    if s % 2 == 0 { "min" } else { "max" }
                );
                mesh.face_sets.insert(name, f);
            }
        }
        let mesh = merge_coincident_nodes(mesh, self.merge_tolerance * min_h);
        let mut mesh = mesh;
        // Node sets for every face set.
        let node_sets: BTreeMap<String, Vec<u32>> = mesh
            .face_sets
            .iter()
            .map(|(n, f)| (n.clone(), mesh.face_set_nodes(f)))
            .collect();
        mesh.node_sets.extend(node_sets);
        split_region_pairs(&mut mesh, &self.split).map_err(|e| {
            let [a, b] = &self.split[e.pair];
            DcfmError::invalid(
                file,
                format!("mesh.split[{}]", e.pair),
                format!("[{a}, {b}]"),
                e.message,
            )
        })?;
        mesh.validate()?;
        Ok(mesh)
    }
}

/// Duplicate the nodes shared by regions `a` and `b`: elements of `b` get new copies.
/// Creates face sets `a-b` (faces of `a` that coincide with a face of `b`) and `b-a`, and
/// node sets of the same names. One pair of [`split_region_pairs`]; split several pairs in
/// one call to that function (nodes on several interfaces). Errors (as text) if a region
/// is unknown or the two share no face.
pub fn split_between_regions(mesh: &mut Mesh, a: &str, b: &str) -> std::result::Result<(), String> {
    split_region_pairs(mesh, &[[a.to_string(), b.to_string()]]).map_err(|e| e.message)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn graded_axis_ends_and_ratio() {
        let p = axis_points(1.0, 10.0, 5, 4.0);
        assert_eq!(p.len(), 6);
        assert!((p[0] - 1.0).abs() < 1e-14 && (p[5] - 11.0).abs() < 1e-12);
        let first = p[1] - p[0];
        let last = p[5] - p[4];
        assert!((last / first - 4.0).abs() < 1e-10);
    }

    #[test]
    fn single_block_counts_and_sets() {
        let m = BoxMeshSpec::single("rock", [0.0; 3], [2.0, 3.0, 4.0], [2, 3, 4])
            .build("t")
            .unwrap();
        assert_eq!(m.n_elements(), 24);
        assert_eq!(m.n_nodes(), 3 * 4 * 5);
        assert_eq!(m.face_sets["rock.zmin"].len(), 6);
        assert_eq!(m.node_sets["rock.zmax"].len(), 12);
    }

    #[test]
    fn two_blocks_merge_then_split() {
        let spec = BoxMeshSpec {
            blocks: vec![
                BlockSpec {
                    name: "base".into(),
                    region: None,
                    origin: [0.0; 3],
                    size: [1.0, 1.0, 1.0],
                    divisions: [2, 2, 2],
                    grading: [1.0; 3],
                },
                BlockSpec {
                    name: "top".into(),
                    region: None,
                    origin: [0.0, 0.0, 1.0],
                    size: [1.0, 1.0, 1.0],
                    divisions: [2, 2, 1],
                    grading: [1.0; 3],
                },
            ],
            split: vec![],
            merge_tolerance: 1e-6,
        };
        let merged = spec.build("t").unwrap();
        assert_eq!(merged.n_nodes(), 27 + 9);
        let mut split = spec.clone();
        split.split = vec![["base".into(), "top".into()]];
        let m = split.build("t").unwrap();
        assert_eq!(m.n_nodes(), 27 + 18);
        assert_eq!(m.face_sets["base-top"].len(), 4);
        assert_eq!(m.face_sets["top-base"].len(), 4);
        assert_eq!(m.node_sets["top-base"].len(), 9);
        // The copies sit where the originals are.
        let a = &m.node_sets["base-top"];
        let b = &m.node_sets["top-base"];
        assert!(a.iter().all(|n| !b.contains(n)));
    }

    #[test]
    fn overlapping_blocks_are_named_touching_ones_are_not() {
        let block = |name: &str, origin: [f64; 3]| BlockSpec {
            name: name.into(),
            region: None,
            origin,
            size: [1.0; 3],
            divisions: [2, 2, 2],
            grading: [1.0; 3],
        };
        let spec = |blocks: Vec<BlockSpec>, split: Vec<[String; 2]>| BoxMeshSpec {
            blocks,
            split,
            merge_tolerance: 1e-6,
        };
        let touching = spec(
            vec![block("a", [0.0; 3]), block("b", [1.0, 0.0, 0.0])],
            vec![],
        );
        assert!(touching.build("t").is_ok());
        let overlapping = spec(
            vec![block("a", [0.0; 3]), block("b", [0.5, 0.25, 0.0])],
            vec![],
        );
        let err = overlapping.build("c.toml").unwrap_err().to_string();
        assert!(
            err.contains("c.toml: mesh.blocks[1] = 'b'") && err.contains("overlaps block 'a'"),
            "{err}"
        );
        assert!(err.contains("0.5000 × 0.7500 × 1.0000"), "{err}");
        let intended = spec(
            vec![block("a", [0.0; 3]), block("b", [0.5, 0.0, 0.0])],
            vec![["a".into(), "b".into()]],
        );
        assert!(intended.check_overlaps("t").is_ok());
    }

    #[test]
    fn bad_divisions_named() {
        let mut s = BoxMeshSpec::single("rock", [0.0; 3], [1.0; 3], [1, 1, 1]);
        s.blocks[0].divisions[1] = 0;
        let err = s.build("case.toml").unwrap_err().to_string();
        assert!(
            err.contains("case.toml: mesh.blocks[0].divisions[1] = 0"),
            "{err}"
        );
    }
}
