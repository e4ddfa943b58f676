//! The explicit dynamic stage: central difference in leapfrog form with the dynamic
//! contact force correction.
//!
//! The paper writes the scheme as a predictor Ū^{t+Δt} (eq. 4) that ignores contact, a
//! correction U^{t+Δt} = Ū^{t+Δt} + Δt²/2 M⁻¹ R^t (eq. 2) and a velocity (eq. 3). Eq. (3)
//! read literally with eq. (4) has the amplification |λ|² = 1 + ω²Δt²/2 > 1 for an
//! undamped oscillator, i.e. it is unstable; the stable central-difference trajectory with
//! the same predictor/corrector structure is the leapfrog form used here:
//!
//! ```text
//! V̄^{n+½} = V^{n−½} + Δt M⁻¹ (Fⁿ − f_int(Uⁿ) − C V^{n−½})     (predictor, eq. 4)
//! Ū^{n+1} = Uⁿ + Δt V̄^{n+½}
//! U^{n+1} = Ū^{n+1} + Δt² M⁻¹ Rⁿ,  V^{n+½} = V̄^{n+½} + Δt M⁻¹ Rⁿ  (correction, eqs. 2–3)
//! ```
//!
//! The contact force that closes a gap in one step is then R = (Ū_j − Ū_i)/((wᵢ+wⱼ)Δt²)
//! instead of the paper's 2MᵢMⱼ/((Mᵢ+Mⱼ)Δt²) factor — the same physical force
//! (VERIFICATION.md W9), see docs/ARCHITECTURE.md.
//!
//! A step of another length h (the last step of a run whose end is not a multiple of Δt,
//! [`Simulation::step_to`]) is the variable-step central difference (Belytschko, Liu &
//! Moran 2000, §6.2.1): with Δt⁻ the length of the step before,
//!
//! ```text
//! V^{n+½} = V^{n−½} + ½(Δt⁻ + h) M⁻¹ Fⁿ,   U^{n+1} = Uⁿ + h V^{n+½},
//! ```
//!
//! the contact force closing a gap in that step R = ΔU/(w h ½(Δt⁻ + h)), and the work of
//! Fⁿ over the trapezoidal half-intervals ½Δt⁻ V^{n−½} and ½h V^{n+½}. Models with
//! absorbing boundaries (centred dashpots and free-field grids prepared for Δt) take full
//! steps only.
//!
//! With subcycling ([`Simulation::enable_subcycling`], `stage::subcycling`) a node of level
//! L takes the step above with h = Δt⁻ = 2^L Δt at the fine steps n ≡ 0 (mod 2^L) and is
//! interpolated linearly in between; the elements are evaluated only when one of their
//! nodes updates.

use rayon::prelude::*;

use crate::contact::{ContactStepInput, ContactSystem};
use crate::element::groups::{add_internal_forces, ForceSettings, SharedMut};
use crate::error::{DcfmError, Result};
use crate::load::LoadsByNode;
use crate::model::Model;
use crate::stage::contact_overlap::{ContactPredictor, PredictedNode};
use crate::stage::energy::{Energies, EnergyParts};
use crate::stage::subcycling::{Subcycling, SubcyclingSummary};

mod free_node_block;

/// Nodes per chunk of the node loops: fixed, so that reductions are summed in the same
/// order whatever the number of threads.
const NODE_CHUNK: usize = 1024;

/// Touched nodes per parallel task (and per partial energy sum) of the contact correction.
const CONTACT_CHUNK: usize = 256;

/// Bit of `Simulation::node_kind` marking a node of the boundary system.
const BOUNDARY_NODE: u8 = 1 << 3;

/// Per-chunk result of the node pass.
#[derive(Clone, Copy, Debug, Default)]
struct ChunkResult {
    parts: EnergyParts,
    vmax: f64,
    vmax_node: u32,
    nonfinite: bool,
}

impl ChunkResult {
    /// The velocity check of node `i` (largest velocity component `vm`, `nonfinite`
    /// motion), the nodes of a chunk in order: the first non-finite node, else the
    /// fastest.
    #[inline(always)]
    fn check(&mut self, i: usize, vm: f64, nonfinite: bool) {
        if nonfinite {
            if !self.nonfinite {
                self.vmax_node = i as u32;
            }
            self.nonfinite = true;
        } else if vm > self.vmax && !self.nonfinite {
            self.vmax = vm;
            self.vmax_node = i as u32;
        }
    }

    /// Add the result `node` of node `i` alone (formed from a default result): the same
    /// sums and check as forming it here. Its parts are 0 + p, and adding 0 + p to a sum
    /// is adding p (a sum that starts at +0 never becomes −0, and the parts a node does
    /// not touch add +0); its check holds the node's own velocity, or 0 for a node at
    /// rest, which a check already at or above 0 ignores either way.
    #[inline(always)]
    fn merge(&mut self, i: usize, node: &ChunkResult) {
        for (s, x) in self.parts.iter_mut().zip(node.parts) {
            *s += x;
        }
        self.check(i, node.vmax, node.nonfinite);
    }
}

/// Contact forces Rⁿ of `contact` for `input` into `r` (eqs. 5–22); the wall time it took
/// (s), for the benchmarks.
fn contact_forces(
    contact: &mut ContactSystem,
    input: &ContactStepInput,
    r: &mut [[f64; 3]],
) -> Result<f64> {
    let started = std::time::Instant::now();
    contact.compute(input, r)?;
    Ok(started.elapsed().as_secs_f64())
}

