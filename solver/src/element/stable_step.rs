//! Critical time step of the explicit scheme. Each element gets the smaller of
//! L_e / c_p (L_e = V / A_max, volume over the largest face area; Belytschko, Liu & Moran
//! 2000, §6.2) and 2/ω_max,e from its own eigenvalue problem (a bound no mesh can break,
//! see [`element_max_eigenvalue`]); the global step is the minimum over the elements times
//! a safety factor. For a cube the eigenvalue bound governs: 0.775 h/c_p (W13).

use crate::element::lanes::{run_lane_work, LaneWork, Simd};
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

/// Largest eigenvalue ω²_max of M_e⁻¹ K_e of one free element (lumped mass, initial
/// elastic stiffness, hourglass stiffness included), by power iteration on the element's
/// own force kernel. By the Irons–Treharne bound (Irons 1970; Belytschko, Liu & Moran
/// 2000, §6.2.3) the global ω_max never exceeds the largest element ω_max, so
/// Δt_e = 2/ω_max,e is a step that no mesh containing the element can make unstable —
/// unlike L/c_p, which a single free element (or a thin body held by contact) violates:
/// its bound is 0.775 h/c_p for a cube (VERIFICATION.md W13).
///
/// Run under the lanes' dispatch ([`run_lane_work`]) so that the element kernels' fused
/// multiply-adds compile to the CPU's FMA instructions instead of calls of the C library's
/// `fma` (the same bits either way).
pub fn element_max_eigenvalue(
    x: &[[f64; 3]; 8],
    material: &crate::material::Material,
    integration: crate::element::Integration,
    hourglass: f64,
) -> Option<f64> {
    run_lane_work(MaxEigenvalue {
        x,
        material,
        integration,
        hourglass,
    })
}

/// [`element_max_eigenvalue`]'s arguments, as the work its dispatch runs.
struct MaxEigenvalue<'a> {
    x: &'a [[f64; 3]; 8],
    material: &'a crate::material::Material,
    integration: crate::element::Integration,
    hourglass: f64,
}

impl LaneWork for MaxEigenvalue<'_> {
    type Output = Option<f64>;
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) -> Option<f64> {
        power_iteration(self.x, self.material, self.integration, self.hourglass)
    }
}

/// The power iteration of [`element_max_eigenvalue`].
#[inline(always)]
fn power_iteration(
    x: &[[f64; 3]; 8],
    material: &crate::material::Material,
    integration: crate::element::Integration,
    hourglass: f64,
) -> Option<f64> {
    use crate::element::{hex8_full, hex8_uniform, lumped_mass::element_masses, Integration};
    use crate::material::{Material, PointContext};
    let elastic = Material::Elastic(*material.elastic());
    let masses = element_masses(x, material.density());
    let ctx = PointContext {
        char_length: 1.0,
        dt: 0.0,
        reads_damage: false,
    };
    let uniform = hex8_uniform::UniformGeometry::new(x, material.elastic(), hourglass);
    let full = hex8_full::FullGeometry::new(x);
    let apply = |u: &[[f64; 3]; 8], f: &mut [[f64; 3]; 8]| match integration {
        Integration::OnePoint => {
            if let Some(g) = &uniform {
                hex8_uniform::internal_force(g, &elastic, u, &[], &mut [], &ctx, f);
            }
        }
        Integration::Full => {
            if let Some(g) = &full {
                hex8_full::internal_force(g, &elastic, u, &[], &mut [], &ctx, f);
            }
        }
    };
    let valid = match integration {
        Integration::OnePoint => uniform.is_some(),
        Integration::Full => full.is_some(),
    };
    if !valid {
        return None;
    }
    // Symmetric form S = M^{-1/2} K M^{-1/2}; start from a vector with every component.
    let sq: [f64; 8] = masses.map(f64::sqrt);
    let mut y = [[0.0; 3]; 8];
    for a in 0..8 {
        for d in 0..3 {
            y[a][d] =
                1.0 + 0.37 * ((3 * a + d) as f64).sin() + if (a + d) % 2 == 0 { 1.0 } else { -1.0 };
        }
    }
    let mut lambda = 0.0;
    for _ in 0..200 {
        let norm = y.iter().flatten().map(|v| v * v).sum::<f64>().sqrt();
        if norm.is_nan() || norm <= 0.0 {
            return None;
        }
        let q: [[f64; 3]; 8] = std::array::from_fn(|a| std::array::from_fn(|d| y[a][d] / norm));
        let u: [[f64; 3]; 8] = std::array::from_fn(|a| std::array::from_fn(|d| q[a][d] / sq[a]));
        let mut f = [[0.0; 3]; 8];
        apply(&u, &mut f);
        let z: [[f64; 3]; 8] = std::array::from_fn(|a| std::array::from_fn(|d| f[a][d] / sq[a]));
        let next: f64 = (0..8)
            .map(|a| (0..3).map(|d| q[a][d] * z[a][d]).sum::<f64>())
            .sum();
        let converged = (next - lambda).abs() <= 1e-10 * next.abs();
        lambda = next;
        y = z;
        if converged {
            break;
        }
    }
    Some(lambda)
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
