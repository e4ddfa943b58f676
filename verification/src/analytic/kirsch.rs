//! Kirsch (1898): a circular opening of radius a in an infinite elastic plate under
//! plane strain with far-field vertical stress p and horizontal stress q = K0 p
//! (compression positive), the opening excavated in the pre-stressed plate
//! (docs/verification_references.md §W4; Jaeger, Cook & Zimmerman 2007, §8.4; Brady & Brown 2006, §7.2).
//!
//! With θ measured from the horizontal axis:
//!
//! ```text
//!   σ_θθ(r, θ) = (p+q)/2 (1 + a²/r²) + (p−q)/2 (1 + 3a⁴/r⁴) cos 2θ
//!   σ_rr(r, θ) = (p+q)/2 (1 − a²/r²) − (p−q)/2 (1 − 4a²/r² + 3a⁴/r⁴) cos 2θ
//!   wall: σ_θθ(a, θ) = (p+q) + 2(p−q) cos 2θ   (sidewall θ = 0: 3p − q; crown θ = 90°: 3q − p)
//!   excavation-induced inward wall displacement, θ_p from the p (vertical) axis:
//!   u_r = a/(4G) [(p+q) + (p−q)(3 − 4ν) cos 2θ_p]
//! ```

/// The Kirsch problem of one parameter set.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Kirsch {
    /// Opening radius a (m).
    pub radius: f64,
    /// Vertical far-field stress p (Pa, compression positive).
    pub p: f64,
    /// Horizontal far-field stress q = K0 p (Pa, compression positive).
    pub q: f64,
    /// Shear modulus G (Pa).
    pub shear_modulus: f64,
    /// Poisson's ratio ν.
    pub poisson: f64,
}

impl Kirsch {
    /// Validated constructor: a, p, G > 0, K0 ≥ 0, −1 < ν < 0.5.
    pub fn new(
        radius: f64,
        p: f64,
        k0: f64,
        shear_modulus: f64,
        poisson: f64,
    ) -> Result<Self, String> {
        for (n, x) in [
            ("radius", radius),
            ("p", p),
            ("shear_modulus", shear_modulus),
        ] {
            if !(x.is_finite() && x > 0.0) {
                return Err(format!("{n} = {x}: must be finite and > 0"));
            }
        }
        if !(k0.is_finite() && k0 >= 0.0) {
            return Err(format!("k0 = {k0}: must be finite and ≥ 0"));
        }
        if !(poisson > -1.0 && poisson < 0.5) {
            return Err(format!("poisson = {poisson}: must be in (-1, 0.5)"));
        }
        Ok(Self {
            radius,
            p,
            q: k0 * p,
            shear_modulus,
            poisson,
        })
    }

    /// Hoop stress (compression positive) at radius r ≥ a and angle θ from the horizontal.
    pub fn hoop_stress(&self, r: f64, theta: f64) -> f64 {
        let s = (self.radius / r).powi(2);
        0.5 * (self.p + self.q) * (1.0 + s)
            + 0.5 * (self.p - self.q) * (1.0 + 3.0 * s * s) * (2.0 * theta).cos()
    }

    /// Radial stress (compression positive) at radius r ≥ a and angle θ from the horizontal.
    pub fn radial_stress(&self, r: f64, theta: f64) -> f64 {
        let s = (self.radius / r).powi(2);
        0.5 * (self.p + self.q) * (1.0 - s)
            - 0.5 * (self.p - self.q) * (1.0 - 4.0 * s + 3.0 * s * s) * (2.0 * theta).cos()
    }

    /// Hoop stress at the sidewall (θ = 0): 3p − q.
    pub fn sidewall_hoop_stress(&self) -> f64 {
        self.hoop_stress(self.radius, 0.0)
    }

    /// Hoop stress at the crown (θ = 90°): 3q − p.
    pub fn crown_hoop_stress(&self) -> f64 {
        self.hoop_stress(self.radius, std::f64::consts::FRAC_PI_2)
    }

    /// Excavation-induced inward radial displacement of the wall at θ_p from the vertical.
    pub fn wall_displacement(&self, theta_p: f64) -> f64 {
        self.radius / (4.0 * self.shear_modulus)
            * ((self.p + self.q)
                + (self.p - self.q) * (3.0 - 4.0 * self.poisson) * (2.0 * theta_p).cos())
    }

    /// At the sidewall (θ_p = 90°).
    pub fn sidewall_displacement(&self) -> f64 {
        self.wall_displacement(std::f64::consts::FRAC_PI_2)
    }

    /// At the crown (θ_p = 0).
    pub fn crown_displacement(&self) -> f64 {
        self.wall_displacement(0.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// docs/verification_references.md §W4 table (p = 10 MPa, a = 10 m, G = 8 GPa, ν = 0.25).
    #[test]
    fn w4_table() {
        for (k0, side, crown, us, uc) in [
            (0.5, 25e6, 5e6, 1.5625e-3, 7.8125e-3),
            (1.0, 20e6, 20e6, 6.25e-3, 6.25e-3),
            (1.5, 15e6, 35e6, 10.9375e-3, 4.6875e-3),
        ] {
            let k = Kirsch::new(10.0, 10e6, k0, 8e9, 0.25).unwrap();
            assert!((k.sidewall_hoop_stress() - side).abs() < 1e-6);
            assert!((k.crown_hoop_stress() - crown).abs() < 1e-6);
            assert!((k.sidewall_displacement() - us).abs() < 1e-12);
            assert!((k.crown_displacement() - uc).abs() < 1e-12);
            // The free wall; far away the hoop direction at θ = 0 is vertical (σ = p), at
            // θ = 90° horizontal (σ = q).
            assert!((k.radial_stress(10.0, 0.3)).abs() < 1e-6);
            assert!((k.hoop_stress(1e6, 0.0) - 10e6).abs() < 1.0);
            let half_pi = std::f64::consts::FRAC_PI_2;
            assert!((k.hoop_stress(1e6, half_pi) - 10e6 * k0).abs() < 1.0);
            assert!((k.radial_stress(1e6, half_pi) - 10e6).abs() < 1.0);
        }
    }
}
