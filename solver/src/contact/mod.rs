//! Dynamic contact force method with bond-slip (Yang, Chen & Xiao 2014, §2, eqs. (5)–(22)).
//!
//! An interface joins two face sets: `surface_a` and `surface_b`. Its nodes are, at first,
//! coincident pairs (point-to-point contact, eqs. (5)–(15), [`pair`]); a node of surface a
//! whose slip exceeds a threshold leaves its pair and contacts the faces of surface b
//! (point-to-surface contact, eqs. (16)–(22), [`surface`]). Interfaces in
//! [`ContactMode::Surface`] start in point-to-surface contact.
//!
//! Integration form (leapfrog central difference): the driver computes the predictor
//! Ū^{n+1} = Uⁿ + Δt V̄^{n+½} for every node as if no contact existed, calls
//! [`ContactSystem::compute`], then corrects U^{n+1} = Ū^{n+1} + Δt² w R and
//! V^{n+½} = V̄^{n+½} + Δt w R with w = 1/M (0 for a fully constrained node).
//!
//! One step of [`ContactSystem::compute`]:
//! 1. for each interface, every pair still in point-to-point contact: trial stick force
//!    (6)–(9), state checks (12)–(15), forces +R on node a and −R on node b;
//! 2. for each interface with nodes in point-to-surface contact: search the faces of
//!    surface b (grid buckets over the configuration at tⁿ), bilinear projection, the
//!    coupled system (17)–(21) for the nodes whose predicted gap is closed, solved
//!    with a sparse LU (faer), sliding and separation switches until consistent;
//! 3. the work of the contact forces over the step, accumulated as dissipation.
//!
//! Forces of earlier interfaces are included in the predictor of later ones (interfaces in
//! input order). Within an interface that has both pairs and point-to-surface nodes, steps
//! 1 and 2 are repeated (block Gauss–Seidel) until their forces agree to 1e-12, so that
//! every pair and node ends consistent with the others. No threads: results are
//! deterministic.
//! See `docs/contact.md` for the equations, the sign conventions and the choices made
//! where the paper is terse.

mod activity;
mod checkpoint;
mod face_bins;
/// The bilinear face geometry and vector helpers (they belong to the mesh; contact uses them).
pub use crate::mesh::face_geometry as geom;
pub mod pair;
mod setup;
pub mod surface;

use serde::Deserialize;

use crate::error::{DcfmError, Result};
use crate::mesh::Mesh;
use geom::{axpy, dot, norm, sub, tangential};
pub use pair::{solve_pair, PairInput, PairOutcome, PairParams, PairState};

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

/// Everything [`ContactSystem::compute`] reads for one step (all slices of length n_nodes).
#[derive(Clone, Copy, Debug)]
pub struct ContactStepInput<'a> {
    /// Step number n.
    pub step: u64,
    /// Time tⁿ.
    pub time: f64,
    /// Time step Δt.
    pub dt: f64,
    /// Inverse lumped masses w = 1/M (0 for fully constrained nodes).
    pub inv_mass: &'a [f64],
    /// Reference coordinates.
    pub coords: &'a [[f64; 3]],
    /// Displacements Uⁿ.
    pub u_old: &'a [[f64; 3]],
    /// Predicted displacements Ū^{n+1} (no contact).
    pub u_pred: &'a [[f64; 3]],
    /// Predicted velocities V̄^{n+½} (no contact).
    pub v_pred: &'a [[f64; 3]],
}

/// Marker for "no node / no face".
pub(crate) const NONE: u32 = u32::MAX;

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
    /// Face of surface b takes part in contact (none of its nodes dormant).
    pub b_face_active: Vec<bool>,
    /// Largest diagonal of the faces of surface b (reference configuration).
    pub b_face_size: f64,
    /// Records at the start of the step and forces of the previous sweep (interfaces with
    /// both pairs and point-to-surface nodes).
    pub snapshot: Vec<SlaveNode>,
    pub prev_force: Vec<[f64; 3]>,
    /// (node of surface a, index into `slaves`), sorted by node: the slave record of a
    /// node by binary search.
    pub slave_index: Vec<(u32, u32)>,
}

