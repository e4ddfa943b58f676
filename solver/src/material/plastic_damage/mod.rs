//! Lee–Fenves plastic-damage model (Lee & Fenves 1998, J. Eng. Mech. 124(8)) in the 3D
//! form of Omidi & Lotfi (2010), as used by the paper (§3, eqs. 23–26).
//!
//! Stages of one update (trial → check → return → degrade), see `docs/plastic_damage.md`:
//!
//! 1. trial effective stress σ̄ᵗʳ = E₀ : (ε − εᵖₙ) (eq. 23);
//! 2. check the yield function F of eq. (25) at the start-of-step hardening: F ≤ 0 is elastic;
//! 3. otherwise the implicit return in principal space (`return_mapping.rs`) with the
//!    non-associated hyperbolic Drucker–Prager potential of eq. (26) gives Δλ, εᵖₙ₊₁ and the
//!    hardening variables; a return that does not converge is redone in 4, 16, 64 sub-steps;
//! 4. optional Duvaut–Lions regularisation relaxes the state towards the inviscid one;
//! 5. degradation: σ from σ̄, D_t and D_c by the [`Recovery`] rule (`recovery.rs`): the
//!    default from a Gibbs energy (no energy created on closing-crack cycles), or eq. (24)
//!    D = 1 − (1 − D_c)(1 − s D_t), s = s₀ + (1 − s₀) r(σ̄), σ = (1 − D) σ̄ (eq. 23).
//!
//! The hardening variables are the equivalent plastic strains ε̃ᵖ_t, ε̃ᵖ_c, stored scaled by
//! b (y = b ε̃ᵖ), which makes the stored state independent of the element size; b (and, for
//! elements too large for their fracture energy, a strength factor k) follows from the
//! fracture energy and `PointContext::char_length` (crack band, [`Regularisation`]).

mod elements_in_lanes;
mod hardening;
mod params;
mod points_in_lanes;
mod potential;
mod principal;
mod recovery;
mod recovery_in_lanes;
mod return_mapping;
mod yield_surface;

#[cfg(test)]
mod tests;

pub use hardening::{
    compressive_shape, ElementLaw, Regularisation, SofteningLaw, MIN_SOFTENING_SHARE,
};
pub use params::{mohr_coulomb_fc, Constants, PlasticDamageParams};
pub use recovery::Recovery;

use crate::element::lanes::{part, parts, set_part, F64s, Lane, Simd, VoigtLanes};
use crate::error::{DcfmError, Result};
use crate::material::{Elastic, PointContext, Voigt};
use potential::Potential;
use principal::{definiteness, principal_values, Definiteness, Spectral};
use return_mapping::{LocalProblem, Start};
use yield_surface::{invariants, YieldSurface};

/// Layout of the per-point state.
mod slot {
    /// Plastic strain εᵖ (Voigt, engineering shear), 6 values.
    pub const PLASTIC: usize = 0;
    /// Total strain of the last update (start of the next increment), 6 values.
    pub const STRAIN: usize = 6;
    /// y_t = b_t ε̃ᵖ_t.
    pub const Y_T: usize = 12;
    /// y_c = b_c ε̃ᵖ_c.
    pub const Y_C: usize = 13;
    /// D of eq. (24) at the end of the last update under the `lee_fenves` recovery rule.
    /// Under the consistent rule, where D is a diagnostic that no update reads, it is not
    /// formed in the step unless the element reads it ([`PointContext::reads_damage`]):
    /// NaN for a point with D_t or D_c > 0, else 0, and [`PlasticDamage::damage`] forms
    /// it from the state when asked.
    pub const DAMAGE: usize = 14;
    /// Fracture energy density g_t κ_t + g_c κ_c (J/m³), Lee & Fenves (1998).
    pub const FRACTURE: usize = 15;
    /// Total mechanical dissipation density ∫σ:dε − ψ (J/m³).
    pub const DISSIPATED: usize = 16;
    /// Nominal stress σ of the last update (Voigt, 6 values): the σₙ of the next
    /// increment's dissipation, kept rather than recomputed from the state (under the
    /// consistent recovery rule that needs the spectral decomposition of a damaged point).
    pub const STRESS: usize = 17;
    /// Number of values.
    pub const LEN: usize = 23;
}

/// Number of `f64` of state per integration point.
pub const STATE_LEN: usize = slot::LEN;

/// Margin below zero, relative to c̄_c, of the yield bound under which
/// [`PlasticDamage::virgin_elastic`] takes a never-yielded point, and
/// [`PlasticDamage::yielded_elastic`] a yielded one, as elastic: far above the rounding of
/// F (≈ 1e-16 of the stress), far below any physical distance to the surface.
const VIRGIN_MARGIN: f64 = 1e-9;

/// β and the bracket limit (1 − α)(1 − [`VIRGIN_MARGIN`]) c̄_c of eq. (25) for the
/// effective cohesions `ct`, `cc` (c̄(0) for a never-yielded point, c̄(y) of its
/// hardening for a yielded one).
fn virgin_bound(surface: &YieldSurface, ct: f64, cc: f64) -> (f64, f64) {
    (
        surface.beta(ct, cc),
        (1.0 - surface.alpha) * (1.0 - VIRGIN_MARGIN) * cc,
    )
}