/// A model in motion: displacements Uⁿ, half-step velocities V^{n−½}, energies and the
/// scratch buffers of the step (allocated once).
pub struct Simulation {
    pub model: Model,
    /// Time step (s).
    pub dt: f64,
    /// Steps done.
    pub step: u64,
    /// Time tⁿ (s).
    pub time: f64,
    /// Displacements Uⁿ (m).
    pub u: Vec<[f64; 3]>,
    /// Half-step velocities V^{n−½} (m/s).
    pub v: Vec<[f64; 3]>,
    /// Accelerations of the last step (V^{n+½} − V^{n−½})/Δt (m/s²).
    pub a: Vec<[f64; 3]>,
    /// Energies at the last completed step.
    pub energies: Energies,
    /// Wall time spent in the contact phase (stage 4) so far (s), for the benchmarks (beside
    /// the node pass, [`Simulation::set_contact_beside_node_pass`], the phase's own time).
    pub contact_seconds: f64,
    u_next: Vec<[f64; 3]>,
    v_next: Vec<[f64; 3]>,
    f_int: Vec<[f64; 3]>,
    f_damp: Vec<[f64; 3]>,
    f_ext: Vec<[f64; 3]>,
    /// The nodal loads gathered per node (their node sets as at construction).
    loads_by_node: LoadsByNode,
    /// Contact forces Rⁿ (zero except at the nodes listed in `contact_nodes`).
    r: Vec<[f64; 3]>,
    contact_nodes: Vec<u32>,
    /// Scratch of the contact correction: the energy fix-up of each chunk of touched nodes.
    contact_fix_parts: Vec<EnergyParts>,
    /// Index into `model.constraints.prescribed` for each node DOF (u32::MAX: none).
    prescribed_of: Vec<[u32; 3]>,
    /// Per node: its constrained DOF bits, plus [`BOUNDARY_NODE`] for a node of the
    /// boundary system (updated in the boundary pass, not in the node pass).
    node_kind: Vec<u8>,
    /// Slot of each node in the boundary system (u32::MAX: none).
    boundary_slot: Vec<u32>,
    /// Stiffness-proportional damping β of each element group.
    group_beta: Vec<f64>,
    /// Mass-proportional damping α of each node, when the regions differ in α.
    node_alpha: Option<Vec<f64>>,
    chunks: Vec<ChunkResult>,
    /// Largest energy scale seen so far (for the balance check).
    peak_energy: f64,
    /// Consecutive steps with the balance residual above half of `peak_energy`.
    unbalanced_steps: u32,
    /// Energies below this are round-off: 1e-12 × Σ M × c_max² (the energy of strains of
    /// order one is Σ M c²).
    energy_floor: f64,
    /// Largest P-wave speed of the model's materials (m/s).
    max_wave_speed: f64,
    /// Length of the last step taken (s): Δt, or the shortened step of `step_to`.
    last_step: f64,
    /// Every step so far was a full step: the time is `step` × Δt.
    on_grid: bool,
    /// Multi-time-step integration, when enabled.
    subcycling: Option<Subcycling>,
    /// The contact set's predictor, formed before the node pass (module
    /// `contact_overlap`); built with the simulation (or at the first step, for contact
    /// added to the model after it).
    contact_predictor: Option<ContactPredictor<ChunkResult>>,
    /// Solve contact beside the node pass ([`Simulation::set_contact_beside_node_pass`]).
    contact_beside: bool,
}

impl Simulation {
    /// Start from rest (plus the model's initial velocities) with time step `dt`, which
    /// must not exceed `safety` × the critical step (damping included).
    pub fn new(mut model: Model, dt: f64, safety: f64) -> Result<Self> {
        // The shared-mass bound depends on the nodal masses, which a static stage's
        // excavation and the anchors' steel change: bound the step of this model.
        if model.step_bound == crate::model::StepBound::SharedMass {
            model.refresh_stable_step();
        }
        let dt = model.time_step(Some(dt), safety)?;
        Ok(Self::new_unchecked(model, dt))
    }

    /// Like [`Simulation::new`] without the stability check (for tests that probe it).
    pub fn new_unchecked(mut model: Model, dt: f64) -> Self {
        model.refresh_inverse_mass();
        // Every force pass is committed: update the material states in place.
        for g in model.groups.iter_mut() {
            g.set_states_in_place(true);
        }
        let n = model.mesh.n_nodes();
        let mut v = vec![[0.0; 3]; n];
        for (nodes, value) in &model.initial_velocity {
            for &i in nodes {
                v[i as usize] = *value;
            }
        }
        let mut prescribed_of = vec![[u32::MAX; 3]; n];
        for (k, p) in model.constraints.prescribed.iter().enumerate() {
            for &i in &p.nodes {
                prescribed_of[i as usize][p.dof] = k as u32;
            }
        }
        for (i, vi) in v.iter_mut().enumerate() {
            for (d, c) in vi.iter_mut().enumerate() {
                if model.constraints.fixed[i] & (1 << d) != 0 {
                    *c = 0.0;
                }
            }
        }
        let loads_by_node = LoadsByNode::new(&model.nodal_loads);
        let kinetic = kinetic_energy(&v, &model.mass);
        let n_chunks = n.div_ceil(NODE_CHUNK);
        let mut node_kind = model.constraints.constrained.clone();
        let mut boundary_slot = vec![u32::MAX; n];
        let group_beta: Vec<f64> = (0..model.groups.len())
            .map(|g| model.group_damping(g).beta)
            .collect();
        let node_alpha = model.node_alpha();
        if let Some(b) = model.boundaries.as_mut() {
            b.prepare(dt, &model.mass, &model.constraints.constrained);
            for (slot, &i) in b.nodes.iter().enumerate() {
                node_kind[i as usize] |= BOUNDARY_NODE;
                boundary_slot[i as usize] = slot as u32;
            }
        }
        Self {
            group_beta,
            node_alpha,
            node_kind,
            boundary_slot,
            dt,
            step: 0,
            time: 0.0,
            u: vec![[0.0; 3]; n],
            v,
            a: vec![[0.0; 3]; n],
            energies: Energies {
                kinetic,
                initial_kinetic: kinetic,
                ..Default::default()
            },
            u_next: vec![[0.0; 3]; n],
            v_next: vec![[0.0; 3]; n],
            f_int: vec![[0.0; 3]; n],
            f_damp: vec![[0.0; 3]; n],
            f_ext: vec![[0.0; 3]; n],
            loads_by_node,
            r: vec![[0.0; 3]; n],
            contact_nodes: Vec::new(),
            contact_fix_parts: Vec::new(),
            prescribed_of,
            chunks: vec![ChunkResult::default(); n_chunks],
            contact_seconds: 0.0,
            peak_energy: 0.0,
            unbalanced_steps: 0,
            energy_floor: 1e-12
                * model.mass.iter().sum::<f64>()
                * model
                    .groups
                    .iter()
                    .map(|g| g.material.elastic().p_wave_speed().powi(2))
                    .fold(0.0, f64::max),
            max_wave_speed: model
                .groups
                .iter()
                .map(|g| g.material.elastic().p_wave_speed())
                .fold(0.0, f64::max),
            last_step: dt,
            on_grid: true,
            subcycling: None,
            contact_predictor: model
                .contact
                .as_ref()
                .filter(|c| !c.is_empty())
                .map(|c| ContactPredictor::new(c, n)),
            contact_beside: true,
            model,
        }
    }

    /// Whether the contact solve runs beside the node pass (module `contact_overlap`; on
    /// by default, and always off with subcycling). Off: every node's predictor in the
    /// node pass, then the contact solve, as the step was first written — the same step
    /// bit for bit (`solver/tests/contact_beside_node_pass.rs`); for that comparison and
    /// for benchmarks.
    pub fn set_contact_beside_node_pass(&mut self, on: bool) {
        self.contact_beside = on;
    }

    /// Whether steps shorter than Δt are taken exactly ([`Simulation::step_to`]): not with
    /// absorbing boundaries, whose centred dashpots and free-field grids are prepared for
    /// Δt.
    pub fn can_shorten_steps(&self) -> bool {
        self.model.boundaries.is_none() && self.subcycling.is_none()
    }