/// All contact interfaces of a model and their states.
#[derive(Clone, Debug)]
pub struct ContactSystem {
    interfaces: Vec<Interface>,
    touched: Vec<u32>,
    mark: Vec<u64>,
    stamp: u64,
    friction_work: f64,
    n_nodes: usize,
    scratch: surface::Scratch,
}

impl ContactSystem {
    /// Set up every interface: pairing, normals, control areas and checks (see [`setup`]).
    pub fn new(mesh: &Mesh, specs: &[InterfaceSpec], file: &str) -> Result<Self> {
        let mut interfaces = Vec::with_capacity(specs.len());
        for (k, spec) in specs.iter().enumerate() {
            if specs[..k].iter().any(|s| s.name == spec.name) {
                return Err(DcfmError::invalid(
                    file,
                    format!("interfaces[{k}].name"),
                    &spec.name,
                    "interface names must be unique",
                ));
            }
            interfaces.push(setup::build_interface(mesh, spec, k, file)?);
        }
        let n = mesh.n_nodes();
        let cap: usize = interfaces
            .iter()
            .map(|i| 2 * i.slaves.len() + 4 * i.b_faces.len())
            .sum();
        Ok(ContactSystem {
            interfaces,
            touched: Vec::with_capacity(cap.min(n)),
            mark: vec![0; n],
            stamp: 0,
            friction_work: 0.0,
            n_nodes: n,
            scratch: surface::Scratch::default(),
        })
    }

    /// True when the model has no interface.
    pub fn is_empty(&self) -> bool {
        self.interfaces.is_empty()
    }

    /// Number of interfaces.
    pub fn len(&self) -> usize {
        self.interfaces.len()
    }

    /// Nodes whose contact force the last [`compute`](Self::compute) wrote (sorted by first
    /// touch, unique).
    pub fn touched_nodes(&self) -> &[u32] {
        &self.touched
    }

    /// Cumulative work dissipated by the contact forces: −Σ R·(U^{n+1} − Uⁿ) over all steps
    /// (friction while sliding and the inelastic closing of gaps). Zero for sticking pairs.
    pub fn friction_work(&self) -> f64 {
        self.friction_work
    }

    #[inline]
    fn touch(&mut self, node: u32) {
        let m = &mut self.mark[node as usize];
        if *m != self.stamp {
            *m = self.stamp;
            self.touched.push(node);
        }
    }

    /// Contact forces R for one step, eqs. (5)–(22): adds R into `r` for every node it
    /// touches (the caller zeroes the nodes of the previous call's
    /// [`touched_nodes`](Self::touched_nodes)), updates the states. Errors name the
    /// interface and the step when the inputs are inconsistent or a point-to-surface
    /// solve does not settle.
    pub fn compute(&mut self, inp: &ContactStepInput, r: &mut [[f64; 3]]) -> Result<()> {
        let n = self.n_nodes;
        let lens = [
            inp.inv_mass.len(),
            inp.coords.len(),
            inp.u_old.len(),
            inp.u_pred.len(),
            inp.v_pred.len(),
            r.len(),
        ];
        if lens.iter().any(|&l| l != n) {
            return Err(DcfmError::Contact {
                interface: "*".into(),
                message: format!(
                    "step {}: input lengths {lens:?} (inv_mass, coords, u_old, u_pred, v_pred, r) \
                     differ from the {n} nodes of the mesh",
                    inp.step
                ),
            });
        }
        if !(inp.dt.is_finite() && inp.dt > 0.0) {
            return Err(DcfmError::Contact {
                interface: "*".into(),
                message: format!(
                    "step {}: time step {} must be finite and > 0",
                    inp.step, inp.dt
                ),
            });
        }
        self.stamp += 1;
        self.touched.clear();
        let dt2 = inp.dt * inp.dt;
        let mut interfaces = std::mem::take(&mut self.interfaces);
        let mut result = Ok(());
        for iface in interfaces.iter_mut() {
            result = self.interface_step(iface, inp, r);
            if result.is_err() {
                break;
            }
        }
        self.interfaces = interfaces;
        result?;
        // Work of the contact forces over the step (dissipation is minus it).
        let mut work = 0.0;
        for &k in &self.touched {
            let k = k as usize;
            let du = axpy(
                sub(inp.u_pred[k], inp.u_old[k]),
                dt2 * inp.inv_mass[k],
                r[k],
            );
            work += dot(r[k], du);
        }
        self.friction_work -= work;
        Ok(())
    }

