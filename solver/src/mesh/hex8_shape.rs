//! Trilinear hex8 shape functions N_a = ⅛(1+ξ_a ξ)(1+η_a η)(1+ζ_a ζ), their derivatives,
//! the 2×2×2 Gauss rule and Jacobian checks.

/// Natural coordinates of the eight nodes (VTK / Gmsh order).
pub const NODE_XI: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// 2×2×2 Gauss points (weights all 1), ordered like the nodes.
pub fn gauss_points() -> [[f64; 3]; 8] {
    let g = 1.0 / 3f64.sqrt();
    NODE_XI.map(|p| p.map(|c| c * g))
}

/// Shape function values at a natural point.
#[inline]
pub fn shape(xi: &[f64; 3]) -> [f64; 8] {
    std::array::from_fn(|a| {
        let n = NODE_XI[a];
        0.125 * (1.0 + n[0] * xi[0]) * (1.0 + n[1] * xi[1]) * (1.0 + n[2] * xi[2])
    })
}

/// Derivatives ∂N_a/∂(ξ, η, ζ) at a natural point.
#[inline]
pub fn shape_derivatives(xi: &[f64; 3]) -> [[f64; 3]; 8] {
    std::array::from_fn(|a| {
        let n = NODE_XI[a];
        let (a0, a1, a2) = (1.0 + n[0] * xi[0], 1.0 + n[1] * xi[1], 1.0 + n[2] * xi[2]);
        [
            0.125 * n[0] * a1 * a2,
            0.125 * n[1] * a0 * a2,
            0.125 * n[2] * a0 * a1,
        ]
    })
}

/// Jacobian J_ij = ∂x_i/∂ξ_j and its determinant at a natural point.
#[inline]
pub fn jacobian(x: &[[f64; 3]; 8], dn: &[[f64; 3]; 8]) -> ([[f64; 3]; 3], f64) {
    let mut j = [[0.0; 3]; 3];
    for a in 0..8 {
        for (i, row) in j.iter_mut().enumerate() {
            for (k, v) in row.iter_mut().enumerate() {
                *v += x[a][i] * dn[a][k];
            }
        }
    }
    let det = j[0][0] * (j[1][1] * j[2][2] - j[1][2] * j[2][1])
        - j[0][1] * (j[1][0] * j[2][2] - j[1][2] * j[2][0])
        + j[0][2] * (j[1][0] * j[2][1] - j[1][1] * j[2][0]);
    (j, det)
}

/// Inverse of a 3×3 matrix with determinant `det`, by cofactors.
#[inline]
pub fn inverse_3x3(j: &[[f64; 3]; 3], det: f64) -> [[f64; 3]; 3] {
    [
        [
            (j[1][1] * j[2][2] - j[1][2] * j[2][1]) / det,
            (j[0][2] * j[2][1] - j[0][1] * j[2][2]) / det,
            (j[0][1] * j[1][2] - j[0][2] * j[1][1]) / det,
        ],
        [
            (j[1][2] * j[2][0] - j[1][0] * j[2][2]) / det,
            (j[0][0] * j[2][2] - j[0][2] * j[2][0]) / det,
            (j[0][2] * j[1][0] - j[0][0] * j[1][2]) / det,
        ],
        [
            (j[1][0] * j[2][1] - j[1][1] * j[2][0]) / det,
            (j[0][1] * j[2][0] - j[0][0] * j[2][1]) / det,
            (j[0][0] * j[1][1] - j[0][1] * j[1][0]) / det,
        ],
    ]
}

/// Cartesian derivatives ∂N_a/∂x_i and det J at a natural point. Returns `None` when
/// det J ≤ 0.
#[inline]
pub fn cartesian_derivatives(x: &[[f64; 3]; 8], xi: &[f64; 3]) -> Option<([[f64; 3]; 8], f64)> {
    let dn = shape_derivatives(xi);
    let (j, det) = jacobian(x, &dn);
    if det.is_nan() || det <= 0.0 {
        return None;
    }
    // ∂N/∂x_i = Σ_k ∂N/∂ξ_k (J⁻¹)_ki.
    let inv = inverse_3x3(&j, det);
    let mut d = [[0.0; 3]; 8];
    for a in 0..8 {
        for i in 0..3 {
            d[a][i] = dn[a][0] * inv[0][i] + dn[a][1] * inv[1][i] + dn[a][2] * inv[2][i];
        }
    }
    Some((d, det))
}

/// Positive Jacobian at the centre, the eight Gauss points and the eight corners; the
/// error text says where it fails and the value.
pub fn check_jacobian(x: &[[f64; 3]; 8]) -> Result<(), String> {
    let mut points = vec![("centre".to_string(), [0.0; 3])];
    for (g, p) in gauss_points().iter().enumerate() {
        points.push((format!("Gauss point {g}"), *p));
    }
    for (a, p) in NODE_XI.iter().enumerate() {
        points.push((format!("corner {a}"), *p));
    }
    let (_, det0) = jacobian(x, &shape_derivatives(&[0.0; 3]));
    let scale = det0.abs().max(f64::MIN_POSITIVE);
    for (name, p) in points {
        let (_, det) = jacobian(x, &shape_derivatives(&p));
        if !det.is_finite() || det <= 1e-10 * scale || det <= 0.0 {
            let kind = if det < 0.0 { "inverted" } else { "degenerate" };
            return Err(format!(
                "{kind} hex8: det J = {det:.3e} at {name} (node order must follow VTK/Gmsh hex8)"
            ));
        }
    }
    Ok(())
}

/// Element volume by 2×2×2 Gauss quadrature (exact for trilinear geometry).
pub fn volume(x: &[[f64; 3]; 8]) -> f64 {
    gauss_points()
        .iter()
        .map(|p| jacobian(x, &shape_derivatives(p)).1)
        .sum()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_cube(h: f64) -> [[f64; 3]; 8] {
        NODE_XI.map(|p| p.map(|c| 0.5 * h * (c + 1.0)))
    }

    #[test]
    fn partition_of_unity_and_derivative_sum() {
        let p = [0.3, -0.7, 0.1];
        let n = shape(&p);
        assert!((n.iter().sum::<f64>() - 1.0).abs() < 1e-15);
        let d = shape_derivatives(&p);
        for k in 0..3 {
            assert!(d.iter().map(|r| r[k]).sum::<f64>().abs() < 1e-15);
        }
    }

    #[test]
    fn cube_volume_and_inversion_detected() {
        let x = unit_cube(2.0);
        assert!((volume(&x) - 8.0).abs() < 1e-12);
        assert!(check_jacobian(&x).is_ok());
        let mut bad = x;
        bad.swap(0, 6);
        assert!(check_jacobian(&bad).is_err());
        let mut flat = x;
        for p in flat.iter_mut().skip(4) {
            p[2] = 0.0;
        }
        assert!(check_jacobian(&flat).unwrap_err().contains("degenerate"));
    }
}
