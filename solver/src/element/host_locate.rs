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
    /// The elements that may host a point ([`Self::locate`]); `None`: every binned one.
    /// The others are still binned, so that [`Self::locate_any`] tells a point held only
    /// by ineligible elements from one outside the mesh.
    eligible: Option<Vec<bool>>,
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
            eligible: None,
        }
    }

    /// Bins over every element of `mesh` (the same bins and sampling as
    /// `new(mesh, |_| true)`), of which only those with `eligible[e]` host points: the
    /// anchors' locator, whose eligible elements are those active when the bars are
    /// installed (docs/anchors.md, "Host elements").
    pub fn with_eligible(mesh: &Mesh, eligible: Vec<bool>) -> Self {
        assert_eq!(eligible.len(), mesh.n_elements(), "one flag per element");
        Self {
            eligible: Some(eligible),
            ..Self::new(mesh, |_| true)
        }
    }

    /// Whether element `e` may host a point.
    pub fn is_eligible(&self, e: u32) -> bool {
        self.eligible.as_ref().is_none_or(|m| m[e as usize])
    }

    /// The element holding `p` (the lowest element number among the eligible ones that do,
    /// within a tolerance of 1e-9 in natural coordinates), or `None` where no eligible
    /// element holds it.
    pub fn locate(&self, mesh: &Mesh, p: &[f64; 3]) -> Option<HostPoint> {
        self.locate_among(mesh, p, true)
    }

    /// The lowest-numbered element holding `p`, eligible or not (to explain why
    /// [`Self::locate`] found none).
    pub fn locate_any(&self, mesh: &Mesh, p: &[f64; 3]) -> Option<HostPoint> {
        self.locate_among(mesh, p, false)
    }

    fn locate_among(&self, mesh: &Mesh, p: &[f64; 3], eligible_only: bool) -> Option<HostPoint> {
        let k = p.map(|v| (v / self.cell).floor() as i64);
        let cands = self.bins.get(&k)?;
        let mut best: Option<HostPoint> = None;
        for &e in cands {
            if best.is_some_and(|b| b.element < e) || (eligible_only && !self.is_eligible(e)) {
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
        // Sample parameters: the two ends and the midpoints of `samples` equal pieces, so
        // that a face crossed within half a piece of an end is found as well. An end on
        // the mesh's boundary that the locator misses by round-off takes the host of the
        // sample next to it.
        let mut params = Vec::with_capacity(samples + 2);
        params.push(0.0);
        params.extend((1..=samples).map(|i| (i as f64 - 0.5) / samples as f64));
        params.push(1.0);
        let host_at = |s: f64| self.locate(mesh, &at(s)).map(|h| h.element).ok_or(s);
        let mut sample_hosts = Vec::with_capacity(params.len());
        for (i, &s) in params.iter().enumerate() {
            let h = match host_at(s) {
                Ok(h) => Some(h),
                Err(_) if i == 0 || i + 1 == params.len() => None,
                Err(s) => return Err(s),
            };
            sample_hosts.push(h);
        }
        let n = params.len();
        if sample_hosts[0].is_none() {
            sample_hosts[0] = sample_hosts[1];
        }
        if sample_hosts[n - 1].is_none() {
            sample_hosts[n - 1] = sample_hosts[n - 2];
        }
        let mut cuts = vec![0.0];
        let mut hosts = Vec::new();
        let mut s_prev = 0.0f64;
        let mut e_prev = sample_hosts[0].ok_or(0.0)?;
        for (&s, e) in params.iter().zip(&sample_hosts).skip(1) {
            let e = e.ok_or(s)?;
            // Between two samples the bar may cross more than one face (it clips the
            // corner or edge of a third element): follow it element by element.
            let mut lo_bound = s_prev;
            let mut crossings = 0;
            while e != e_prev {
                crossings += 1;
                if crossings > 16 {
                    return Err(s);
                }
                // Bisect the crossing out of e_prev between lo_bound and s.
                let (mut lo, mut hi) = (lo_bound, s);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if self.locate_in(mesh, e_prev, &at(mid), 1e-12).is_some() {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let c = 0.5 * (lo + hi);
                // An end on a face shared by two elements: no piece of zero length.
                if (c - cuts[cuts.len() - 1]) * len > 1e-9 {
                    cuts.push(c);
                    hosts.push(e_prev);
                }
                // The element just past the crossing (1 µm along the bar); a clip shorter
                // than that is left to the element of the next sample.
                let past = (c + 1e-6 / len).min(s);
                let next = match self.locate(mesh, &at(past)) {
                    Some(h) if h.element != e_prev => h.element,
                    Some(_) => e,
                    None => return Err(past),
                };
                e_prev = next;
                lo_bound = c;
            }
            s_prev = s;
        }
        if (1.0 - cuts[cuts.len() - 1]) * len <= 1e-9 && cuts.len() > 1 {
            // The last crossing lies on the end itself: the last piece ends there.
            cuts.pop();
            e_prev = hosts.pop().unwrap_or(e_prev);
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::box_generator::BoxMeshSpec;

    /// A bar whose end lies just past a face (closer to it than half a sample) gets a piece
    /// in the element beyond, and one that ends on a face gets no piece of zero length.
    #[test]
    fn cuts_found_near_the_ends_of_a_bar() {
        // Ten 1 m cubes along x; the locator samples at 0.25 m (a quarter of the edge).
        let mesh = BoxMeshSpec::single("b", [0.0; 3], [10.0, 1.0, 1.0], [10, 1, 1])
            .build("test")
            .unwrap();
        let loc = HostLocator::new(&mesh, |_| true);
        let host = |x: f64| loc.locate(&mesh, &[x, 0.5, 0.5]).unwrap().element;
        // 0.2 → 3.02 m: 12 samples of 0.235 m; the last midpoint (2.90 m) lies in the third
        // cube, the end in the fourth.
        let (cuts, hosts) = loc
            .cut(&mesh, &[0.2, 0.5, 0.5], &[3.02, 0.5, 0.5], None)
            .unwrap();
        let len = 2.82;
        let at: Vec<f64> = cuts.iter().map(|s| 0.2 + s * len).collect();
        assert_eq!(hosts, vec![host(0.5), host(1.5), host(2.5), host(3.01)]);
        for (x, want) in at.iter().zip([0.2, 1.0, 2.0, 3.0, 3.02]) {
            assert!((x - want).abs() < 1e-9, "cuts at {at:?}");
        }
        // 0.5 → 3.0 m: the end on the face between the third and the fourth cube.
        let (cuts, hosts) = loc
            .cut(&mesh, &[0.5, 0.5, 0.5], &[3.0, 0.5, 0.5], None)
            .unwrap();
        assert_eq!(hosts, vec![host(0.5), host(1.5), host(2.5)]);
        assert_eq!(cuts.len(), 4);
        assert!(cuts.windows(2).all(|w| (w[1] - w[0]) * 2.5 > 0.1));
    }

    /// A bar that clips the corner of an element between two samples: every piece lies
    /// in its host (both ends located in it).
    #[test]
    fn corner_clips_get_their_own_piece() {
        let mesh = BoxMeshSpec::single("b", [0.0; 3], [4.0, 4.0, 1.0], [4, 4, 1])
            .build("test")
            .unwrap();
        let loc = HostLocator::new(&mesh, |_| true);
        // From (0.1, 1.05) to (3.9, 3.05) — through cells (0,1), (1,1) … passing the
        // corner (1, 2) region diagonally; and a steep one that clips corners closely.
        for (a, b) in [
            ([0.1, 1.05, 0.5], [3.9, 3.05, 0.5]),
            ([0.5, 0.999, 0.5], [3.5, 1.001, 0.5]),
            ([0.9, 1.9, 0.5], [1.2, 2.2001, 0.5]),
        ] {
            let (cuts, hosts) = loc.cut(&mesh, &a, &b, None).unwrap();
            let at = |s: f64| -> [f64; 3] { std::array::from_fn(|d| a[d] + s * (b[d] - a[d])) };
            for (w, &h) in cuts.windows(2).zip(&hosts) {
                assert!(loc.locate_in(&mesh, h, &at(w[0]), 1e-6).is_some(), "{a:?}");
                assert!(loc.locate_in(&mesh, h, &at(w[1]), 1e-6).is_some(), "{a:?}");
                assert!(w[1] > w[0]);
            }
        }
    }
}
