//! What the contact system reports: per-node fields for the VTU, areas per state for the
//! histories (the paper's Figures 13–14), per-node records for probes, and views for tests.

use super::{ContactSystem, PairState, NONE};

impl ContactSystem {
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
