//! Linear elastic, fully integrated elements through their stiffness matrices, each
//! distinct matrix kept once (issue 11).
//!
//! For a linear elastic material the 2×2×2 kernel's internal force is linear in the nodal
//! displacements: f = K u with K = Σ_g (w det J)_g Bᵀ_g D B_g ([`full_stiffness`],
//! Zienkiewicz, Taylor & Zhu 2005, eq. 6.16), and the stiffness-proportional damping
//! force is β K v. The Gauss-point kernel ([`hex8_full_lanes`](crate::element::hex8_full_lanes))
//! spends ≈ 230 vector operations per element on the strains, the stresses and their
//! nodal sums; K u is 72 vector multiply-adds (K's 24 rows as three 8-lane vectors, one
//! column per displacement component). K is 4,608 bytes against the 640 of the Gauss
//! geometry, so the matrix pays only where elements share it: meshes of repeated cells —
//! structured boxes, tensor-product rock — hold few distinct geometries. A geometry gets a
//! matrix when at least [`MIN_SHARE`] elements have it (the matrices then cost at most
//! 576 bytes per element, less than the Gauss geometry); the other elements keep the Gauss
//! kernel.
//!
//! Elements share a matrix when their geometries, computed from the coordinates relative to
//! the element's first node rounded to a multiple of 2⁻⁴⁴ of the group's extent
//! ([`quantum`]: 8.5e-12 m for a 150 m model), have the same bits (all 80 values): repeated
//! cells anywhere in the mesh, whose coordinate differences agree only to the coordinates'
//! round-off (≈ 1e-14 m), compare equal. The matrix is that of the first such element, from
//! its own (unrounded) relative coordinates, so another element's matrix differs from its
//! exact one by the cells' round-off, and at most by the rounding step. The forces equal the
//! Gauss kernel's to that, not bit for bit (the sums run in another order); they are the
//! same on any thread count (each element's force is one fixed sequence of operations).
//! The scalar and Gauss kernels stay the reference the tests compare with
//! (`solver/tests/elastic_matrices.rs`).

use std::collections::HashMap;

use crate::element::hex8_full::FullGeometry;
use crate::element::lanes::F64s;
use crate::element::stiffness::full_stiffness;
use crate::fnv::Fnv64;
use crate::material::Elastic;

/// Elements that must share a geometry before it gets a matrix: 4,608 bytes of matrix
/// over 8 elements is 576 bytes each, below the 640 bytes of a [`FullGeometry`].
pub const MIN_SHARE: usize = 8;

/// Marks an element without a matrix in [`ElasticMatrices::matrix_of`].
const NONE: u32 = u32::MAX;

/// A symmetric 24 × 24 element stiffness stored by columns, each column's 24 rows (DOF
/// `3a + i`) as three 8-lane vectors: `columns[j][r][l]` is K_(8r + l) j.
#[derive(Clone, Debug)]
#[repr(C, align(64))]
pub struct ElementMatrix {
    columns: [[F64s; 3]; 24],
}

impl ElementMatrix {
    /// The matrix of the elastic element with geometry `geo` and constants `el`.
    pub fn new(geo: &FullGeometry, el: &Elastic) -> Self {
        let k = full_stiffness(geo, el);
        let mut columns = [[F64s::ZERO; 3]; 24];
        for (j, column) in columns.iter_mut().enumerate() {
            for (row, kr) in k.iter().enumerate() {
                column[row / 8][row % 8] = kr[j];
            }
        }
        Self { columns }
    }

    /// K x for the nodal vectors `x` (`x[a][i]` is DOF `3a + i`): the internal force of
    /// the displacements x, or with x the velocities and a factor β, the damping force.
    #[inline(always)]
    pub fn apply(&self, x: &[[f64; 3]; 8]) -> [[f64; 3]; 8] {
        let mut f = [F64s::ZERO; 3];
        for (a, xa) in x.iter().enumerate() {
            for (i, &xai) in xa.iter().enumerate() {
                let s = F64s::splat(xai);
                let column = &self.columns[3 * a + i];
                f[0] = f[0] + column[0] * s;
                f[1] = f[1] + column[1] * s;
                f[2] = f[2] + column[2] * s;
            }
        }
        std::array::from_fn(|a| std::array::from_fn(|i| f[(3 * a + i) / 8][(3 * a + i) % 8]))
    }
}

/// The stiffness matrices of a group's linear elastic, fully integrated elements: one per
/// geometry shared by at least [`MIN_SHARE`] elements, and each element's index into them.
#[derive(Clone, Debug, Default)]
pub struct ElasticMatrices {
    /// The distinct matrices, in order of first appearance.
    matrices: Vec<ElementMatrix>,
    /// Element → its matrix in `matrices`, or [`NONE`].
    of: Vec<u32>,
}

