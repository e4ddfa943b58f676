//! Interface data: the case file's description of an interface ([`InterfaceSpec`]) and
//! the records the contact method keeps for it (one [`SlaveNode`] per node of surface a,
//! the faces of surface b), paper §2.1–2.3.

use serde::Deserialize;

use super::PairState;

/// How an interface starts.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq, Default)]
#[serde(rename_all = "lowercase")]
pub enum ContactMode {
    /// Coincident node pairs, bonded with cohesion (the paper's initial state); a pair
    /// switches to point-to-surface contact once its slip exceeds the threshold.
    #[default]
    Paired,
    /// Every node of surface a in point-to-surface contact with surface b from the start,
    /// without cohesion; nodes need not coincide.
    Surface,
}

/// One contact interface of the case file.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct InterfaceSpec {
    /// Interface name (for messages and outputs).
    pub name: String,
    /// Face set on one side; its outward normals define the contact normal.
    pub surface_a: String,
    /// Face set on the other side.
    pub surface_b: String,
    /// Static friction coefficient μs ≥ 0.
    pub mu_s: f64,
    /// Kinetic friction coefficient, 0 ≤ μd ≤ μs.
    pub mu_d: f64,
    /// Cohesion c (Pa): shear capacity cA of a bonded pair, lost at first slide or separation.
    pub cohesion: f64,
    /// Tensile strength (Pa) of eq. (14); defaults to the cohesion.
    #[serde(default)]
    pub tensile_strength: Option<f64>,
    /// Paired (default) or surface.
    #[serde(default)]
    pub mode: ContactMode,
    /// Slip (m) after which a pair leaves point-to-point contact; not together with
    /// `slip_threshold_fraction`.
    #[serde(default)]
    pub slip_threshold: Option<f64>,
    /// Slip threshold as a fraction of the local element size √(mean adjacent face area);
    /// default 0.5 ([`InterfaceSpec::slip_fraction`]). An option so that setting it beside
    /// `slip_threshold` is seen (an error), not silently overridden.
    #[serde(default)]
    pub slip_threshold_fraction: Option<f64>,
    /// Pairing / penetration tolerance as a fraction of the shortest interface face edge.
    #[serde(default = "default_tolerance")]
    pub tolerance: f64,
    /// Paired mode: allow nodes of surface b without a partner (surface b extends beyond
    /// surface a, e.g. rock faces around a lining). Off by default: every node of both
    /// surfaces must then be paired.
    #[serde(default)]
    pub b_may_extend: bool,
}

fn default_slip_fraction() -> f64 {
    0.5
}

fn default_tolerance() -> f64 {
    1e-4
}

impl InterfaceSpec {
    /// The slip threshold as a fraction of the local element size (default 0.5).
    pub fn slip_fraction(&self) -> f64 {
        self.slip_threshold_fraction
            .unwrap_or_else(default_slip_fraction)
    }

    /// A paired interface with the default slip threshold and tolerance.
    pub fn new(
        name: &str,
        surface_a: &str,
        surface_b: &str,
        mu_s: f64,
        mu_d: f64,
        cohesion: f64,
    ) -> Self {
        InterfaceSpec {
            name: name.into(),
            surface_a: surface_a.into(),
            surface_b: surface_b.into(),
            mu_s,
            mu_d,
            cohesion,
            tensile_strength: None,
            mode: ContactMode::Paired,
            slip_threshold: None,
            slip_threshold_fraction: None,
            tolerance: default_tolerance(),
            b_may_extend: false,
        }
    }
}

/// One node of surface a with its contact record.
#[derive(Clone, Debug)]
pub(crate) struct SlaveNode {
    pub node: u32,
    /// Paired node of surface b (NONE once in point-to-surface contact, or in surface mode).
    pub partner: u32,
    /// Control area A (exact bilinear nodal area on surface a).
    pub area: f64,
    /// Unit node normal of surface a (reference configuration).
    pub normal: [f64; 3],
    /// Slip after which the pair switches to point-to-surface.
    pub slip_threshold: f64,
    /// Point-to-surface contact.
    pub surface: bool,
    pub state: PairState,
    /// Normal gap after the correction (m), positive when open.
    pub gap: f64,
    /// Net relative tangential displacement of the opposite side with respect to this node.
    pub slip: [f64; 3],
    /// Path length of sliding (m).
    pub acc_slip: f64,
    /// Normal force λ (N), compression positive.
    pub normal_force: f64,
    /// Tangential force on this node (N).
    pub tangential: [f64; 3],
    /// Face of surface b (index into `Interface::b_faces`) in point-to-surface contact.
    pub face: u32,
    pub xi: [f64; 2],
    /// Force applied to this node in the current step (R; −R on the partner, −φⱼR on the
    /// face nodes), so that a sweep can be taken back.
    pub force: [f64; 3],
    /// Slid in the current step (keeps μd for the rest of the step).
    pub slid: bool,
    /// Point-to-surface: normal gap at tⁿ to this step's contact point (negative: a
    /// penetration that the step holds).
    pub gap_start: f64,
    /// Lost its cohesion in the current step.
    pub broke: bool,
    /// Takes part in contact: false while the node or its partner is dormant (its elements
    /// not yet placed, or excavated) in the static stage.
    pub active: bool,
    /// Reference relative displacement δ₀ = U_b − U_a at the pair's activation (0 unless it
    /// came alive in a deformed configuration): gaps and slips are measured from it, so a
    /// bond placed against rock that has already moved is at rest (`activity.rs`).
    pub rel0: [f64; 3],
    /// The node or its partner also belongs to another interface (a junction of interfaces
    /// that meet): re-solved in every sweep of the joint solve (`joint.rs`).
    pub junction: bool,
}

/// Parameters and geometry of one interface.
#[derive(Clone, Debug)]
pub(crate) struct Interface {
    pub name: String,
    pub mu_s: f64,
    pub mu_d: f64,
    pub cohesion: f64,
    pub tensile: f64,
    pub slaves: Vec<SlaveNode>,
    /// Faces of surface b (node numbers, counter-clockwise from outside b).
    pub b_faces: Vec<[u32; 4]>,
    /// Face of surface b takes part in contact (none of its nodes dormant, the interface
    /// not held).
    pub b_face_active: Vec<bool>,
    /// Held out of contact by the static stage until the step that bonds it (`bond` of a
    /// static step): every pair and face inactive, as if its nodes were dormant.
    pub held: bool,
    /// Largest diagonal of the faces of surface b (reference configuration).
    pub b_face_size: f64,
    /// Records at the start of the step and forces of the previous sweep (interfaces with
    /// both pairs and point-to-surface nodes).
    pub snapshot: Vec<SlaveNode>,
    pub prev_force: Vec<[f64; 3]>,
    /// (node of surface a, index into `slaves`), sorted by node: the slave record of a
    /// node by binary search.
    pub slave_index: Vec<(u32, u32)>,
    /// The contact search of the current step for the nodes in point-to-surface contact
    /// (found by the step's first point-to-surface solve, used by all of them).
    pub faces: super::surface::StepFaces,
}
