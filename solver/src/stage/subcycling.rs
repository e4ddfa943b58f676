//! Multi-time-step integration (subcycling) in the nodal partition of Belytschko, Yen &
//! Mullen (1979, "Mixed methods for time integration", Comput. Methods Appl. Mech. Eng.
//! 17/18, 259–275) and Belytschko & Mullen (1978, "Stability of explicit-implicit mesh
//! partitions in time integration", Int. J. Numer. Meth. Eng. 12, 1575–1586), with
//! power-of-two step ratios as in LS-DYNA's subcycling (Hallquist, LS-DYNA Theory Manual,
//! "Subcycling (mixed time integration)").
//!
//! Levels (fine step Δt, `max_level` from the case):
//!
//! * element e: L_e = the largest k ≤ `max_level` with 2^k Δt ≤ s · Δt_e, Δt_e the
//!   element's own stable step (`Model::element_steps`, lowered for mass-proportional
//!   damping α as in `Model::critical_step_with_damping`) and s the case's safety factor;
//! * node i: L_i = min over its elements of L_e, forced to 0 at every node that is
//!   constrained (fixed or prescribed), loaded, on a contact interface (every node of its
//!   surfaces, `ContactSystem::surface_nodes`) or on the boundary system (absorbing
//!   boundaries, free-field coupling): those stay on the finest step, and so do the
//!   elements around them, so the contact solve sees only nodes stepping at Δt;
//! * element e is evaluated with period 2^{m_e}, m_e = min over its nodes of L_i ≤ L_e,
//!   so its own stable step is respected.
//!
//! A node of level L takes the central-difference step of length H = 2^L Δt at the fine
//! steps n ≡ 0 (mod 2^L), with the internal force summed from its elements evaluated at
//! that same n (every element of the node is due then, m_e ≤ L). After the update it holds
//! U^{n+2^L} and V^{n+2^{L−1}}; at a fine step n + r in between (0 < r < 2^L) its
//! displacement is the linear interpolation U^{n+2^L} − (2^L − r) Δt V^{n+2^{L−1}}, which
//! is what the elements read (`Simulation::u` holds the displacements at the current fine
//! time for every node). Between evaluations an element is not computed; its material
//! state commits at its evaluations (the strain increment over its whole period, with the
//! period as the material's Δt).
//!
//! Energies: a node books its work over its own steps (the trapezoid of its force over
//! ½H V^{−} and ½H V^{+}); at a fine step where it does not update it contributes
//! ½ M |V|² of its current half-step velocity to the kinetic energy. With that, the
//! running balance of `stage::energy` telescopes node by node exactly as for single
//! stepping (the residual is Σ (H²/8) M |a|² over the nodes that updated). At the
//! synchronous steps n ≡ 0 (mod 2^top), top the largest node level, every node updates
//! and the energies are those of the single-step definitions.
//!
//! Checkpoints are written only at synchronous steps (`Simulation::on_grid`), where
//! every node holds (U^n, V^{n−½H}) and every material state is committed: a resumed run
//! continues bit-identically. Shortened steps (`Simulation::step_to`) are not taken (the
//! run ends on the first full step at or after its end, as with absorbing boundaries).
//! Anchor bars and stiffness-proportional damping β are refused by [`plan`] (not yet
//! handled).

use serde::Serialize;

use crate::element::groups::Due;
use crate::error::{DcfmError, Result};
use crate::model::Model;

/// Largest `time.subcycling.max_level` accepted (steps up to 128 Δt).
pub const MAX_LEVEL: u8 = 7;

/// What the run summary reports of the subcycling.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct SubcyclingSummary {
    /// The case's `max_level`.
    pub max_level: u8,
    /// Elements per evaluation period 2^m Δt, m = 0, 1, …, `max_level`.
    pub elements_per_level: Vec<u64>,
    /// Nodes per step 2^L Δt, L = 0, 1, …, `max_level`.
    pub nodes_per_level: Vec<u64>,
    /// Element evaluations per fine step with subcycling over those without: Σ_e 2^{−m_e} / N_e.
    pub element_update_fraction: f64,
    /// Element evaluations saved per fine step (1 − `element_update_fraction`) × N_e.
    pub element_updates_saved_per_step: f64,
}

/// The levels of a subcycled run and the nodes' end-of-step displacements.
#[derive(Clone, Debug)]
pub(crate) struct Subcycling {
    /// Largest node level present (the cycle is 2^top fine steps).
    pub top: u8,
    /// Level L_i of every node.
    pub node_level: Vec<u8>,
    /// The nodes with L_i > 0, ascending.
    pub coarse_nodes: Vec<u32>,
    /// Period exponent m_e of every element, per group in the group's order.
    pub group_levels: Vec<Vec<u8>>,
    /// Smallest m_e of every colouring run, per group.
    pub group_run_levels: Vec<Vec<u8>>,
    /// U^{n+2^L} of every coarse node after its last update (the other nodes: unused).
    pub u_end: Vec<[f64; 3]>,
    pub summary: SubcyclingSummary,
}

