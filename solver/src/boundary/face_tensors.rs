//! Nodal integrals of a bilinear boundary face that distributed boundary tractions need:
//! for each face node k, the tributary area A_k = ∫φ_k dA, the area vector ∫φ_k n dA and
//! the normal tensor ∫φ_k n⊗n dA (2×2 Gauss: exact for a plane face, the integrand being
//! bilinear there). A distributed dashpot or spring with normal coefficient p and
//! tangential coefficient s (per unit area) then gives the nodal matrix
//! s A_k I + (p − s) ∫φ_k n⊗n dA — the exact tributary-area lumping of
//! t = −p (v·n) n − s (v − (v·n) n).

use nalgebra::{Matrix3, Vector3};

use crate::mesh::face_geometry::{cross, face_point, face_shape, norm};

/// Integrals of one face node.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceNodeIntegrals {
    /// ∫φ_k dA (m²).
    pub area: f64,
    /// ∫φ_k n dA (m²), n the outward unit normal.
    pub area_vector: Vector3<f64>,
    /// ∫φ_k n⊗n dA (m²).
    pub normal_tensor: Matrix3<f64>,
}

impl FaceNodeIntegrals {
    /// Nodal matrix of a distributed isotropic-in-plane operator with normal coefficient
    /// `normal` and tangential coefficient `tangential` per unit area.
    pub fn matrix(&self, normal: f64, tangential: f64) -> Matrix3<f64> {
        Matrix3::identity() * (tangential * self.area) + self.normal_tensor * (normal - tangential)
    }
}

/// The integrals of the four nodes of a face with corner coordinates `x` (counter-clockwise
/// seen from outside, so ∂x/∂ξ × ∂x/∂η points outwards). `None` for a degenerate face.
pub fn face_node_integrals(x: &[[f64; 3]; 4]) -> Option<[FaceNodeIntegrals; 4]> {
    let g = 1.0 / 3f64.sqrt();
    let mut out = [FaceNodeIntegrals {
        area: 0.0,
        area_vector: Vector3::zeros(),
        normal_tensor: Matrix3::zeros(),
    }; 4];
    for (gx, ge) in [(-g, -g), (g, -g), (g, g), (-g, g)] {
        let (_, a, b) = face_point(x, gx, ge);
        let c = cross(a, b);
        let da = norm(c); // dA per unit (ξ, η) area; the Gauss weights are 1
        if !(da > 0.0 && da.is_finite()) {
            return None;
        }
        let n = Vector3::new(c[0], c[1], c[2]) / da;
        let nn = n * n.transpose();
        let phi = face_shape(gx, ge);
        for k in 0..4 {
            out[k].area += phi[k] * da;
            out[k].area_vector += n * (phi[k] * da);
            out[k].normal_tensor += nn * (phi[k] * da);
        }
    }
    Some(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn plane_face_tensor_is_area_times_normal_square() {
        // A 2 × 3 rectangle in the plane z = 1 facing +z.
        let x = [
            [0.0, 0.0, 1.0],
            [2.0, 0.0, 1.0],
            [2.0, 3.0, 1.0],
            [0.0, 3.0, 1.0],
        ];
        let f = face_node_integrals(&x).unwrap();
        for k in 0..4 {
            assert!((f[k].area - 1.5).abs() < 1e-12);
            assert!((f[k].area_vector - Vector3::new(0.0, 0.0, 1.5)).norm() < 1e-12);
            let c = f[k].matrix(10.0, 4.0);
            assert!((c[(2, 2)] - 15.0).abs() < 1e-12);
            assert!((c[(0, 0)] - 6.0).abs() < 1e-12 && (c[(1, 1)] - 6.0).abs() < 1e-12);
            assert!(c[(0, 2)].abs() < 1e-12);
        }
    }

    #[test]
    fn tilted_face_matrix_is_rotation_invariant() {
        // The unit square rotated about x by 30°: the matrix is R diag(s, s, p) Rᵀ × area.
        let (s30, c30) = (0.5f64, 3f64.sqrt() / 2.0);
        let rot = |p: [f64; 3]| [p[0], c30 * p[1] - s30 * p[2], s30 * p[1] + c30 * p[2]];
        let x = [
            rot([0.0, 0.0, 0.0]),
            rot([1.0, 0.0, 0.0]),
            rot([1.0, 1.0, 0.0]),
            rot([0.0, 1.0, 0.0]),
        ];
        let f = face_node_integrals(&x).unwrap();
        let total: Matrix3<f64> = f.iter().map(|k| k.matrix(3.0, 1.0)).sum();
        let n = Vector3::new(0.0, -s30, c30);
        let expected = Matrix3::identity() + n * n.transpose() * 2.0;
        assert!((total - expected).norm() < 1e-12, "{total} vs {expected}");
    }
}
