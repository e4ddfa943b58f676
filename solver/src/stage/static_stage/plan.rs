//! The static stage as the model sees it: validated boundary conditions, loads, in-situ
//! method and the sequence of excavation / activation steps (built from the case's
//! `[static]` section by `case/build/static_stage.rs`, or by hand in programs and tests).

use super::linear_solver::LinearSettings;
use crate::boundary::Constraints;

/// How a step is solved.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum StepSolver {
    /// Sparse Cholesky of the assembled initial stiffness: exact for linear elastic
    /// steps; a step whose material yields is refused (its out-of-balance stays).
    Direct,
    /// Dynamic relaxation with the explicit core (plastic-damage, contact).
    Relaxation,
}

impl StepSolver {
    /// Name used in outputs.
    pub fn name(self) -> &'static str {
        match self {
            StepSolver::Direct => "direct",
            StepSolver::Relaxation => "relaxation",
        }
    }
}

/// Damping of the dynamic relaxation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, serde::Deserialize, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum RelaxationDamping {
    /// Kinetic damping: all velocities set to zero at every peak of the kinetic energy
    /// (Cundall 1976; Shrestha & Ghaboussi 1998).
    Kinetic,
    /// Critical mass-proportional damping c = 2ω₀M, ω₀ from the Rayleigh quotient of the
    /// current displacement increment (Underwood 1983).
    Viscous,
}

/// Settings of the dynamic relaxation.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelaxationSettings {
    pub damping: RelaxationDamping,
    /// Fictitious masses M_i = ½ max_d Σ_j |K_(i,d) j| with Δt = 1 (Underwood 1983), for
    /// the relaxation only; otherwise the physical masses with `safety` × the critical step.
    pub mass_scaling: bool,
    /// Safety factor on the critical step without mass scaling.
    pub safety: f64,
    /// Start from the direct elastic solution of the step where the model allows it
    /// (every active contact pair bonded).
    pub predictor: bool,
    /// Iterations between two rows of the history (the last one is always kept).
    pub history_every: usize,
}

impl Default for RelaxationSettings {
    fn default() -> Self {
        Self {
            damping: RelaxationDamping::Kinetic,
            mass_scaling: true,
            safety: 0.9,
            predictor: true,
            history_every: 10,
        }
    }
}

/// Convergence of a step on the out-of-balance ratio ‖f_ext − f_int‖ / max(‖f_ext‖,
/// ‖f_int‖) over the free DOFs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Convergence {
    /// Largest accepted out-of-balance ratio.
    pub tolerance: f64,
    /// Most relaxation iterations before the step is declared not converged.
    pub max_iterations: usize,
}

impl Default for Convergence {
    fn default() -> Self {
        Self {
            tolerance: 1e-5,
            max_iterations: 200_000,
        }
    }
}

/// Named set of elements (a region or an element set of the mesh).
#[derive(Clone, Debug, PartialEq)]
pub struct ElementSet {
    pub name: String,
    /// Global element ids, sorted, unique.
    pub elements: Vec<u32>,
}

/// One excavation / construction step.
#[derive(Clone, Debug, PartialEq)]
pub struct StaticStep {
    pub name: String,
    /// Sets removed at the start of the step, in order.
    pub excavate: Vec<ElementSet>,
    /// Sets placed (stress-free, in the deformed configuration) after the excavation.
    pub activate: Vec<ElementSet>,
    /// Contact interfaces (index in the model's contact system, name) held out of contact
    /// until this step, bonded at rest in it.
    pub bond: Vec<(usize, String)>,
    pub solver: StepSolver,
    /// The release forces are applied in this many equal increments (relaxation).
    pub substeps: usize,
    pub convergence: Convergence,
}

