//! The geometry of a group's one-point elements, each distinct geometry kept once (issue 11).
//!
//! A one-point element's geometry ([`UniformGeometry`]: mean gradient b, hourglass vectors
//! h, volume V, hourglass stiffness κ; 304 bytes) is read at every step, and out of cache
//! that stream costs as much as the arithmetic it feeds: on the 40³ one-point cube the
//! elastic pass ran 1.45–1.6× faster when every element read one shared geometry
//! (docs/benchmarks.md, 2026-11-28, night). Meshes made of repeated cells share most of it
//! — the structured generators' boxes, the Yingxiuwan model's tensor-product rock — so the
//! set keeps each geometry that occurs once, **bit for bit** (two elements share a record
//! only when all 38 values have the same bits), and each element a 4-byte index into the
//! records. Sharing changes no value an element reads (what changed results, at round-off,
//! is computing the geometry from relative coordinates, [`UniformGeometry::new`], which
//! makes the repeated cells' bits equal).
//!
//! The lane blocks of [`hex8_uniform_lanes`](crate::element::hex8_uniform_lanes) (the
//! geometry of eight consecutive elements as structure of arrays, 2,432 bytes) are kept the
//! same way, once per distinct tuple of the eight elements' geometries, and only for a set
//! whose elements can run in lanes ([`UniformSet::new`]: a group of linear elastic
//! elements; plastic-damage one-point elements stay scalar).

use crate::element::hex8_uniform::UniformGeometry;
use crate::element::hex8_uniform_lanes::UniformBlock;
use crate::element::lanes::LANES;
use std::collections::HashMap;

/// Values of a [`UniformGeometry`].
const VALUES: usize = 38;

/// The geometry of a group's one-point elements: element by element (`set[le]`) and, for
/// the kernel in lanes, in blocks of [`LANES`] (block k holds elements 8k … 8k + 7; the
/// last `len % 8` elements have none and run the scalar kernel). Each distinct geometry
/// and each distinct block is stored once (module docs). Built once from the elements and
/// never changed, so the two views stay the same geometry.
#[derive(Clone, Debug, Default)]
pub struct UniformSet {
    /// The distinct geometries, in order of first appearance.
    shapes: Vec<UniformGeometry>,
    /// Element → its geometry in `shapes`.
    shape_of: Vec<u32>,
    /// The distinct lane blocks, in order of first appearance.
    blocks: Vec<UniformBlock>,
    /// Block k → its lane geometry in `blocks`.
    block_of: Vec<u32>,
    /// Whether the set holds lane blocks (kept by [`UniformSet::subset`]).
    lane_blocks: bool,
}

/// The bits of every value of `g`: equal keys, identical geometry.
fn key(g: &UniformGeometry) -> [u64; VALUES] {
    let mut k = [0u64; VALUES];
    let values =
        g.b.iter()
            .flatten()
            .chain(g.h.iter().flatten())
            .chain([&g.volume, &g.kappa]);
    for (slot, v) in k.iter_mut().zip(values) {
        *slot = v.to_bits();
    }
    k
}

/// Index of `item` in `table`, appending it when it is new (`seen` maps keys to indices).
fn intern<K: std::hash::Hash + Eq, T>(
    seen: &mut HashMap<K, u32>,
    table: &mut Vec<T>,
    k: K,
    item: impl FnOnce() -> T,
) -> u32 {
    *seen.entry(k).or_insert_with(|| {
        table.push(item());
        u32::try_from(table.len() - 1).expect("fewer than 2³² distinct geometries")
    })
}

impl UniformSet {
    /// Number of elements.
    #[inline]
    pub fn len(&self) -> usize {
        self.shape_of.len()
    }

    /// No elements.
    #[inline]
    pub fn is_empty(&self) -> bool {
        self.shape_of.is_empty()
    }

    /// Geometry of the first element, if any.
    pub fn first(&self) -> Option<&UniformGeometry> {
        self.shape_of.first().map(|&s| &self.shapes[s as usize])
    }

