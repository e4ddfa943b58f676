//! Small vector helpers and the bilinear quadrilateral face: nodal areas and normals, shape
//! functions φⱼ(ξ, η) and the closest-point (Newton) projection used by point-to-surface
//! contact.
//!
//! Face nodes are in the order of [`Mesh::face_nodes`](crate::mesh::Mesh::face_nodes):
//! counter-clockwise seen from outside, so ∂x/∂ξ × ∂x/∂η points out of the element with
//! ξ along node 0 → 1 and η along node 0 → 3.

/// a · b
#[inline]
pub fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// a − b
#[inline]
pub fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

/// a + b
#[inline]
pub fn add(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [a[0] + b[0], a[1] + b[1], a[2] + b[2]]
}

/// s a
#[inline]
pub fn scale(s: f64, a: [f64; 3]) -> [f64; 3] {
    [s * a[0], s * a[1], s * a[2]]
}

/// a + s b
#[inline]
pub fn axpy(a: [f64; 3], s: f64, b: [f64; 3]) -> [f64; 3] {
    [a[0] + s * b[0], a[1] + s * b[1], a[2] + s * b[2]]
}

/// a × b
#[inline]
pub fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// |a|
#[inline]
pub fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// Tangential part of `a` with respect to the unit normal `n`: a − (a·n) n.
#[inline]
pub fn tangential(a: [f64; 3], n: [f64; 3]) -> [f64; 3] {
    axpy(a, -dot(a, n), n)
}

/// Natural coordinates of the four face nodes.
pub const FACE_XI: [[f64; 2]; 4] = [[-1.0, -1.0], [1.0, -1.0], [1.0, 1.0], [-1.0, 1.0]];

/// Bilinear shape functions φⱼ(ξ, η) of the face.
#[inline]
pub fn face_shape(xi: f64, eta: f64) -> [f64; 4] {
    std::array::from_fn(|j| 0.25 * (1.0 + FACE_XI[j][0] * xi) * (1.0 + FACE_XI[j][1] * eta))
}

/// Point x(ξ, η) = Σ φⱼ xⱼ and its tangents ∂x/∂ξ, ∂x/∂η.
#[inline]
pub fn face_point(x: &[[f64; 3]; 4], xi: f64, eta: f64) -> ([f64; 3], [f64; 3], [f64; 3]) {
    let mut p = [0.0; 3];
    let mut dxi = [0.0; 3];
    let mut deta = [0.0; 3];
    for j in 0..4 {
        let (sx, se) = (FACE_XI[j][0], FACE_XI[j][1]);
        let phi = 0.25 * (1.0 + sx * xi) * (1.0 + se * eta);
        let dpx = 0.25 * sx * (1.0 + se * eta);
        let dpe = 0.25 * se * (1.0 + sx * xi);
        for d in 0..3 {
            p[d] += phi * x[j][d];
            dxi[d] += dpx * x[j][d];
            deta[d] += dpe * x[j][d];
        }
    }
    (p, dxi, deta)
}

/// Unit outward normal of the face at (ξ, η); `None` if the face is degenerate there.
#[inline]
pub fn face_normal(x: &[[f64; 3]; 4], xi: f64, eta: f64) -> Option<[f64; 3]> {
    let (_, a, b) = face_point(x, xi, eta);
    let c = cross(a, b);
    let l = norm(c);
    (l > 0.0 && l.is_finite()).then(|| scale(1.0 / l, c))
}

/// Exact nodal area vectors ∫ φⱼ n dA of a bilinear face (2×2 Gauss, exact for the
/// bilinear integrand), and the face area. Their sum is the face's area vector.
pub fn face_nodal_area_vectors(x: &[[f64; 3]; 4]) -> ([[f64; 3]; 4], f64) {
    let g = 1.0 / 3f64.sqrt();
    let mut out = [[0.0; 3]; 4];
    let mut area = 0.0;
    for (gx, ge) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
        let (_, a, b) = face_point(x, gx, ge);
        let nda = cross(a, b); // n dA per unit (ξ, η) area; Gauss weights are 1
        area += norm(nda);
        let phi = face_shape(gx, ge);
        for j in 0..4 {
            out[j] = axpy(out[j], phi[j], nda);
        }
    }
    (out, area)
}