/// Vertical in-situ stress profile: σ_v (compression positive) and K0 = σ_h/σ_v along x
/// and y as functions of z.
#[derive(Clone, Debug, PartialEq)]
pub enum StressProfile {
    /// σ_v = p₀ + Σ γ_k Δz_k from the ground surface down through horizontal layers; the
    /// last layer extends downwards without end. A layer without unit weight uses ρ|g| of
    /// the material of the element the point lies in.
    Layers {
        ground_surface: f64,
        surface_pressure: f64,
        layers: Vec<Layer>,
    },
    /// Piecewise-linear table (z descending): σ_v and K0 interpolated, held constant
    /// outside the table.
    Table { points: Vec<TablePoint> },
}

/// A horizontal layer of [`StressProfile::Layers`], from the previous layer's bottom (or
/// the ground surface) down to `bottom`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Layer {
    /// z of the layer's base (m); −∞ for the last layer.
    pub bottom: f64,
    /// γ (N/m³); `None`: ρ|g| of the element's material.
    pub unit_weight: Option<f64>,
    /// K0 along x and y.
    pub k0: [f64; 2],
}

/// One row of [`StressProfile::Table`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct TablePoint {
    pub z: f64,
    /// Vertical stress, compression positive (Pa).
    pub sigma_v: f64,
    pub k0: [f64; 2],
}

/// How the in-situ stress is established.
#[derive(Clone, Debug, PartialEq)]
pub enum InSitu {
    /// None: the stage starts stress-free (the first step solves whatever loads there are).
    None,
    /// Solve the model under its gravity (and the static loads) with the static boundary
    /// conditions.
    Gravity {
        solver: StepSolver,
        convergence: Convergence,
    },
    /// Set the given stress field at the integration points (as an initial strain), then
    /// equilibrate the out-of-balance that is left with the discrete loads.
    Field {
        profile: StressProfile,
        solver: StepSolver,
        convergence: Convergence,
    },
}

/// A static load that stays on after the static stage (it is handed over to the dynamic
/// stage as a constant nodal load).
#[derive(Clone, Debug, PartialEq)]
pub enum StaticLoad {
    /// The same force on every node of a set (N).
    Nodal { nodes: Vec<u32>, force: [f64; 3] },
    /// Uniform pressure (Pa, compression positive: along the inward normal) on a face set;
    /// consistent nodal forces −p ∫ φⱼ n dA over the faces of active elements.
    Pressure {
        faces: Vec<crate::mesh::Face>,
        pressure: f64,
    },
    /// Uniform traction (Pa) on a face set: t ∫ φⱼ dA over the faces of active elements.
    Traction {
        faces: Vec<crate::mesh::Face>,
        traction: [f64; 3],
    },
}

/// The static stage.
#[derive(Clone, Debug)]
pub struct StaticPlan {
    /// Boundary conditions of the static stage (rollers, fixed base, ...).
    pub constraints: Constraints,
    pub in_situ: InSitu,
    /// Static loads (besides gravity and the nodal loads of the dynamic model at t = 0).
    pub loads: Vec<StaticLoad>,
    pub steps: Vec<StaticStep>,
    /// Elements placed by a step before they were ever active (they start inactive).
    pub initially_inactive: Vec<u32>,
    pub relaxation: RelaxationSettings,
    /// The linear solver of the direct steps and of the relaxation's predictor.
    pub linear: LinearSettings,
    /// Damaged-volume measure of eq. (27): threshold and per-element flag (as `[output]`).
    pub damage_threshold: f64,
    pub damage_per_element: bool,
}

impl StaticPlan {
    /// A plan with the given static constraints and nothing else (no in-situ method, no
    /// loads, no steps).
    pub fn new(constraints: Constraints) -> Self {
        Self {
            constraints,
            in_situ: InSitu::None,
            loads: Vec::new(),
            steps: Vec::new(),
            initially_inactive: Vec::new(),
            relaxation: RelaxationSettings::default(),
            linear: LinearSettings::default(),
            damage_threshold: 0.1,
            damage_per_element: false,
        }
    }