impl Subcycling {
    /// The elements of group `g` due at fine step `step`.
    pub fn due(&self, g: usize, step: u64) -> Due<'_> {
        Due {
            step,
            level: &self.group_levels[g],
            run_level: &self.group_run_levels[g],
        }
    }

    /// Whether every node updates at `step` (a synchronous step).
    pub fn synchronous(&self, step: u64) -> bool {
        Due::at(step, self.top)
    }
}

/// Refusal of a model feature subcycling does not handle yet.
fn refuse(what: &str, max_level: u8) -> DcfmError {
    DcfmError::invalid(
        "",
        "time.subcycling",
        format!("{{ max_level = {max_level} }}"),
        format!(
            "\"off\" for a model with {what} (subcycling does not handle it yet: \
             docs/case_format.md, [time])"
        ),
    )
}

/// The levels of `model` stepped at `dt` with safety factor `safety` (module docs).
/// `forced` marks the nodes held on the finest level besides the constrained and boundary
/// nodes (the loaded ones). Refuses stiffness-proportional damping.
pub(crate) fn plan(
    model: &Model,
    dt: f64,
    safety: f64,
    max_level: u8,
    forced: &[u32],
) -> Result<Subcycling> {
    if max_level == 0 || max_level > MAX_LEVEL {
        return Err(DcfmError::invalid(
            "",
            "time.subcycling.max_level",
            max_level,
            format!("a whole number from 1 to {MAX_LEVEL}"),
        ));
    }
    let (alpha, beta) = model.max_damping();
    if beta > 0.0 {
        return Err(refuse("stiffness-proportional damping β", max_level));
    }
    let n = model.mesh.n_nodes();
    // `NO_ELEMENT` until an element's level lowers it: one walk over the connectivity
    // gives both the node levels and the nodes without an element.
    const NO_ELEMENT: u8 = u8::MAX;
    let mut node_level = vec![NO_ELEMENT; n];
    let mut group_levels: Vec<Vec<u8>> = Vec::with_capacity(model.groups.len());
    for g in &model.groups {
        let mut lv = Vec::with_capacity(g.len());
        for (le, &e) in g.elements.iter().enumerate() {
            let own = model.element_steps[e as usize];
            // Mass-proportional damping lowers the step: Δt = (2/ω)(√(1+ξ²) − ξ),
            // ξ = α/(2ω) at the element's highest frequency ω = 2/Δt_e.
            let omega = 2.0 / own;
            let xi = 0.5 * alpha / omega;
            let limit = safety * own * ((1.0 + xi * xi).sqrt() - xi);
            let mut k = 0u8;
            while k < max_level && (1u64 << (k + 1)) as f64 * dt <= limit {
                k += 1;
            }
            lv.push(k);
            for &i in &g.conn[le] {
                let l = &mut node_level[i as usize];
                *l = (*l).min(k);
            }
        }
        group_levels.push(lv);
    }
    // Nodes without an element stay on the finest step.
    for (i, l) in node_level.iter_mut().enumerate() {
        if *l == NO_ELEMENT || model.constraints.constrained[i] != 0 {
            *l = 0;
        }
    }
    for &i in forced {
        node_level[i as usize] = 0;
    }
    if let Some(b) = &model.boundaries {
        for &i in &b.nodes {
            node_level[i as usize] = 0;
        }
    }
    if let Some(c) = &model.contact {
        for i in c.surface_nodes() {
            node_level[i as usize] = 0;
        }
    }
    // Anchor bars: every node of a host element steps at Δt, so the bars (their forces
    // taken from the displacements at every fine step, their bond–slip nodes stepped at Δt)
    // only ever touch nodes that update at every step.
    if let Some(a) = &model.anchors {
        for e in a.host_elements() {
            for &i in &model.mesh.elements[e as usize] {
                node_level[i as usize] = 0;
            }
        }
    }
    let mut elements_per_level = vec![0u64; max_level as usize + 1];
    let mut updates = 0.0;
    let mut n_elements = 0u64;
    let mut group_run_levels = Vec::with_capacity(model.groups.len());
    for (g, lv) in model.groups.iter().zip(group_levels.iter_mut()) {
        for (le, m) in lv.iter_mut().enumerate() {
            *m = g.conn[le]
                .iter()
                .map(|&i| node_level[i as usize])
                .min()
                .unwrap_or(0);
            elements_per_level[*m as usize] += 1;
            updates += 1.0 / (1u64 << *m) as f64;
            n_elements += 1;
        }
        group_run_levels.push(g.run_levels(lv));
    }
    let mut nodes_per_level = vec![0u64; max_level as usize + 1];
    for &l in &node_level {
        nodes_per_level[l as usize] += 1;
    }
    let coarse_nodes: Vec<u32> = (0..n as u32)
        .filter(|&i| node_level[i as usize] > 0)
        .collect();
    let top = node_level.iter().copied().max().unwrap_or(0);
    let fraction = if n_elements > 0 {
        updates / n_elements as f64
    } else {
        1.0
    };
    Ok(Subcycling {
        top,
        node_level,
        coarse_nodes,
        group_levels,
        group_run_levels,
        u_end: Vec::new(),
        summary: SubcyclingSummary {
            max_level,
            elements_per_level,
            nodes_per_level,
            element_update_fraction: fraction,
            element_updates_saved_per_step: (1.0 - fraction) * n_elements as f64,
        },
    })
}