    /// Point-to-surface solve of one interface (its touched nodes marked).
    fn surface_step(
        &mut self,
        iface: &mut Interface,
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) -> Result<()> {
        let mut scratch = std::mem::take(&mut self.scratch);
        let res = surface::solve(iface, inp, r, &mut scratch);
        for &node in &scratch.touched {
            self.touch(node);
        }
        self.scratch = scratch;
        res
    }

    /// One interface for one step. Pairs first, then point-to-surface nodes. Where the
    /// interface has both, the two are repeated (block Gauss–Seidel, each sweep from the
    /// records at the start of the step, the previous sweep's forces taken back) until no
    /// force changes by more than 1e-12 of the largest, so that every pair and every node
    /// ends consistent with the forces of the others.
    fn interface_step(
        &mut self,
        iface: &mut Interface,
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) -> Result<()> {
        const MAX_SWEEPS: usize = 500;
        for s in iface.slaves.iter_mut() {
            s.force = [0.0; 3];
            s.slid = false;
            s.broke = false;
        }
        let any_surface = iface.slaves.iter().any(|s| s.surface && s.active);
        let any_pair = iface
            .slaves
            .iter()
            .any(|s| !s.surface && s.partner != NONE && s.active);
        if !(any_surface && any_pair) {
            self.point_to_point(iface, inp, r);
            if any_surface {
                self.surface_step(iface, inp, r)?;
            }
            apply_switches(iface);
            return Ok(());
        }
        iface.snapshot.clone_from(&iface.slaves);
        iface.prev_force.clear();
        iface.prev_force.resize(iface.slaves.len(), [0.0; 3]);
        for sweep in 0..MAX_SWEEPS {
            // Each part is solved again with the other part's latest forces in `r`.
            if sweep > 0 {
                restart(iface, r, false);
            }
            self.point_to_point(iface, inp, r);
            if sweep > 0 {
                restart(iface, r, true);
            }
            self.surface_step(iface, inp, r)?;
            let mut change: f64 = 0.0;
            let mut fmax: f64 = 0.0;
            for (s, prev) in iface.slaves.iter().zip(iface.prev_force.iter_mut()) {
                change = change.max(norm(sub(s.force, *prev)));
                fmax = fmax.max(norm(s.force));
                *prev = s.force;
            }
            if sweep > 0 && change <= 1e-12 * fmax.max(f64::MIN_POSITIVE) {
                apply_switches(iface);
                return Ok(());
            }
        }
        Err(DcfmError::Contact {
            interface: iface.name.clone(),
            message: format!(
                "step {} (t = {:.6e} s): pairs and point-to-surface nodes did not settle \
                 in {MAX_SWEEPS} sweeps",
                inp.step, inp.time
            ),
        })
    }