    /// Elements that start inactive: those whose first appearance in the steps is in an
    /// `activate` list.
    pub fn derive_initially_inactive(&mut self, n_elements: usize) {
        let mut seen = vec![false; n_elements];
        let mut inactive = Vec::new();
        for step in &self.steps {
            for set in &step.excavate {
                for &e in &set.elements {
                    seen[e as usize] = true;
                }
            }
            for set in &step.activate {
                for &e in &set.elements {
                    if !seen[e as usize] {
                        inactive.push(e);
                    }
                    seen[e as usize] = true;
                }
            }
        }
        inactive.sort_unstable();
        inactive.dedup();
        self.initially_inactive = inactive;
    }

    /// A readable account of the plan, one line per item (`dcfm check`).
    pub fn describe(&self) -> Vec<String> {
        let mut out = Vec::new();
        let fixed: usize = self
            .constraints
            .fixed
            .iter()
            .map(|m| m.count_ones() as usize)
            .sum();
        out.push(format!("static    {fixed} fixed DOFs in the static stage"));
        let line = match &self.in_situ {
            InSitu::None => "in-situ   none (the stage starts stress-free)".to_string(),
            InSitu::Gravity {
                solver,
                convergence,
            } => format!(
                "in-situ   gravity, {} (tolerance {:.1e})",
                solver.name(),
                convergence.tolerance
            ),
            InSitu::Field {
                profile,
                solver,
                convergence,
            } => {
                let what = match profile {
                    StressProfile::Layers {
                        ground_surface,
                        surface_pressure,
                        layers,
                    } => format!(
                        "K0 field from ground surface z = {ground_surface} m, surface pressure {surface_pressure:.3e} Pa, {} layer(s), K0 {:?}",
                        layers.len(),
                        layers.iter().map(|l| l.k0).collect::<Vec<_>>()
                    ),
                    StressProfile::Table { points } => {
                        format!("σ_v/K0 table of {} points", points.len())
                    }
                };
                format!(
                    "in-situ   {what}; equilibrated by {} (tolerance {:.1e})",
                    solver.name(),
                    convergence.tolerance
                )
            }
        };
        out.push(line);
        for l in &self.loads {
            out.push(match l {
                StaticLoad::Nodal { nodes, force } => {
                    format!("load      {force:?} N on each of {} nodes", nodes.len())
                }
                StaticLoad::Pressure { faces, pressure } => {
                    format!(
                        "load      pressure {pressure:.3e} Pa on {} faces",
                        faces.len()
                    )
                }
                StaticLoad::Traction { faces, traction } => {
                    format!(
                        "load      traction {traction:?} Pa on {} faces",
                        faces.len()
                    )
                }
            });
        }
        if !self.initially_inactive.is_empty() {
            out.push(format!(
                "inactive  {} elements start inactive (placed by a step)",
                self.initially_inactive.len()
            ));
        }
        for (k, s) in self.steps.iter().enumerate() {
            let names = |sets: &[ElementSet]| {
                sets.iter()
                    .map(|s| format!("{} ({} el.)", s.name, s.elements.len()))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let mut line = format!("step {:<4} {}: ", k + 1, s.name);
            if !s.excavate.is_empty() {
                line += &format!("excavate {}; ", names(&s.excavate));
            }
            if !s.activate.is_empty() {
                line += &format!("activate {}; ", names(&s.activate));
            }
            if !s.bond.is_empty() {
                let bond: Vec<&str> = s.bond.iter().map(|(_, n)| n.as_str()).collect();
                line += &format!("bond {}; ", bond.join(", "));
            }
            line += &format!(
                "{}{} (tolerance {:.1e})",
                s.solver.name(),
                if s.substeps > 1 {
                    format!(" in {} substeps", s.substeps)
                } else {
                    String::new()
                },
                s.convergence.tolerance
            );
            out.push(line);
        }
        out
    }
}
