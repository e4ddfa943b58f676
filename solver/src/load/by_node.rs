//! The nodal loads gathered per node, for the external force Fⁿ of each step.
//!
//! F_i(t) = Σ_k F_k h_k(t) over the loads k whose node set holds node i. Summed load by
//! load (the natural loop) this is a scatter over every load's node list, serial, and
//! with the static stage's hand-over loads — one load per loaded node, thousands of them
//! in a cavern model — it is a pass over as many small node lists per step. Gathered per
//! node instead (a list built once: for each loaded node its loads, in load order), each
//! node's sum is formed on its own, in parallel, with the additions of the load-by-load
//! loop in its order — the same F bit for bit on any number of threads.

use super::NodalLoad;
use crate::element::groups::SharedMut;
use rayon::prelude::*;

/// Loaded nodes per task of the parallel sum.
const NODES_PER_TASK: usize = 2048;
/// Loads per task of the parallel evaluation of their histories.
const LOADS_PER_TASK: usize = 2048;

/// For each loaded node (ascending) the loads acting on it, in load order.
#[derive(Clone, Debug, Default)]
pub struct LoadsByNode {
    /// The loaded nodes, ascending, each once.
    nodes: Vec<u32>,
    /// Loads of `nodes[j]`: `load[start[j]..start[j + 1]]`.
    start: Vec<u32>,
    /// Load indices, per node in load order (a load listing a node twice, twice).
    load: Vec<u32>,
    /// Scratch: h_k(t) of every load at the current time.
    scale: Vec<f64>,
}

impl LoadsByNode {
    /// The per-node lists of `loads` (their node sets; the forces and histories are read
    /// at each [`Self::apply`], so they may change between steps).
    pub fn new(loads: &[NodalLoad]) -> Self {
        let mut entries: Vec<(u32, u32)> = loads
            .iter()
            .enumerate()
            .flat_map(|(k, l)| l.nodes.iter().map(move |&i| (i, k as u32)))
            .collect();
        // Stable: a node's loads stay in load order.
        entries.sort_by_key(|&(i, _)| i);
        let mut nodes = Vec::new();
        let mut start = Vec::new();
        for (e, &(i, _)) in entries.iter().enumerate() {
            if nodes.last() != Some(&i) {
                nodes.push(i);
                start.push(e as u32);
            }
        }
        start.push(entries.len() as u32);
        Self {
            nodes,
            start,
            load: entries.iter().map(|&(_, k)| k).collect(),
            scale: vec![0.0; loads.len()],
        }
    }

    /// The loaded nodes, ascending.
    pub fn nodes(&self) -> &[u32] {
        &self.nodes
    }

    /// F(t) of every loaded node into `f_ext` (the other nodes untouched): from zero, each
    /// load's F_k h_k(t) added in load order. `loads` must be those of [`Self::new`] (the
    /// same node sets, in the same order).
    pub fn apply(&mut self, loads: &[NodalLoad], t: f64, f_ext: &mut [[f64; 3]]) {
        debug_assert_eq!(loads.len(), self.scale.len(), "the loads of `new`");
        self.scale
            .par_iter_mut()
            .zip(loads.par_iter())
            .with_min_len(LOADS_PER_TASK)
            .for_each(|(h, l)| *h = l.history.value(t));
        let (start, load, scale) = (&self.start, &self.load, &self.scale);
        // The nodes are ascending and each listed once: the last is the largest.
        assert!(
            self.nodes
                .last()
                .is_none_or(|&i| (i as usize) < f_ext.len()),
            "a loaded node outside the mesh"
        );
        let out = SharedMut(f_ext.as_mut_ptr());
        self.nodes
            .par_iter()
            .enumerate()
            .with_min_len(NODES_PER_TASK)
            .for_each(|(j, &i)| {
                let mut f = [0.0; 3];
                for &k in &load[start[j] as usize..start[j + 1] as usize] {
                    let (force, h) = (&loads[k as usize].force, scale[k as usize]);
                    for d in 0..3 {
                        f[d] += force[d] * h;
                    }
                }
                // SAFETY: i < f_ext.len() (asserted: the nodes are ascending) and each node
                // is listed once, so no other iteration writes entry i.
                unsafe { *out.at(i as usize) = f };
            });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::load::TimeFunction;
    use crate::test_random::Lcg;

    /// The load-by-load loop the gathered sum replaces.
    fn scattered(loads: &[NodalLoad], t: f64, n: usize) -> Vec<[f64; 3]> {
        let mut f = vec![[0.0; 3]; n];
        for l in loads {
            let h = l.history.value(t);
            for &i in &l.nodes {
                for d in 0..3 {
                    f[i as usize][d] += l.force[d] * h;
                }
            }
        }
        f
    }

    #[test]
    fn gathered_per_node_is_the_load_by_load_sum_bit_for_bit() {
        let mut rng = Lcg(0x0001_0adb_70de);
        let n = 5000;
        // Overlapping sets (some nodes in many loads, one listed twice), histories of
        // several kinds, forces over many magnitudes and both signs (−0.0 among them).
        let mut loads: Vec<NodalLoad> = (0..300)
            .map(|k| {
                let len = 1 + (rng.next() * 60.0) as usize;
                let mut nodes: Vec<u32> =
                    (0..len).map(|_| (rng.next() * n as f64) as u32).collect();
                if k == 7 {
                    nodes.push(nodes[0]);
                }
                let history = match k % 3 {
                    0 => TimeFunction::Constant { value: 1.0 },
                    1 => TimeFunction::Ramp {
                        rate: 3.0 * rng.sym(),
                        start: 0.1,
                    },
                    _ => TimeFunction::Constant { value: rng.sym() },
                };
                let force = std::array::from_fn(|_| rng.sym() * 10f64.powf(6.0 * rng.sym()));
                NodalLoad {
                    nodes,
                    force,
                    history,
                }
            })
            .collect();
        loads[3].force = [-0.0, 0.0, -0.0];
        let mut by_node = LoadsByNode::new(&loads);
        for t in [0.0, 0.05, 0.3, 2.0] {
            let want = scattered(&loads, t, n);
            // Untouched nodes keep what they had; loaded ones get their sum.
            let mut got = vec![[f64::NAN; 3]; n];
            by_node.apply(&loads, t, &mut got);
            for i in 0..n {
                if by_node.nodes().binary_search(&(i as u32)).is_ok() {
                    assert_eq!(
                        got[i].map(f64::to_bits),
                        want[i].map(f64::to_bits),
                        "node {i}, t {t}"
                    );
                } else {
                    assert!(got[i].iter().all(|x| x.is_nan()), "node {i} untouched");
                    assert_eq!(want[i], [0.0; 3]);
                }
            }
            // Forces changed between steps are read at the next apply.
            loads[5].force[0] *= -2.0;
        }
    }

    #[test]
    fn no_loads_touch_nothing() {
        let mut by_node = LoadsByNode::new(&[]);
        let mut f = vec![[1.0; 3]; 4];
        by_node.apply(&[], 0.0, &mut f);
        assert_eq!(f, vec![[1.0; 3]; 4]);
        assert!(by_node.nodes().is_empty());
    }
}