/// Upper bound of the bracket of eq. (25) at effective stress `eff` and β, one vector of
/// points in the vectors of `simd`, for the elastic shortcuts' check: F ≤ −margin c̄_c ⇔
/// bracket ≤ (1 − α)(1 − margin) c̄_c, with σ̂_max ≤ Ī₁/3 + (2/3)√(3J̄₂) (F does not
/// decrease with σ̂_max when β ≥ 0). A decision with a margin: products instead of the
/// quotients of `invariants`. The one spelling of it: the scalar shortcuts call it under
/// `pulp::Scalar` (`f64s` = `f64`, the plain IEEE operations and `f64::max`), the lanes in
/// the dispatched vectors, where each lane performs the same operations in the same order.
/// Only its comparison with the limit is used, and that is the scalar one lane by lane:
/// a vector maximum differs from `f64::max` only in the sign of a zero (which a comparison
/// ignores) and where σ̂_max is NaN, and then the bracket is NaN under either (σ̂_max is
/// NaN only where Ī₁ or q is, and both enter it).
#[inline(always)]
fn virgin_bracket_in<S: Simd>(
    simd: S,
    surface: &YieldSurface,
    beta: S::f64s,
    eff: &[S::f64s; 6],
) -> S::f64s {
    const THIRD: f64 = 1.0 / 3.0;
    // Spelled out call by call: closures are not reliably inlined into the dispatched
    // code (docs/benchmarks.md, stop 60).
    let i1 = simd.add_f64s(simd.add_f64s(eff[0], eff[1]), eff[2]);
    let m = simd.mul_f64s(i1, simd.splat_f64s(THIRD));
    let a = simd.sub_f64s(eff[0], m);
    let b = simd.sub_f64s(eff[1], m);
    let c = simd.sub_f64s(eff[2], m);
    let normal = simd.add_f64s(
        simd.add_f64s(simd.mul_f64s(a, a), simd.mul_f64s(b, b)),
        simd.mul_f64s(c, c),
    );
    let shear = simd.add_f64s(
        simd.add_f64s(simd.mul_f64s(eff[3], eff[3]), simd.mul_f64s(eff[4], eff[4])),
        simd.mul_f64s(eff[5], eff[5]),
    );
    let ss = simd.add_f64s(normal, simd.mul_f64s(simd.splat_f64s(2.0), shear));
    let q = simd.sqrt_f64s(simd.mul_f64s(simd.splat_f64s(1.5), ss));
    let smax = simd.add_f64s(m, simd.mul_f64s(simd.splat_f64s(2.0 * THIRD), q));
    let zero = simd.splat_f64s(0.0);
    let tension = simd.mul_f64s(beta, simd.max_f64s(smax, zero));
    let compression = simd.mul_f64s(
        simd.splat_f64s(surface.gamma),
        simd.max_f64s(simd.neg_f64s(smax), zero),
    );
    let linear = simd.add_f64s(simd.mul_f64s(simd.splat_f64s(surface.alpha), i1), q);
    simd.sub_f64s(simd.add_f64s(linear, tension), compression)
}

/// [`virgin_bracket_in`] of the eight lanes of `eff` with β per lane, one vector of `simd`
/// at a time.
#[inline(always)]
fn virgin_bracket_lanes<S: Simd>(
    simd: S,
    surface: &YieldSurface,
    beta: &F64s,
    eff: &VoigtLanes,
) -> F64s {
    let mut bracket = F64s::ZERO;
    for p in 0..parts::<S>() {
        let mut stress = [simd.splat_f64s(0.0); 6];
        for (v, x) in stress.iter_mut().zip(eff) {
            *v = part::<S>(x, p);
        }
        let b = virgin_bracket_in(simd, surface, part::<S>(beta, p), &stress);
        set_part::<S>(&mut bracket, p, b);
    }
    bracket
}

/// Allowance on the bracket of eq. (25) evaluated at closed-form principal values
/// `values` (sorted), for [`PlasticDamage::yielded_elastic`]'s exact test: the general
/// path evaluates the bracket at the principal values of its own trial stress, which
/// may differ from these by the closed form's rounding (up to ~1e-11 of the largest
/// |σ̂ᵢ| near a double root, [`principal_values`]) and by the rounding of its trial
/// strain; the bracket moves by at most (1 + α + |β| + γ) times that. 1e-9 of the
/// largest |σ̂ᵢ| per unit of that slope: a hundred times the rounding, far below any
/// physical distance to the surface.
#[inline(always)]
fn exact_bracket_margin(surface: &YieldSurface, beta: f64, values: &[f64; 3]) -> f64 {
    let largest = values[0].abs().max(values[2].abs());
    (1.0 + surface.alpha.abs() + beta.abs() + surface.gamma.abs()) * 1e-9 * largest
}

/// Sub-step counts tried in turn when a return does not converge.
const SUBSTEPS: [usize; 4] = [1, 4, 16, 64];

/// The plastic-damage material of one region.
#[derive(Clone, Debug)]
pub struct PlasticDamage {
    name: String,
    elastic: Elastic,
    constants: Constants,
    surface: YieldSurface,
    potential: Potential,
    max_element_size: f64,
    /// (w_e, w_e + g_min) of the tension and the compression law (J/m³), for
    /// [`SofteningLaw::for_length_with`].
    release: [(f64, f64); 2],
    tol: f64,
    /// (β, (1 − α)(1 − [`VIRGIN_MARGIN`]) c̄_c) at y_t = y_c = 0 under the plastic
    /// regularisation (element laws with the material's strengths) for
    /// [`Self::virgin_elastic`]; `None` under the total one (per element length).
    virgin_bound: Option<(f64, f64)>,
}

/// Internal variables advanced by one return.
#[derive(Clone, Copy, Debug)]
struct Internal {
    plastic: Voigt,
    y_t: f64,
    y_c: f64,
}

impl Internal {
    /// The internal variables held by the state `state`.
    #[inline(always)]
    fn of(state: &[f64]) -> Self {
        Self {
            plastic: voigt(&state[slot::PLASTIC..]),
            y_t: state[slot::Y_T],
            y_c: state[slot::Y_C],
        }
    }
}

/// What [`PlasticDamage::yielded_elastic`] decided.
enum Shortcut {
    /// The shortcut was taken: the nominal stress (the state is written).
    Taken(Voigt),
    /// The general path decides, with what the shortcut already formed.
    Declined(Known),
}

/// What the general path can take from [`PlasticDamage::yielded_elastic`] instead of
/// forming it again; nothing by default.
#[derive(Clone, Copy, Default)]
struct Known {
    /// The start state's hardening variables and their cohesions c̄_t, c̄_c
    /// ([`LocalProblem::start`] of them, bit for bit).
    start: Option<Start>,
    /// The principal values of the trial stress, when the exact test formed them.
    trial: Option<KnownTrial>,
}

/// Principal values of a trial effective stress σ̄ = E₀ : (ε − εᵖ) already formed, with the
/// strain and plastic strain it was formed from, so that the return mapping can take them
/// instead of forming them again ([`principal_values`]: two polynomials of degree 19 and
/// three square roots).
#[derive(Clone, Copy)]
struct KnownTrial {
    strain: Voigt,
    plastic: Voigt,
    values: [f64; 3],
}

