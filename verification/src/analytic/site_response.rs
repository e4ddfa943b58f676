//! One soil layer on an elastic half-space under vertically incident SH waves (Kramer
//! 1996, Geotechnical Earthquake Engineering, §7.2.1): the transfer function from the
//! rock-outcrop motion (twice the incident wave) to the ground surface
//!
//! ```text
//! |H(f)| = 1 / |cos(k* H) + i α* sin(k* H)|,   k* = ω / V_s*,   α* = ρ_s V_s* / (ρ_r V_r)
//! ```
//!
//! with the complex shear-wave speed of the damped soil: V_s* = V_s √(1 + 2iξ) for
//! hysteretic damping ξ (Kramer's form), or V_s* = V_s √((1 + iωβ)/(1 − iα_R/ω)) for
//! Rayleigh damping C = α_R M + β K (G* = G(1 + iωβ), ρ* = ρ(1 − iα_R/ω)). The rock is
//! undamped. Surface / incident motion = 2|H|.

/// A complex number (just what the formula needs).
#[derive(Clone, Copy, Debug, PartialEq)]
struct C(f64, f64);

impl C {
    fn add(self, o: C) -> C {
        C(self.0 + o.0, self.1 + o.1)
    }
    fn mul(self, o: C) -> C {
        C(self.0 * o.0 - self.1 * o.1, self.0 * o.1 + self.1 * o.0)
    }
    fn div(self, o: C) -> C {
        let d = o.0 * o.0 + o.1 * o.1;
        C(
            (self.0 * o.0 + self.1 * o.1) / d,
            (self.1 * o.0 - self.0 * o.1) / d,
        )
    }
    fn sqrt(self) -> C {
        let r = (self.0 * self.0 + self.1 * self.1).sqrt();
        let re = ((r + self.0) / 2.0).sqrt();
        let im = ((r - self.0) / 2.0).sqrt().copysign(self.1);
        C(re, im)
    }
    /// cos and sin of a complex argument.
    fn cos_sin(self) -> (C, C) {
        let (a, b) = (self.0, self.1);
        (
            C(a.cos() * b.cosh(), -a.sin() * b.sinh()),
            C(a.sin() * b.cosh(), a.cos() * b.sinh()),
        )
    }
    fn abs(self) -> f64 {
        (self.0 * self.0 + self.1 * self.1).sqrt()
    }
}

/// Damping of the soil.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum SoilDamping {
    None,
    /// Frequency-independent (hysteretic) ratio ξ.
    Hysteretic(f64),
    /// Rayleigh α (1/s) and β (s).
    Rayleigh(f64, f64),
}

/// The layer-on-half-space system.
#[derive(Clone, Copy, Debug)]
pub struct LayerOnHalfSpace {
    /// Soil shear-wave speed (m/s), density (kg/m³), thickness (m).
    pub vs: f64,
    pub rho_s: f64,
    pub thickness: f64,
    /// Rock shear-wave speed (m/s) and density (kg/m³).
    pub vr: f64,
    pub rho_r: f64,
    pub damping: SoilDamping,
}

impl LayerOnHalfSpace {
    /// docs/verification_references.md §W3: V_s 300 m/s, H 30 m, ρ_s 2000 kg/m³ over V_r 1500 m/s,
    /// ρ_r 2500 kg/m³ (impedance ratio 0.16).
    pub fn w3(damping: SoilDamping) -> Self {
        Self {
            vs: 300.0,
            rho_s: 2000.0,
            thickness: 30.0,
            vr: 1500.0,
            rho_r: 2500.0,
            damping,
        }
    }

    /// |H(f)|: surface motion over rock-outcrop motion (surface over incident is 2|H|).
    pub fn transfer(&self, f: f64) -> f64 {
        let w = 2.0 * std::f64::consts::PI * f;
        let vs = match self.damping {
            SoilDamping::None => C(self.vs, 0.0),
            SoilDamping::Hysteretic(xi) => C(self.vs, 0.0).mul(C(1.0, 2.0 * xi).sqrt()),
            SoilDamping::Rayleigh(a, b) => {
                C(self.vs, 0.0).mul(C(1.0, w * b).div(C(1.0, -a / w)).sqrt())
            }
        };
        // ρ* V_s* of the soil: with mass-proportional damping ρ* = ρ (1 − iα/ω).
        let rho = match self.damping {
            SoilDamping::Rayleigh(a, _) => C(self.rho_s, 0.0).mul(C(1.0, -a / w)),
            _ => C(self.rho_s, 0.0),
        };
        let alpha = rho.mul(vs).div(C(self.rho_r * self.vr, 0.0));
        let kh = C(w * self.thickness, 0.0).div(vs);
        let (c, s) = kh.cos_sin();
        let d = c.add(C(0.0, 1.0).mul(alpha).mul(s));
        1.0 / d.abs()
    }

    /// Undamped resonances f_n = (2n − 1) V_s / (4H).
    pub fn resonance(&self, n: usize) -> f64 {
        (2 * n - 1) as f64 * self.vs / (4.0 * self.thickness)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn reproduces_the_w3_numbers() {
        let undamped = LayerOnHalfSpace::w3(SoilDamping::None);
        for (f, h) in [
            (2.5, 6.25),
            (7.5, 6.25),
            (5.0, 1.0),
            (0.5, 1.050),
            (1.0, 1.228),
            (2.0, 2.903),
            (3.0, 2.903),
        ] {
            assert!(
                (undamped.transfer(f) - h).abs() < 1.5e-3,
                "{f} Hz: {}",
                undamped.transfer(f)
            );
        }
        let damped = LayerOnHalfSpace::w3(SoilDamping::Hysteretic(0.05));
        for (n, peak) in [(1, 4.195), (2, 2.495), (3, 1.745)] {
            let f0 = damped.resonance(n);
            let best = (0..2000)
                .map(|k| damped.transfer(f0 * (0.9 + 0.2 * k as f64 / 2000.0)))
                .fold(0.0, f64::max);
            assert!((best - peak).abs() < 2e-3, "mode {n}: {best}");
        }
    }
}