    /// Turn on multi-time-step integration with steps up to 2^`max_level` Δt
    /// (`stage::subcycling`), `safety` the factor the case's Δt was chosen with. Only at
    /// a synchronous state (every node at the same time: before the first step, or a
    /// state restored from a checkpoint). Refuses (an error naming `time.subcycling`)
    /// models with stiffness-proportional damping (anchor bars: their host elements' nodes step at Δt).
    pub fn enable_subcycling(&mut self, max_level: u8, safety: f64) -> Result<&SubcyclingSummary> {
        let mut s = crate::stage::subcycling::plan(
            &self.model,
            self.dt,
            safety,
            max_level,
            self.loads_by_node.nodes(),
        )?;
        s.u_end = self.u.clone();
        self.subcycling = Some(s);
        Ok(&self.subcycling.as_ref().expect("just set").summary)
    }

    /// The subcycling levels, when enabled.
    pub fn subcycling(&self) -> Option<&SubcyclingSummary> {
        self.subcycling.as_ref().map(|s| &s.summary)
    }

    /// Fine steps of one subcycling cycle (2^top, top the largest node level; 1 without
    /// subcycling): the states at multiples of it are synchronous.
    pub fn cycle_steps(&self) -> u64 {
        self.subcycling.as_ref().map_or(1, |s| 1u64 << s.top)
    }

    /// Element evaluations per fine step, on average over a cycle (the number of
    /// elements without subcycling).
    pub fn element_updates_per_step(&self) -> f64 {
        let n = self.model.n_elements() as f64;
        self.subcycling
            .as_ref()
            .map_or(n, |s| n * s.summary.element_update_fraction)
    }

    /// Whether the state lies on the step grid (every step so far a full step, the time
    /// `step` × Δt): what a checkpoint can hold.
    pub fn on_grid(&self) -> bool {
        self.on_grid
            && self
                .subcycling
                .as_ref()
                .is_none_or(|s| s.synchronous(self.step))
    }

    /// Length of the last step taken (s): Δt, or the shortened step of
    /// [`Simulation::step_to`].
    pub fn last_step(&self) -> f64 {
        self.last_step
    }

    /// The state was restored from a checkpoint (always on the step grid).
    pub(crate) fn restored_on_grid(&mut self) {
        self.on_grid = true;
        self.last_step = self.dt;
        if let Some(s) = self.subcycling.as_mut() {
            s.u_end.copy_from_slice(&self.u);
        }
    }

    /// Start the energy account afresh from the current velocities (after they were set
    /// by hand, e.g. an initial velocity field that no node set describes).
    pub fn restart_energy_account(&mut self) {
        let k = kinetic_energy(&self.v, &self.model.mass);
        self.energies = Energies {
            kinetic: k,
            initial_kinetic: k,
            ..Default::default()
        };
        self.peak_energy = 0.0;
    }

    /// Internal forces f_int(Uⁿ) (and β K0 V^{n−½}) of every element, colour by colour,
    /// into the internal-force buffer ([`Simulation::internal_force`]). Material states
    /// are updated in place (committed by the pass itself).
    pub fn internal_forces(&mut self) {
        let any_beta = self.group_beta.iter().any(|&b| b > 0.0);
        self.f_int
            .par_iter_mut()
            .with_min_len(4096)
            .for_each(|f| *f = [0.0; 3]);
        if any_beta {
            self.f_damp
                .par_iter_mut()
                .with_min_len(4096)
                .for_each(|f| *f = [0.0; 3]);
        }
        let sub = self.subcycling.as_ref();
        let group_beta = &self.group_beta;
        let (dt, step) = (self.dt, self.step);
        add_internal_forces(
            &mut self.model.groups,
            self.model.n_colours,
            &self.u,
            &self.v,
            |k| ForceSettings {
                beta: group_beta[k],
                dt,
                due: sub.map(|s| s.due(k, step)),
            },
            &mut self.f_int,
            &mut self.f_damp,
        );
        let model = &mut self.model;
        if let Some(anchors) = model.anchors.as_mut() {
            anchors.add_internal_forces(&model.mesh, &self.u, &mut self.f_int);
        }
    }

    /// External nodal loads Fⁿ into `f_ext`.
    fn external_forces(&mut self) {
        self.loads_by_node
            .apply(&self.model.nodal_loads, self.time, &mut self.f_ext);
    }

    /// One step tⁿ → tⁿ⁺¹, in this order:
    /// 1. internal forces from Uⁿ (element kernels + material update), damping forces;
    /// 2. external loads Fⁿ and gravity;
    /// 3. predictor V̄^{n+½}, Ū^{n+1} for every node as if no contact existed (eq. 4), with
    ///    fixed and prescribed DOFs imposed;
    /// 4. contact forces Rⁿ from the predictor (eqs. 5–22) — none without interfaces; it
    ///    reads the predictor of the contact set alone, which is formed first, so that
    ///    the serial contact solve runs beside the rest of step 3 (`contact_overlap`);
    /// 5. correction U^{n+1} = Ū + Δt² M⁻¹ R, V^{n+½} = V̄ + Δt M⁻¹ R (eqs. 2–3);
    /// 6. energies at tⁿ, instability check, commit of material states.
    pub fn step(&mut self) -> Result<()> {
        self.advance(self.dt, None)
    }

    /// One step that ends exactly at `t_end`, at most Δt after the current time: a full
    /// step when `t_end` is one Δt later (within 10⁻⁹ Δt; the time is then `t_end` itself),
    /// else a shortened step h = `t_end` − tⁿ by the variable-step central difference
    /// (module docs). A model that cannot shorten its steps
    /// ([`Simulation::can_shorten_steps`]) takes a full step instead, past `t_end`.
    pub fn step_to(&mut self, t_end: f64) -> Result<()> {
        let h = t_end - self.time;
        if !(h > 0.0 && h <= self.dt * (1.0 + 1e-9)) {
            return Err(DcfmError::invalid(
                "",
                "time.end",
                t_end,
                format!(
                    "a time after the current time {:e} s and at most one step Δt = {:e} s later",
                    self.time, self.dt
                ),
            ));
        }
        if crate::stage::schedule::is_full_step(self.time, t_end, self.dt) {
            self.advance(self.dt, Some(t_end))
        } else if self.can_shorten_steps() {
            self.advance(h, Some(t_end))
        } else {
            self.advance(self.dt, None)
        }
    }