impl KnownTrial {
    /// Whether the trial stress at total strain `eps` and plastic strain `plastic` is this
    /// one: the same inputs bit for bit (then the same σ̄, and the same principal values,
    /// bit for bit; a sign of zero or a NaN payload differs, so no `==` on the values).
    #[inline(always)]
    fn is_trial_of(&self, eps: &Voigt, plastic: &Voigt) -> bool {
        let same = |a: &Voigt, b: &Voigt| a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits());
        same(&self.strain, eps) && same(&self.plastic, plastic)
    }
}

impl PlasticDamage {
    /// Validate the parameters of material `name` (errors: [`DcfmError::Material`]).
    pub fn new(name: &str, elastic: Elastic, p: &PlasticDamageParams) -> Result<Self> {
        let constants = params::validate(name, p)?;
        let max_element_size = match constants.regularisation {
            // Elements too large get reduced strengths instead (no snap-back by construction).
            Regularisation::Total => f64::INFINITY,
            Regularisation::Plastic => constants
                .tension
                .max_char_length(elastic.young)
                .min(constants.compression.max_char_length(elastic.young)),
        };
        let release = [&constants.tension, &constants.compression].map(|law| {
            let we = law.released_elastic_energy(elastic.young);
            (we, we + law.min_softening_energy(elastic.young))
        });
        let surface = YieldSurface {
            alpha: constants.alpha,
            gamma: constants.gamma,
        };
        let virgin_bound = match constants.regularisation {
            Regularisation::Plastic => Some(virgin_bound(
                &surface,
                constants.tension.f0,
                constants.compression.f0,
            )),
            Regularisation::Total => None,
        };
        Ok(Self {
            name: name.to_string(),
            virgin_bound,
            elastic,
            release,
            surface,
            potential: Potential {
                tan_psi: constants.tan_psi,
                hyper: constants.hyper,
            },
            tol: 1e-10 * constants.compression.f0,
            constants,
            max_element_size,
        })
    }

    /// Initial elastic constants E₀.
    pub fn elastic(&self) -> &Elastic {
        &self.elastic
    }

    /// Validated model constants.
    pub fn constants(&self) -> &Constants {
        &self.constants
    }

    /// Number of `f64` per integration point.
    pub fn state_len(&self) -> usize {
        slot::LEN
    }

    /// Virgin state: no plastic strain, no damage.
    pub fn init_state(&self, s: &mut [f64]) {
        s[..slot::LEN].fill(0.0);
    }

    /// Record `strain` as the strain of the last update (the start of the next increment)
    /// of a point state: an initial strain ε₀ set by the static stage, reached elastically.
    pub fn prime_strain(&self, s: &mut [f64], strain: &Voigt) {
        s[slot::STRAIN..slot::STRAIN + 6].copy_from_slice(strain);
        self.refresh_stress(s);
    }

    /// Store in a point state the nominal stress at its recorded strain ([`slot::STRESS`],
    /// what an update would have returned there): after the strain or the internal
    /// variables of a state were set other than by [`Self::update`].
    pub fn refresh_stress(&self, s: &mut [f64]) {
        let sig = self.stress_from_state(&voigt(&s[slot::STRAIN..]), s);
        s[slot::STRESS..slot::STRESS + 6].copy_from_slice(&sig);
    }

    /// Largest characteristic length (m) without snap-back of the uniaxial tensile or
    /// compressive response of one element ([`SofteningLaw::max_char_length`]);
    /// `f64::INFINITY` when the effective strengths never soften.
    pub fn max_element_size(&self) -> f64 {
        self.max_element_size
    }

    /// Error naming the material and the limit when an element of characteristic length
    /// `l` (m) would snap back.
    pub fn check_char_length(&self, l: f64) -> Result<()> {
        if l <= self.max_element_size {
            return Ok(());
        }
        Err(DcfmError::Material {
            material: self.name.clone(),
            message: format!(
                "element characteristic length {l:.4e} m exceeds {:.4e} m, the largest \
                 element size without snap-back for gt = {} N/m, gc = {} N/m (increase the \
                 fracture energies, or refine the mesh)",
                self.max_element_size, self.constants.tension.g_f, self.constants.compression.g_f
            ),
        })
    }

    /// Tension and compression laws of an element of characteristic length `l` (m): the
    /// strength factors k_t, k_c, scales b_t, b_c and dissipation densities g_t, g_c of the
    /// material's [`Regularisation`].
    pub fn element_laws(&self, l: f64) -> (ElementLaw, ElementLaw) {
        let reg = self.constants.regularisation;
        let [(wt, nt), (wc, nc)] = self.release;
        (
            self.constants.tension.for_length_with(l, reg, wt, nt),
            self.constants.compression.for_length_with(l, reg, wc, nc),
        )
    }

