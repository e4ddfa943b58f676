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
//! solved by block Gauss–Seidel over its interfaces: each sweep solves every interface with
//! the latest forces of the others in the predictor (its own forces of the previous sweep
//! taken back and its records restored to the start of the step, keeping what the step has
//! learnt: a pair that slid keeps μd, a broken bond stays broken). After the first sweep
//! only the pairs at a junction (node or partner on another interface), the pairs that
//! share a node with a point-to-surface system (its nodes in contact and their faces' nodes,
//! from the step's contact search, `surface::StepFaces`) and those systems can change: a
//! pair's force depends on the forces at its two nodes only, and pairs of one interface
//! share no node. Each later sweep solves just those, once each (pairs, then the
//! point-to-surface system of the interface, eqs. (16)–(22)); the other pairs keep their
//! first solve. For sticking
//! pairs the sweeps are alternating projections onto the pairs' constraints in the mass
//! metric, which converge linearly when the constraints are consistent.
//!
//! **What converges.** Three pairs joining three coincident nodes close a loop, and a
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
//! after convergence. No settling within the sweep limit is an error naming the interfaces.

use super::{
    apply_switches, begin_step, restart, ContactStepInput, ContactSystem, Interface, Pairs,
};
use super::{geom::norm, geom::sub, NONE};
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
    /// `interfaces`): block Gauss–Seidel until the net contact forces of its nodes settle.
    pub(super) fn joint_step(
        &mut self,
        interfaces: &mut [Interface],
        members: &[usize],
        inp: &ContactStepInput,
        r: &mut [[f64; 3]],
    ) -> Result<()> {
        for &k in members {
            let iface = &mut interfaces[k];
            begin_step(iface);
            iface.snapshot.clone_from(&iface.slaves);
        }
        // The group's nodes are the ones touched from here on (groups share no node).
        let first = self.touched.len();
        let mut change: f64 = 0.0;
        let mut late_from = u64::MAX;
        self.joint_stats.group_steps += 1;
        for sweep in 0..MAX_SWEEPS {
            self.joint_stats.sweeps += 1;
            let count = sweep as u64 + 1;
            self.joint_stats.max_sweeps = self.joint_stats.max_sweeps.max(count);
            if sweep == 1 {
                late_from = self.joint_stats.pair_solves;
            }
            for &k in members {
                let iface = &mut interfaces[k];
                if sweep == 0 {
                    self.interface_step(iface, inp, r)?;
                } else if iface.slaves.iter().any(|s| s.surface && s.active) {
                    // One Gauss–Seidel sweep of the interface's parts that the others can
                    // change: the pairs at a junction or sharing a node with the
                    // point-to-surface system, then the system, each with the latest forces
                    // of the rest.
                    let coupled = Pairs::Coupled(self.stamp);
                    restart(iface, r, false, coupled);
                    self.point_to_point(iface, inp, r, coupled);
                    restart(iface, r, true, Pairs::All);
                    self.surface_step(iface, inp, r)?;
                } else {
                    restart(iface, r, false, Pairs::Junctions);
                    self.point_to_point(iface, inp, r, Pairs::Junctions);
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
