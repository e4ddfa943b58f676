//! Fully integrated hex8: 2×2×2 Gauss points, B matrices precomputed per point.

use crate::element::hex8_shape::{cartesian_derivatives, gauss_points};
use crate::material::{Material, PointContext, Voigt};

/// Precomputed geometry of one fully integrated element (1600 bytes): ∂N_a/∂x_i and
/// w·det J at each Gauss point.
#[derive(Clone, Copy, Debug)]
pub struct FullGeometry {
    pub d: [[[f64; 3]; 8]; 8],
    pub wdet: [f64; 8],
}

impl FullGeometry {
    /// Geometry from nodal coordinates; `None` if det J ≤ 0 at a Gauss point.
    pub fn new(x: &[[f64; 3]; 8]) -> Option<Self> {
        let mut d = [[[0.0; 3]; 8]; 8];
        let mut wdet = [0.0; 8];
        for (g, p) in gauss_points().iter().enumerate() {
            let (dg, det) = cartesian_derivatives(x, p)?;
            d[g] = dg;
            wdet[g] = det;
        }
        Some(Self { d, wdet })
    }

    /// Element volume.
    pub fn volume(&self) -> f64 {
        self.wdet.iter().sum()
    }

    /// Strain at Gauss point `g`.
    #[inline(always)]
    pub fn strain(&self, g: usize, u: &[[f64; 3]; 8]) -> Voigt {
        let b = &self.d[g];
        let mut e = [0.0; 6];
        for a in 0..8 {
            let (bx, by, bz) = (b[a][0], b[a][1], b[a][2]);
            let (ux, uy, uz) = (u[a][0], u[a][1], u[a][2]);
            e[0] += bx * ux;
            e[1] += by * uy;
            e[2] += bz * uz;
            e[3] += by * ux + bx * uy;
            e[4] += bz * uy + by * uz;
            e[5] += bx * uz + bz * ux;
        }
        e
    }

    /// f_a += w det J · B_aᵀ σ at Gauss point `g`.
    #[inline(always)]
    pub fn add_forces(&self, g: usize, s: &Voigt, f: &mut [[f64; 3]; 8]) {
        let b = &self.d[g];
        let w = self.wdet[g];
        for a in 0..8 {
            let (bx, by, bz) = (b[a][0] * w, b[a][1] * w, b[a][2] * w);
            f[a][0] += bx * s[0] + by * s[3] + bz * s[5];
            f[a][1] += bx * s[3] + by * s[1] + bz * s[4];
            f[a][2] += bx * s[5] + by * s[4] + bz * s[2];
        }
    }
}

/// Internal force of one fully integrated element; the material state of Gauss point g is
/// `old[g*stride..]` → `new[g*stride..]`. Returns the volume-averaged stress.
#[inline(always)]
pub fn internal_force(
    geo: &FullGeometry,
    material: &Material,
    u: &[[f64; 3]; 8],
    old: &[f64],
    new: &mut [f64],
    ctx: &PointContext,
    f: &mut [[f64; 3]; 8],
) -> Voigt {
    let stride = material.state_len();
    *f = [[0.0; 3]; 8];
    let mut mean = [0.0; 6];
    for g in 0..8 {
        let eps = geo.strain(g, u);
        let range = g * stride..(g + 1) * stride;
        let sigma = material.update(&eps, &old[range.clone()], &mut new[range], ctx);
        geo.add_forces(g, &sigma, f);
        for i in 0..6 {
            mean[i] += sigma[i] * geo.wdet[g];
        }
    }
    let vol = geo.volume();
    mean.map(|m| m / vol)
}
