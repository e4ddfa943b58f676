//! Critical time step of the explicit scheme: Δt_e = L_e / c_p with the characteristic
//! length L_e = V / A_max (volume over the largest face area), the usual bound for hex8
//! with lumped mass (Belytschko, Liu & Moran 2000, §6.2). A uniform mesh is stable up to
//! Δt = h / c_p (VERIFICATION.md W13); the global step is the minimum times a safety factor.

use crate::mesh::HEX8_FACES;

/// Area of a (possibly warped) quadrilateral face: half the norm of the diagonal product.
pub fn face_area(p: [[f64; 3]; 4]) -> f64 {
    let d1 = [p[2][0] - p[0][0], p[2][1] - p[0][1], p[2][2] - p[0][2]];
    let d2 = [p[3][0] - p[1][0], p[3][1] - p[1][1], p[3][2] - p[1][2]];
    let c = [
        d1[1] * d2[2] - d1[2] * d2[1],
        d1[2] * d2[0] - d1[0] * d2[2],
        d1[0] * d2[1] - d1[1] * d2[0],
    ];
    0.5 * (c[0] * c[0] + c[1] * c[1] + c[2] * c[2]).sqrt()
}

/// Characteristic length V / A_max of an element.
pub fn characteristic_length(x: &[[f64; 3]; 8], volume: f64) -> f64 {
    let amax = HEX8_FACES
        .iter()
        .map(|f| face_area(f.map(|a| x[a])))
        .fold(0.0, f64::max);
    volume / amax
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::hex8_shape::{volume, NODE_XI};

    #[test]
    fn cube_length_is_side() {
        let x = NODE_XI.map(|p| p.map(|c| 0.75 * (c + 1.0)));
        assert!((characteristic_length(&x, volume(&x)) - 1.5).abs() < 1e-12);
    }
}
