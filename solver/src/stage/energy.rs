//! Energy accounting (VERIFICATION.md W12): every force category's work is accumulated
//! with the midpoint rule of the leapfrog scheme, ΔW = F(tⁿ) · Δt Vⁿ with
//! Vⁿ = ½(V^{n−½} + V^{n+½}), which is the rule under which the scheme's momentum update
//! is exact, so the balance residual measures only what the method itself loses.

use serde::Serialize;

/// Energies at time tⁿ (J).
#[derive(Clone, Copy, Debug, Default, PartialEq, Serialize)]
pub struct Energies {
    /// ½ Σ M |Vⁿ|².
    pub kinetic: f64,
    /// Work done on the body by its internal forces (stored + dissipated in the material).
    pub internal: f64,
    /// Work absorbed by Rayleigh damping.
    pub damping: f64,
    /// Work absorbed by the contact forces (friction, debonding); ≥ 0 for a dissipative interface.
    pub contact: f64,
    /// Work of external loads (nodal loads, gravity).
    pub external: f64,
    /// Work of the reactions at prescribed DOFs (input motion).
    pub input: f64,
    /// Kinetic energy at the start.
    pub initial_kinetic: f64,
}

impl Energies {
    /// Balance residual: kinetic + internal + damping + contact − external − input − initial.
    pub fn residual(&self) -> f64 {
        self.kinetic + self.internal + self.damping + self.contact
            - self.external
            - self.input
            - self.initial_kinetic
    }

    /// The largest magnitude among the terms (scale for the relative residual).
    pub fn scale(&self) -> f64 {
        [
            self.kinetic,
            self.internal,
            self.damping,
            self.contact,
            self.external,
            self.input,
            self.initial_kinetic,
        ]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
    }

    /// |residual| / scale (0 when everything is zero).
    pub fn relative_residual(&self) -> f64 {
        let s = self.scale();
        if s > 0.0 {
            self.residual().abs() / s
        } else {
            0.0
        }
    }
}

/// Per-node increments gathered in one pass: [kinetic, internal, damping, contact,
/// external, input].
pub(crate) type EnergyParts = [f64; 6];
