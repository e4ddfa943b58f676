//! Constitutive models and their per-integration-point state.
//!
//! Every model maps a total small strain ε (Voigt xx, yy, zz, xy, yz, zx; engineering
//! shear strains; tension positive) and the point's state at the start of the step to the
//! stress and the state at the end of the step. The element kernels only see
//! [`Material::update`], so a new model plugs in without touching element code.
//!
//! State lives in [`PointStates`]: a fixed number of `f64` per integration point, in an
//! old and a new buffer swapped at the end of every step, or updated in place by the
//! explicit core.

pub mod elastic;
pub mod plastic_damage;
mod point_states;

use crate::element::lanes::{elastic_stress_lanes, Simd, VoigtLanes, LANES};
pub use elastic::Elastic;
pub use plastic_damage::PlasticDamage;
pub use point_states::{PointStates, StateAccess, MAX_ELEMENT_STATE};

/// Voigt 6-vector: xx, yy, zz, xy, yz, zx (engineering shear for strains).
pub type Voigt = [f64; 6];

/// Damage variables of one integration point (models without damage have none).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct DamageState {
    /// D of eq. (24).
    pub d: f64,
    /// Tensile damage D_t.
    pub dt: f64,
    /// Compressive damage D_c.
    pub dc: f64,
    /// Tensile and compressive hardening variables κ_t, κ_c.
    pub kappa_t: f64,
    pub kappa_c: f64,
    /// Plastic strain εᵖ (Voigt, engineering shear).
    pub plastic_strain: Voigt,
}

/// What a material update may need to know about the point besides its strain.
#[derive(Clone, Copy, Debug)]
pub struct PointContext {
    /// Characteristic length of the element (m), for fracture-energy regularisation.
    pub char_length: f64,
    /// Time step (s), for viscous regularisation.
    pub dt: f64,
    /// The element reads D of eq. (24) of the new state right after the update (the
    /// one-point element's hourglass factor, [`Material::stiffness_factor`]): a rule that
    /// would otherwise leave D to be formed on demand (the plastic-damage consistent
    /// recovery) stores it, from the effective stress the update has already classified.
    /// Never changes the stress or the state's other slots.
    pub reads_damage: bool,
}

/// A constitutive model, chosen per region. Enum dispatch keeps the element loop
/// monomorphic and inlinable.
#[derive(Clone, Debug)]
pub enum Material {
    /// Isotropic linear elasticity.
    Elastic(Elastic),
    /// Lee–Fenves plastic-damage (3D after Omidi & Lotfi), eqs. (23)–(26).
    PlasticDamage(Box<PlasticDamage>),
}

impl Material {
    /// Isotropic elastic constants behind the model (initial stiffness E0 for damage models).
    #[inline]
    pub fn elastic(&self) -> &Elastic {
        match self {
            Material::Elastic(e) => e,
            Material::PlasticDamage(p) => p.elastic(),
        }
    }

    /// Mass density (kg/m³).
    #[inline]
    pub fn density(&self) -> f64 {
        self.elastic().density
    }

    /// Number of `f64` state variables stored per integration point.
    #[inline]
    pub fn state_len(&self) -> usize {
        match self {
            Material::Elastic(_) => 0,
            Material::PlasticDamage(p) => p.state_len(),
        }
    }

    /// Write the virgin state of one point.
    pub fn init_state(&self, state: &mut [f64]) {
        match self {
            Material::Elastic(_) => {}
            Material::PlasticDamage(p) => p.init_state(state),
        }
    }

    /// Prime a virgin point state as if the point had been strained elastically to
    /// `strain` (an initial strain ε₀ set by the static stage): the next update starts its
    /// increment there. No effect on models that keep no strain.
    pub fn prime_strain(&self, state: &mut [f64], strain: &Voigt) {
        match self {
            Material::Elastic(_) => {}
            Material::PlasticDamage(p) => p.prime_strain(state, strain),
        }
    }

    /// Stress at the end of the step from the total strain, updating the point's state
    /// from `old` into `new` (both `state_len()` long).
    #[inline]
    pub fn update(
        &self,
        strain: &Voigt,
        old: &[f64],
        new: &mut [f64],
        ctx: &PointContext,
    ) -> Voigt {
        match self {
            Material::Elastic(e) => e.stress(strain),
            Material::PlasticDamage(p) => p.update(strain, old, new, ctx),
        }
    }

