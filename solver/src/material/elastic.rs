//! Isotropic linear elasticity, σ = λ tr(ε) I + 2 μ ε (Voigt, engineering shear).

use crate::error::{DcfmError, Result};
use crate::material::Voigt;

/// Isotropic elastic constants and density.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Elastic {
    /// Young's modulus E (Pa).
    pub young: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
    /// Density ρ (kg/m³).
    pub density: f64,
    /// Lamé's first parameter λ (Pa).
    pub lambda: f64,
    /// Shear modulus μ = G (Pa).
    pub mu: f64,
}

impl Elastic {
    /// Validated constructor: E > 0, −1 < ν < 0.5, ρ > 0. `name` is the material's name
    /// for the error message.
    pub fn new(name: &str, young: f64, poisson: f64, density: f64) -> Result<Self> {
        let bad = |msg: String| DcfmError::Material {
            material: name.to_string(),
            message: msg,
        };
        if !(young.is_finite() && young > 0.0) {
            return Err(bad(format!(
                "young = {young}: must be a finite value > 0 (Pa)"
            )));
        }
        if !(poisson.is_finite() && poisson > -1.0 && poisson < 0.5) {
            return Err(bad(format!("poisson = {poisson}: must be in (-1, 0.5)")));
        }
        if !(density.is_finite() && density > 0.0) {
            return Err(bad(format!(
                "density = {density}: must be a finite value > 0 (kg/m³)"
            )));
        }
        let mu = young / (2.0 * (1.0 + poisson));
        let lambda = young * poisson / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
        Ok(Self {
            young,
            poisson,
            density,
            lambda,
            mu,
        })
    }

    /// P-wave modulus λ + 2μ (Pa).
    #[inline]
    pub fn p_modulus(&self) -> f64 {
        self.lambda + 2.0 * self.mu
    }

    /// Bulk modulus K = λ + 2μ/3 (Pa).
    #[inline]
    pub fn bulk(&self) -> f64 {
        self.lambda + 2.0 * self.mu / 3.0
    }

    /// Dilatational wave speed c_p = √((λ+2μ)/ρ) (m/s).
    #[inline]
    pub fn p_wave_speed(&self) -> f64 {
        (self.p_modulus() / self.density).sqrt()
    }

    /// Shear wave speed c_s = √(μ/ρ) (m/s).
    #[inline]
    pub fn s_wave_speed(&self) -> f64 {
        (self.mu / self.density).sqrt()
    }

    /// σ = E0 : ε in Voigt form (shear strains engineering, so τ = μ γ).
    #[inline(always)]
    pub fn stress(&self, e: &Voigt) -> Voigt {
        crate::element::lanes::elastic_stress_in(pulp::Scalar::new(), self.lambda, self.mu, e)
    }

    /// ε = E0⁻¹ : σ (engineering shear).
    pub fn strain(&self, s: &Voigt) -> Voigt {
        let e = self.young;
        let nu = self.poisson;
        let tr = s[0] + s[1] + s[2];
        [
            ((1.0 + nu) * s[0] - nu * tr) / e,
            ((1.0 + nu) * s[1] - nu * tr) / e,
            ((1.0 + nu) * s[2] - nu * tr) / e,
            s[3] / self.mu,
            s[4] / self.mu,
            s[5] / self.mu,
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wave_speeds_match_verification_default_rock() {
        // ../shared/VERIFICATION.md: E 20 GPa, ν 0.25, ρ 2700 → c_p 2981.42, c_s 1721.33 m/s.
        let m = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
        assert!((m.p_wave_speed() - 2981.42).abs() < 0.01);
        assert!((m.s_wave_speed() - 1721.33).abs() < 0.01);
    }

    #[test]
    fn strain_inverts_stress() {
        let m = Elastic::new("c", 25e9, 0.17, 2400.0).unwrap();
        let e = [1e-4, -2e-5, 3e-5, 4e-5, -1e-5, 2e-5];
        let back = m.strain(&m.stress(&e));
        for i in 0..6 {
            assert!((back[i] - e[i]).abs() < 1e-18);
        }
    }

    #[test]
    fn rejects_bad_poisson() {
        let err = Elastic::new("rock", 1e9, 0.7, 2000.0)
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("rock") && err.contains("poisson = 0.7"),
            "{err}"
        );
    }
}