    fn problem(&self, l: f64) -> LocalProblem<'_> {
        let (t, c) = self.element_laws(l);
        LocalProblem {
            bulk: self.elastic.bulk(),
            mu: self.elastic.mu,
            surface: &self.surface,
            potential: &self.potential,
            tension: t.law,
            compression: c.law,
            b_t: t.b,
            b_c: c.b,
            g_t: t.g,
            g_c: c.g,
            tol: self.tol,
            max_iter: return_mapping::MAX_ITER,
        }
    }

    /// One backward-Euler return to total strain `eps`; `false` if the local solve did
    /// not converge. `first`: [`LocalProblem::start`] of the state the step starts from,
    /// taken where `st` has its hardening variables bit for bit (the same cohesions).
    fn return_map(
        &self,
        pb: &LocalProblem,
        eps: &Voigt,
        st: &Internal,
        first: &Start,
        known: Option<&KnownTrial>,
    ) -> (Internal, bool) {
        let trial = self.elastic.stress(&sub(eps, &st.plastic));
        // Cheap check on the invariants first; the eigenvalues only near the surface.
        let (i1, q) = invariants(&trial);
        let start =
            if st.y_t.to_bits() == first.y_t.to_bits() && st.y_c.to_bits() == first.y_c.to_bits() {
                *first
            } else {
                pb.start(st.y_t, st.y_c)
            };
        let (ct, cc) = (start.ct, start.cc);
        if self.surface.surely_inside(i1, q, ct, cc)
            || (definiteness(&trial) == Definiteness::NonPositive
                && self.surface.surely_inside_compressed(i1, q, ct, cc))
        {
            return (*st, true);
        }
        let values = match known {
            Some(k) if k.is_trial_of(eps, &st.plastic) => k.values,
            _ => principal_values(&trial),
        };
        if self.surface.value(&values, ct, cc) <= 0.0 {
            return (*st, true);
        }
        let sp = Spectral::with_values(&trial, values);
        let ret = pb.solve(&sp.values, &start);
        let dp = [
            ret.dlam * ret.m[0],
            ret.dlam * ret.m[1],
            ret.dlam * ret.m[2],
        ];
        let dep = sp.strain_voigt(&dp);
        let mut plastic = st.plastic;
        for (p, d) in plastic.iter_mut().zip(dep.iter()) {
            *p += d;
        }
        let ok = ret.converged && plastic.iter().all(|v| v.is_finite());
        if !ok && !plastic.iter().all(|v| v.is_finite()) {
            return (*st, false);
        }
        (
            Internal {
                plastic,
                y_t: ret.y_t,
                y_c: ret.y_c,
            },
            ok,
        )
    }

    /// Inviscid state at `eps` from `start` (strain `eps0`), sub-stepping on failure;
    /// with what [`Self::yielded_elastic`] formed (`known`).
    fn integrate(
        &self,
        pb: &LocalProblem,
        eps0: &Voigt,
        eps: &Voigt,
        start: &Internal,
        known: &Known,
    ) -> Internal {
        let first = known
            .start
            .unwrap_or_else(|| pb.start(start.y_t, start.y_c));
        let mut last = *start;
        for &n in SUBSTEPS.iter() {
            let mut st = *start;
            let mut ok = true;
            for k in 1..=n {
                let t = k as f64 / n as f64;
                let mut e = [0.0; 6];
                for i in 0..6 {
                    e[i] = eps0[i] + t * (eps[i] - eps0[i]);
                }
                let (next, conv) = self.return_map(pb, &e, &st, &first, known.trial.as_ref());
                st = next;
                ok &= conv;
            }
            if ok {
                return st;
            }
            last = st;
        }
        last
    }

    /// Stress at total strain `strain`, advancing the state `old` → `new` (eqs. 23–26).
    /// Allocation free.
    pub fn update(
        &self,
        strain: &Voigt,
        old: &[f64],
        new: &mut [f64],
        ctx: &PointContext,
    ) -> Voigt {
        let old = &old[..slot::LEN];
        let new = &mut new[..slot::LEN];
        if !strain.iter().all(|v| v.is_finite()) {
            // Let the driver see the bad input as a non-finite stress; keep the state.
            new.copy_from_slice(old);
            return [f64::NAN; 6];
        }
        debug_assert!(ctx.char_length > 0.0, "characteristic length must be > 0");
        let l = ctx.char_length.max(1e-12);
        if old[slot::Y_T] == 0.0 && old[slot::Y_C] == 0.0 {
            if let Some(sig) = self.virgin_elastic(strain, old, new, l) {
                return sig;
            }
            self.general_update(strain, old, new, ctx.dt, l, ctx.reads_damage)
        } else {
            match self.yielded_elastic(strain, old, new, l, ctx.reads_damage) {
                Shortcut::Taken(sig) => sig,
                Shortcut::Declined(known) => {
                    self.general_update_with(strain, old, new, (ctx.dt, l, ctx.reads_damage), known)
                }
            }
        }
    }

    /// The update of a point that has yielded (y_t or y_c > 0) and whose trial stress is
    /// inside its current surface by a margin: the internal variables stay, σ̄ =
    /// E₀ : (ε − εᵖ), and the nominal stress, D and the dissipation are those of
    /// [`Self::general_update`] for an unchanged state ([`Self::commit`], the same code).
    /// Skipped: the local problem's set-up, the sub-step loop, its trial stress and the
    /// return mapping's own check. Two tests, the cheap one first: the invariant bound of
    /// [`YieldSurface::surely_inside`] ([`VIRGIN_MARGIN`] of c̄_c); failing it (a point
    /// near its surface, where σ̂_max ≤ Ī₁/3 + (2/3)√(3J̄₂) is loose), eq. (25) at the
    /// exact principal values ([`exact_bracket_margin`]), which [`Self::commit`] then
    /// reuses for the recovery. Bit for bit what the general path gives, as for
    /// [`Self::virgin_elastic`] — that path finds the trial elastic too (the margins
    /// cover its trial strain ε₀ + 1·(ε − ε₀), which may differ from ε by rounding, and
    /// the rounding of the closed-form principal values) and then keeps the start state.
    /// The branch most points of a damaged region take in most steps.
    /// [`Shortcut::Declined`]: take the general path (with the exact test's principal
    /// values when it formed them).
    #[inline]
    fn yielded_elastic(
        &self,
        strain: &Voigt,
        old: &[f64],
        new: &mut [f64],
        l: f64,
        reads_damage: bool,
    ) -> Shortcut {
        let start = Internal::of(old);
        let eff = self.elastic.stress(&sub(strain, &start.plastic));
        let (t, c) = self.element_laws(l);
        // c̄ and D of each law from one exponential where r = 1 (bit for bit the separate
        // functions, [`SofteningLaw::effective_and_damage`]; the element laws share r with
        // the material's).
        let (ct, d_t) = t.law.effective_and_damage(start.y_t);
        let (cc, d_c) = c.law.effective_and_damage(start.y_c);
        let (beta, limit) = virgin_bound(&self.surface, ct, cc);
        // The bound needs F non-decreasing in σ̂_max (β ≥ 0): any other point (β < 0 or
        // NaN) takes the general path, as it always has.
        let monotone = beta >= 0.0;
        // The local problem's start from this state: these cohesions, bit for bit
        // (`effective_and_damage` is `effective`, and `t`, `c` the problem's laws).
        let known_start = Some(Start {
            y_t: start.y_t,
            y_c: start.y_c,
            ct,
            cc,
        });
        if !monotone {
            return Shortcut::Declined(Known {
                start: known_start,
                trial: None,
            });
        }
        let laws = [(&t.law, t.g), (&c.law, c.g)];
        // The state kept, at the new strain: the tail of the general path for an unchanged
        // state, with the principal values when formed.
        let mut keep = |values| {
            self.commit(
                strain,
                old,
                new,
                &start,
                &start,
                eff,
                laws,
                ((d_t, d_c), None),
                values,
                reads_damage,
            )
        };
        if virgin_bracket_in(pulp::Scalar::new(), &self.surface, beta, &eff) <= limit {
            return Shortcut::Taken(keep(None));
        }
        // F of eq. (25) at the exact values, inside by the bound's margin plus the allowance.
        let values = principal_values(&eff);
        let allowance = VIRGIN_MARGIN * cc
            + exact_bracket_margin(&self.surface, beta, &values) / (1.0 - self.surface.alpha);
        let inside = self.surface.value(&values, ct, cc) + allowance <= 0.0;
        if !inside {
            return Shortcut::Declined(Known {
                start: known_start,
                trial: Some(KnownTrial {
                    strain: *strain,
                    plastic: start.plastic,
                    values,
                }),
            });
        }
        Shortcut::Taken(keep(Some(values)))
    }

    /// [`Self::update`] by the return mapping (no shortcut) at characteristic length `l`.
    fn general_update(
        &self,
        strain: &Voigt,
        old: &[f64],
        new: &mut [f64],
        dt: f64,
        l: f64,
        reads_damage: bool,
    ) -> Voigt {
        self.general_update_with(strain, old, new, (dt, l, reads_damage), Known::default())
    }

    /// [`Self::general_update`] (Δt, l and whether D is read in `(dt, l, reads_damage)`)
    /// given what the caller has already formed (`known`, [`Self::yielded_elastic`]): the
    /// start state's cohesions, and the principal values of a trial stress, which the
    /// return mapping takes instead of forming them again where its trial is that one bit
    /// for bit.
    fn general_update_with(
        &self,
        strain: &Voigt,
        old: &[f64],
        new: &mut [f64],
        (dt, l, reads_damage): (f64, f64, bool),
        known: Known,
    ) -> Voigt {
        let pb = self.problem(l);
        let start = Internal::of(old);
        let eps0 = voigt(&old[slot::STRAIN..]);
        let mut st = self.integrate(&pb, &eps0, strain, &start, &known);

        // Duvaut–Lions: x' = (x_n − x_∞)/η ⇒ x_{n+1} = x_n + w (x_∞ − x_n), w = Δt/(η + Δt).
        if self.constants.viscosity > 0.0 {
            let w = if dt > 0.0 {
                dt / (self.constants.viscosity + dt)
            } else {
                0.0
            };
            for i in 0..6 {
                st.plastic[i] = start.plastic[i] + w * (st.plastic[i] - start.plastic[i]);
            }
            st.y_t = start.y_t + w * (st.y_t - start.y_t);
            st.y_c = start.y_c + w * (st.y_c - start.y_c);
        }

        let eff = self.elastic.stress(&sub(strain, &st.plastic));
        let laws = [(&pb.tension, pb.g_t), (&pb.compression, pb.g_c)];
        // D (eq. 24) and κ at the end state from one exponential per law where r = 1
        // (bit for bit `damages` and `kappa`: the element laws differ from the material's
        // in f₀ only).
        let (d_t, kappa_t) = self.constants.tension.damage_and_kappa(st.y_t);
        let (d_c, kappa_c) = self.constants.compression.damage_and_kappa(st.y_c);
        self.commit(
            strain,
            old,
            new,
            &start,
            &st,
            eff,
            laws,
            ((d_t, d_c), Some((kappa_t, kappa_c))),
            None,
            reads_damage,
        )
    }

    /// The new state `new` and the nominal stress of a point that moved from `start`
    /// (state `old`) to `st` with effective stress `eff` = E₀ : (ε − εᵖ) at strain
    /// `strain`, for the element laws `laws` (tension, compression: the softening law and
    /// its dissipation density g of [`ElementLaw`]): the tail of
    /// [`Self::general_update`] (eqs. 23–24 and the tracked energies). `at_end`: (D_t, D_c)
    /// of eq. (24) at `st` ([`Self::damages`], bit for bit) and, when the caller has them,
    /// (κ_t, κ_c) at `st` ([`SofteningLaw::kappa`], bit for bit; else formed where a
    /// hardening variable moved). `values`: the
    /// principal values of `eff` when the caller has them ([`principal_values`], the
    /// recovery's own values bit for bit), else `None`. `reads_damage`: store D under
    /// every rule ([`PointContext::reads_damage`]).
    #[allow(clippy::too_many_arguments)]
    #[inline(always)]
    fn commit(
        &self,
        strain: &Voigt,
        old: &[f64],
        new: &mut [f64],
        start: &Internal,
        st: &Internal,
        eff: Voigt,
        laws: [(&SofteningLaw, f64); 2],
        (damage, kappa_end): ((f64, f64), Option<(f64, f64)>),
        values: Option<[f64; 3]>,
        reads_damage: bool,
    ) -> Voigt {
        let [(t, g_t), (c, g_c)] = laws;
        let mut classified = recovery::Classified::new(&eff);
        if let Some(v) = values {
            classified = classified.with_values(v);
        }
        let (sig, d) = self.nominal_with(&mut classified, damage, reads_damage);
        let d_t = damage.0;
        new[slot::PLASTIC..slot::PLASTIC + 6].copy_from_slice(&st.plastic);
        new[slot::STRAIN..slot::STRAIN + 6].copy_from_slice(strain);
        new[slot::Y_T] = st.y_t;
        new[slot::Y_C] = st.y_c;
        new[slot::DAMAGE] = d;
        let mut w = old[slot::FRACTURE];
        if st.y_t != start.y_t {
            let kappa = kappa_end.map_or_else(|| t.kappa(st.y_t), |k| k.0);
            w += g_t * (kappa - t.kappa(start.y_t));
        }
        if st.y_c != start.y_c {
            let kappa = kappa_end.map_or_else(|| c.kappa(st.y_c), |k| k.1);
            w += g_c * (kappa - c.kappa(start.y_c));
        }
        new[slot::FRACTURE] = w;
        // Total dissipation: trapezoidal work ½(σₙ + σₙ₊₁):Δε minus the change of the
        // recoverable energy ψ = ½ σ:(ε − εᵖ). Zero (and skipped) when neither the internal
        // variables nor D can have changed.
        let unchanged = st.plastic == start.plastic && st.y_t == start.y_t && st.y_c == start.y_c;
        // (unchanged: y_t is start.y_t, so d_t is D_t(start.y_t); tension and
        // compression laws share r with the element's, scaled in f₀ only)
        new[slot::DISSIPATED] = if unchanged && d_t == 0.0 {
            old[slot::DISSIPATED]
        } else {
            // σₙ as the last update returned it: stress_from_state(ε₀, old) bit for bit.
            let sig0 = voigt(&old[slot::STRESS..]);
            let eps0 = voigt(&old[slot::STRAIN..]);
            let from = (&sig0, &eps0, &start.plastic);
            dissipated_after(old[slot::DISSIPATED], from, (&sig, strain, &st.plastic))
        };
        new[slot::STRESS..slot::STRESS + 6].copy_from_slice(&sig);
        sig
    }

    /// The update of a point that has never yielded (y_t = y_c = 0, hence D = 0) and whose
    /// trial stress is inside the initial surface by a margin ([`VIRGIN_MARGIN`] of c̄_c),
    /// from the invariant bound of [`YieldSurface::surely_inside`]: the state is the old
    /// one at the new strain and σ = σ̄ = E₀ : (ε − εᵖ) (eqs. 23–24 with D = 0), without
    /// the local problem, the sub-step loop and the second stress evaluation of the general
    /// path. Bit for bit what that path gives — for an elastic trial it keeps the start
    /// state (viscosity moves nothing), D = D_c(0) = 0 and (1 − 0) σ̄ = σ̄ under both recovery
    /// rules — and the margin makes sure that path would find the trial elastic too (its
    /// trial strain ε₀ + 1·(ε − ε₀) may differ from ε by rounding). `None`: take the
    /// general path. Most points of a large model take this one in most steps.
    #[inline]
    fn virgin_elastic(
        &self,
        strain: &Voigt,
        old: &[f64],
        new: &mut [f64],
        l: f64,
    ) -> Option<Voigt> {
        let eff = self.virgin_stress(strain, old, l)?;
        new.copy_from_slice(old);
        write_virgin_point(new, strain, &eff);
        Some(eff)
    }

    /// The check of [`Self::virgin_elastic`] alone: σ̄ = E₀ : (ε − εᵖ) of the never-yielded
    /// state `old` when it is inside the initial surface by the margin, else `None`.
    #[inline(always)]
    fn virgin_stress(&self, strain: &Voigt, old: &[f64], l: f64) -> Option<Voigt> {
        let eff = self
            .elastic
            .stress(&sub(strain, &voigt(&old[slot::PLASTIC..])));
        let (beta, limit) = self.virgin_bound_for(l);
        let bracket = virgin_bracket_in(pulp::Scalar::new(), &self.surface, beta, &eff);
        (beta >= 0.0 && bracket <= limit).then_some(eff)
    }

    /// (β, limit) of the never-yielded check for an element of characteristic length `l`
    /// ([`virgin_bound`] of its strengths; the same for every length under
    /// [`Regularisation::Plastic`]).
    #[inline(always)]
    fn virgin_bound_for(&self, l: f64) -> (f64, f64) {
        self.virgin_bound.unwrap_or_else(|| {
            let (t, c) = self.element_laws(l);
            virgin_bound(&self.surface, t.law.f0, c.law.f0)
        })
    }

    /// [`Self::update`] with the state updated in place (`state`: the committed state on
    /// entry, the new one on return): a point that takes the never-yielded shortcut has
    /// only its strain, stress and D written (the rest is the old state already); any
    /// other is copied to the stack as its old state first. The same stress and state as
    /// [`Self::update`] bit for bit; second: whether the hardening moved
    /// ([`Self::hardening_moved`] of the old and the new state). Inlined whole, so that
    /// the shortcut is compiled for the instruction set of the dispatched element kernel
    /// that calls it (out of line it ran as baseline SSE2 code).
    #[inline(always)]
    pub fn update_in_place(
        &self,
        strain: &Voigt,
        state: &mut [f64],
        ctx: &PointContext,
    ) -> (Voigt, bool) {
        let state = &mut state[..slot::LEN];
        if state[slot::Y_T] == 0.0
            && state[slot::Y_C] == 0.0
            && strain.iter().all(|v| v.is_finite())
        {
            if let Some(eff) = self.virgin_stress(strain, state, ctx.char_length.max(1e-12)) {
                write_virgin_point(state, strain, &eff);
                return (eff, false);
            }
        }
        self.update_general_in_place(strain, state, ctx)
    }

    /// [`Self::update`] of a point whose state `state` is updated in place, the committed
    /// state copied to the stack first (the general path of [`Self::update_in_place`] and
    /// of the lane updates); second: whether the hardening moved.
    #[inline(always)]
    fn update_general_in_place(
        &self,
        strain: &Voigt,
        state: &mut [f64],
        ctx: &PointContext,
    ) -> (Voigt, bool) {
        let mut old = [0.0; slot::LEN];
        old.copy_from_slice(state);
        let sig = self.update(strain, &old, state, ctx);
        (sig, self.hardening_moved(&old, state))
    }

    /// Nominal stress σ and the D of eq. (24) for effective stress `eff` and hardening
    /// y_t, y_c, by the material's [`Recovery`] rule (`recovery.rs`): σ = (1 − D) σ̄ (eq. 23)
    /// for `LeeFenves`; from the Gibbs energy for `Consistent` (equal in uniaxial states),
    /// whose D is reported as a diagnostic only. Third: the tensile degradation D_t(y_t).
    #[inline]
    fn nominal(&self, eff: &Voigt, y_t: f64, y_c: f64) -> (Voigt, f64, f64) {
        let damage = self.damages(y_t, y_c);
        let (sig, d) = self.nominal_with(&mut recovery::Classified::new(eff), damage, false);
        (sig, d, damage.0)
    }

    /// (D_t, D_c) = (1 − e^(−d_t ε̃ᵖ_t), 1 − e^(−d_c ε̃ᵖ_c)) of eq. (24) at y_t, y_c.
    #[inline(always)]
    fn damages(&self, y_t: f64, y_c: f64) -> (f64, f64) {
        (
            self.constants.tension.damage(y_t),
            self.constants.compression.damage(y_c),
        )
    }

    /// σ and D of [`Self::nominal`] for a [`recovery::Classified`] effective stress and
    /// `damage` = (D_t, D_c) of [`Self::damages`]. Under the consistent rule D is formed
    /// only when `reads_damage` ([`PointContext::reads_damage`]: from the same classified
    /// σ̄, so the principal values are formed once); else NaN, or 0 where D_t = D_c = 0
    /// ([`slot::DAMAGE`]; [`Self::damage`] forms it from the state).
    #[inline(always)]
    fn nominal_with(
        &self,
        classified: &mut recovery::Classified,
        (dt, dc): (f64, f64),
        reads_damage: bool,
    ) -> (Voigt, f64) {
        let s0 = self.constants.s0;
        match self.constants.recovery {
            Recovery::LeeFenves => {
                let d = recovery::lee_fenves_damage(classified, dt, dc, s0);
                (scale(classified.stress(), 1.0 - d), d)
            }
            Recovery::Consistent => (
                recovery::consistent_stress_of(classified, dt, dc, s0, self.elastic.poisson),
                // D_t = D_c = 0 (never yielded): D = 0, what the shortcuts write.
                if dt == 0.0 && dc == 0.0 {
                    0.0
                } else if reads_damage {
                    recovery::lee_fenves_damage(classified, dt, dc, s0)
                } else {
                    f64::NAN
                },
            ),
        }
    }

    /// D of eq. (24) of a state: D = 1 − (1 − D_c)(1 − s D_t) at the effective stress
    /// σ̄ = E₀ : (ε − εᵖ) of its last update (its stored strain and plastic strain: the
    /// σ̄ that update formed, bit for bit), 0 for a point that has never yielded.
    fn damage_from_state(&self, s: &[f64]) -> f64 {
        if !self.has_yielded(s) {
            return 0.0;
        }
        let eff = self.effective_stress(&voigt(&s[slot::STRAIN..]), s);
        let (dt, dc) = self.damages(s[slot::Y_T], s[slot::Y_C]);
        recovery::lee_fenves_damage(
            &mut recovery::Classified::new(&eff),
            dt,
            dc,
            self.constants.s0,
        )
    }

    /// Nominal stress at total strain `strain` for an updated state (eqs. 23–24, by the
    /// [`Recovery`] rule), D re-evaluated at this strain.
    pub fn stress_from_state(&self, strain: &Voigt, state: &[f64]) -> Voigt {
        let eff = self.effective_stress(strain, state);
        self.nominal(&eff, state[slot::Y_T], state[slot::Y_C]).0
    }

    /// σ̄ = E₀ : (ε − εᵖ) (eq. 23).
    pub fn effective_stress(&self, strain: &Voigt, state: &[f64]) -> Voigt {
        self.elastic
            .stress(&sub(strain, &voigt(&state[slot::PLASTIC..])))
    }

    /// F of eq. (25) (Pa) at `strain` with the hardening of `state`, for an element of
    /// characteristic length `l` (m; its strengths, [`Self::element_laws`]); ≤ 0 inside.
    pub fn yield_function(&self, strain: &Voigt, state: &[f64], l: f64) -> f64 {
        let s = principal_values(&self.effective_stress(strain, state));
        let (t, c) = self.element_laws(l);
        self.surface.value(
            &s,
            t.law.effective(state[slot::Y_T]),
            c.law.effective(state[slot::Y_C]),
        )
    }

    /// D of eq. (24) at the end of the last update: stored by the update under the
    /// `lee_fenves` rule, and under the consistent one where the element reads it
    /// ([`PointContext::reads_damage`]); else formed from the state ([`slot::DAMAGE`]).
    #[inline]
    pub fn damage(&self, s: &[f64]) -> f64 {
        match self.constants.recovery {
            Recovery::LeeFenves => s[slot::DAMAGE],
            // Stored where the element asked for it ([`PointContext::reads_damage`]): the
            // value formed from the state, bit for bit.
            Recovery::Consistent if !s[slot::DAMAGE].is_nan() => s[slot::DAMAGE],
            Recovery::Consistent => self.damage_from_state(s),
        }
    }

    /// Secant stiffness factor 1 − D (D of eq. (24) at the end of the last update,
    /// [`Self::damage`]): what the one-point element scales its hourglass stiffness by, so
    /// that a cracked element resists its hourglass modes as its damaged material does
    /// (docs/plastic_damage.md §8).
    #[inline]
    pub fn stiffness_factor(&self, s: &[f64]) -> f64 {
        1.0 - self.damage(s)
    }

    /// D_t = 1 − e^(−d_t ε̃ᵖ_t) (eq. 24).
    pub fn tensile_damage(&self, s: &[f64]) -> f64 {
        self.constants.tension.damage(s[slot::Y_T])
    }

    /// The point has yielded (y_t or y_c ≠ 0; also true for a non-finite state). A point
    /// for which this is false has D_t = D_c = 0 exactly (eq. 24: `Hardening::damage` of
    /// y = 0 is 0).
    #[inline]
    pub fn has_yielded(&self, s: &[f64]) -> bool {
        s[slot::Y_T] != 0.0 || s[slot::Y_C] != 0.0
    }

    /// y_t or y_c differs between the states `old` and `new` of a point (so may D_t, D_c
    /// of eq. 24); also true when either is NaN.
    #[inline]
    pub fn hardening_moved(&self, old: &[f64], new: &[f64]) -> bool {
        old[slot::Y_T] != new[slot::Y_T] || old[slot::Y_C] != new[slot::Y_C]
    }

    /// D_c = 1 − e^(−d_c ε̃ᵖ_c) (eq. 24).
    pub fn compressive_damage(&self, s: &[f64]) -> f64 {
        self.constants.compression.damage(s[slot::Y_C])
    }

    /// Lee–Fenves tensile damage variable κ_t = (1/g_t)∫f_t dε̃ᵖ_t ∈ [0, 1].
    pub fn kappa_t(&self, s: &[f64]) -> f64 {
        self.constants.tension.kappa(s[slot::Y_T])
    }

    /// Lee–Fenves compressive damage variable κ_c ∈ [0, 1].
    pub fn kappa_c(&self, s: &[f64]) -> f64 {
        self.constants.compression.kappa(s[slot::Y_C])
    }

    /// Equivalent tensile plastic strain ε̃ᵖ_t for characteristic length `l`.
    pub fn equivalent_plastic_strain_t(&self, s: &[f64], l: f64) -> f64 {
        s[slot::Y_T] / self.element_laws(l).0.b
    }

    /// Equivalent compressive plastic strain ε̃ᵖ_c for characteristic length `l`.
    pub fn equivalent_plastic_strain_c(&self, s: &[f64], l: f64) -> f64 {
        s[slot::Y_C] / self.element_laws(l).1.b
    }

    /// Plastic strain εᵖ (Voigt, engineering shear).
    pub fn plastic_strain(&self, s: &[f64]) -> Voigt {
        voigt(&s[slot::PLASTIC..])
    }

    /// Total energy dissipated per unit volume (J/m³) by plastic flow and stiffness
    /// degradation: Σ ½(σₙ + σₙ₊₁):Δε − ψ, ψ = ½ σ:(ε − εᵖ), accumulated over the updates
    /// (the term W_damage/plastic of the energy balance, W12).
    pub fn dissipated_energy_density(&self, s: &[f64]) -> f64 {
        s[slot::DISSIPATED]
    }

    /// Fracture energy density of Lee & Fenves (1998), g_t κ_t + g_c κ_c = ∫f_t dε̃ᵖ_t +
    /// ∫f_c dε̃ᵖ_c (J/m³): what G/l_ch regularises under [`Regularisation::Plastic`]
    /// (G/l_ch − w_e under [`Regularisation::Total`]). It measures the equivalent plastic strains
    /// against the uniaxial laws, so it differs from [`Self::dissipated_energy_density`]:
    /// uniaxially it omits the elastic energy released by degradation.
    pub fn fracture_energy_density(&self, s: &[f64]) -> f64 {
        s[slot::FRACTURE]
    }

    /// Recoverable (elastic) energy density ψ = ½ σ : (ε − εᵖ) (J/m³).
    pub fn recoverable_energy_density(&self, strain: &Voigt, state: &[f64]) -> f64 {
        let sig = self.stress_from_state(strain, state);
        0.5 * dot(&sig, &sub(strain, &voigt(&state[slot::PLASTIC..])))
    }
}