    /// [`Material::update`] with the state updated in place (the committed state on
    /// entry, the new one on return); second: whether the hardening moved
    /// ([`Material::hardening_moved`] of the old and the new state).
    #[inline(always)]
    pub fn update_in_place(
        &self,
        strain: &Voigt,
        state: &mut [f64],
        ctx: &PointContext,
    ) -> (Voigt, bool) {
        match self {
            Material::Elastic(e) => (e.stress(strain), false),
            Material::PlasticDamage(p) => p.update_in_place(strain, state, ctx),
        }
    }

    /// [`Material::update_in_place`] of the points of eight elements at once, element l at
    /// strain lane l with state `states[l]` and context `ctx[l]`: the stresses in lanes
    /// and whether each element's hardening moved, bit for bit those of eight calls of
    /// [`Material::update_in_place`] (the one-point elements in lanes,
    /// `element::hex8_uniform_lanes`).
    #[inline(always)]
    pub fn update_elements_in_place<S: Simd>(
        &self,
        simd: S,
        strain: &VoigtLanes,
        states: &mut [&mut [f64]; LANES],
        ctx: &[PointContext; LANES],
    ) -> (VoigtLanes, [bool; LANES]) {
        match self {
            Material::Elastic(e) => (
                elastic_stress_lanes(simd, e.lambda, e.mu, strain),
                [false; LANES],
            ),
            Material::PlasticDamage(p) => p.update_elements_in_place(simd, strain, states, ctx),
        }
    }

    /// Stress implied by a strain and an already-updated state (for output: no state change).
    pub fn stress_from_state(&self, strain: &Voigt, state: &[f64]) -> Voigt {
        match self {
            Material::Elastic(e) => e.stress(strain),
            Material::PlasticDamage(p) => p.stress_from_state(strain, state),
        }
    }

    /// The hardening variables (hence D_t, D_c) of a point differ between its states
    /// `old` and `new` (false for models without damage).
    #[inline]
    pub fn hardening_moved(&self, old: &[f64], new: &[f64]) -> bool {
        match self {
            Material::Elastic(_) => false,
            Material::PlasticDamage(p) => p.hardening_moved(old, new),
        }
    }

    /// True when the model carries damage variables.
    pub fn has_damage(&self) -> bool {
        matches!(self, Material::PlasticDamage(_))
    }

    /// The point state may hold damage: false only when D_t = D_c = 0 exactly (a
    /// plastic-damage point that has never yielded; every point of a model without
    /// damage).
    #[inline]
    pub fn may_hold_damage(&self, state: &[f64]) -> bool {
        match self {
            Material::Elastic(_) => false,
            Material::PlasticDamage(p) => p.has_yielded(state),
        }
    }

    /// (D_t, D_c) of a point state (eq. 24; `None` for models without damage): the two
    /// values of [`Material::damage_state`] that the damaged volume needs, without its
    /// other fields.
    #[inline]
    pub fn tensile_and_compressive_damage(&self, state: &[f64]) -> Option<(f64, f64)> {
        match self {
            Material::Elastic(_) => None,
            Material::PlasticDamage(p) => {
                Some((p.tensile_damage(state), p.compressive_damage(state)))
            }
        }
    }

    /// Damage variables of a point state (`None` for models without damage).
    pub fn damage_state(&self, state: &[f64]) -> Option<DamageState> {
        match self {
            Material::Elastic(_) => None,
            Material::PlasticDamage(p) => Some(DamageState {
                d: p.damage(state),
                dt: p.tensile_damage(state),
                dc: p.compressive_damage(state),
                kappa_t: p.kappa_t(state),
                kappa_c: p.kappa_c(state),
                plastic_strain: p.plastic_strain(state),
            }),
        }
    }

    /// Secant stiffness factor of a point state: 1 − D for the plastic-damage model (D of
    /// eq. (24) after the last update), exactly 1 for the elastic one. The one-point
    /// element multiplies its hourglass stiffness by it (docs/plastic_damage.md §8).
    #[inline(always)]
    pub fn stiffness_factor(&self, state: &[f64]) -> f64 {
        match self {
            Material::Elastic(_) => 1.0,
            Material::PlasticDamage(p) => p.stiffness_factor(state),
        }
    }

    /// Scalar damage D of a point state (0 for models without damage).
    pub fn damage(&self, state: &[f64]) -> f64 {
        match self {
            Material::Elastic(_) => 0.0,
            Material::PlasticDamage(p) => p.damage(state),
        }
    }
}
