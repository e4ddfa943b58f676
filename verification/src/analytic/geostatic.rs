//! Geostatic states of a laterally confined (uniaxial-strain) column: self weight, and a
//! surcharge placed on top (Timoshenko & Goodier 1970, §1; the uniaxial-strain modulus
//! M = λ + 2μ = E(1−ν)/((1+ν)(1−2ν))).
//!
//! ```text
//!   σ_zz(z) = −ρ g (H − z)                       (vertical equilibrium, tension positive)
//!   u_z(z)  = −(ρ g / M)(H z − z²/2)             (base z = 0 fixed, top z = H free)
//!   surcharge s on top: σ_zz = −s, u_z(z) = −(s/M) z
//! ```

/// A laterally confined elastic column of height H on a fixed base.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ConfinedColumn {
    pub height: f64,
    pub density: f64,
    pub gravity: f64,
    /// Uniaxial-strain modulus M = λ + 2μ (Pa).
    pub modulus: f64,
}

impl ConfinedColumn {
    /// Validated constructor (all > 0, ν in (−1, 0.5)).
    pub fn new(
        height: f64,
        density: f64,
        gravity: f64,
        young: f64,
        poisson: f64,
    ) -> Result<Self, String> {
        for (n, x) in [
            ("height", height),
            ("density", density),
            ("gravity", gravity),
            ("young", young),
        ] {
            if !(x.is_finite() && x > 0.0) {
                return Err(format!("{n} = {x}: must be finite and > 0"));
            }
        }
        if !(poisson > -1.0 && poisson < 0.5) {
            return Err(format!("poisson = {poisson}: must be in (-1, 0.5)"));
        }
        let modulus = young * (1.0 - poisson) / ((1.0 + poisson) * (1.0 - 2.0 * poisson));
        Ok(Self {
            height,
            density,
            gravity,
            modulus,
        })
    }

    /// Vertical stress under self weight (Pa, tension positive).
    pub fn stress(&self, z: f64) -> f64 {
        -self.density * self.gravity * (self.height - z)
    }

    /// Vertical displacement under self weight (m).
    pub fn displacement(&self, z: f64) -> f64 {
        -(self.density * self.gravity / self.modulus) * (self.height * z - 0.5 * z * z)
    }

    /// Additional vertical displacement of a surcharge s (Pa, compression positive).
    pub fn surcharge_displacement(&self, s: f64, z: f64) -> f64 {
        -(s / self.modulus) * z
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn top_settlement_and_modulus() {
        let c = ConfinedColumn::new(100.0, 2700.0, 9.81, 20e9, 0.25).unwrap();
        assert!((c.modulus - 24e9).abs() < 1.0);
        let top = c.displacement(100.0);
        assert!((top + 2700.0 * 9.81 * 100.0 * 100.0 / (2.0 * 24e9)).abs() < 1e-15);
        assert_eq!(c.stress(100.0), 0.0);
    }
}
