//! Bars laid out over a face set: start points spread over the surface, one per
//! `spacing`² of area, each bar along the inward normal of its face (into the face's own
//! element) for the pattern's length.
//!
//! Candidate points are the centres of a regular n × n subdivision of every face (n so
//! that the sub-faces are at most a quarter spacing across), taken in face-set order; a
//! candidate is kept when it is at least d = spacing · √(2/√3) ≈ 1.0746 · spacing from
//! every kept point. Greedy packing at that distance is hexagonal on a plane, one point per
//! (√3/2) d² = spacing² of surface.

use std::collections::HashMap;

use crate::element::anchor_mat::point_and_normal;
use crate::mesh::face_geometry::{norm, sub};
use crate::mesh::{Face, Mesh};

/// Start points and inward unit normals of the bars of a pattern.
pub fn pattern_points(mesh: &Mesh, faces: &[Face], spacing: f64) -> Vec<([f64; 3], [f64; 3])> {
    let d_min = spacing * (2.0 / 3f64.sqrt()).sqrt();
    let cell = d_min;
    let key = |p: &[f64; 3]| p.map(|v| (v / cell).floor() as i64);
    let mut grid: HashMap<[i64; 3], Vec<usize>> = HashMap::new();
    let mut kept: Vec<([f64; 3], [f64; 3])> = Vec::new();
    for f in faces {
        let q = mesh.face_nodes(*f).map(|n| mesh.coords[n as usize]);
        let size = (0..4)
            .map(|i| norm(sub(q[(i + 1) % 4], q[i])))
            .fold(0.0, f64::max);
        let n = ((4.0 * size / spacing).ceil() as usize).max(1);
        for i in 0..n {
            for j in 0..n {
                let (s, t) = ((i as f64 + 0.5) / n as f64, (j as f64 + 0.5) / n as f64);
                // Bilinear point and the (outward, counter-clockwise) normal there.
                let Some((p, outward)) = point_and_normal(&q, s, t) else {
                    continue;
                };
                let inward = outward.map(|v| -v);
                let k = key(&p);
                let mut far = true;
                'near: for dx in -1..=1 {
                    for dy in -1..=1 {
                        for dz in -1..=1 {
                            if let Some(list) = grid.get(&[k[0] + dx, k[1] + dy, k[2] + dz]) {
                                for &o in list {
                                    let y = kept[o].0;
                                    let d2: f64 = (0..3).map(|d| (p[d] - y[d]).powi(2)).sum();
                                    if d2 < d_min * d_min {
                                        far = false;
                                        break 'near;
                                    }
                                }
                            }
                        }
                    }
                }
                if far {
                    grid.entry(k).or_default().push(kept.len());
                    kept.push((p, inward));
                }
            }
        }
    }
    kept
}
