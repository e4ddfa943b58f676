//! Energy accounting (VERIFICATION.md W12, docs/ARCHITECTURE.md "Energy accounting").
//! Energies are reported at the full steps tⁿ: kinetic ½ M |Vⁿ|² with
//! Vⁿ = ½(V^{n−½} + V^{n+½}), and the work of every force category by the trapezoidal rule
//! over each step, W(tⁿ) = ½ F⁰·ΔU^{−½} + Σ_{k=1..n} ½(F^{k−1} + F^k)·(U^k − U^{k−1}).
//!
//! The account starts from the state the scheme starts from: the initial velocities are
//! V^{−½} (`Simulation::new`), so the initial kinetic energy is K₀ = ½ M |V^{−½}|² — the
//! case's initial velocity field, before any force has acted — and the first force F⁰
//! works over the half step before t⁰ as well, ½ F⁰·Δt V^{−½}. With M(V^{n+½} − V^{n−½}) =
//! Δt Fⁿ (every force, the reactions at prescribed DOFs included) this gives the exact
//! identity ½ V^{n−½}·M V^{n+½} = K₀ + W(tⁿ), so the residual is
//!
//!   kinetic − K₀ − W(tⁿ) = ½ M|Vⁿ|² − ½ V^{n−½}·M V^{n+½} = (Δt²/8) Σ M |aⁿ|²,
//!   aⁿ = (V^{n+½} − V^{n−½})/Δt,
//!
//! O(Δt²) for smooth motion and free of any term of the first step: a prescribed velocity
//! that jumps from 0 to v at t = 0 (a belt started impulsively) has a reaction M v/Δt at
//! t⁰ whose work ½ (M v/Δt)·Δt (0 + v) = ½ M v² is exactly the kinetic energy it injects,
//! booked as `input`. (Starting the sums at t⁰ with K₀ = ½ M |V⁰|², the scheme's
//! velocity at t⁰, left (Δt²/8) M |a⁰|² = ¼ ½ M v² of such a jump as a constant residual.)
//! The trapezoidal sums are kept as two running half-sums, so no force of the previous
//! step has to be stored: ½ F^k·ΔU^{k−½} is added at step k and ½ F^k·ΔU^{k+½} once step k
//! is done.

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
    /// Work of the reactions at prescribed DOFs (input motion) and of the equivalent
    /// seismic forces of the boundaries (free-field tractions and sources).
    pub input: f64,
    /// Work absorbed by the absorbing boundaries' dashpots and springs.
    pub boundary: f64,
    /// Kinetic energy at the start, ½ M |V^{−½}|² of the initial velocities (the value of
    /// histories.csv's row at t = 0).
    pub initial_kinetic: f64,
    /// Running trapezoidal sums of the work categories up to the last completed
    /// interval (internal, damping, contact, external, input, boundary).
    #[serde(skip)]
    pub accumulated: [f64; N_WORK],
}

/// Number of work categories: internal, damping, contact, external, input, boundary.
pub const N_WORK: usize = 6;

impl Energies {
    /// Balance residual: kinetic + internal + damping + contact + boundary − external −
    /// input − initial.
    pub fn residual(&self) -> f64 {
        self.kinetic + self.internal + self.damping + self.contact + self.boundary
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
            self.boundary,
            self.initial_kinetic,
        ]
        .iter()
        .fold(0.0f64, |m, x| m.max(x.abs()))
    }

    /// Take the parts of step n: report the energies at tⁿ and advance the running sums.
    /// Contact work is stored with its sign flipped (energy absorbed by the interface).
    /// At n = 0 the running sums are zero, so ½ F⁰·ΔU^{−½} (the half step before t⁰) is
    /// booked: see the module documentation.
    pub(crate) fn advance(&mut self, parts: &EnergyParts) {
        let now: [f64; N_WORK] = std::array::from_fn(|k| self.accumulated[k] + parts[1 + k]);
        self.kinetic = parts[0];
        self.internal = now[0];
        self.damping = now[1];
        self.contact = -now[2];
        self.external = now[3];
        self.input = now[4];
        self.boundary = now[5];
        for k in 0..N_WORK {
            self.accumulated[k] = now[k] + parts[1 + N_WORK + k];
        }
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

/// Per-node sums gathered in one pass: kinetic at tⁿ, then for internal, damping, contact,
/// external, input and boundary work ½ Fⁿ·Δt V^{n−½} (indices 1–6) and ½ Fⁿ·Δt V^{n+½}
/// (7–12). The force of each category is the one that does positive work when energy
/// enters that account: the force on the body for contact, external and input, the force
/// of the body on the element / damper / boundary for internal, damping and boundary.
pub(crate) type EnergyParts = [f64; 1 + 2 * N_WORK];
