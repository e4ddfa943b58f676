//! Points of a bar inside the hex8 mesh: which element holds a point and where (its natural
//! coordinates, by Newton's method on the trilinear map), and where a straight bar crosses
//! element faces (bisection on "still inside the element").

use std::collections::HashMap;

use crate::mesh::hex8_shape::{inverse_3x3, jacobian, shape, shape_derivatives};
use crate::mesh::Mesh;

/// A point located in a host element: the element, its natural coordinates and the shape
/// function values there.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HostPoint {
    pub element: u32,
    pub xi: [f64; 3],
    pub n: [f64; 8],
}

/// Natural coordinates of `p` in the element with corners `x`, by Newton's method on
/// x(ξ) = Σ N_a(ξ) x_a from the centre; `None` if it does not converge (far outside a
/// distorted element).
pub fn inverse_map(x: &[[f64; 3]; 8], p: &[f64; 3]) -> Option<[f64; 3]> {
    let mut xi = [0.0; 3];
    let scale = (0..3)
        .map(|d| (x[6][d] - x[0][d]).abs())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    for _ in 0..40 {
        let n = shape(&xi);
        let r: [f64; 3] =
            std::array::from_fn(|d| p[d] - (0..8).map(|a| n[a] * x[a][d]).sum::<f64>());
        if r.iter().map(|v| v.abs()).fold(0.0, f64::max) <= 1e-13 * scale {
            return Some(xi);
        }
        let (j, det) = jacobian(x, &shape_derivatives(&xi));
        if !(det.is_finite() && det > 0.0) {
            return None;
        }
        let inv = inverse_3x3(&j, det);
        for k in 0..3 {
            xi[k] += (0..3).map(|d| inv[k][d] * r[d]).sum::<f64>();
        }
        if xi.iter().any(|v| !v.is_finite() || v.abs() > 10.0) {
            return None;
        }
    }
    None
}

/// Inside within `tol` in natural coordinates.
fn inside(xi: &[f64; 3], tol: f64) -> bool {
    xi.iter().all(|v| v.abs() <= 1.0 + tol)
}

/// A bin grid of element bounding boxes for point location.
pub struct HostLocator {
    cell: f64,
    bins: HashMap<[i64; 3], Vec<u32>>,
    /// Smallest element edge (sets the sampling of bars along their length).
    pub min_size: f64,
}

impl HostLocator {
    /// Bins of about the mean element size, over the elements `allowed` selects.
    pub fn new(mesh: &Mesh, allowed: impl Fn(usize) -> bool) -> Self {
        let mut total = 0.0;
        let mut count = 0usize;
        let mut min_size = f64::INFINITY;
        let mut boxes = Vec::new();
        for e in 0..mesh.n_elements() {
            if !allowed(e) {
                continue;
            }
            let x = mesh.element_coords(e);
            let mut lo = [f64::INFINITY; 3];
            let mut hi = [-f64::INFINITY; 3];
            for p in &x {
                for d in 0..3 {
                    lo[d] = lo[d].min(p[d]);
                    hi[d] = hi[d].max(p[d]);
                }
            }
            let size = (0..3).map(|d| hi[d] - lo[d]).fold(f64::INFINITY, f64::min);
            min_size = min_size.min(size);
            total += (0..3).map(|d| hi[d] - lo[d]).sum::<f64>() / 3.0;
            count += 1;
            boxes.push((e as u32, lo, hi));
        }
        let cell = (total / count.max(1) as f64).max(1e-9);
        let mut bins: HashMap<[i64; 3], Vec<u32>> = HashMap::new();
        let key = |v: f64| (v / cell).floor() as i64;
        for (e, lo, hi) in boxes {
            let eps = 1e-9 * cell;
            for i in key(lo[0] - eps)..=key(hi[0] + eps) {
                for j in key(lo[1] - eps)..=key(hi[1] + eps) {
                    for k in key(lo[2] - eps)..=key(hi[2] + eps) {
                        bins.entry([i, j, k]).or_default().push(e);
                    }
                }
            }
        }
        Self {
            cell,
            bins,
            min_size,
        }
    }

