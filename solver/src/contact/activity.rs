//! Which pairs and faces take part in contact while elements are excavated or placed (the
//! static stage): a node of no active element is dormant and so are the pairs and the
//! faces of surface b that hold it.
//!
//! A pair that comes alive (both nodes active again, or for the first time) starts bonded
//! and at rest: its reference relative displacement δ₀ = U_b − U_a is the offset at that
//! moment (concrete placed against rock that has already converged), so the pair formula
//! of eqs. (6)–(9) measures gaps and slips from there (VERIFICATION.md W9 with δ₀).
//!
//! An interface can also be held out of contact by the static stage ([`ContactSystem::
//! set_held`]) until a later step bonds it: its pairs and faces stay inactive while
//! both sides are placed and settle on their own (fresh concrete carries no bond), and
//! come alive bonded at rest in the offset they have reached.

use super::geom::sub;
use super::{ContactSystem, PairState, NONE};

impl ContactSystem {
    /// Update the activity of every pair and face from the dormant flags of the nodes;
    /// pairs that come alive get δ₀ from the displacements `u` and the bonded state (paired
    /// interfaces; point-to-surface nodes keep their state, δ₀ from their partner if any).
    pub fn set_activity(&mut self, dormant: &[bool], u: &[[f64; 3]]) {
        for iface in self.interfaces.iter_mut() {
            let held = iface.held;
            for s in iface.slaves.iter_mut() {
                let alive = !held
                    && !dormant[s.node as usize]
                    && (s.partner == NONE || !dormant[s.partner as usize]);
                if alive && !s.active {
                    if s.partner != NONE {
                        s.rel0 = sub(u[s.partner as usize], u[s.node as usize]);
                        if !s.surface {
                            s.state = PairState::Bonded;
                        }
                    }
                    s.gap = 0.0;
                    s.slip = [0.0; 3];
                    s.acc_slip = 0.0;
                    s.normal_force = 0.0;
                    s.tangential = [0.0; 3];
                    s.force = [0.0; 3];
                }
                if !alive {
                    s.normal_force = 0.0;
                    s.tangential = [0.0; 3];
                    s.force = [0.0; 3];
                }
                s.active = alive;
            }
            for (f, a) in iface.b_faces.iter().zip(iface.b_face_active.iter_mut()) {
                *a = !held && f.iter().all(|&k| !dormant[k as usize]);
            }
        }
    }

    /// Hold interface `k` out of contact (`true`) or let it act (`false`) from the next
    /// [`Self::set_activity`] on: the static stage's `bond` (module documentation).
    pub fn set_held(&mut self, k: usize, held: bool) {
        if let Some(iface) = self.interfaces.get_mut(k) {
            iface.held = held;
        }
    }

    /// Index of the interface named `name`.
    pub fn interface_index(&self, name: &str) -> Option<usize> {
        self.interfaces.iter().position(|i| i.name == name)
    }

    /// The active pairs of point-to-point contact of every interface, with their state:
    /// (interface, node a, node b, state). For the static solve (bonded pairs are tied).
    pub fn active_pairs(&self) -> Vec<(usize, u32, u32, PairState)> {
        let mut out = Vec::new();
        for (k, iface) in self.interfaces.iter().enumerate() {
            for s in &iface.slaves {
                if s.active && !s.surface && s.partner != NONE {
                    out.push((k, s.node, s.partner, s.state));
                }
            }
        }
        out
    }

    /// Whether some active node of interface `k` is in point-to-surface contact.
    pub fn has_active_surface_nodes(&self, k: usize) -> bool {
        self.interfaces
            .get(k)
            .is_some_and(|i| i.slaves.iter().any(|s| s.active && s.surface))
    }

    /// Name of interface `k`.
    pub fn interface_name(&self, k: usize) -> &str {
        self.interfaces.get(k).map_or("", |i| i.name.as_str())
    }

    /// The strength of the pair of node `node` of interface `k`: (μs, cA, σt A, unit normal
    /// of surface a). Binary search in the interface's node index (a linear scan here made
    /// a loop over the pairs quadratic).
    pub fn pair_strength(&self, k: usize, node: u32) -> Option<(f64, f64, f64, [f64; 3])> {
        let iface = self.interfaces.get(k)?;
        let i = iface
            .slave_index
            .binary_search_by_key(&node, |&(n, _)| n)
            .ok()?;
        let s = &iface.slaves[iface.slave_index[i].1 as usize];
        Some((
            iface.mu_s,
            iface.cohesion * s.area,
            iface.tensile * s.area,
            s.normal,
        ))
    }
}