    /// The elements' geometries, in element order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &UniformGeometry> + '_ {
        self.shape_of.iter().map(|&s| &self.shapes[s as usize])
    }

    /// Number of lane blocks (one per eight consecutive elements).
    pub fn block_count(&self) -> usize {
        self.block_of.len()
    }

    /// Lane block `k` (elements 8k … 8k + 7), if the set has it.
    #[inline]
    pub fn block(&self, k: usize) -> Option<&UniformBlock> {
        self.block_of.get(k).map(|&b| &self.blocks[b as usize])
    }

    /// Distinct geometries and distinct lane blocks stored.
    pub fn distinct(&self) -> (usize, usize) {
        (self.shapes.len(), self.blocks.len())
    }

    /// Bytes held: the distinct records and the per-element and per-block indices.
    pub fn bytes(&self) -> usize {
        self.shapes.len() * std::mem::size_of::<UniformGeometry>()
            + self.blocks.len() * std::mem::size_of::<UniformBlock>()
            + (self.shape_of.len() + self.block_of.len()) * std::mem::size_of::<u32>()
    }
}

impl std::ops::Index<usize> for UniformSet {
    type Output = UniformGeometry;
    #[inline(always)]
    fn index(&self, le: usize) -> &UniformGeometry {
        &self.shapes[self.shape_of[le] as usize]
    }
}

impl UniformSet {
    /// The set of `elements` (in element order), with lane blocks when `lane_blocks` (for
    /// a group whose elements can run in lanes; without them [`Self::block`] is `None`
    /// and every element runs the scalar kernel).
    pub fn new(elements: &[UniformGeometry], lane_blocks: bool) -> Self {
        let mut set = UniformSet {
            lane_blocks,
            ..UniformSet::default()
        };
        let mut seen = HashMap::new();
        set.shape_of = elements
            .iter()
            .map(|g| intern(&mut seen, &mut set.shapes, key(g), || *g))
            .collect();
        if lane_blocks {
            let mut seen_blocks = HashMap::new();
            set.block_of = set
                .shape_of
                .chunks_exact(LANES)
                .zip(elements.chunks_exact(LANES))
                .map(|(ids, geo)| {
                    let ids: [u32; LANES] = ids.try_into().expect("chunks of LANES");
                    intern(&mut seen_blocks, &mut set.blocks, ids, || {
                        UniformBlock::new(geo.try_into().expect("chunks of LANES"))
                    })
                })
                .collect();
        }
        set
    }

