//! Interfaces that meet, solved jointly.
//!
//! A node may belong to several interfaces: at a cavern junction the lining, the inner
//! structure and the rock meet at one edge, whose three coincident nodes form three pairs
//! on three interfaces (lining–rock, inner–rock, lining–inner). Solving the interfaces one
//! after the other leaves every interface but the last inconsistent: the pair solved last
//! moves a node that an earlier pair had already brought to its contact law (eqs. (6)–(15)),
//! so bonded pairs drift apart or into each other step by step.
//!
//! Interfaces that share a node form a group ([`group_interfaces`], at set-up). A group is
//! solved directly: a pair's force depends on the forces at its two nodes only, and pairs
//! of one interface share no node, so the pairs that are neither at a junction (node or
//! partner on another interface) nor on a node of a point-to-surface system (its nodes in
//! contact and their faces' nodes, from the step's contact search, `surface::StepFaces`)
//! are solved on their own, once (eqs. (6)–(15)). The rest — junction pairs, coupled pairs
//! and the point-to-surface nodes of every interface of the group — form one system: a
//! pair is a constraint between node a and its partner (a one-node "face", φ = 1), a
//! point-to-surface node one between the node and the contact point of its face, and
//! Hᵢₖ = Δt² Σⱼ wⱼ eᵢ(j) eₖ(j) couples every two constraints that share a node j (eqs.
//! (17)–(18) written for any constraints). The active set of `surface.rs` solves it with
//! each constraint's own law — a bonded pair holds its gap and carries tension up to σt A
//! and shear up to μs λ + cA, then loses its bond for the rest of the step; friction
//! static, then kinetic; separation (eqs. (12)–(15)) — and a projected Gauss–Seidel polish
//! checks that every constraint holds its law given the others (usually one or two
//! sweeps). A loop of pairs (three interfaces pairing three coincident nodes) makes H
//! singular; a Tikhonov term of 1e-11 of its largest diagonal in the direct solves picks
//! the split of least norm, and the polish works on H itself.
//!
//! Where the direct solve fails (a singular system the active set cannot settle, or
//! constraints that cannot all hold — forces beyond 10⁶ times what any constraint needs on
//! its own), its forces are taken back and the group falls back to block Gauss–Seidel
//! over its interfaces: each sweep solves every interface with the latest forces of the
//! others in the predictor (its own forces of the previous sweep taken back and its
//! records restored to the start of the step, keeping what the step has learnt: a pair
//! that slid keeps μd, a broken bond stays broken). After the first sweep only the
//! junction pairs, the coupled pairs and the point-to-surface systems are solved again,
//! once each. For sticking pairs the sweeps are alternating projections onto the pairs'
//! constraints in the mass metric, which converge linearly when the constraints are
//! consistent — slowly where a point-to-surface node meets a junction (200–2000 sweeps per
//! step in the Yingxiuwan CI case at 5–8 s of the 20 s record, before the direct solve).
//!
//! **What converges** (the polish of a joint system and the sweeps alike). Three pairs joining three coincident nodes close a loop, and a
//! force circulating round the loop (+f on one pair, carried on by the next two) leaves
//! the net contact force of every node unchanged: the split of the loop's forces among its
//! pairs is statically indeterminate, and the sweeps may walk along it without end — in
//! the Yingxiuwan CI case a loop of one bonded, one sticking and one sliding pair shifted
//! 43 N of normal force per sweep from the sliding pair to the bonded one for 2000 sweeps
//! (the sliding pair's friction cap feeds the walk). The motion is decided by the net
//! nodal forces alone, so the sweeps stop when no node's net contact force changes by more
//! than [`TOLERANCE`] of the largest force of the group. Every pair then holds its contact
//! law (each sweep leaves each pair's own force inside its law, eqs. (12)–(15)), and every
//! gap its target (the positions follow from the converged net forces); the split of a
//! loop is the last sweep's. Switches to point-to-surface contact (large slip) are applied
//! after convergence. No settling within the sweep limit is an error naming the interfaces,
//! unless the last change is within [`ACCEPTED`] (the step is then counted as unsettled).
//! The fallback's sweeps can also drift: in the Yingxiuwan full mesh at 15.04 s a group
//! came down to a change of 7e-8 in ≈ 1,040 sweeps, then one junction node's net force
//! moved further each sweep (its change growing ≈ 0.35 % a sweep, to 1.5e-6 at the 2,000th
//! sweep), and the step failed. A group within [`ACCEPTED`] whose change has grown for
//! [`DRIFT_SWEEPS`] sweeps in a row stops there and is accepted as at the limit.