    /// The element holding `p` (the lowest element number among those that do, within a
    /// tolerance of 1e-9 in natural coordinates), or `None` outside the mesh.
    pub fn locate(&self, mesh: &Mesh, p: &[f64; 3]) -> Option<HostPoint> {
        let k = p.map(|v| (v / self.cell).floor() as i64);
        let cands = self.bins.get(&k)?;
        let mut best: Option<HostPoint> = None;
        for &e in cands {
            if best.is_some_and(|b| b.element < e) {
                continue;
            }
            let x = mesh.element_coords(e as usize);
            if let Some(xi) = inverse_map(&x, p) {
                if inside(&xi, 1e-9) {
                    let xi = xi.map(|v| v.clamp(-1.0, 1.0));
                    best = Some(HostPoint {
                        element: e,
                        xi,
                        n: shape(&xi),
                    });
                }
            }
        }
        best
    }

    /// `p` located in element `e` (natural coordinates clamped to the element), if `p` is
    /// in it within `tol`.
    pub fn locate_in(&self, mesh: &Mesh, e: u32, p: &[f64; 3], tol: f64) -> Option<HostPoint> {
        let x = mesh.element_coords(e as usize);
        let xi = inverse_map(&x, p)?;
        if !inside(&xi, tol) {
            return None;
        }
        let xi = xi.map(|v| v.clamp(-1.0, 1.0));
        Some(HostPoint {
            element: e,
            xi,
            n: shape(&xi),
        })
    }

    /// Cut the straight bar `a → b` where it crosses element faces (and, if `max_length`
    /// is given, into pieces no longer than it): the parameters s ∈ [0, 1] of the cuts,
    /// 0 and 1 included, and the host element of each piece. `Err(s)` when the bar leaves
    /// the mesh at parameter s.
    pub fn cut(
        &self,
        mesh: &Mesh,
        a: &[f64; 3],
        b: &[f64; 3],
        max_length: Option<f64>,
    ) -> Result<(Vec<f64>, Vec<u32>), f64> {
        let len = (0..3).map(|d| (b[d] - a[d]).powi(2)).sum::<f64>().sqrt();
        let at = |s: f64| -> [f64; 3] { std::array::from_fn(|d| a[d] + s * (b[d] - a[d])) };
        let samples = ((len / (0.25 * self.min_size)).ceil() as usize).max(4);
        // Host of each sample (the point just inside the bar at the ends).
        let mut cuts = vec![0.0];
        let mut hosts = Vec::new();
        let host_at = |s: f64| self.locate(mesh, &at(s)).map(|h| h.element).ok_or(s);
        let mut s_prev = 0.0f64;
        let mut e_prev = host_at(0.5 / samples as f64)?;
        for i in 1..=samples {
            let s = (i as f64 - 0.5) / samples as f64;
            let s = if i == samples {
                1.0 - 0.5 / samples as f64
            } else {
                s
            };
            let e = host_at(s)?;
            if e != e_prev {
                // Bisect the crossing out of e_prev between s_prev and s.
                let (mut lo, mut hi) = (s_prev.max(0.5 / samples as f64), s);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if self.locate_in(mesh, e_prev, &at(mid), 1e-12).is_some() {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                cuts.push(0.5 * (lo + hi));
                hosts.push(e_prev);
                e_prev = e;
            }
            s_prev = s;
        }
        cuts.push(1.0);
        hosts.push(e_prev);
        // Pieces no longer than max_length.
        if let Some(lmax) = max_length {
            let mut c2 = vec![0.0];
            let mut h2 = Vec::new();
            for (w, &h) in cuts.windows(2).zip(&hosts) {
                let n = (((w[1] - w[0]) * len / lmax) - 1e-9).ceil().max(1.0) as usize;
                for k in 1..=n {
                    c2.push(w[0] + (w[1] - w[0]) * k as f64 / n as f64);
                    h2.push(h);
                }
            }
            return Ok((c2, h2));
        }
        Ok((cuts, hosts))
    }
}
