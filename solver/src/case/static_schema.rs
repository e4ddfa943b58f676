//! Serde types of the case file's `[static]` section (the static stage; see
//! `docs/static_stage.md`). Unknown fields are rejected; `case/build/static_stage.rs`
//! validates the values against the model.

use serde::Deserialize;

use crate::case::schema::FixedSection;
use crate::stage::static_stage::linear_solver::LinearSolverChoice;
use crate::stage::static_stage::{RelaxationDamping, StepSolver};

/// `[static]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StaticSection {
    /// Default solver of the steps: "direct" (default) or "relaxation".
    #[serde(default)]
    pub solver: Option<StepSolver>,
    /// Default out-of-balance ratio tolerance (default 1e-5).
    #[serde(default)]
    pub tolerance: Option<f64>,
    /// Default most relaxation iterations per step (default 200000).
    #[serde(default)]
    pub max_iterations: Option<usize>,
    /// Relaxation damping: "kinetic" (default) or "viscous".
    #[serde(default)]
    pub damping: Option<RelaxationDamping>,
    /// Fictitious masses for the relaxation (default true).
    #[serde(default)]
    pub mass_scaling: Option<bool>,
    /// Start each relaxation from the direct elastic solution where possible (default true).
    #[serde(default)]
    pub predictor: Option<bool>,
    /// Linear solver of the direct steps and of the predictor: "auto" (default: Cholesky
    /// when its factor fits `factor_memory_limit`), "cholesky" or "conjugate_gradients".
    #[serde(default)]
    pub linear_solver: Option<LinearSolverChoice>,
    /// Largest Cholesky factor "auto" accepts, GiB (default 4).
    #[serde(default)]
    pub factor_memory_limit: Option<f64>,
    /// Relative residual the conjugate gradients reach (default 1e-10).
    #[serde(default)]
    pub cg_tolerance: Option<f64>,
    /// Most conjugate-gradient iterations per solve (default 50000).
    #[serde(default)]
    pub cg_max_iterations: Option<usize>,
    /// Relaxation iterations between two rows of static_histories.csv (default 10).
    #[serde(default)]
    pub history_every: Option<usize>,
    /// Boundary conditions of the static stage (`[[static.fixed]]`); default: the DOFs the
    /// case's `[boundary]` fixes or prescribes, held fixed.
    #[serde(default)]
    pub fixed: Option<Vec<FixedSection>>,
    /// Static loads that stay on (`[[static.loads]]`).
    #[serde(default)]
    pub loads: Vec<StaticLoadSection>,
    /// In-situ stress (`[static.in_situ]`); default: none.
    #[serde(default)]
    pub in_situ: Option<InSituSection>,
    /// Excavation / construction steps (`[[static.steps]]`).
    #[serde(default)]
    pub steps: Vec<StaticStepSection>,
}

/// `[[static.loads]]`: exactly one of `force` (N per node of a set), `pressure` (Pa,
/// compression positive, on a face set) or `traction` (Pa, on a face set).
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StaticLoadSection {
    pub set: String,
    #[serde(default)]
    pub force: Option<[f64; 3]>,
    #[serde(default)]
    pub pressure: Option<f64>,
    #[serde(default)]
    pub traction: Option<[f64; 3]>,
}

/// How the in-situ stress is set.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum InSituMethod {
    /// No in-situ step.
    None,
    /// Solve under gravity ([loads.gravity]) and the static loads.
    Gravity,
    /// σ_v from the ground surface down (unit weights, layers), σ_h = K0 σ_v.
    K0,
    /// σ_v and K0 tabulated against z.
    Table,
}

/// K0 along both horizontal axes, or `[K0_x, K0_y]`.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum K0Value {
    Same(f64),
    PerAxis([f64; 2]),
}

impl K0Value {
    /// (K0_x, K0_y).
    pub fn pair(self) -> [f64; 2] {
        match self {
            K0Value::Same(k) => [k, k],
            K0Value::PerAxis(k) => k,
        }
    }
}

/// `[static.in_situ]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct InSituSection {
    pub method: InSituMethod,
    /// Solver of the in-situ step (default: `static.solver`).
    #[serde(default)]
    pub solver: Option<StepSolver>,
    #[serde(default)]
    pub tolerance: Option<f64>,
    #[serde(default)]
    pub max_iterations: Option<usize>,
    /// method = "k0": z of the ground surface (m), at or above the model's top.
    #[serde(default)]
    pub ground_surface: Option<f64>,
    /// method = "k0": vertical stress at the ground surface (Pa, compression positive).
    #[serde(default)]
    pub surface_pressure: f64,
    /// method = "k0": σ_h/σ_v (one value, or [x, y]); per layer when layers are given.
    #[serde(default)]
    pub k0: Option<K0Value>,
    /// method = "k0": unit weight γ (N/m³); default ρ|g| of each element's material.
    #[serde(default)]
    pub unit_weight: Option<f64>,
    /// method = "k0": horizontal layers from the top down (`[[static.in_situ.layers]]`).
    #[serde(default)]
    pub layers: Vec<LayerSection>,
    /// method = "table": rows [z, σ_v, K0] or [z, σ_v, K0_x, K0_y] (σ_v compression
    /// positive, Pa), z descending; linear in between, constant outside.
    #[serde(default)]
    pub table: Vec<Vec<f64>>,
}

/// `[[static.in_situ.layers]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct LayerSection {
    /// z of the layer's base (m); omitted for the last layer (no end).
    #[serde(default)]
    pub bottom: Option<f64>,
    /// γ (N/m³); default: the section's `unit_weight`, else ρ|g| of the element.
    #[serde(default)]
    pub unit_weight: Option<f64>,
    /// σ_h/σ_v; default: the section's `k0`.
    #[serde(default)]
    pub k0: Option<K0Value>,
}

/// `[[static.steps]]`.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct StaticStepSection {
    /// Name in reports (default "step N").
    #[serde(default)]
    pub name: Option<String>,
    /// Element sets or regions removed, in order.
    #[serde(default)]
    pub excavate: Vec<String>,
    /// Element sets or regions placed stress-free after the excavation.
    #[serde(default)]
    pub activate: Vec<String>,
    /// Contact interfaces that start to act in this step, bonded at rest in the offset
    /// their sides have reached; until then they are held out of contact (both sides
    /// settle on their own, as fresh concrete that carries no bond yet).
    #[serde(default)]
    pub bond: Vec<String>,
    #[serde(default)]
    pub solver: Option<StepSolver>,
    /// Release the excavation forces in this many increments (relaxation; default 1).
    #[serde(default)]
    pub substeps: Option<usize>,
    #[serde(default)]
    pub tolerance: Option<f64>,
    #[serde(default)]
    pub max_iterations: Option<usize>,
}
