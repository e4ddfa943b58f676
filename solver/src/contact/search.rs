//! Contact search for point-to-surface contact (paper §2.3, eq. (16)): which face of
//! surface b a node of surface a touches, and where.
//!
//! The faces of b are binned in a uniform grid over the configuration at tⁿ, with cells of
//! the largest face diagonal; every face is entered in each cell that its bounding box,
//! grown by the capture distance (half a cell), overlaps. A node looks only in its own
//! cell: every face within the capture distance of it is there. Among those, the closest
//! point (bilinear projection) of a face whose outward normal faces the node's normal wins,
//! if it lies within the capture distance and, when clamped to an edge, within 1 % of a
//! cell in the face's plane (a node that has slid off the edge of surface b is free).

use std::collections::HashMap;

use super::geom::{dot, face_normal, face_point, norm, project_on_face, sub, tangential};

/// Faces of surface b binned over their current positions; reused from step to step.
#[derive(Clone, Debug, Default)]
pub struct FaceGrid {
    cells: HashMap<[i64; 3], Vec<u32>>,
    cell_size: f64,
    capture: f64,
    edge_tol: f64,
}

/// The face a node touches: index, local coordinates (ξ, η) of the closest point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceHit {
    pub face: u32,
    pub xi: f64,
    pub eta: f64,
}

impl FaceGrid {
    /// Bin the faces `faces` (corner positions by `position`) whose `active` flag is set.
    /// `min_cell` is a lower bound of the cell size (the reference face size, so that a
    /// collapsed face does not shrink the grid).
    pub fn rebuild(
        &mut self,
        faces: &[[u32; 4]],
        active: &[bool],
        min_cell: f64,
        position: impl Fn(u32) -> [f64; 3],
    ) {
        let mut hmax: f64 = 0.0;
        for f in faces {
            let x = f.map(&position);
            hmax = hmax.max(norm(sub(x[2], x[0]))).max(norm(sub(x[3], x[1])));
        }
        self.cell_size = hmax.max(min_cell).max(f64::MIN_POSITIVE);
        self.capture = 0.5 * self.cell_size;
        self.edge_tol = 1e-2 * self.cell_size;
        for list in self.cells.values_mut() {
            list.clear();
        }
        for (fi, f) in faces.iter().enumerate() {
            if !active[fi] {
                continue;
            }
            let x = f.map(&position);
            let lo = [0, 1, 2]
                .map(|d| x.iter().map(|q| q[d]).fold(f64::INFINITY, f64::min) - self.capture);
            let hi = [0, 1, 2]
                .map(|d| x.iter().map(|q| q[d]).fold(f64::NEG_INFINITY, f64::max) + self.capture);
            let (c0, c1) = (self.cell(lo), self.cell(hi));
            for i in c0[0]..=c1[0] {
                for j in c0[1]..=c1[1] {
                    for k in c0[2]..=c1[2] {
                        self.cells.entry([i, j, k]).or_default().push(fi as u32);
                    }
                }
            }
        }
    }

    /// The capture distance (half a cell): a node farther than this from every face is free.
    pub fn capture(&self) -> f64 {
        self.capture
    }

    /// The closest facing face to point `p` of a node with normal `normal` (outward from
    /// surface a), or `None` when no face is within the capture distance.
    pub fn closest(
        &self,
        p: [f64; 3],
        normal: [f64; 3],
        faces: &[[u32; 4]],
        position: impl Fn(u32) -> [f64; 3],
    ) -> Option<FaceHit> {
        let list = self.cells.get(&self.cell(p))?;
        let mut best: Option<(f64, FaceHit)> = None;
        for &fi in list {
            let x = faces[fi as usize].map(&position);
            let (xi, eta, dist) = project_on_face(&x, p);
            if best.is_some_and(|(bd, _)| dist >= bd) || !self.accept(&x, p, xi, eta) {
                continue;
            }
            match face_normal(&x, xi, eta) {
                Some(nb) if dot(nb, normal) < 0.0 => {
                    best = Some((dist, FaceHit { face: fi, xi, eta }))
                }
                _ => {}
            }
        }
        best.map(|(_, hit)| hit)
    }

    fn cell(&self, x: [f64; 3]) -> [i64; 3] {
        x.map(|c| (c / self.cell_size).floor() as i64)
    }

    /// Whether the closest point found by [`project_on_face`] is a contact candidate:
    /// within the capture distance and, when it was clamped to an edge, with an in-plane
    /// offset of at most the edge tolerance.
    fn accept(&self, x: &[[f64; 3]; 4], p: [f64; 3], xi: f64, eta: f64) -> bool {
        let (q, _, _) = face_point(x, xi, eta);
        let d = sub(p, q);
        if norm(d) > self.capture {
            return false;
        }
        match face_normal(x, xi, eta) {
            Some(nb) => norm(tangential(d, nb)) <= self.edge_tol,
            None => false,
        }
    }
}
