//! Candidate faces of a point search, by sorted bins: every face is entered in the cubic
//! cells of size `h` that its axis-aligned box, widened by `margin`, overlaps; the
//! (cell, face) entries are sorted once, so that the faces of a cell are a contiguous run
//! found by binary search. Building is O(n log n) for n faces of size ≲ h, a query
//! O(log n + candidates).
//!
//! Every face whose widened box contains a point p is among the candidates of p's cell
//! (the cell range of the box is monotone in its bounds), and a cell's faces come in
//! ascending face index: a search that scans the candidates in order and keeps the first
//! strict minimum therefore finds exactly what a scan over all faces finds.

/// Faces binned by the cells their widened boxes overlap.
#[derive(Clone, Debug, Default)]
pub(crate) struct FaceBins {
    h: f64,
    /// (cell, face index), sorted.
    entries: Vec<([i64; 3], u32)>,
}

fn cell(x: [f64; 3], h: f64) -> [i64; 3] {
    x.map(|c| (c / h).floor() as i64)
}

/// Axis-aligned box of a face's corners, widened by `margin` on every side.
pub(crate) fn widened_box(x: &[[f64; 3]; 4], margin: f64) -> ([f64; 3], [f64; 3]) {
    let lo = [0, 1, 2].map(|d| x.iter().map(|q| q[d]).fold(f64::INFINITY, f64::min) - margin);
    let hi = [0, 1, 2].map(|d| x.iter().map(|q| q[d]).fold(f64::NEG_INFINITY, f64::max) + margin);
    (lo, hi)
}

/// Whether `p` lies in the box of `x` widened by `margin` (bounds included).
pub(crate) fn in_widened_box(x: &[[f64; 3]; 4], p: [f64; 3], margin: f64) -> bool {
    let (lo, hi) = widened_box(x, margin);
    (0..3).all(|d| p[d] >= lo[d] && p[d] <= hi[d])
}

impl FaceBins {
    /// Bin `faces` (corner coordinates through `coords`) with cells of size `h` (> 0; the
    /// largest face diagonal keeps the cells per face few) and boxes widened by `margin`.
    pub(crate) fn new(faces: &[[u32; 4]], coords: &[[f64; 3]], h: f64, margin: f64) -> Self {
        let h = if h.is_finite() && h > 0.0 {
            h
        } else {
            f64::MIN_POSITIVE
        };
        let mut entries = Vec::with_capacity(8 * faces.len());
        for (fi, f) in faces.iter().enumerate() {
            let x = f.map(|a| coords[a as usize]);
            let (lo, hi) = widened_box(&x, margin);
            let (c0, c1) = (cell(lo, h), cell(hi, h));
            for i in c0[0]..=c1[0] {
                for j in c0[1]..=c1[1] {
                    for k in c0[2]..=c1[2] {
                        entries.push(([i, j, k], fi as u32));
                    }
                }
            }
        }
        entries.sort_unstable();
        FaceBins { h, entries }
    }

    /// Faces whose widened box overlaps the cell of `p`, in ascending face index: a
    /// superset of the faces whose widened box contains `p`.
    pub(crate) fn candidates(&self, p: [f64; 3]) -> impl Iterator<Item = usize> + '_ {
        let c = cell(p, self.h);
        let start = self.entries.partition_point(|(k, _)| *k < c);
        self.entries[start..]
            .iter()
            .take_while(move |(k, _)| *k == c)
            .map(|&(_, fi)| fi as usize)
    }
}

#[cfg(test)]
mod tests {
    use super::super::setup::closest_face;
    use super::FaceBins;
    use proptest::prelude::*;