/// The bits of every value of `g`: equal keys, identical geometry.
fn key(g: &FullGeometry) -> [u64; 80] {
    let mut k = [0u64; 80];
    let values = g.jinv.iter().flatten().chain([&g.wdet]).flat_map(|v| v.0);
    for (slot, v) in k.iter_mut().zip(values) {
        *slot = v.to_bits();
    }
    k
}

/// The rounding step of the relative coordinates: the power of two 2⁻⁴⁴ times the
/// smallest power of two at or above the largest coordinate magnitude of `coords`.
fn quantum(coords: &[[[f64; 3]; 8]]) -> f64 {
    let extent = coords
        .iter()
        .flatten()
        .flatten()
        .fold(0.0f64, |m, v| m.max(v.abs()))
        .max(f64::MIN_POSITIVE);
    2f64.powi(extent.log2().ceil() as i32 - 44)
}

impl ElasticMatrices {
    /// The matrices of the elements with nodal coordinates `coords` (in the group's order)
    /// and elastic constants `el`. `None` when no geometry is shared by [`MIN_SHARE`]
    /// elements (or one has a non-positive Jacobian: the Gauss kernel then runs, and the
    /// group's own checks report the element).
    ///
    /// Two passes, so that a mesh without repeated cells costs 16 bytes per element while
    /// the set is built, not a 640-byte key per element: the first counts each rounded
    /// geometry by a 64-bit hash of its bits (FNV-1a; a collision can only over-count),
    /// the second compares the bits of the elements whose hash was counted often enough.
    pub fn new(coords: &[[[f64; 3]; 8]], el: &Elastic) -> Option<Self> {
        let q = quantum(coords);
        let rounded_key = |x: &[[f64; 3]; 8]| -> Option<[u64; 80]> {
            let x0 = x[0];
            let rounded = x.map(|xa| std::array::from_fn(|j| ((xa[j] - x0[j]) / q).round() * q));
            Some(key(&FullGeometry::new(&rounded)?))
        };
        let mut hashes = Vec::with_capacity(coords.len());
        let mut hash_count: HashMap<u64, usize> = HashMap::new();
        for x in coords {
            let mut h = Fnv64::new();
            for v in rounded_key(x)? {
                h.u64(v);
            }
            *hash_count.entry(h.finish()).or_default() += 1;
            hashes.push(h.finish());
        }
        // Candidates: their exact keys, the first element of each standing for its shape
        // with its own (unrounded) relative coordinates, and how many elements have it.
        let mut seen: HashMap<[u64; 80], usize> = HashMap::new();
        let mut shapes: Vec<(FullGeometry, usize)> = Vec::new();
        let mut shape_of = vec![NONE; coords.len()];
        for (le, x) in coords.iter().enumerate() {
            if hash_count[&hashes[le]] < MIN_SHARE {
                continue;
            }
            let s = *seen.entry(rounded_key(x)?).or_insert(shapes.len());
            if s == shapes.len() {
                let x0 = x[0];
                let relative = x.map(|xa| std::array::from_fn(|j| xa[j] - x0[j]));
                shapes.push((FullGeometry::new(&relative)?, 0));
            }
            shapes[s].1 += 1;
            shape_of[le] = u32::try_from(s).ok()?;
        }
        let mut matrix_of_shape = vec![NONE; shapes.len()];
        let mut matrices = Vec::new();
        for (s, (g, count)) in shapes.iter().enumerate() {
            if *count >= MIN_SHARE {
                matrix_of_shape[s] = matrices.len() as u32;
                matrices.push(ElementMatrix::new(g, el));
            }
        }
        if matrices.is_empty() {
            return None;
        }
        let of = shape_of
            .iter()
            .map(|&s| {
                if s == NONE {
                    NONE
                } else {
                    matrix_of_shape[s as usize]
                }
            })
            .collect();
        Some(Self { matrices, of })
    }

    /// The matrix of element `le`, if it has one.
    #[inline(always)]
    pub fn matrix_of(&self, le: usize) -> Option<&ElementMatrix> {
        let m = self.of[le];
        (m != NONE).then(|| &self.matrices[m as usize])
    }

    /// The matrices of the elements `kept` (indices into this set, in order).
    pub fn subset(&self, kept: &[usize]) -> Self {
        Self {
            matrices: self.matrices.clone(),
            of: kept.iter().map(|&le| self.of[le]).collect(),
        }
    }

