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
//!    surface b (grid buckets over the configuration at tⁿ, once per step: `surface::StepFaces`), bilinear projection, the
//!    coupled system (17)–(21) for the nodes whose predicted gap is closed, solved
//!    with a sparse LU (faer), sliding and separation switches until consistent;
//! 3. the work of the contact forces over the step, accumulated as dissipation.
//!
//! Interfaces that share nodes (a junction where lining, inner structure and rock meet)
//! are solved jointly, by block Gauss–Seidel over the group until every force agrees
//! ([`joint`]); interfaces that share nothing are independent. Within an interface that has both pairs and point-to-surface nodes, steps
//! 1 and 2 are repeated (block Gauss–Seidel) until their forces agree to 1e-12, so that
//! every pair and node ends consistent with the others. No threads: results are
//! deterministic.
//! Layout, one phase per file: [`interface`] (the case's interface and the records kept
//! per node), `setup` (pairing, normals, control areas, checks), [`search`] (which face a
//! node touches), [`pair`] (the pair kernel, eqs. (6)–(15)), [`surface`] (the coupled
//! point-to-surface system, eqs. (16)–(22)), [`joint`] (interfaces that meet), `activity`
//! (dormant nodes of the static stage), [`outputs`] (fields, areas, records), `checkpoint`.
//! See `docs/contact.md` for the equations, the sign conventions and the choices made
//! where the paper is terse.

mod activity;
mod anderson;
mod checkpoint;
mod face_bins;
mod interface;
mod joint;
mod outputs;
/// The bilinear face geometry and vector helpers (they belong to the mesh; contact uses them).
pub use crate::mesh::face_geometry as geom;
pub mod pair;
mod search;
mod setup;
pub mod surface;

use crate::error::{DcfmError, Result};
use crate::mesh::Mesh;
use geom::{axpy, dot, norm, sub, tangential};
pub use interface::{ContactMode, InterfaceSpec};
pub(crate) use interface::{Interface, SlaveNode};
pub use pair::{solve_pair, PairInput, PairOutcome, PairParams, PairState};

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

/// Which pairs of an interface a sweep takes back and solves again.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Pairs {
    /// Every pair.
    All,
    /// The pairs at a junction of interfaces (node or partner on another interface).
    Junctions,
    /// The pairs at a junction and those that share a node with the point-to-surface
    /// system of the `compute` call given (the stamp): the only pairs whose inputs the
    /// other parts of a group change within the step.
    Coupled(u64),
    /// The pairs that nothing else in a group changes within the step: not at a junction
    /// and, where the interface has a point-to-surface system in the `compute` call given
    /// (the stamp), sharing no node with it. Solved on their own by the joint solve.
    Alone(Option<u64>),
}

impl Pairs {
    /// Whether the pair record `k` of `iface` (`s`) is selected.
    fn selects(self, faces: &surface::StepFaces, k: usize, s: &SlaveNode) -> bool {
        match self {
            Pairs::All => true,
            Pairs::Junctions => s.junction,
            Pairs::Coupled(stamp) => s.junction || faces.coupled(stamp, k),
            Pairs::Alone(None) => !s.junction,
            Pairs::Alone(Some(stamp)) => !(s.junction || faces.coupled(stamp, k)),
        }
    }
}

/// Work counts of the joint solves of groups of interfaces that meet (`joint.rs`) since the
/// model was built or restored.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize)]
pub struct JointStats {
    /// Steps of a group (one per group per step).
    pub group_steps: u64,
    /// Gauss–Seidel sweeps over all of them.
    pub sweeps: u64,
    /// Most sweeps of one group in one step.
    pub max_sweeps: u64,
    /// Pair solves (eqs. (6)–(15)) of every step, in groups or not, every sweep counted.
    pub pair_solves: u64,
    /// Pair solves in the sweeps after the first of the groups' steps.
    pub late_pair_solves: u64,
    /// Steps of a group settled by its direct solve (the rest fell back to the sweeps).
    pub direct: u64,
    /// Steps of a group whose direct solve failed and that fell back to the sweeps.
    pub fallbacks: u64,
    /// Most constraints (pairs and point-to-surface nodes) of one direct solve.
    pub max_system: u64,
    /// Most active-set solves of one direct solve.
    pub max_active_set_solves: u64,
    /// Most polish sweeps of one direct solve.
    pub max_polish_sweeps: u64,
    /// Polish sweeps of all direct solves.
    pub polish_sweeps: u64,
    /// Fallback steps whose sweeps, already within the accepted change, drifted (their
    /// change grew for `DRIFT_SWEEPS` sweeps in a row) and were stopped there as unsettled.
    pub drift_stops: u64,
}

