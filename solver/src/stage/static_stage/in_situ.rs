//! A given in-situ stress field: σ_v(z) and K0(z) at the integration points, set as an
//! initial strain ε₀ = E₀⁻¹ : σ₀ of every active element, so that the material update sees
//! ε(u) + ε₀ (elastic: σ = E(ε + ε₀); plastic-damage: σ̄ = E₀ : (ε + ε₀ − εᵖ), which yields
//! with the in-situ confinement).
//!
//! σ₀ = −[K0_x σ_v, K0_y σ_v, σ_v, 0, 0, 0] (tension positive; σ_v ≥ 0 in compression):
//! principal axes vertical and along x, y.

use super::plan::{StressProfile, TablePoint};
use crate::error::{DcfmError, Result};
use crate::material::Voigt;
use crate::model::Model;

impl StressProfile {
    /// Vertical stress σ_v (compression positive) and (K0_x, K0_y) at height z, for a
    /// point in a material of unit weight `gamma_material` (ρ|g|).
    pub fn vertical(&self, z: f64, gamma_material: f64) -> (f64, [f64; 2]) {
        match self {
            StressProfile::Layers {
                ground_surface,
                surface_pressure,
                layers,
            } => {
                let mut top = *ground_surface;
                let mut s = *surface_pressure;
                for (k, l) in layers.iter().enumerate() {
                    let gamma = l.unit_weight.unwrap_or(gamma_material);
                    let last = k + 1 == layers.len();
                    if z >= l.bottom || last {
                        s += gamma * (top - z).max(0.0);
                        return (s, l.k0);
                    }
                    s += gamma * (top - l.bottom);
                    top = l.bottom;
                }
                (s, [1.0, 1.0])
            }
            StressProfile::Table { points } => table_at(points, z),
        }
    }

    /// σ₀ at height z (tension positive).
    pub fn stress(&self, z: f64, gamma_material: f64) -> Voigt {
        let (sv, k0) = self.vertical(z, gamma_material);
        [-k0[0] * sv, -k0[1] * sv, -sv, 0.0, 0.0, 0.0]
    }
}

/// Linear interpolation in a table sorted by descending z, constant outside.
fn table_at(points: &[TablePoint], z: f64) -> (f64, [f64; 2]) {
    let first = points[0];
    let last = points[points.len() - 1];
    if z >= first.z {
        return (first.sigma_v, first.k0);
    }
    if z <= last.z {
        return (last.sigma_v, last.k0);
    }
    for w in points.windows(2) {
        let (a, b) = (w[0], w[1]);
        if z <= a.z && z >= b.z {
            let t = if a.z > b.z {
                (a.z - z) / (a.z - b.z)
            } else {
                0.0
            };
            let lerp = |x: f64, y: f64| x + t * (y - x);
            return (
                lerp(a.sigma_v, b.sigma_v),
                [lerp(a.k0[0], b.k0[0]), lerp(a.k0[1], b.k0[1])],
            );
        }
    }
    (last.sigma_v, last.k0)
}

/// Set the profile's stress as the initial stress of every active element of the model;
/// `g` is |g| (m/s²) for layers without a unit weight. Errors if a layer needs ρ|g| and
/// the model has no gravity.
pub fn set_field(model: &mut Model, profile: &StressProfile, g: f64) -> Result<()> {
    if let StressProfile::Layers { layers, .. } = profile {
        if g <= 0.0 && layers.iter().any(|l| l.unit_weight.is_none()) {
            return Err(DcfmError::invalid(
                "",
                "static.in_situ.unit_weight",
                "missing",
                "a unit weight (N/m³) for every layer, or [loads.gravity] to take ρ|g| of the materials",
            ));
        }
    }
    let mesh = &model.mesh;
    for grp in model.groups.iter_mut() {
        let gamma = grp.material.density() * g;
        grp.set_initial_stress(mesh, |x| profile.stress(x[2], gamma));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::super::plan::Layer;
    use super::*;

    #[test]
    fn layers_accumulate_from_the_surface() {
        let p = StressProfile::Layers {
            ground_surface: 100.0,
            surface_pressure: 1e5,
            layers: vec![
                Layer {
                    bottom: 80.0,
                    unit_weight: Some(20e3),
                    k0: [0.5, 0.6],
                },
                Layer {
                    bottom: f64::NEG_INFINITY,
                    unit_weight: None,
                    k0: [1.2, 1.2],
                },
            ],
        };
        let (s, k) = p.vertical(90.0, 27e3);
        assert!((s - (1e5 + 20e3 * 10.0)).abs() < 1e-6 && k == [0.5, 0.6]);
        let (s, k) = p.vertical(50.0, 27e3);
        assert!((s - (1e5 + 20e3 * 20.0 + 27e3 * 30.0)).abs() < 1e-6 && k == [1.2, 1.2]);
        let st = p.stress(50.0, 27e3);
        assert_eq!(st[2], -s);
        assert_eq!(st[0], -1.2 * s);
        // Above the ground surface: the surface pressure.
        assert_eq!(p.vertical(120.0, 27e3).0, 1e5);
    }

    #[test]
    fn table_interpolates_and_clamps() {
        let p = StressProfile::Table {
            points: vec![
                TablePoint {
                    z: 10.0,
                    sigma_v: 0.0,
                    k0: [1.0, 1.0],
                },
                TablePoint {
                    z: 0.0,
                    sigma_v: 2e5,
                    k0: [0.5, 0.7],
                },
            ],
        };
        let (s, k) = p.vertical(2.5, 0.0);
        assert!((s - 1.5e5).abs() < 1e-9);
        assert!((k[0] - 0.625).abs() < 1e-12 && (k[1] - 0.775).abs() < 1e-12);
        assert_eq!(p.vertical(-5.0, 0.0).0, 2e5);
        assert_eq!(p.vertical(50.0, 0.0).0, 0.0);
    }
}