use super::geom::{axpy, dot, norm, sub, tangential};
use super::{
    apply_switches, begin_step, record_pair, restart, restart_record, surface, ContactStepInput,
    ContactSystem, Interface, PairOutcome, PairParams, PairState, Pairs, NONE,
};
use crate::error::{DcfmError, Result};

/// Most sweeps of a group's joint solve.
const MAX_SWEEPS: usize = 2000;

/// Largest change of any node's net contact force between two sweeps, relative to the
/// largest force of the group (net nodal or pair), at which the sweeps stop.
const TOLERANCE: f64 = 1e-10;

/// Largest change at which a group that has not settled in [`MAX_SWEEPS`] sweeps is still
/// accepted (its last sweep kept), counted in [`ContactSystem::unsettled_joint_steps`] and
/// reported in the run's summary; above it the step fails.
const ACCEPTED: f64 = 1e-6;

/// Consecutive sweeps of growing change after which a group already within [`ACCEPTED`]
/// stops sweeping and is accepted as at the sweep limit: the sweeps are drifting away
/// from the settled state, not towards it (module documentation, "What converges").
const DRIFT_SWEEPS: usize = 50;

/// Groups of interfaces that share nodes (each sorted, groups ordered by their first
/// interface), and the `junction` flag of every slave record whose node or partner is on
/// another interface. `n_nodes` bounds every node number.
pub(super) fn group_interfaces(interfaces: &mut [Interface], n_nodes: usize) -> Vec<Vec<usize>> {
    let m = interfaces.len();
    let mut parent: Vec<usize> = (0..m).collect();
    fn root(parent: &mut [usize], mut k: usize) -> usize {
        while parent[k] != k {
            parent[k] = parent[parent[k]];
            k = parent[k];
        }
        k
    }
    // Distinct interfaces per node (saturating at 2) and the first interface of each node.
    let mut count = vec![0u8; n_nodes];
    let mut last = vec![usize::MAX; n_nodes];
    for (k, iface) in interfaces.iter().enumerate() {
        let nodes = iface
            .slaves
            .iter()
            .flat_map(|s| [s.node, s.partner])
            .chain(iface.b_faces.iter().flatten().copied())
            .filter(|&n| n != NONE && (n as usize) < n_nodes);
        for node in nodes {
            let i = node as usize;
            if last[i] == k {
                continue;
            }
            if last[i] != usize::MAX {
                let (a, b) = (root(&mut parent, last[i]), root(&mut parent, k));
                parent[a.max(b)] = a.min(b);
            }
            last[i] = k;
            count[i] = count[i].saturating_add(1).min(2);
        }
    }
    let shared = |n: u32| n != NONE && (n as usize) < n_nodes && count[n as usize] > 1;
    for iface in interfaces.iter_mut() {
        for s in iface.slaves.iter_mut() {
            s.junction = shared(s.node) || shared(s.partner);
        }
    }
    let mut groups: Vec<Vec<usize>> = Vec::new();
    let mut group_of_root = vec![usize::MAX; m];
    for k in 0..m {
        let r = root(&mut parent, k);
        if group_of_root[r] == usize::MAX {
            group_of_root[r] = groups.len();
            groups.push(Vec::new());
        }
        groups[group_of_root[r]].push(k);
    }
    groups
}