    /// One step of length `h` (Δt, or shorter from [`Simulation::step_to`]), ending at
    /// `t_end` when given.
    fn advance(&mut self, h: f64, t_end: Option<f64>) -> Result<()> {
        // 1–2.
        self.internal_forces();
        self.external_forces();
        if let Some(b) = self.model.boundaries.as_mut() {
            b.begin_step(self.time, self.dt);
        }
        // 3. Predictor + energies of the uncorrected motion, in fixed chunks.
        let dt = self.dt;
        let t = self.time;
        // Velocity increment ½(Δt⁻ + h) (Δt for a full step after a full step).
        let dt_prev = self.last_step;
        let dt_v = if h == dt && dt_prev == dt {
            dt
        } else {
            0.5 * (dt_prev + h)
        };
        let alpha = self.model.damping.alpha;
        let gravity = self
            .model
            .gravity
            .as_ref()
            .map(|g| {
                let h = g.history.value(t);
                g.acceleration.map(|a| a * h)
            })
            .unwrap_or([0.0; 3]);
        let ctx = NodeContext {
            dt,
            dt_v,
            dt_u: h,
            dt_prev,
            uniform: h == dt && dt_prev == dt,
            t,
            alpha,
            node_alpha: self.node_alpha.as_deref(),
            gravity,
            mass: &self.model.mass,
            inv_mass: &self.model.inv_mass,
            constrained: &self.model.constraints.constrained,
            node_kind: &self.node_kind,
            fixed: &self.model.constraints.fixed,
            prescribed: &self.model.constraints.prescribed,
            prescribed_of: &self.prescribed_of,
            u: &self.u,
            v: &self.v,
            f_int: &self.f_int,
            f_damp: &self.f_damp,
            f_ext: &self.f_ext,
            // f_damp is written only for groups with β > 0 (`internal_forces`) and f_ext
            // only at loaded nodes (`external_forces`): otherwise they hold zeros.
            damping_forces: self.group_beta.iter().any(|&b| b > 0.0),
            external_forces: !self.loads_by_node.nodes().is_empty(),
        };
        // Subcycling: the node levels and one context per level (steps 2^L Δt, full steps
        // only: `can_shorten_steps`).
        let step = self.step;
        let levels = self.subcycling.as_ref().map(|s| s.node_level.as_slice());
        let level_ctx: [NodeContext; crate::stage::subcycling::MAX_LEVEL as usize + 1] =
            std::array::from_fn(|l| {
                let hl = dt * (1u64 << l) as f64;
                NodeContext {
                    dt_v: hl,
                    dt_u: hl,
                    dt_prev: hl,
                    uniform: true,
                    ..ctx
                }
            });
        let n = self.u.len();
        let boundaries = self.model.boundaries.as_ref();
        let boundary_slot = &self.boundary_slot;
        // The predictor of node i: its Ū^{n+1}, V̄^{n+½} and acceleration, its energy parts
        // and velocity check added to `out` (the node pass's chunk result).
        let node = |i: usize,
                    ui: &mut [f64; 3],
                    vi: &mut [f64; 3],
                    ai: &mut [f64; 3],
                    out: &mut ChunkResult| {
            let kind = ctx.node_kind[i];
            let level = levels.map_or(0, |l| l[i]);
            let mut step_v = dt_v;
            if level > 0 {
                // A coarse node (free by construction): its own step when due, else
                // nothing here (interpolated after the pass).
                if !crate::element::groups::Due::at(step, level) {
                    return;
                }
                let c = &level_ctx[level as usize];
                c.predict_free(i, ui, vi, &mut out.parts);
                step_v = c.dt_v;
            } else if kind == 0 {
                ctx.predict_free(i, ui, vi, &mut out.parts);
            } else if kind & BOUNDARY_NODE != 0 {
                // A boundary node: the leapfrog with the boundary forces and the
                // centred dashpot (a contact force is added in step 5).
                let bs = boundaries.expect("boundary nodes come with boundaries");
                let b = boundary_slot[i] as usize;
                let (u_b, v_b, p) = ctx.boundary_node(i, bs, b, &[0.0; 3]);
                *ui = u_b;
                *vi = v_b;
                for (s, x) in out.parts.iter_mut().zip(p) {
                    *s += x;
                }
                step_v = dt;
            } else {
                ctx.predict(i, ui, vi);
                let p = ctx.energy_parts(i, vi, &[0.0; 3]);
                for (s, x) in out.parts.iter_mut().zip(p) {
                    *s += x;
                }
            }
            // Acceleration (V^{n+½} − V^{n−½})/Δt of the uncorrected motion;
            // recomputed at the contact nodes after the correction.
            let vo = &ctx.v[i];
            *ai = std::array::from_fn(|d| (vi[d] - vo[d]) / step_v);
            let vm = vi[0].abs().max(vi[1].abs()).max(vi[2].abs());
            out.check(i, vm, !vm.is_finite() || !ui.iter().all(|x| x.is_finite()));
        };
        // With contact and no subcycling, the contact set's predictor first (module
        // `contact_overlap`), so that the contact solve can run beside the node pass.
        let contact = self.model.contact.as_mut().filter(|c| !c.is_empty());
        if contact.is_some() && self.contact_predictor.is_none() {
            let c = contact.as_deref().expect("checked");
            self.contact_predictor = Some(ContactPredictor::new(c, n));
        }
        let beside = self.contact_beside && contact.is_some() && levels.is_none();
        let predictor = self.contact_predictor.as_mut().filter(|_| beside);
        let predicted = match predictor {
            Some(p) => {
                p.predict(CONTACT_CHUNK, |i| {
                    let mut result = ChunkResult::default();
                    let (mut u, mut v, mut a) = ([0.0; 3], [0.0; 3], [0.0; 3]);
                    node(i, &mut u, &mut v, &mut a, &mut result);
                    PredictedNode { u, v, a, result }
                });
                Some(&*p)
            }
            None => None,
        };
        // 3. The node pass (the contact set's nodes taken from the pre-pass, at their
        // place in the chunk sums).
        let (u_next, v_next, accel, chunks) = (
            &mut self.u_next,
            &mut self.v_next,
            &mut self.a,
            &mut self.chunks,
        );
        let mut node_pass = || {
            u_next
                .par_chunks_mut(NODE_CHUNK)
                .zip(v_next.par_chunks_mut(NODE_CHUNK))
                .zip(accel.par_chunks_mut(NODE_CHUNK))
                .zip(chunks.par_iter_mut())
                .enumerate()
                .for_each(|(ci, (((un, vn), an), res))| {
                    let mut out = ChunkResult::default();
                    let first = ci * NODE_CHUNK;
                    // A free node at the finest level that is not in the contact set's
                    // pre-pass: its runs go through the block predictor.
                    let free = |i: usize| {
                        levels.is_none()
                            && ctx.node_kind[i] == 0
                            && predicted.is_none_or(|p| p.slot[i] == u32::MAX)
                    };
                    let len = un.len();
                    let mut k = 0;
                    while k < len {
                        let i = first + k;
                        if free(i) {
                            let start = k;
                            while k < len && free(first + k) {
                                k += 1;
                            }
                            ctx.predict_free_run(
                                i,
                                &mut un[start..k],
                                &mut vn[start..k],
                                &mut an[start..k],
                                &mut out,
                            );
                            continue;
                        }
                        let (ui, vi, ai) = (&mut un[k], &mut vn[k], &mut an[k]);
                        k += 1;
                        if let Some(p) = predicted {
                            let j = p.slot[i];
                            if j != u32::MAX {
                                let q = &p.predicted[j as usize];
                                (*ui, *vi, *ai) = (q.u, q.v, q.a);
                                out.merge(i, &q.result);
                                continue;
                            }
                        }
                        node(i, ui, vi, ai, &mut out);
                    }
                    *res = out;
                });
        };
        // 4. Contact forces Rⁿ from the predictor (eqs. 5–22).
        for &i in &self.contact_nodes {
            self.r[i as usize] = [0.0; 3];
        }
        self.contact_nodes.clear();
        // The contact forces enter U^{n+1} through h·½(Δt⁻ + h) M⁻¹ R (Δt² M⁻¹ R for full
        // steps): the contact solver's Δt² is that product.
        let dt_contact = if ctx.uniform { dt } else { (h * dt_v).sqrt() };
        let (r, coords) = (&mut self.r, &self.model.mesh.coords);
        let mut sub_kinetic = 0.0;
        let contact_result = match (contact, predicted) {
            (Some(contact), Some(p)) => {
                let input = ContactStepInput {
                    step,
                    time: t,
                    dt: dt_contact,
                    inv_mass: ctx.inv_mass,
                    coords,
                    u_old: ctx.u,
                    u_pred: &p.u_pred,
                    v_pred: &p.v_pred,
                };
                let (result, ()) = rayon::join(|| contact_forces(contact, &input, r), node_pass);
                Some(result)
            }
            (contact, _) => {
                node_pass();
                // 3a. Coarse nodes: keep U^{n+2^L} of those that updated, and set every
                // coarse node's displacement at t^{n+1} by linear interpolation (serial,
                // fixed order); those that did not update keep their velocity and count
                // ½ M |V|² as kinetic.
                if let Some(s) = self.subcycling.as_mut() {
                    let next = step + 1;
                    for &i in &s.coarse_nodes {
                        let i = i as usize;
                        let l = s.node_level[i];
                        if crate::element::groups::Due::at(step, l) {
                            s.u_end[i] = self.u_next[i];
                        } else {
                            let v = self.v[i];
                            self.v_next[i] = v;
                            sub_kinetic += 0.5
                                * self.model.mass[i]
                                * (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
                        }
                        let period = 1u64 << l;
                        let left = (period - next % period) % period;
                        self.u_next[i] = if left == 0 {
                            s.u_end[i]
                        } else {
                            let tau = left as f64 * dt;
                            let (ue, v) = (s.u_end[i], self.v_next[i]);
                            std::array::from_fn(|d| ue[d] - tau * v[d])
                        };
                    }
                }
                contact.map(|contact| {
                    let input = ContactStepInput {
                        step,
                        time: t,
                        dt: dt_contact,
                        inv_mass: &self.model.inv_mass,
                        coords,
                        u_old: &self.u,
                        u_pred: &self.u_next,
                        v_pred: &self.v_next,
                    };
                    contact_forces(contact, &input, r)
                })
            }
        };
        debug_assert_eq!(n, self.u_next.len());
        if let Some(result) = contact_result {
            let seconds = result?;
            self.contact_seconds += seconds;
            let contact = self.model.contact.as_ref().expect("contact solved");
            self.contact_nodes
                .extend_from_slice(contact.touched_nodes());
        }
        // 5. Correction at the touched nodes (with the energy fix-up), in fixed chunks of
        // the touched-node list: each node's new motion on its own, the energy fix-up
        // summed per chunk and the chunks in order (the same sums on any thread count).
        // Each touched node's corrected Ū, V̄ and its acceleration are written in place:
        // the list holds each node once (`ContactSystem::touched_nodes`, its stamps; the
        // property test `contact_properties` checks it every step), so each entry is read
        // and written by one iteration alone.
        let nodes = &self.contact_nodes;
        assert!(
            nodes.iter().all(|&i| (i as usize) < n),
            "touched node outside the mesh"
        );
        let fix_parts = &mut self.contact_fix_parts;
        fix_parts.clear();
        fix_parts.resize(nodes.len().div_ceil(CONTACT_CHUNK), [0.0; 13]);
        {
            let u_next = SharedMut(self.u_next.as_mut_ptr());
            let v_next = SharedMut(self.v_next.as_mut_ptr());
            let accel = SharedMut(self.a.as_mut_ptr());
            let r = &self.r;
            let boundary_slot = &self.boundary_slot;
            let boundaries = self.model.boundaries.as_ref();
            let inv_mass = &self.model.inv_mass;
            fix_parts
                .par_iter_mut()
                .zip(nodes.par_chunks(CONTACT_CHUNK))
                .for_each(|(fix, ids)| {
                    for &i in ids {
                        let i = i as usize;
                        // SAFETY: i < n (asserted) and listed once: no other iteration
                        // reads or writes entry i of these arrays.
                        let (u_i, v_i, a_i) =
                            unsafe { (&mut *u_next.at(i), &mut *v_next.at(i), &mut *accel.at(i)) };
                        let slot = boundary_slot[i];
                        let (un, vn, before, after) = if slot != u32::MAX {
                            // A boundary node: its update with the contact force as one
                            // more force (the dashpot reacts to it within the step).
                            let bs = boundaries.expect("slot of a boundary node");
                            let (_, _, before) = ctx.boundary_node(i, bs, slot as usize, &[0.0; 3]);
                            let (un, vn, after) = ctx.boundary_node(i, bs, slot as usize, &r[i]);
                            (un, vn, before, after)
                        } else {
                            let w = inv_mass[i];
                            let before = ctx.energy_parts(i, v_i, &[0.0; 3]);
                            let (mut un, mut vn) = (*u_i, *v_i);
                            for d in 0..3 {
                                un[d] += h * dt_v * w * r[i][d];
                                vn[d] += dt_v * w * r[i][d];
                            }
                            (un, vn, before, ctx.energy_parts(i, &vn, &r[i]))
                        };
                        (*u_i, *v_i) = (un, vn);
                        // The acceleration of the corrected motion.
                        let vo = &ctx.v[i];
                        *a_i = std::array::from_fn(|d| (vn[d] - vo[d]) / dt_v);
                        for k in 0..13 {
                            fix[k] += after[k] - before[k];
                        }
                    }
                });
        }
        let mut contact_fix: EnergyParts = [0.0; 13];
        for part in fix_parts.iter() {
            for k in 0..13 {
                contact_fix[k] += part[k];
            }
        }
        // 6. Energies, instability check.
        let mut parts: EnergyParts = [0.0; 13];
        let mut worst: Option<(u32, bool, f64)> = None;
        for c in &self.chunks {
            for k in 0..13 {
                parts[k] += c.parts[k];
            }
            if c.nonfinite {
                worst = Some((c.vmax_node, true, f64::NAN));
                break;
            }
            if worst.is_none_or(|w| c.vmax > w.2) {
                worst = Some((c.vmax_node, false, c.vmax));
            }
        }
        for k in 0..13 {
            parts[k] += contact_fix[k];
        }
        parts[0] += sub_kinetic;
        let e = &mut self.energies;
        e.advance(&parts);
        if let Some((node, true, _)) = worst {
            return Err(self.instability(node as usize, "non-finite displacement or velocity"));
        }
        let scale = e.scale();
        self.peak_energy = self.peak_energy.max(scale);
        let (vmax_node, vmax) = worst.map_or((0, 0.0), |w| (w.0 as usize, w.2));
        if vmax > 0.5 * self.max_wave_speed {
            return Err(self.instability(
                vmax_node,
                &format!(
                    "velocity {vmax:.3e} m/s above half the largest wave speed ({:.1} m/s): strains of order one",
                    self.max_wave_speed
                ),
            ));
        }
        // The balance is O(Δt²) in absolute terms; where the motion itself is only a few
        // steps old (a node just released, all energies at round-off) that can be a large
        // fraction of the energies, so only a residual that stays above half the largest
        // energy for 10 steps in a row (a growing instability) stops the run, and only once
        // the energies rise above round-off (`energy_floor`).
        let residual = e.residual();
        if self.peak_energy > self.energy_floor && residual.abs() > 0.5 * self.peak_energy {
            self.unbalanced_steps += 1;
        } else {
            self.unbalanced_steps = 0;
        }
        if self.step > 20 && self.unbalanced_steps >= 10 {
            return Err(self.instability(
                vmax_node,
                &format!(
                    "energy balance lost for 10 steps (residual {residual:.3e} J against a largest energy of {:.3e} J)",
                    self.peak_energy
                ),
            ));
        }
        // Commit (the accelerations were set in the node pass and, at the touched nodes,
        // in the correction).
        std::mem::swap(&mut self.u, &mut self.u_next);
        std::mem::swap(&mut self.v, &mut self.v_next);
        match self.subcycling.as_ref() {
            None => {
                for g in self.model.groups.iter_mut() {
                    g.commit_states();
                }
            }
            Some(s) => {
                for (k, g) in self.model.groups.iter_mut().enumerate() {
                    g.commit_due(s.due(k, step));
                }
            }
        }
        if let Some(anchors) = self.model.anchors.as_mut() {
            anchors.commit(dt_v, h, alpha);
        }
        self.step += 1;
        self.on_grid &= h == dt;
        self.last_step = h;
        self.time = match t_end {
            Some(end) => end,
            None if self.on_grid => (self.step as f64) * dt,
            None => t + h,
        };
        Ok(())
    }

    /// After a step that the instability check stopped ([`DcfmError::Unstable`]): take
    /// the state that step reached — U^{n+1} and V^{n+½} as they were checked, every node
    /// computed — in place of the last committed one, at step n + 1 and time tⁿ + Δt, so
    /// that the failure frame of a failed run shows the diverging motion
    /// (docs/outputs.md, "A failed run"). The material states are those of the failed
    /// step's force pass (at Uⁿ, updated in place, as after any step); accelerations and
    /// energies stay those of step n. The simulation must not step again after this.
    pub fn adopt_failed_step(&mut self) {
        std::mem::swap(&mut self.u, &mut self.u_next);
        std::mem::swap(&mut self.v, &mut self.v_next);
        self.step += 1;
        self.time += self.dt;
    }

    /// The error of an instability found at `node`, with its likely cause read from what
    /// is large there (issue 13 item 3), in this order:
    /// 1. the step above a stability limit — and which term sets that limit: the elements
    ///    (the limiting element), the anchor bars, the absorbing boundaries' springs, the
    ///    free-field grids or Rayleigh damping (α, β);
    /// 2. an element around the node inverted (a corner Jacobian of the deformed element
    ///    ≤ 0);
    /// 3. a material update that diverged (a non-finite stress, or a plastic-damage
    ///    stress far above the material's strength);
    /// 4. strains of order one (a small-strain model driven far outside its range);
    /// 5. heavy Rayleigh damping (ξ at the highest mode near its limit), a contact
    ///    interface or an absorbing boundary at the node;
    ///
    /// else a growth whose cause the state does not show.
    fn instability(&self, node: usize, what: &str) -> DcfmError {
        DcfmError::Unstable {
            step: self.step,
            time: self.time,
            node,
            what: what.to_string(),
            cause: self.instability_cause(node),
        }
    }

    fn instability_cause(&self, node: usize) -> String {
        let model = &self.model;
        let dt = self.dt;
        let (alpha, beta) = model.max_damping();
        // 1. Above a limit: walk the terms in the order they enter the limit.
        let with_damping = model.critical_step_with_damping();
        if dt > with_damping * (1.0 + 1e-9) {
            let mut elements = model.stable.critical;
            let anchors_w2 = model
                .anchors
                .as_ref()
                .map_or(0.0, |a| a.omega_squared_bound(&model.mesh, &model.mass));
            if anchors_w2 > 0.0 {
                // model.stable.critical already holds the anchors (Weyl's bound).
                let w2 = (2.0 / elements).powi(2) - anchors_w2;
                if w2 > 0.0 {
                    elements = 2.0 / w2.sqrt();
                }
            }
            let limits = [
                (
                    elements,
                    format!(
                        "the elements' limit (element {}, length {:.3e} m, c_p {:.1} m/s)",
                        model.stable.element, model.stable.length, model.stable.speed
                    ),
                ),
                (
                    model.stable.critical,
                    "the anchor bars' stiffness".to_string(),
                ),
                (
                    model.critical_step(),
                    "the absorbing boundaries' springs or the free-field grids".to_string(),
                ),
                (
                    with_damping,
                    format!("Rayleigh damping (largest α = {alpha:.3e} 1/s, β = {beta:.3e} s)"),
                ),
            ];
            let (limit, term) = limits
                .iter()
                .find(|(l, _)| dt > *l * (1.0 + 1e-9))
                .expect("dt is above the last limit");
            return format!(
                "time step {dt:.4e} s above the stable step {limit:.4e} s set by {term} \
                 (the step with every term: {with_damping:.4e} s); lower time.dt or time.safety"
            );
        }
        // 2.–4. The elements around the node, in the last finite configuration.
        let u_at = |i: usize| {
            let n = self.u_next[i];
            if n.iter().all(|x| x.is_finite()) {
                n
            } else {
                self.u[i]
            }
        };
        let mut worst_strain: Option<(usize, f64)> = None;
        for (e, conn) in model.mesh.elements.iter().enumerate() {
            if !conn.contains(&(node as u32)) {
                continue;
            }
            let (g, le) = model.element_location[e];
            let Some(group) = model.groups.get(g as usize) else {
                continue;
            };
            if group.elements.get(le as usize) != Some(&(e as u32)) {
                continue; // not active (excavated or not yet placed)
            }
            let x0 = model.mesh.element_coords(e);
            let x: [[f64; 3]; 8] = std::array::from_fn(|a| {
                let u = u_at(conn[a] as usize);
                std::array::from_fn(|d| x0[a][d] + u[d])
            });
            for (k, xi) in crate::mesh::hex8_shape::NODE_XI.iter().enumerate() {
                let dn = crate::mesh::hex8_shape::shape_derivatives(xi);
                let (_, det) = crate::mesh::hex8_shape::jacobian(&x, &dn);
                if det.is_nan() || det <= 0.0 {
                    return format!(
                        "element {e} (region '{}') inverted: its Jacobian at corner {k} is {det:.3e} \
                         in the deformed configuration — the motion there is too large for the \
                         mesh (refine it, check the loads, the supports and the contact there)",
                        group.name
                    );
                }
            }
            let (eps, sig) = group.strain_stress_of(le as usize, &self.u);
            let young = group.material.elastic().young;
            let smax = sig.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            let emax = eps.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            if !(smax.is_finite() && emax.is_finite())
                || (group.material.has_damage() && smax > 0.1 * young)
            {
                return format!(
                    "the {} update of element {e} (region '{}') diverged (stress {smax:.3e} Pa \
                     against E = {young:.3e} Pa): check the material's strengths and fracture \
                     energies (units), or lower time.safety",
                    if group.material.has_damage() {
                        "plastic-damage"
                    } else {
                        "material"
                    },
                    group.name
                );
            }
            if worst_strain.is_none_or(|(_, w)| emax > w) {
                worst_strain = Some((e, emax));
            }
        }
        if let Some((e, emax)) = worst_strain.filter(|&(_, w)| w > 0.1) {
            return format!(
                "strains of order one in element {e} (largest component {emax:.3e}): the \
                 small-strain model is driven far outside its range there — check the loads, \
                 the prescribed motions and the supports"
            );
        }
        // 5. What else acts at the node.
        let omega = 2.0 / model.critical_step();
        let xi = 0.5 * (alpha / omega + beta * omega);
        if xi > 0.5 {
            return format!(
                "heavy Rayleigh damping: ξ = {xi:.2} at the highest mode (α = {alpha:.3e} 1/s, \
                 β = {beta:.3e} s) takes the step close to its limit; lower the damping or \
                 time.safety"
            );
        }
        if let Some((k, _, _)) = model
            .contact
            .as_ref()
            .and_then(|c| c.locate_node(node as u32))
        {
            let name = model
                .contact
                .as_ref()
                .map(|c| c.interface_names()[k].clone());
            return format!(
                "the node is on contact interface '{}': check that its surfaces face each \
                 other and are not driven into each other by prescribed motions",
                name.unwrap_or_default()
            );
        }
        if self.boundary_slot.get(node).is_some_and(|&s| s != u32::MAX) {
            return "the node is on an absorbing boundary: check its springs (distance, \
                    alpha_n, alpha_t) and its material"
                .to_string();
        }
        "a growth without a large strain, an inverted element or a step above a limit \
         there; lower time.safety and check the loads and the mesh near this node"
            .to_string()
    }

    /// Run `n` steps.
    pub fn run_steps(&mut self, n: u64) -> Result<()> {
        for _ in 0..n {
            self.step()?;
        }
        Ok(())
    }

    /// Exact elastic strain energy of the current displacements (linear elastic groups).
    pub fn elastic_strain_energy(&self) -> f64 {
        self.model
            .groups
            .iter()
            .map(|g| g.elastic_strain_energy(&self.u))
            .sum()
    }

    /// Full-step velocity estimate at tⁿ for output: the last half-step velocity V^{n−½}.
    pub fn velocity(&self) -> &[[f64; 3]] {
        &self.v
    }

    /// Internal force vector of the last step (for reactions and checks).
    pub fn internal_force(&self) -> &[[f64; 3]] {
        &self.f_int
    }
}

/// ½ Σ M |v|².
fn kinetic_energy(v: &[[f64; 3]], mass: &[f64]) -> f64 {
    v.iter()
        .zip(mass)
        .map(|(vi, m)| 0.5 * m * (vi[0] * vi[0] + vi[1] * vi[1] + vi[2] * vi[2]))
        .sum()
}

/// Read-only data of the node pass.
#[derive(Clone, Copy)]
struct NodeContext<'a> {
    /// The full step Δt (the boundary nodes' updates, prepared for it).
    dt: f64,
    /// Velocity increment ½(Δt⁻ + h) of this step.
    dt_v: f64,
    /// Length h of this step (displacement increment U^{n+1} − Uⁿ = h V^{n+½}).
    dt_u: f64,
    /// Length Δt⁻ of the step before (the work over ½Δt⁻ V^{n−½}).
    dt_prev: f64,
    /// Full steps before and now: h = Δt⁻ = Δt.
    uniform: bool,
    t: f64,
    alpha: f64,
    node_alpha: Option<&'a [f64]>,
    gravity: [f64; 3],
    mass: &'a [f64],
    inv_mass: &'a [f64],
    constrained: &'a [u8],
    node_kind: &'a [u8],
    fixed: &'a [u8],
    prescribed: &'a [crate::boundary::Prescribed],
    prescribed_of: &'a [[u32; 3]],
    u: &'a [[f64; 3]],
    v: &'a [[f64; 3]],
    f_int: &'a [[f64; 3]],
    f_damp: &'a [[f64; 3]],
    f_ext: &'a [[f64; 3]],
    /// Whether `f_damp` may hold a non-zero value (else it is all +0).
    damping_forces: bool,
    /// Whether `f_ext` may hold a non-zero value (else it is all +0).
    external_forces: bool,
}