    /// Step 1 of [`compute`](Self::compute): every pair in point-to-point contact.
    fn point_to_point(
        &mut self,
        iface: &mut Interface,
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) {
        let dt2 = inp.dt * inp.dt;
        let base = PairParams {
            mu_s: iface.mu_s,
            mu_d: iface.mu_d,
            shear_capacity: 0.0,
            tensile_capacity: 0.0,
        };
        for s in iface.slaves.iter_mut() {
            if s.surface || s.partner == NONE || !s.active {
                continue;
            }
            let (a, b) = (s.node as usize, s.partner as usize);
            let (wa, wb) = (inp.inv_mass[a], inp.inv_mass[b]);
            let w_sum = wa + wb;
            let ua = axpy(inp.u_pred[a], dt2 * wa, r[a]);
            let ub = axpy(inp.u_pred[b], dt2 * wb, r[b]);
            let rel_pred = sub(sub(ub, ua), s.rel0);
            let rel_old = sub(sub(inp.u_old[b], inp.u_old[a]), s.rel0);
            if w_sum <= 0.0 {
                // Both sides fixed: nothing can move, no force is needed.
                s.gap = dot(rel_pred, s.normal);
                continue;
            }
            let params = PairParams {
                shear_capacity: iface.cohesion * s.area,
                tensile_capacity: iface.tensile * s.area,
                // A pair that slid in an earlier sweep of this step keeps μd.
                mu_s: if s.slid { iface.mu_d } else { iface.mu_s },
                ..base
            };
            // A pair that lost its bond in an earlier sweep of this step stays unbonded.
            let state = if s.broke && s.state == PairState::Bonded {
                PairState::Stick
            } else {
                s.state
            };
            let pin = PairInput {
                n: s.normal,
                w_sum,
                dt: inp.dt,
                rel_pred,
                rel_old,
            };
            let out = solve_pair(state, &params, &pin);
            r[a] = geom::add(r[a], out.r);
            r[b] = sub(r[b], out.r);
            s.force = out.r;
            s.slid |= out.state == PairState::Sliding;
            s.broke |= state == PairState::Bonded && out.state != PairState::Bonded;
            let m = &mut self.mark;
            for k in [s.node, s.partner] {
                if m[k as usize] != self.stamp {
                    m[k as usize] = self.stamp;
                    self.touched.push(k);
                }
            }
            let rel_new = axpy(rel_pred, -w_sum * dt2, out.r);
            let dslip = tangential(sub(rel_new, rel_old), s.normal);
            s.state = out.state;
            s.gap = dot(rel_new, s.normal);
            s.slip = tangential(rel_new, s.normal);
            if out.state == PairState::Sliding {
                s.acc_slip += norm(dslip);
            }
            s.normal_force = out.normal;
            s.tangential = out.tangential;
        }
    }

    /// Per-node output fields for the VTU writer: (name, components, values) with
    /// `n_nodes × components` values. Nodes on no interface get state −1 and zeros.
    ///
    /// - `contact_state`: 0 bonded, 1 stick, 2 sliding, 3 separated (pairs); +10 for nodes
    ///   of surface a in point-to-surface contact; −1 elsewhere;
    /// - `contact_gap` (m, open positive), `contact_slip` (vector, m: net relative
    ///   tangential displacement of the opposite side), `contact_slip_accumulated` (m),
    ///   `contact_normal_force` (N, compression positive), `contact_tangential_force`
    ///   (vector, N, on the node).
    ///
    /// The partner (surface b) node of a pair shows the pair's values with the slip and the
    /// tangential force reversed.
    pub fn node_fields(&self, n_nodes: usize) -> Vec<(String, usize, Vec<f64>)> {
        let mut state = vec![-1.0; n_nodes];
        let mut gap = vec![0.0; n_nodes];
        let mut slip = vec![0.0; 3 * n_nodes];
        let mut acc = vec![0.0; n_nodes];
        let mut nf = vec![0.0; n_nodes];
        let mut tf = vec![0.0; 3 * n_nodes];
        for iface in &self.interfaces {
            for s in iface.slaves.iter().filter(|s| s.active) {
                let code = s.state.code() as f64 + if s.surface { 10.0 } else { 0.0 };
                let mut put = |k: usize, sign: f64| {
                    if k >= n_nodes {
                        return;
                    }
                    state[k] = code;
                    gap[k] = s.gap;
                    acc[k] = s.acc_slip;
                    nf[k] = s.normal_force;
                    for d in 0..3 {
                        slip[3 * k + d] = sign * s.slip[d];
                        tf[3 * k + d] = sign * s.tangential[d];
                    }
                };
                put(s.node as usize, 1.0);
                if s.partner != NONE {
                    put(s.partner as usize, -1.0);
                }
            }
        }
        vec![
            ("contact_state".into(), 1, state),
            ("contact_gap".into(), 1, gap),
            ("contact_slip".into(), 3, slip),
            ("contact_slip_accumulated".into(), 1, acc),
            ("contact_normal_force".into(), 1, nf),
            ("contact_tangential_force".into(), 3, tf),
        ]
    }