impl ContactSystem {
    /// One step of a group of interfaces that share nodes (`members`, indices into
    /// `interfaces`): the direct solve, or, where it fails, block Gauss–Seidel until the
    /// net contact forces of its nodes settle.
    pub(super) fn joint_step(
        &mut self,
        interfaces: &mut [Interface],
        members: &[usize],
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) -> Result<()> {
        self.joint_surface.clear();
        for &k in members {
            let iface = &mut interfaces[k];
            begin_step(iface);
            iface.snapshot.clone_from(&iface.slaves);
            let surface = iface.slaves.iter().any(|s| s.surface && s.active);
            self.joint_surface.push(surface);
        }
        self.joint_stats.group_steps += 1;
        if self.direct_joint {
            if self.direct_step(interfaces, members, inp, r) {
                self.joint_stats.direct += 1;
                for &k in members {
                    apply_switches(&mut interfaces[k]);
                }
                return Ok(());
            }
            // Take back everything the direct solve applied and start the step again.
            self.joint_stats.fallbacks += 1;
            for &k in members {
                let iface = &mut interfaces[k];
                restart(iface, r, false, Pairs::All);
                restart(iface, r, true, Pairs::All);
                begin_step(iface);
            }
        }
        self.sweep_step(interfaces, members, inp, r)
    }

    /// The direct solve of a group for one step: the pairs that nothing else in the group
    /// changes (away from junctions and from point-to-surface systems) are solved on their
    /// own (eqs. (6)–(15)); the rest — the pairs at junctions, the pairs that share a node
    /// with a point-to-surface system and the nodes of those systems, of every interface of
    /// the group — form one system in which each pair is a constraint between two nodes
    /// and each point-to-surface node one between a node and a face (eqs. (17)–(21) with
    /// Hᵢₖ summed over every node two constraints share, `surface::Active`). It is solved
    /// by the active set of `surface.rs` with each constraint's own law (bond, static and
    /// kinetic friction, separation, eqs. (12)–(15)), then polished until every constraint
    /// holds its law given the others. Returns false, with the forces and records left for
    /// the caller to take back, where that fails (a singular system the polish cannot
    /// settle, constraints that cannot all hold).
    fn direct_step(
        &mut self,
        interfaces: &mut [Interface],
        members: &[usize],
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) -> bool {
        let stamp = self.stamp;
        let mut sys = std::mem::take(&mut self.scratch);
        sys.active.clear();
        sys.touched.clear();
        sys.joint = true;
        for (m, &k) in members.iter().enumerate() {
            let iface = &mut interfaces[k];
            let surface = self.joint_surface[m];
            if surface {
                surface::step_faces(iface, inp, stamp, &mut sys.grid);
            }
            self.point_to_point(iface, inp, r, Pairs::Alone(surface.then_some(stamp)));
        }
        for (&k, &surface) in members.iter().zip(&self.joint_surface) {
            let iface = &mut interfaces[k];
            let alone = Pairs::Alone(surface.then_some(stamp));
            for si in 0..iface.slaves.len() {
                let s = &iface.slaves[si];
                let constraint = if s.surface {
                    surface::constraint(iface, k, si, inp, r)
                } else if s.partner != NONE && s.active && !alone.selects(&iface.faces, si, s) {
                    pair_constraint(iface, k, si, inp, r)
                } else {
                    None
                };
                sys.active.extend(constraint);
            }
        }
        let w = inp.inv_mass;
        let solved = surface::solve_active(&mut sys, inp.dt, &|j| w[j as usize]);
        let Ok((solves, sweeps)) = solved else {
            self.scratch = sys;
            return false;
        };
        let st = &mut self.joint_stats;
        st.max_system = st.max_system.max(sys.active.len() as u64);
        st.max_active_set_solves = st.max_active_set_solves.max(solves as u64);
        st.max_polish_sweeps = st.max_polish_sweeps.max(sweeps as u64);
        st.polish_sweeps += sweeps as u64;
        for a in &sys.active {
            surface::apply_force(a, r, &mut sys.touched);
        }
        for &node in &sys.touched {
            self.touch(node);
        }
        let dt2 = inp.dt * inp.dt;
        for a in &sys.active {
            let s = &mut interfaces[a.owner].slaves[a.slave];
            if s.surface {
                surface::record(s, a, inp, r);
                continue;
            }
            let corr = |k: u32| {
                let k = k as usize;
                axpy(inp.u_pred[k], dt2 * inp.inv_mass[k], r[k])
            };
            let rel_new = sub(sub(corr(s.partner), corr(s.node)), s.rel0);
            let state = a.state();
            let open = state == PairState::Separated;
            let out = PairOutcome {
                r: a.r,
                state,
                normal: if open { 0.0 } else { -dot(a.r, a.n) },
                tangential: if open { [0.0; 3] } else { tangential(a.r, a.n) },
            };
            let started = s.state;
            record_pair(s, &out, started, rel_new, a.dn);
        }
        self.scratch = sys;
        true
    }