    /// Number of distinct matrices.
    pub fn distinct(&self) -> usize {
        self.matrices.len()
    }

    /// Number of elements with a matrix.
    pub fn elements_with_matrix(&self) -> usize {
        self.of.iter().filter(|&&m| m != NONE).count()
    }

    /// Bytes held (the matrices and the indices).
    pub fn bytes(&self) -> usize {
        self.matrices.len() * std::mem::size_of::<ElementMatrix>()
            + self.of.len() * std::mem::size_of::<u32>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8_full;
    use crate::material::{Material, PointContext};
    use crate::mesh::hex8_shape::NODE_XI;
    use crate::test_random::{distorted_hex, Lcg};

    /// A box cell at `origin` with edges `size`.
    fn cell(origin: [f64; 3], size: [f64; 3]) -> [[f64; 3]; 8] {
        NODE_XI.map(|c| std::array::from_fn(|i| origin[i] + 0.5 * (c[i] + 1.0) * size[i]))
    }

    /// Nodal values of up to 5e-4 from `seed`.
    fn nodal(seed: u64) -> [[f64; 3]; 8] {
        let mut lcg = Lcg(seed);
        std::array::from_fn(|_| std::array::from_fn(|_| 5e-4 * lcg.sym()))
    }

    /// K u is the scalar Gauss kernel's force to round-off, on a box cell and on a
    /// distorted one, and K v β its damping force.
    #[test]
    fn matrix_force_is_the_gauss_kernel_force() {
        let el = Elastic::new("rock", 20e9, 0.25, 2600.0).unwrap();
        let material = Material::Elastic(el);
        let distorted = distorted_hex();
        for (x, seed) in [
            (cell([3.0, -2.0, 7.5], [0.7, 1.3, 2.1]), 7),
            (distorted, 11),
        ] {
            let geo = FullGeometry::new(&x).unwrap();
            let u = nodal(seed);
            let mut reference = [[0.0; 3]; 8];
            let ctx = PointContext {
                char_length: 1.0,
                dt: 1e-4,
                reads_damage: false,
            };
            hex8_full::internal_force(&geo, &material, &u, &[], &mut [], &ctx, &mut reference);
            let f = ElementMatrix::new(&geo, &el).apply(&u);
            let scale = reference
                .iter()
                .flatten()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            assert!(scale > 0.0);
            for (fa, ra) in f.iter().zip(&reference) {
                for (v, r) in fa.iter().zip(ra) {
                    assert!((v - r).abs() <= 1e-13 * scale, "{v} against {r}");
                }
            }
        }
    }

    /// Repeated cells share one matrix wherever they lie; a geometry held by fewer than
    /// [`MIN_SHARE`] elements gets none; a subset keeps each element's matrix.
    #[test]
    fn repeated_cells_share_a_matrix() {
        let el = Elastic::new("rock", 20e9, 0.25, 2600.0).unwrap();
        let mut cells = Vec::new();
        for i in 0..12 {
            cells.push(cell([0.37 * i as f64, 1.9, -3.3], [0.37, 0.5, 0.25]));
        }
        for i in 0..3 {
            cells.push(cell([10.0 + i as f64, 0.0, 0.0], [1.0, 2.0, 3.0]));
        }
        let set = ElasticMatrices::new(&cells, &el).unwrap();
        assert_eq!(set.distinct(), 1);
        assert_eq!(set.elements_with_matrix(), 12);
        assert!(set.matrix_of(13).is_none());
        // Every shared element's force is its own Gauss force to its cell's round-off.
        let material = Material::Elastic(el);
        let ctx = PointContext {
            char_length: 1.0,
            dt: 1e-4,
            reads_damage: false,
        };
        for (le, x) in cells.iter().enumerate().take(12) {
            let geo = FullGeometry::new(x).unwrap();
            let u = nodal(le as u64);
            let mut expected = [[0.0; 3]; 8];
            hex8_full::internal_force(&geo, &material, &u, &[], &mut [], &ctx, &mut expected);
            let got = set.matrix_of(le).unwrap().apply(&u);
            let scale = expected
                .iter()
                .flatten()
                .fold(0.0f64, |m, v| m.max(v.abs()));
            for (g, e) in got.iter().flatten().zip(expected.iter().flatten()) {
                assert!(
                    (g - e).abs() <= 1e-12 * scale,
                    "element {le}: {g} against {e}"
                );
            }
        }
        let sub = set.subset(&[13, 2]);
        assert!(sub.matrix_of(0).is_none());
        assert!(sub.matrix_of(1).is_some());
        assert!(ElasticMatrices::new(&cells[12..], &el).is_none());
    }
}