    /// Area of each interface (control areas of surface a) per state:
    /// [point-to-point sticking (bonded or not), point-to-point sliding, separated (either
    /// mode), point-to-surface in contact (sticking or sliding)].
    pub fn state_areas(&self) -> Vec<(String, [f64; 4])> {
        self.interfaces
            .iter()
            .map(|iface| {
                let mut a = [0.0; 4];
                for s in iface.slaves.iter().filter(|s| s.active) {
                    let k = match (s.surface, s.state) {
                        (_, PairState::Separated) => 2,
                        (true, _) => 3,
                        (false, PairState::Sliding) => 1,
                        (false, _) => 0,
                    };
                    a[k] += s.area;
                }
                (iface.name.clone(), a)
            })
            .collect()
    }

    /// Names of the interfaces, in input order.
    pub fn interface_names(&self) -> Vec<String> {
        self.interfaces.iter().map(|i| i.name.clone()).collect()
    }

    /// Area of interface `k` (control areas of surface a, active nodes) per state whatever
    /// the mode: `[bonded, sticking, sliding, separated, of which in point-to-surface
    /// contact]` — the map of the paper's Figures 13–14. A point-to-surface node without a
    /// face under it counts as separated. Allocation-free (for history rows).
    pub fn state_area_split(&self, k: usize) -> [f64; 5] {
        let mut a = [0.0; 5];
        if let Some(iface) = self.interfaces.get(k) {
            for s in iface.slaves.iter().filter(|s| s.active) {
                let state = if s.surface && s.face == NONE {
                    PairState::Separated
                } else {
                    s.state
                };
                a[state.code() as usize] += s.area;
                if s.surface && state != PairState::Separated {
                    a[4] += s.area;
                }
            }
        }
        a
    }

    /// Where `node` takes part in contact: (interface, index of its record, sign) with
    /// sign +1 for the node of surface a and −1 for the partner of a pair (whose slip and
    /// tangential force are the pair's reversed); `None` for a node on no interface. The
    /// first interface in input order wins. A lookup for setting up probes (linear).
    pub fn locate_node(&self, node: u32) -> Option<(usize, usize, f64)> {
        for (k, iface) in self.interfaces.iter().enumerate() {
            for (j, s) in iface.slaves.iter().enumerate() {
                if s.node == node {
                    return Some((k, j, 1.0));
                }
                if s.partner == node {
                    return Some((k, j, -1.0));
                }
            }
        }
        None
    }

    /// The contact record `j` of interface `k` seen from a node with `sign` (see
    /// [`ContactSystem::locate_node`]): [state code (0 bonded, 1 stick, 2 sliding,
    /// 3 separated, +10 point-to-surface; −1 dormant), gap (m), normal force (N,
    /// compression positive), tangential force x, y, z (N), slip x, y, z (m), accumulated
    /// slip (m)]. Allocation-free (for history rows).
    pub fn node_record(&self, k: usize, j: usize, sign: f64) -> [f64; 10] {
        let Some(s) = self.interfaces.get(k).and_then(|i| i.slaves.get(j)) else {
            return [f64::NAN; 10];
        };
        // A pair that switched to point-to-surface contact no longer moves its old partner.
        if !s.active || (sign < 0.0 && s.partner == NONE) {
            let mut r = [0.0; 10];
            r[0] = -1.0;
            return r;
        }
        let code = s.state.code() as f64 + if s.surface { 10.0 } else { 0.0 };
        [
            code,
            s.gap,
            s.normal_force,
            sign * s.tangential[0],
            sign * s.tangential[1],
            sign * s.tangential[2],
            sign * s.slip[0],
            sign * s.slip[1],
            sign * s.slip[2],
            s.acc_slip,
        ]
    }