/// Exact nodal areas ∫ φⱼ dA of a bilinear face.
pub fn face_nodal_areas(x: &[[f64; 3]; 4]) -> [f64; 4] {
    let g = 1.0 / 3f64.sqrt();
    let mut out = [0.0; 4];
    for (gx, ge) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
        let (_, a, b) = face_point(x, gx, ge);
        let da = norm(cross(a, b));
        let phi = face_shape(gx, ge);
        for j in 0..4 {
            out[j] += phi[j] * da;
        }
    }
    out
}

/// Closest point of the bilinear face to `p`: (ξ, η) in [−1, 1]², found by a projected
/// Gauss–Newton iteration on |x(ξ, η) − p|² started at the centre. Returns (ξ, η, distance).
pub fn project_on_face(x: &[[f64; 3]; 4], p: [f64; 3]) -> (f64, f64, f64) {
    let (mut xi, mut eta) = (0.0f64, 0.0f64);
    for _ in 0..30 {
        let (q, a, b) = face_point(x, xi, eta);
        let r = sub(p, q);
        // Normal equations (JᵀJ) δ = Jᵀ r.
        let (aa, ab, bb) = (dot(a, a), dot(a, b), dot(b, b));
        let (ra, rb) = (dot(r, a), dot(r, b));
        let det = aa * bb - ab * ab;
        if det.abs() <= f64::EPSILON * aa * bb || !det.is_finite() {
            break;
        }
        let dxi = (bb * ra - ab * rb) / det;
        let deta = (aa * rb - ab * ra) / det;
        let nxi = (xi + dxi).clamp(-1.0, 1.0);
        let neta = (eta + deta).clamp(-1.0, 1.0);
        let step = (nxi - xi).abs().max((neta - eta).abs());
        xi = nxi;
        eta = neta;
        if step < 1e-13 {
            break;
        }
    }
    let (q, _, _) = face_point(x, xi, eta);
    (xi, eta, norm(sub(p, q)))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn skew() -> [[f64; 3]; 4] {
        [
            [0.0, 0.0, 0.0],
            [2.0, 0.1, 0.0],
            [2.2, 1.5, 0.3],
            [-0.1, 1.2, 0.1],
        ]
    }

    #[test]
    fn nodal_areas_sum_to_face_area_and_area_vector_is_exact() {
        let x = skew();
        let (v, area) = face_nodal_area_vectors(&x);
        let a = face_nodal_areas(&x);
        assert!((a.iter().sum::<f64>() - area).abs() < 1e-12 * area);
        // Area vector of a (possibly warped) quad = ½ d₁ × d₂ exactly.
        let exact = scale(0.5, cross(sub(x[2], x[0]), sub(x[3], x[1])));
        let s = v.iter().fold([0.0; 3], |s, &q| add(s, q));
        assert!(norm(sub(s, exact)) < 1e-12 * norm(exact));
    }

    #[test]
    fn projection_recovers_a_point_above_the_face() {
        let x = skew();
        let (q, a, b) = face_point(&x, 0.3, -0.4);
        let n = scale(1.0 / norm(cross(a, b)), cross(a, b));
        let p = axpy(q, 0.05, n);
        let (xi, eta, d) = project_on_face(&x, p);
        assert!(
            (xi - 0.3).abs() < 1e-9 && (eta + 0.4).abs() < 1e-9,
            "{xi} {eta}"
        );
        assert!((d - 0.05).abs() < 1e-9);
    }

    #[test]
    fn projection_clamps_outside_points() {
        let x = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let (xi, eta, d) = project_on_face(&x, [2.0, 0.5, 0.0]);
        assert_eq!(xi, 1.0);
        assert!(eta.abs() < 1e-12);
        assert!((d - 1.0).abs() < 1e-12);
    }
}