impl NodeContext<'_> {
    /// Mass-proportional damping α of node i.
    #[inline(always)]
    fn alpha_at(&self, i: usize) -> f64 {
        match self.node_alpha {
            Some(a) => a[i],
            None => self.alpha,
        }
    }

    /// Force on DOF d of node i except the reaction: Fⁿ + M g − f_int − f_damp − αM V^{n−½} + R.
    #[inline(always)]
    fn applied_force(&self, i: usize, d: usize, r: &[f64; 3]) -> f64 {
        let m = self.mass[i];
        self.f_ext[i][d] + m * self.gravity[d]
            - self.f_int[i][d]
            - self.f_damp[i][d]
            - self.alpha_at(i) * m * self.v[i][d]
            + r[d]
    }

    /// Predictor of node i (eq. 4): V̄^{n+½} and Ū^{n+1}, constraints imposed (a
    /// prescribed DOF moves by its history over [tⁿ, tⁿ + h]).
    #[inline(always)]
    fn predict(&self, i: usize, u_next: &mut [f64; 3], v_next: &mut [f64; 3]) {
        let m = self.mass[i];
        let c = self.constrained[i];
        for d in 0..3 {
            let vd = if c & (1 << d) == 0 {
                self.v[i][d] + self.dt_v * self.applied_force(i, d, &[0.0; 3]) / m
            } else if self.fixed[i] & (1 << d) != 0 {
                0.0
            } else {
                let p = &self.prescribed[self.prescribed_of[i][d] as usize];
                p.half_step_velocity(self.t, self.dt_u, self.u[i][d])
            };
            v_next[d] = vd;
            u_next[d] = self.u[i][d] + self.dt_u * vd;
        }
    }

    /// Predictor and energy parts of a node with no constrained DOF and no contact force
    /// ([`NodeContext::predict`] and [`NodeContext::energy_parts`] without the branches
    /// and the reaction, with the inverse mass), energy parts added to `parts`.
    #[inline(always)]
    fn predict_free(
        &self,
        i: usize,
        u_next: &mut [f64; 3],
        v_next: &mut [f64; 3],
        parts: &mut EnergyParts,
    ) {
        let m = self.mass[i];
        let w = self.inv_mass[i];
        let (u, v) = (&self.u[i], &self.v[i]);
        let alpha = self.alpha_at(i);
        let (fi, fd, fe) = (&self.f_int[i], &self.f_damp[i], &self.f_ext[i]);
        let mut kin = 0.0;
        let mut before = [0.0; 3];
        let mut after = [0.0; 3];
        for d in 0..3 {
            let ext = fe[d] + m * self.gravity[d];
            let damp = fd[d] + alpha * m * v[d];
            let force = ext - fi[d] - damp;
            let vd = v[d] + self.dt_v * force * w;
            v_next[d] = vd;
            u_next[d] = u[d] + self.dt_u * vd;
            let vn = self.velocity_at_t(v[d], vd);
            kin += 0.5 * m * vn * vn;
            let b = 0.5 * self.dt_prev * v[d];
            let a = 0.5 * self.dt_u * vd;
            before[0] += fi[d] * b;
            before[1] += damp * b;
            before[2] += ext * b;
            after[0] += fi[d] * a;
            after[1] += damp * a;
            after[2] += ext * a;
        }
        parts[0] += kin;
        parts[1] += before[0];
        parts[2] += before[1];
        parts[4] += before[2];
        parts[7] += after[0];
        parts[8] += after[1];
        parts[10] += after[2];
    }

    /// Energy parts of node i for the motion V^{n−½} → `v_next` with contact force `r`
    /// (layout of [`EnergyParts`]).
    #[inline(always)]
    fn energy_parts(&self, i: usize, v_next: &[f64; 3], r: &[f64; 3]) -> EnergyParts {
        let m = self.mass[i];
        let mut p = [0.0; 13];
        for d in 0..3 {
            let vn = self.velocity_at_t(self.v[i][d], v_next[d]);
            p[0] += 0.5 * m * vn * vn;
            let reaction = if self.constrained[i] & (1 << d) != 0 {
                m * (v_next[d] - self.v[i][d]) / self.dt_v - self.applied_force(i, d, r)
            } else {
                0.0
            };
            let forces = [
                self.f_int[i][d],
                self.f_damp[i][d] + self.alpha_at(i) * m * self.v[i][d],
                r[d],
                self.f_ext[i][d] + m * self.gravity[d],
                reaction,
                0.0,
            ];
            let before = 0.5 * self.dt_prev * self.v[i][d];
            let after = 0.5 * self.dt_u * v_next[d];
            for k in 0..6 {
                p[1 + k] += forces[k] * before;
                p[7 + k] += forces[k] * after;
            }
        }
        p
    }

    /// Velocity at tⁿ from V^{n−½} (at tⁿ − ½Δt⁻) and V^{n+½} (at tⁿ + ½h): their mean for
    /// full steps, the linear interpolation (h V^{n−½} + Δt⁻ V^{n+½})/(Δt⁻ + h) otherwise.
    #[inline(always)]
    fn velocity_at_t(&self, before: f64, after: f64) -> f64 {
        if self.uniform {
            0.5 * (before + after)
        } else {
            (self.dt_u * before + self.dt_prev * after) / (self.dt_prev + self.dt_u)
        }
    }

    /// Predictor of boundary node i (slot b of `bs`) with contact force `r`: the leapfrog
    /// with the boundary's explicit forces S_b − K_b Uⁿ and its centred dashpot
    /// (boundary::centred_dashpot), fixed and prescribed DOFs imposed. Returns U^{n+1},
    /// V^{n+½} and the energy parts (the boundary's source S_b books as input, the spring
    /// and dashpot forces of the body on the boundary as boundary work).
    fn boundary_node(
        &self,
        i: usize,
        bs: &crate::boundary::BoundarySystem,
        b: usize,
        r: &[f64; 3],
    ) -> ([f64; 3], [f64; 3], EnergyParts) {
        let dt = self.dt;
        let m = self.mass[i];
        let (u, v) = (self.u[i], self.v[i]);
        let source = bs.source(b);
        let ku = bs.spring[b] * nalgebra::Vector3::from(u);
        let mut force = [0.0; 3];
        let mut v_constrained = [0.0; 3];
        for d in 0..3 {
            force[d] = self.applied_force(i, d, r) + source[d] - ku[d];
            if self.constrained[i] & (1 << d) != 0 && self.fixed[i] & (1 << d) == 0 {
                let p = &self.prescribed[self.prescribed_of[i][d] as usize];
                v_constrained[d] = p.half_step_velocity(self.t, dt, u[d]);
            }
        }
        let update = bs.update(b);
        let vn = update.half_step_velocity(v, force, v_constrained, dt);
        let fd = update.dashpot_force(v, vn, dt);
        let un: [f64; 3] = std::array::from_fn(|d| u[d] + dt * vn[d]);
        let mut p = [0.0; 13];
        for d in 0..3 {
            let vm = 0.5 * (v[d] + vn[d]);
            p[0] += 0.5 * m * vm * vm;
            let reaction = if self.constrained[i] & (1 << d) != 0 {
                m * (vn[d] - v[d]) / dt - force[d] - fd[d]
            } else {
                0.0
            };
            let forces = [
                self.f_int[i][d],
                self.f_damp[i][d] + self.alpha_at(i) * m * v[d],
                r[d],
                self.f_ext[i][d] + m * self.gravity[d],
                reaction + source[d],
                ku[d] - fd[d],
            ];
            let before = 0.5 * dt * v[d];
            let after = 0.5 * dt * vn[d];
            for k in 0..6 {
                p[1 + k] += forces[k] * before;
                p[7 + k] += forces[k] * after;
            }
        }
        (un, vn, p)
    }
}