    /// Number of slave nodes per state code (0–3, +10 in point-to-surface) of interface
    /// `k`, for tests and summaries: `[bonded, stick, sliding, separated]` for pairs and
    /// the same for point-to-surface nodes.
    pub fn state_counts(&self, k: usize) -> ([usize; 4], [usize; 4]) {
        let mut p = [0; 4];
        let mut s = [0; 4];
        if let Some(iface) = self.interfaces.get(k) {
            for n in &iface.slaves {
                let c = n.state.code() as usize;
                if n.surface {
                    s[c] += 1;
                } else {
                    p[c] += 1;
                }
            }
        }
        (p, s)
    }

    /// Nodes of interface `k` in point-to-surface contact with a face this step:
    /// (node, normal gap at tⁿ, normal gap after the correction), both to this step's
    /// contact point. For tests and diagnostics.
    pub fn surface_gaps(&self, k: usize) -> Vec<(u32, f64, f64)> {
        self.interfaces
            .get(k)
            .map(|i| {
                i.slaves
                    .iter()
                    .filter(|s| s.surface && s.face != NONE)
                    .map(|s| (s.node, s.gap_start, s.gap))
                    .collect()
            })
            .unwrap_or_default()
    }

    /// The pairs of interface `k`: (node of a, node of b or u32::MAX, control area,
    /// unit normal). For tests and diagnostics.
    pub fn pairs(&self, k: usize) -> Vec<(u32, u32, f64, [f64; 3])> {
        self.interfaces
            .get(k)
            .map(|i| {
                i.slaves
                    .iter()
                    .map(|s| (s.node, s.partner, s.area, s.normal))
                    .collect()
            })
            .unwrap_or_default()
    }
}

/// Large slip: a pair whose net slip exceeds its threshold contacts the faces of b from
/// the next step on (point-to-surface).
fn apply_switches(iface: &mut Interface) {
    for s in iface.slaves.iter_mut() {
        if !s.surface
            && s.partner != NONE
            && s.state != PairState::Bonded
            && norm(s.slip) > s.slip_threshold
        {
            s.surface = true;
            s.partner = NONE;
        }
    }
}

/// Take back the forces that the pairs (`surface = false`) or the point-to-surface nodes
/// (`surface = true`) of the interface applied in the current sweep, and restore their
/// records to the start of the step (keeping what the step has learnt: slid, broke).
fn restart(iface: &mut Interface, r: &mut [[f64; 3]], surface: bool) {
    for (s, snap) in iface.slaves.iter_mut().zip(&iface.snapshot) {
        if s.surface != surface {
            continue;
        }
        let a = s.node as usize;
        r[a] = sub(r[a], s.force);
        if s.surface {
            if s.face != NONE {
                let face = iface.b_faces[s.face as usize];
                let phi = geom::face_shape(s.xi[0], s.xi[1]);
                for j in 0..4 {
                    let k = face[j] as usize;
                    r[k] = axpy(r[k], phi[j], s.force);
                }
            }
        } else if s.partner != NONE {
            let b = s.partner as usize;
            r[b] = geom::add(r[b], s.force);
        }
        let (slid, broke) = (s.slid, s.broke);
        s.clone_from(snap);
        s.slid = slid;
        s.broke = broke;
        s.force = [0.0; 3];
    }
}

#[cfg(test)]
mod tests;
