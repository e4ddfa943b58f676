//! The contact solve beside the node pass (issue 11).
//!
//! Step 4 (contact forces from the predictor, eqs. 5–22) reads the predicted displacements
//! of the nodes that can take part in contact only — the nodes of surface a, their
//! partners and the nodes of surface b's faces ([`ContactSystem::surface_nodes`]) — and it
//! is serial: run after the node pass, as the step was written, it leaves every thread but
//! one idle for its whole length (≈ 4 % of the wall time of a late step of the Yingxiuwan
//! full mesh). So the predictor of those nodes is formed first, on its own (a pre-pass, in
//! parallel, each node's Ū, V̄ written into arrays of the contact's own as it is formed);
//! the contact solve then runs on one thread while the others form the predictor of every
//! other node. Each node's
//! predictor is the same computation either way, and the pre-pass results enter the node
//! pass's per-chunk sums (energy parts, velocity check) at the node's place in node order:
//! the step is the same bit for bit.
//!
//! The published arrays hold NaN at every node outside the set, so that a contact solve
//! reading a node it did not declare gives a non-finite force (the run stops there with
//! the step and the place) instead of a silently stale one.

use crate::contact::ContactSystem;

/// The predictor of one node of the contact set, formed by the pre-pass.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct PredictedNode<R> {
    pub u: [f64; 3],
    pub v: [f64; 3],
    pub a: [f64; 3],
    /// Its energy parts and velocity check, as the node pass's chunk result of this node
    /// alone.
    pub result: R,
}

/// The contact set's predictor, formed before the node pass, and the arrays the contact
/// solve reads it from.
#[derive(Clone, Debug)]
pub(super) struct ContactPredictor<R> {
    /// The contact set, ascending.
    pub nodes: Vec<u32>,
    /// Per node of the mesh: its index in `nodes`, or `u32::MAX`.
    pub slot: Vec<u32>,
    /// The pre-pass results, one per node of `nodes`.
    pub predicted: Vec<PredictedNode<R>>,
    /// Ū^{n+1} and V̄^{n+½} at the contact set, NaN elsewhere (the contact's input).
    pub u_pred: Vec<[f64; 3]>,
    pub v_pred: Vec<[f64; 3]>,
}

impl<R: Copy + Default> ContactPredictor<R> {
    /// The set of `contact` on a mesh of `n` nodes.
    pub fn new(contact: &ContactSystem, n: usize) -> Self {
        let nodes: Vec<u32> = contact
            .surface_nodes()
            .into_iter()
            .filter(|&i| (i as usize) < n)
            .collect();
        let mut slot = vec![u32::MAX; n];
        for (j, &i) in nodes.iter().enumerate() {
            slot[i as usize] = j as u32;
        }
        Self {
            predicted: vec![PredictedNode::default(); nodes.len()],
            nodes,
            slot,
            u_pred: vec![[f64::NAN; 3]; n],
            v_pred: vec![[f64::NAN; 3]; n],
        }
    }

    /// The pre-pass: `predict(i)` of every node of the set, in parallel over chunks of
    /// `chunk` nodes, kept in `predicted` and its Ū, V̄ written into the contact's input
    /// arrays at the node's place (each node of the set is one entry: the set is unique).
    pub fn predict<F>(&mut self, chunk: usize, predict: F)
    where
        R: Send,
        F: Fn(usize) -> PredictedNode<R> + Sync,
    {
        use crate::element::groups::SharedMut;
        use rayon::prelude::*;
        let n = self.u_pred.len();
        assert!(self.v_pred.len() == n && self.nodes.iter().all(|&i| (i as usize) < n));
        let (u_pub, v_pub) = (
            SharedMut(self.u_pred.as_mut_ptr()),
            SharedMut(self.v_pred.as_mut_ptr()),
        );
        self.predicted
            .par_chunks_mut(chunk)
            .zip(self.nodes.par_chunks(chunk))
            .for_each(|(out, ids)| {
                for (o, &i) in out.iter_mut().zip(ids) {
                    let q = predict(i as usize);
                    // SAFETY: i < n (asserted above) and the set lists each node once
                    // (`ContactSystem::surface_nodes` is unique; `new` keeps it so): no
                    // other iteration writes entry i.
                    unsafe {
                        *u_pub.at(i as usize) = q.u;
                        *v_pub.at(i as usize) = q.v;
                    }
                    *o = q;
                }
            });
    }
}