/// Marker for "no node / no face".
pub(crate) const NONE: u32 = u32::MAX;

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
    /// Interfaces that share nodes, solved jointly (indices in input order; one group per
    /// interface that shares nothing). See [`joint`].
    groups: Vec<Vec<usize>>,
    /// Steps in which a group of interfaces did not settle to its tolerance but was
    /// accepted (`joint.rs`), and the largest relative force change left.
    unsettled: (u64, f64),
    /// Net contact force of each node of the group in the previous sweep of a joint solve
    /// (`joint.rs`), in the order of `touched`; empty between solves.
    joint_prev: Vec<[f64; 3]>,
    /// Whether each member of the group being solved (`joint.rs`, in the order of its
    /// members) has point-to-surface nodes, filled once at the start of its step for the
    /// direct solve and every sweep of the fallback (neither flag of a record changes
    /// within a step: the records restored from the snapshot keep them, switches are
    /// applied after the solve).
    joint_surface: Vec<bool>,
    /// The records that the sweeps of a group after the first visit, per member: pairs,
    /// then point-to-surface records (`joint::visit_lists`); refilled for each fallback.
    joint_visit: Vec<u32>,
    /// Where each member's two lists start in `joint_visit` (2 × members + 1 entries).
    joint_visit_at: Vec<usize>,
    /// Work of the joint solves (see [`JointStats`]).
    joint_stats: JointStats,
    /// Groups are solved directly (`joint.rs`), the sweeps only as the fallback; false:
    /// sweeps only (tests of the fallback).
    direct_joint: bool,
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
        let groups = joint::group_interfaces(&mut interfaces, n);
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
            groups,
            unsettled: (0, 0.0),
            joint_prev: Vec::new(),
            joint_surface: Vec::new(),
            joint_visit: Vec::new(),
            joint_visit_at: Vec::new(),
            joint_stats: JointStats::default(),
            direct_joint: true,
        })
    }

    /// Steps (since the model was built or restored) in which a group of interfaces that
    /// meet did not settle to its tolerance within its sweeps and was accepted, and the
    /// largest relative force change left (see `joint.rs`).
    pub fn unsettled_joint_steps(&self) -> (u64, f64) {
        self.unsettled
    }

    /// Work counts of the joint solves of groups of interfaces that meet (`joint.rs`).
    pub fn joint_stats(&self) -> JointStats {
        self.joint_stats
    }

    /// True when the model has no interface.
    pub fn is_empty(&self) -> bool {
        self.interfaces.is_empty()
    }

    /// Number of interfaces.
    pub fn len(&self) -> usize {
        self.interfaces.len()
    }

    /// Every node that can take part in contact: the nodes of surface a, their partners
    /// and the nodes of surface b's faces, ascending and unique (the nodes subcycling keeps
    /// on the finest step, `stage::subcycling`).
    pub fn surface_nodes(&self) -> Vec<u32> {
        let mut nodes: Vec<u32> = Vec::new();
        for iface in &self.interfaces {
            for s in &iface.slaves {
                nodes.push(s.node);
                if s.partner != NONE {
                    nodes.push(s.partner);
                }
            }
            nodes.extend(iface.b_faces.iter().flatten().copied());
        }
        nodes.sort_unstable();
        nodes.dedup();
        nodes
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
        let groups = std::mem::take(&mut self.groups);
        let mut result = Ok(());
        for group in &groups {
            result = match group.as_slice() {
                [k] => self.single_step(&mut interfaces[*k], inp, r),
                members => self.joint_step(&mut interfaces, members, inp, r),
            };
            if result.is_err() {
                break;
            }
        }
        self.interfaces = interfaces;
        self.groups = groups;
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
        let res = surface::solve(iface, inp, self.stamp, r, &mut scratch);
        for &node in &scratch.touched {
            self.touch(node);
        }
        self.scratch = scratch;
        res
    }

    /// An interface that shares no node with another: solved, then its large-slip
    /// switches applied.
    fn single_step(
        &mut self,
        iface: &mut Interface,
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) -> Result<()> {
        begin_step(iface);
        self.interface_step(iface, inp, r)?;
        apply_switches(iface);
        Ok(())
    }

    /// One interface for one step (its records reset by [`begin_step`]; the switches are
    /// the caller's). Pairs first, then point-to-surface nodes. Where the
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
        let any_surface = iface.slaves.iter().any(|s| s.surface && s.active);
        let any_pair = iface
            .slaves
            .iter()
            .any(|s| !s.surface && s.partner != NONE && s.active);
        if !(any_surface && any_pair) {
            self.point_to_point(iface, inp, r, Pairs::All);
            if any_surface {
                self.surface_step(iface, inp, r)?;
            }
            return Ok(());
        }
        iface.snapshot.clone_from(&iface.slaves);
        iface.prev_force.clear();
        iface.prev_force.resize(iface.slaves.len(), [0.0; 3]);
        for sweep in 0..MAX_SWEEPS {
            // Each part is solved again with the other part's latest forces in `r`.
            if sweep > 0 {
                restart(iface, r, false, Pairs::All);
            }
            self.point_to_point(iface, inp, r, Pairs::All);
            if sweep > 0 {
                restart(iface, r, true, Pairs::All);
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

    /// Step 1 of [`compute`](Self::compute): every pair in point-to-point contact that
    /// `which` selects.
    fn point_to_point(
        &mut self,
        iface: &mut Interface,
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
        which: Pairs,
    ) {
        for k in 0..iface.slaves.len() {
            if which.selects(&iface.faces, k, &iface.slaves[k]) {
                self.pair_step(iface, inp, r, k);
            }
        }
    }

    /// Pair record `k` of `iface`, if in point-to-point contact: its force from the pair
    /// kernel (eqs. (6)–(15)) added to `r`, its nodes marked, its record updated.
    fn pair_step(
        &mut self,
        iface: &mut Interface,
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
        k: usize,
    ) {
        let s = &mut iface.slaves[k];
        if s.surface || s.partner == NONE || !s.active {
            return;
        }
        let dt2 = inp.dt * inp.dt;
        self.joint_stats.pair_solves += 1;
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
            return;
        }
        let params = PairParams {
            shear_capacity: iface.cohesion * s.area,
            tensile_capacity: iface.tensile * s.area,
            // A pair that slid in an earlier sweep of this step keeps μd.
            mu_s: if s.slid { iface.mu_d } else { iface.mu_s },
            mu_d: iface.mu_d,
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
        let m = &mut self.mark;
        for k in [s.node, s.partner] {
            if m[k as usize] != self.stamp {
                m[k as usize] = self.stamp;
                self.touched.push(k);
            }
        }
        let rel_new = axpy(rel_pred, -w_sum * dt2, out.r);
        record_pair(s, &out, state, rel_new, rel_old);
    }
}

/// The record of a pair after its solve (`out`: force on node a, state, normal and
/// tangential force), the state it started the solve in, its relative displacements after
/// the step and at tⁿ (less δ₀).
fn record_pair(
    s: &mut SlaveNode,
    out: &PairOutcome,
    started: PairState,
    rel_new: [f64; 3],
    rel_old: [f64; 3],
) {
    s.force = out.r;
    s.slid |= out.state == PairState::Sliding;
    s.broke |= started == PairState::Bonded && out.state != PairState::Bonded;
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

/// Records of an interface at the start of a step: no force yet, nothing slid or broken.
fn begin_step(iface: &mut Interface) {
    for s in iface.slaves.iter_mut() {
        s.force = [0.0; 3];
        s.slid = false;
        s.broke = false;
    }
}

/// Take back the forces that the pairs that `which` selects (`surface = false`) or the
/// point-to-surface nodes (`surface = true`) of the interface applied in the current sweep,
/// and restore their records to the start of the step, `iface.snapshot` (keeping what the
/// step has learnt: slid, broke).
fn restart(iface: &mut Interface, r: &mut [[f64; 3]], surface: bool, which: Pairs) {
    for k in 0..iface.slaves.len().min(iface.snapshot.len()) {
        let s = &iface.slaves[k];
        if s.surface == surface && (surface || which.selects(&iface.faces, k, s)) {
            restart_record(iface, r, k);
        }
    }
}

/// Take back the force of record `k` of `iface` (a pair or a point-to-surface node) and
/// restore the record to the start of the step ([`restart`]).
fn restart_record(iface: &mut Interface, r: &mut [[f64; 3]], k: usize) {
    let s = &mut iface.slaves[k];
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
    s.clone_from(&iface.snapshot[k]);
    s.slid = slid;
    s.broke = broke;
    s.force = [0.0; 3];
}

#[cfg(test)]
mod tests;