    /// The sweeps of a group for one step (module documentation): block Gauss–Seidel over
    /// its interfaces until the net contact forces of its nodes settle.
    fn sweep_step(
        &mut self,
        interfaces: &mut [Interface],
        members: &[usize],
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) -> Result<()> {
        // The group's nodes are the ones touched from here on (groups share no node).
        let first = self.touched.len();
        let mut change: f64 = 0.0;
        let mut previous = f64::INFINITY;
        let mut growing = 0;
        let mut late_from = u64::MAX;
        for sweep in 0..MAX_SWEEPS {
            self.joint_stats.sweeps += 1;
            let count = sweep as u64 + 1;
            self.joint_stats.max_sweeps = self.joint_stats.max_sweeps.max(count);
            if sweep == 1 {
                late_from = self.joint_stats.pair_solves;
                self.visit_lists(interfaces, members);
            }
            for (m, &k) in members.iter().enumerate() {
                let iface = &mut interfaces[k];
                if sweep == 0 {
                    self.interface_step(iface, inp, r)?;
                    continue;
                }
                // One Gauss–Seidel sweep of the interface's parts that the others can
                // change: the pairs at a junction (or, with a point-to-surface system,
                // sharing a node with it), then the system, each with the latest forces of
                // the rest.
                let at = &self.joint_visit_at;
                let (pairs, nodes) = (at[2 * m]..at[2 * m + 1], at[2 * m + 1]..at[2 * m + 2]);
                for i in pairs.clone() {
                    restart_record(iface, r, self.joint_visit[i] as usize);
                }
                for i in pairs {
                    let k = self.joint_visit[i] as usize;
                    self.pair_step(iface, inp, r, k);
                }
                if self.joint_surface[m] {
                    for i in nodes {
                        restart_record(iface, r, self.joint_visit[i] as usize);
                    }
                    self.surface_step(iface, inp, r)?;
                }
            }
            let mut fmax: f64 = 0.0;
            for &k in members {
                for s in &interfaces[k].slaves {
                    fmax = fmax.max(norm(s.force));
                }
            }
            change = 0.0;
            let nodes = &self.touched[first..];
            // A node touched for the first time in this sweep starts from no force.
            self.joint_prev.resize(nodes.len(), [0.0; 3]);
            for (&node, prev) in nodes.iter().zip(self.joint_prev.iter_mut()) {
                let f = r[node as usize];
                change = change.max(norm(sub(f, *prev)));
                fmax = fmax.max(norm(f));
                *prev = f;
            }
            change /= fmax.max(f64::MIN_POSITIVE);
            if sweep > 0 && change <= TOLERANCE {
                self.joint_stats.late_pair_solves += self.joint_stats.pair_solves - late_from;
                self.joint_prev.clear();
                for &k in members {
                    apply_switches(&mut interfaces[k]);
                }
                return Ok(());
            }
            growing = if change > previous { growing + 1 } else { 0 };
            previous = change;
            if growing >= DRIFT_SWEEPS && change <= ACCEPTED {
                self.joint_stats.drift_stops += 1;
                break;
            }
        }
        self.joint_prev.clear();
        self.joint_stats.late_pair_solves += self.joint_stats.pair_solves - late_from;
        if change <= ACCEPTED {
            self.unsettled.0 += 1;
            self.unsettled.1 = self.unsettled.1.max(change);
            for &k in members {
                apply_switches(&mut interfaces[k]);
            }
            return Ok(());
        }
        let names: Vec<&str> = members
            .iter()
            .map(|&k| interfaces[k].name.as_str())
            .collect();
        Err(DcfmError::Contact {
            interface: names.join(" + "),
            message: format!(
                "step {} (t = {:.6e} s): the interfaces that meet at shared nodes did not \
                 settle jointly in {MAX_SWEEPS} sweeps (last relative force change {change:.3e})",
                inp.step, inp.time
            ),
        })
    }
}

