//! d'Alembert solution of a half-sine velocity pulse entering a 1D elastic column
//! (docs/verification_references.md §W1): v_base(t) = v0 sin(πt/T) for 0 ≤ t ≤ T.

/// Shape of the base velocity pulse.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum PulseShape {
    /// v0 sin(πs/T): the W1 pulse (velocity has corners at s = 0 and T).
    #[default]
    HalfSine,
    /// v0 sin²(πs/T): a smooth (Hann) pulse for convergence-rate studies.
    SineSquared,
}

/// Incident pulse in a column of wave speed `c` and impedance ρc.
#[derive(Clone, Copy, Debug)]
pub struct HalfSinePulse1D {
    pub v0: f64,
    pub period: f64,
    pub speed: f64,
    pub density: f64,
    pub shape: PulseShape,
}

impl HalfSinePulse1D {
    /// Validated constructor: all parameters finite and > 0.
    pub fn new(v0: f64, period: f64, speed: f64, density: f64) -> Result<Self, String> {
        for (n, x) in [
            ("v0", v0),
            ("period", period),
            ("speed", speed),
            ("density", density),
        ] {
            if !(x.is_finite() && x > 0.0) {
                return Err(format!("{n} = {x}: must be finite and > 0"));
            }
        }
        Ok(Self {
            v0,
            period,
            speed,
            density,
            shape: PulseShape::HalfSine,
        })
    }

    /// The same pulse with another shape.
    pub fn with_shape(mut self, shape: PulseShape) -> Self {
        self.shape = shape;
        self
    }

    /// Incident particle velocity at height z and time t (before any reflection).
    pub fn velocity(&self, z: f64, t: f64) -> f64 {
        let s = t - z / self.speed;
        if (0.0..=self.period).contains(&s) {
            let v = (std::f64::consts::PI * s / self.period).sin();
            match self.shape {
                PulseShape::HalfSine => self.v0 * v,
                PulseShape::SineSquared => self.v0 * v * v,
            }
        } else {
            0.0
        }
    }

    /// Incident displacement at height z and time t: ∫ v dt.
    pub fn displacement(&self, z: f64, t: f64) -> f64 {
        use std::f64::consts::PI;
        let s = (t - z / self.speed).clamp(0.0, self.period);
        match self.shape {
            PulseShape::HalfSine => {
                self.v0 * self.period / PI * (1.0 - (PI * s / self.period).cos())
            }
            PulseShape::SineSquared => {
                self.v0 * (0.5 * s - self.period / (4.0 * PI) * (2.0 * PI * s / self.period).sin())
            }
        }
    }

    /// Peak stress magnitude of the incident wave, ρ c v0.
    pub fn peak_stress(&self) -> f64 {
        self.density * self.speed * self.v0
    }

    /// Net displacement after the pulse has passed: 2 v0 T / π (half sine), v0 T / 2 (sin²).
    pub fn net_displacement(&self) -> f64 {
        match self.shape {
            PulseShape::HalfSine => 2.0 * self.v0 * self.period / std::f64::consts::PI,
            PulseShape::SineSquared => 0.5 * self.v0 * self.period,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verification_md_numbers() {
        // W1: E 20 GPa, ν 0.25, ρ 2700 → c_p 2981.42, σ = 0.8050 MPa; c_s 1721.33 → 0.4648 MPa.
        let p = HalfSinePulse1D::new(0.1, 0.02, 2981.42, 2700.0).unwrap();
        assert!((p.peak_stress() / 1e6 - 0.8050).abs() < 5e-5);
        assert!((p.net_displacement() * 1e3 - 1.2732).abs() < 5e-5);
        let s = HalfSinePulse1D::new(0.1, 0.02, 1721.33, 2700.0).unwrap();
        assert!((s.peak_stress() / 1e6 - 0.4648).abs() < 5e-5);
        assert!(HalfSinePulse1D::new(0.1, -1.0, 1.0, 1.0).is_err());
    }
}