    /// The set of the elements `kept` (indices into this set, in their new order), with
    /// lane blocks when this set has them.
    pub fn subset(&self, kept: &[usize]) -> Self {
        let elements: Vec<UniformGeometry> = kept.iter().map(|&le| self[le]).collect();
        Self::new(&elements, self.lane_blocks)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::material::Elastic;
    use crate::mesh::hex8_shape::NODE_XI;

    /// A box cell at `origin` with edges `size`, node order of the hex8 (its reference
    /// coordinates ξ ∈ {−1, 1}³ mapped to {0, 1}³).
    fn cell(origin: [f64; 3], size: [f64; 3]) -> [[f64; 3]; 8] {
        NODE_XI.map(|c| std::array::from_fn(|i| origin[i] + 0.5 * (c[i] + 1.0) * size[i]))
    }

    /// Each element reads its own geometry, value for value, and each block the geometry of
    /// its eight elements; identical geometries are stored once, different ones apart.
    #[test]
    fn every_element_and_block_reads_its_own_geometry() {
        let el = Elastic::new("rock", 20e9, 0.25, 2600.0).unwrap();
        // Cells of three sizes in a repeating pattern (shared records) and a distorted cell
        // (a record of its own), 8·5 + 3 elements: five blocks and a tail of three.
        let mut geo = Vec::new();
        for k in 0..43 {
            let size = [[1.0, 1.0, 1.0], [2.0, 1.0, 0.5], [0.25, 4.0, 1.0]][k % 3];
            let mut x = cell([0.0, 0.0, 0.0], size);
            if k == 25 {
                x[6][2] += 0.3;
            }
            geo.push(UniformGeometry::new(&x, &el, 0.05).unwrap());
        }
        let set = UniformSet::new(&geo, true);
        assert_eq!(set.len(), 43);
        assert_eq!(set.block_count(), 5);
        assert!(set.block(5).is_none());
        let (shapes, blocks) = set.distinct();
        assert_eq!(shapes, 4, "three repeated cells and the distorted one");
        // Blocks start at 0, 8, 16, 24, 32: phases 0, 2, 1, 0, 2 of the pattern; blocks 1
        // and 4 share a record, block 3 starts like block 0 but holds the distorted cell.
        assert_eq!(blocks, 4);
        for (le, g) in geo.iter().enumerate() {
            assert_eq!(key(&set[le]), key(g), "element {le}");
        }
        for k in 0..5 {
            let block = set.block(k).unwrap();
            for l in 0..LANES {
                let g = &geo[LANES * k + l];
                assert_eq!(block.volume[l].to_bits(), g.volume.to_bits());
                assert_eq!(block.kappa[l].to_bits(), g.kappa.to_bits());
                for a in 0..8 {
                    for i in 0..3 {
                        assert_eq!(block.b[a][i][l].to_bits(), g.b[a][i].to_bits());
                    }
                }
                for al in 0..4 {
                    for j in 0..3 {
                        assert_eq!(block.h[al][j][l].to_bits(), g.h[al][j].to_bits());
                    }
                }
            }
        }
        assert!(set.bytes() < 43 * std::mem::size_of::<UniformGeometry>() + 5 * 2432);
    }

    /// A set built without lane blocks has none and its subsets neither; a subset of a set
    /// with blocks has the blocks of its own elements, in their new order.
    #[test]
    fn a_subset_keeps_the_choice_of_lane_blocks() {
        let el = Elastic::new("rock", 20e9, 0.25, 2600.0).unwrap();
        let geo: Vec<UniformGeometry> = (0..20)
            .map(|k| {
                let size = [1.0 + 0.1 * k as f64, 1.0, 2.0];
                UniformGeometry::new(&cell([0.0; 3], size), &el, 0.05).unwrap()
            })
            .collect();
        let kept: Vec<usize> = (0..20).rev().filter(|k| k % 3 != 0).collect();
        let scalar = UniformSet::new(&geo, false);
        assert_eq!((scalar.block_count(), scalar.distinct().1), (0, 0));
        assert!(scalar.block(0).is_none());
        assert!(scalar.bytes() < UniformSet::new(&geo, true).bytes());
        let scalar_part = scalar.subset(&kept);
        assert_eq!(scalar_part.block_count(), 0);
        let part = UniformSet::new(&geo, true).subset(&kept);
        assert_eq!(part.len(), kept.len());
        assert_eq!(part.block_count(), kept.len() / LANES);
        for (i, &le) in kept.iter().enumerate() {
            assert_eq!(key(&part[i]), key(&geo[le]));
            assert_eq!(key(&scalar_part[i]), key(&geo[le]));
        }
        // 13 elements: one block, the first eight kept, and a scalar tail.
        assert!(part.block(1).is_none());
        let block = part.block(0).unwrap();
        for l in 0..LANES {
            assert_eq!(block.volume[l].to_bits(), geo[kept[l]].volume.to_bits());
        }
    }

    /// Geometries that differ in one bit of one value are kept apart (−0 and +0 too).
    #[test]
    fn a_single_bit_keeps_two_geometries_apart() {
        let el = Elastic::new("rock", 20e9, 0.25, 2600.0).unwrap();
        let g = UniformGeometry::new(&cell([0.0; 3], [1.0; 3]), &el, 0.05).unwrap();
        let mut nudged = g;
        nudged.h[3][2] = f64::from_bits(g.h[3][2].to_bits() ^ 1);
        let mut signed = g;
        signed.b[0][0] = -0.0;
        let mut unsigned = g;
        unsigned.b[0][0] = 0.0;
        let set = UniformSet::new(&[g, nudged, g, signed, unsigned], true);
        assert_eq!(set.distinct().0, 4);
        assert_eq!(set[1].h[3][2].to_bits(), nudged.h[3][2].to_bits());
        assert_eq!(set[3].b[0][0].to_bits(), (-0.0f64).to_bits());
        assert_eq!(set[4].b[0][0].to_bits(), 0.0f64.to_bits());
        assert_eq!(key(&set[2]), key(&g));
    }
}