impl ContactSystem {
    /// The records that the sweeps after the first visit (`joint_visit`, member `m`'s at
    /// `joint_visit_at[2m..2m + 3]`): the pairs at a junction or, in a member with a
    /// point-to-surface system, sharing a node with it (`Pairs::Coupled`, from the contact
    /// search of the first sweep; `Pairs::Junctions` otherwise), then, in such a member,
    /// its point-to-surface records. Found once: neither a record's flags nor the step's
    /// contact search change over the sweeps.
    fn visit_lists(&mut self, interfaces: &[Interface], members: &[usize]) {
        self.joint_visit.clear();
        self.joint_visit_at.clear();
        self.joint_visit_at.push(0);
        for (m, &k) in members.iter().enumerate() {
            let iface = &interfaces[k];
            let surface = self.joint_surface[m];
            let which = if surface {
                Pairs::Coupled(self.stamp)
            } else {
                Pairs::Junctions
            };
            for (i, s) in iface.slaves.iter().enumerate() {
                if !s.surface && which.selects(&iface.faces, i, s) {
                    self.joint_visit.push(i as u32);
                }
            }
            self.joint_visit_at.push(self.joint_visit.len());
            if surface {
                for (i, s) in iface.slaves.iter().enumerate() {
                    if s.surface {
                        self.joint_visit.push(i as u32);
                    }
                }
            }
            self.joint_visit_at.push(self.joint_visit.len());
        }
    }
}

/// The constraint of pair record `si` of `iface` (interface number `owner`) in a group's
/// direct solve: node a against its partner b as a one-node face (φ = (1, 0, 0, 0)), so that
/// d = x_b − x_a and the force is +R on a, −R on b, with the normal, strengths and bond of
/// the pair and d̄ from the predictor and the forces already in `r`. None for a pair whose
/// nodes are both fixed (its gap recorded, no force: as `point_to_point`).
fn pair_constraint(
    iface: &mut Interface,
    owner: usize,
    si: usize,
    inp: &ContactStepInput,
    r: &[[f64; 3]],
) -> Option<surface::Active> {
    let dt2 = inp.dt * inp.dt;
    let params = PairParams {
        mu_s: iface.mu_s,
        mu_d: iface.mu_d,
        shear_capacity: iface.cohesion * iface.slaves[si].area,
        tensile_capacity: iface.tensile * iface.slaves[si].area,
    };
    let s = &mut iface.slaves[si];
    let (a, b) = (s.node as usize, s.partner as usize);
    let (wa, wb) = (inp.inv_mass[a], inp.inv_mass[b]);
    let ua = axpy(inp.u_pred[a], dt2 * wa, r[a]);
    let ub = axpy(inp.u_pred[b], dt2 * wb, r[b]);
    let rel_pred = sub(sub(ub, ua), s.rel0);
    let rel_old = sub(sub(inp.u_old[b], inp.u_old[a]), s.rel0);
    if wa + wb <= 0.0 {
        s.gap = dot(rel_pred, s.normal);
        return None;
    }
    Some(surface::Active::new(
        (owner, si),
        s.node,
        [s.partner, NONE, NONE, NONE],
        [1.0, 0.0, 0.0, 0.0],
        s.normal,
        rel_pred,
        rel_old,
        params,
        s.state == PairState::Bonded,
    ))
}