    /// A warped nx × ny quad surface: spacing h, corners jittered in plane and out of
    /// plane, shifted by `offset`, faces in the order given by `order_keys`.
    fn surface(
        nx: usize,
        ny: usize,
        h: f64,
        jitter: &[[f64; 3]],
        offset: [f64; 3],
        order_keys: &[u32],
    ) -> (Vec<[f64; 3]>, Vec<[u32; 4]>) {
        let mut coords = Vec::new();
        for j in 0..=ny {
            for i in 0..=nx {
                let r = jitter[(j * (nx + 1) + i) % jitter.len()];
                coords.push([
                    offset[0] + h * (i as f64 + 0.3 * r[0]),
                    offset[1] + h * (j as f64 + 0.3 * r[1]),
                    offset[2] + h * 0.5 * r[2],
                ]);
            }
        }
        let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
        let mut faces: Vec<(u32, [u32; 4])> = Vec::new();
        for j in 0..ny {
            for i in 0..nx {
                let k = faces.len();
                faces.push((
                    order_keys[k % order_keys.len()],
                    [id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1)],
                ));
            }
        }
        faces.sort_by_key(|&(key, _)| key);
        (coords, faces.into_iter().map(|(_, f)| f).collect())
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]
        /// The binned search returns exactly (bit for bit, same face on ties) what a scan
        /// over all faces returns, on random warped surfaces and random points.
        #[test]
        fn closest_face_bins_match_brute_force(
            nx in 1usize..14,
            ny in 1usize..14,
            h in 0.05f64..8.0,
            jitter in prop::collection::vec(prop::array::uniform3(-1.0f64..1.0), 1..60),
            offset in prop::array::uniform3(-500.0f64..500.0),
            order_keys in prop::collection::vec(0u32..1000, 1..200),
            points in prop::collection::vec(prop::array::uniform3(-0.2f64..1.2), 1..80),
            capture_fraction in 0.05f64..1.0,
        ) {
            let (coords, faces) = surface(nx, ny, h, &jitter, offset, &order_keys);
            let max_diag = faces
                .iter()
                .map(|f| {
                    let x = f.map(|a| coords[a as usize]);
                    let d = |a: [f64; 3], b: [f64; 3]| {
                        ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2))
                            .sqrt()
                    };
                    d(x[2], x[0]).max(d(x[3], x[1]))
                })
                .fold(0.0, f64::max);
            let capture = capture_fraction * max_diag;
            let bins = FaceBins::new(&faces, &coords, max_diag, capture);
            let mut found = 0;
            for q in &points {
                // A point near a random face: bilinear in (s, t) ∈ [−0.2, 1.2]², lifted in z
                // by up to ±1.5 capture.
                let fi = (((q[0] + 0.2) / 1.4 * faces.len() as f64) as usize).min(faces.len() - 1);
                let x = faces[fi].map(|a| coords[a as usize]);
                let (s, t) = (q[1], q[2]);
                let w = [(1.0 - s) * (1.0 - t), s * (1.0 - t), s * t, (1.0 - s) * t];
                let mut p = [0.0; 3];
                for (wj, xj) in w.iter().zip(&x) {
                    for d in 0..3 {
                        p[d] += wj * xj[d];
                    }
                }
                p[2] += ((q[0] * 7.0).fract() - 0.5) * 3.0 * capture;
                let brute = closest_face(&coords, &faces, p, capture, 0..faces.len());
                let binned = closest_face(&coords, &faces, p, capture, bins.candidates(p));
                prop_assert_eq!(brute, binned);
                found += usize::from(brute.is_some());
            }
            // Not vacuous: most points lie over the surface.
            prop_assert!(points.len() < 10 || found > 0);
        }
    }

    /// Candidates of a cell come in ascending face index, without repeats.
    #[test]
    fn candidates_are_sorted_and_unique() {
        let (coords, faces) = surface(7, 5, 1.3, &[[0.4, -0.2, 0.9]], [-3.0, 2.0, 1.0], &[5, 1, 4]);
        let bins = FaceBins::new(&faces, &coords, 1.9, 0.95);
        for q in [[-3.0, 2.0, 1.0], [1.0, 4.0, 1.2], [5.5, 8.0, 0.5]] {
            let c: Vec<usize> = bins.candidates(q).collect();
            assert!(!c.is_empty());
            assert!(c.windows(2).all(|w| w[0] < w[1]), "{c:?}");
        }
    }
}
