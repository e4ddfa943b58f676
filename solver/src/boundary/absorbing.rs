//! Absorbing boundaries on face sets of the model's outside (case-file schema and the
//! distributed coefficients).
//!
//! - **Dashpots** (Lysmer & Kuhlemeyer 1969): t = −ρ c_p (v·n) n − ρ c_s (v − (v·n) n),
//!   with c_p = √((λ+2G)/ρ) — the dilatational speed, not the bar speed √(E/ρ) (8.7 % lower
//!   at ν = 0.25) — and c_s = √(G/ρ). Exact at normal incidence.
//! - **Viscous-spring** (Deeks & Randolph 1994; Liu Jingbo et al. 2006): the same dashpots
//!   plus springs K_N = α_N G/R normal and K_T = α_T G/R tangential per unit area, R the
//!   distance from the scattering source to the boundary point, α_N = 1.33 and α_T = 0.67
//!   by default in 3D. The springs give the far field's static stiffness, so a boundary
//!   does not drift under low-frequency or static loads.
//!
//! The coefficients are lumped to the nodes by the exact tributary integrals of
//! [`crate::boundary::face_tensors`]; each face takes the material of its element unless
//! the case names another.

use serde::Deserialize;

/// One set name or a list of set names.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum SetNames {
    One(String),
    Many(Vec<String>),
}

impl SetNames {
    /// The names as a list.
    pub fn names(&self) -> Vec<&str> {
        match self {
            SetNames::One(s) => vec![s.as_str()],
            SetNames::Many(v) => v.iter().map(String::as_str).collect(),
        }
    }
}

/// Kind of absorbing boundary.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum AbsorbingKind {
    /// Lysmer–Kuhlemeyer dashpots.
    Dashpot,
    /// Dashpots plus springs (viscoelastic artificial boundary).
    ViscousSpring,
}

/// `[[boundary.absorbing]]`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AbsorbingSpec {
    /// Face set(s) on the model's outside.
    pub set: SetNames,
    pub kind: AbsorbingKind,
    /// Material of the far field (default: the material of each face's element).
    #[serde(default)]
    pub material: Option<String>,
    /// Normal spring coefficient α_N (viscous-spring).
    #[serde(default = "default_alpha_n")]
    pub alpha_n: f64,
    /// Tangential spring coefficient α_T (viscous-spring).
    #[serde(default = "default_alpha_t")]
    pub alpha_t: f64,
    /// Distance R from the scattering source to the boundary (m), the same for every node.
    #[serde(default)]
    pub distance: Option<f64>,
    /// Scattering source point: R is each node's distance from it (default: the centre of
    /// the model's bounding box).
    #[serde(default)]
    pub source: Option<[f64; 3]>,
    /// The seismic input (`[seismic]`) enters through this face set: equivalent nodal
    /// forces F = A (K u_ff + C v_ff + σ_ff·n). The faces must form the model's horizontal base.
    #[serde(default)]
    pub input: bool,
}

fn default_alpha_n() -> f64 {
    1.33
}

fn default_alpha_t() -> f64 {
    0.67
}

/// Per-unit-area coefficients of one face: dashpots (normal, tangential) and the spring
/// modulus G (multiplied by α/R per node).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct FaceCoefficients {
    /// ρ c_p (Pa·s/m).
    pub dashpot_normal: f64,
    /// ρ c_s (Pa·s/m).
    pub dashpot_tangential: f64,
    /// Shear modulus G of the far field (Pa).
    pub shear_modulus: f64,
}

impl FaceCoefficients {
    /// The coefficients of a far field of the given elastic material.
    pub fn of(material: &crate::material::Elastic) -> Self {
        Self {
            dashpot_normal: material.density * material.p_wave_speed(),
            dashpot_tangential: material.density * material.s_wave_speed(),
            shear_modulus: material.mu,
        }
    }
}