/// What the never-yielded shortcut changes in a point state `n` whose other values are its
/// old ones: the strain, D = 0 and the stress σ = σ̄ = `eff`.
#[inline]
fn write_virgin_point(n: &mut [f64], strain: &Voigt, eff: &Voigt) {
    n[slot::STRAIN..slot::STRAIN + 6].copy_from_slice(strain);
    n[slot::DAMAGE] = 0.0;
    n[slot::STRESS..slot::STRESS + 6].copy_from_slice(eff);
}

/// What the never-yielded shortcut changes in the state `n` of the point in lane `l` (whose
/// other values are its old ones): the strain, the stress σ = σ̄ and D = 0. Value by value
/// from the lanes: a point's Voigt vectors are never staged as arrays (a wide load of narrow
/// stores stalls store forwarding).
#[inline(always)]
fn write_virgin_lane(n: &mut [f64], strain: &VoigtLanes, eff: &VoigtLanes, l: usize) {
    for i in 0..6 {
        n[slot::STRAIN + i] = strain[i][l];
        n[slot::STRESS + i] = eff[i][l];
    }
    n[slot::DAMAGE] = 0.0;
}

/// The total dissipation density after a step from (σₙ, εₙ, εᵖₙ) = `from` to (σₙ₊₁,
/// εₙ₊₁, εᵖₙ₊₁) = `to` (one point, or one per lane): `old` plus the trapezoidal work
/// ½(σₙ + σₙ₊₁):Δε minus the change of the recoverable energy ψ = ½ σ:(ε − εᵖ).
#[inline(always)]
fn dissipated_after<T: Lane>(
    old: T,
    (sig0, eps0, plastic0): (&[T; 6], &[T; 6], &[T; 6]),
    (sig, eps, plastic): (&[T; 6], &[T; 6], &[T; 6]),
) -> T {
    let half = T::splat(0.5);
    let work = half * dot(&add(sig0, sig), &sub(eps, eps0));
    let psi0 = half * dot(sig0, &sub(eps0, plastic0));
    let psi1 = half * dot(sig, &sub(eps, plastic));
    old + work - (psi1 - psi0)
}

#[inline]
fn voigt(s: &[f64]) -> Voigt {
    [s[0], s[1], s[2], s[3], s[4], s[5]]
}

#[inline]
fn sub<T: Lane>(a: &[T; 6], b: &[T; 6]) -> [T; 6] {
    [
        a[0] - b[0],
        a[1] - b[1],
        a[2] - b[2],
        a[3] - b[3],
        a[4] - b[4],
        a[5] - b[5],
    ]
}

#[inline]
fn add<T: Lane>(a: &[T; 6], b: &[T; 6]) -> [T; 6] {
    [
        a[0] + b[0],
        a[1] + b[1],
        a[2] + b[2],
        a[3] + b[3],
        a[4] + b[4],
        a[5] + b[5],
    ]
}

#[inline]
fn dot<T: Lane>(a: &[T; 6], b: &[T; 6]) -> T {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2] + a[3] * b[3] + a[4] * b[4] + a[5] * b[5]
}

#[inline]
fn scale(a: &Voigt, k: f64) -> Voigt {
    [k * a[0], k * a[1], k * a[2], k * a[3], k * a[4], k * a[5]]
}
