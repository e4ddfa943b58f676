//! The predictor of a run of free nodes, degree of freedom by degree of freedom.
//!
//! A free node (no constrained DOF, no boundary, no contact force, the finest level) takes
//! the leapfrog predictor of eq. (4) with the energy parts of its motion
//! ([`NodeContext::predict_free`]). Written node by node, the three components and the
//! seven energy sums form one long chain of scalar operations: the node pass cost about
//! 37 ns a node, as much as the force scatter of an element (docs/benchmarks.md, stop 70).
//!
//! Here a run of consecutive free nodes is updated in blocks of [`BLOCK`] nodes. First,
//! one loop over the block's 3 × [`BLOCK`] degrees of freedom, with every node's mass,
//! inverse mass and damping coefficient repeated per component, forms V̄^{n+½}, Ū^{n+1},
//! the acceleration and every energy term. The loop has no branch and no dependence
//! between its iterations, so the compiler runs it in vectors. Then the terms are summed
//! node by node, component by component, and the nodes are checked in order: the same
//! operations in the same order as [`NodeContext::predict_free`] and the node pass's
//! check, so the results are bit for bit those of the node-by-node predictor.
//!
//! Forces known to be zero everywhere (no group with stiffness-proportional damping, no
//! nodal load) are read from a block of zeros instead of their nodal arrays. Measured on
//! the one-point plastic-damage cube (docs/benchmarks.md, stop 71), the pass fell from
//! about 37 to 34 ns a node, not further: it moves about 233 bytes a node through eight
//! nodal arrays, and that traffic, not its arithmetic, now sets its time.

use super::{ChunkResult, NodeContext};

/// Nodes per block of the degree-of-freedom loop (its scratch stays in the first-level
/// cache: eleven arrays of 3 × 32 values, 8.4 KB).
const BLOCK: usize = 32;

/// Degrees of freedom per block.
const BLOCK_DOFS: usize = 3 * BLOCK;

/// A block of forces that are +0 everywhere.
static ZEROS: [f64; BLOCK_DOFS] = [0.0; BLOCK_DOFS];

/// The gravity components repeated per node, one block's per-node values repeated per
/// degree of freedom, and its energy terms degree of freedom by degree of freedom (the
/// layout of [`NodeContext::predict_free`]'s sums).
struct BlockScratch {
    gravity: [f64; BLOCK_DOFS],
    mass: [f64; BLOCK_DOFS],
    inv_mass: [f64; BLOCK_DOFS],
    alpha: [f64; BLOCK_DOFS],
    kinetic: [f64; BLOCK_DOFS],
    internal_before: [f64; BLOCK_DOFS],
    damping_before: [f64; BLOCK_DOFS],
    external_before: [f64; BLOCK_DOFS],
    internal_after: [f64; BLOCK_DOFS],
    damping_after: [f64; BLOCK_DOFS],
    external_after: [f64; BLOCK_DOFS],
}

/// [`NodeContext::predict_free_run`]'s arguments, for pulp's dispatch.
struct FreeRun<'c, 'a> {
    ctx: &'c NodeContext<'a>,
    first: usize,
    u_next: &'c mut [[f64; 3]],
    v_next: &'c mut [[f64; 3]],
    accel: &'c mut [[f64; 3]],
    out: &'c mut ChunkResult,
}

impl pulp::WithSimd for FreeRun<'_, '_> {
    type Output = ();
    #[inline(always)]
    fn with_simd<S: pulp::Simd>(self, _simd: S) {
        self.ctx
            .predict_free_run_in(self.first, self.u_next, self.v_next, self.accel, self.out)
    }
}

impl NodeContext<'_> {
    /// The predictor of the free nodes `first`, `first + 1`, … (one per entry of `u_next`),
    /// at the finest level: Ū^{n+1} into `u_next`, V̄^{n+½} into `v_next`, the acceleration
    /// (V̄^{n+½} − V^{n−½})/Δt_v into `accel`, and their energy parts and velocity checks
    /// added to `out` in node order, exactly as [`NodeContext::predict_free`] and the node
    /// pass do for each node in turn.
    ///
    /// Compiled for the widest instruction set the CPU has (pulp's dispatch): the vectors
    /// change how many degrees of freedom one instruction takes, never a value.
    pub(super) fn predict_free_run(
        &self,
        first: usize,
        u_next: &mut [[f64; 3]],
        v_next: &mut [[f64; 3]],
        accel: &mut [[f64; 3]],
        out: &mut ChunkResult,
    ) {
        pulp::Arch::new().dispatch(FreeRun {
            ctx: self,
            first,
            u_next,
            v_next,
            accel,
            out,
        })
    }

    /// The body of [`NodeContext::predict_free_run`], inlined into each instruction set's
    /// entry point.
    #[inline(always)]
    fn predict_free_run_in(
        &self,
        first: usize,
        u_next: &mut [[f64; 3]],
        v_next: &mut [[f64; 3]],
        accel: &mut [[f64; 3]],
        out: &mut ChunkResult,
    ) {
        let n = u_next.len();
        debug_assert!(v_next.len() == n && accel.len() == n);
        // Scratch of the blocks, set up once for the run (each block overwrites what it
        // reads): zeroing it per block cost more than the block's arithmetic.
        let mut scratch = BlockScratch {
            gravity: std::array::from_fn(|j| self.gravity[j % 3]),
            mass: [0.0; BLOCK_DOFS],
            inv_mass: [0.0; BLOCK_DOFS],
            alpha: [0.0; BLOCK_DOFS],
            kinetic: [0.0; BLOCK_DOFS],
            internal_before: [0.0; BLOCK_DOFS],
            damping_before: [0.0; BLOCK_DOFS],
            external_before: [0.0; BLOCK_DOFS],
            internal_after: [0.0; BLOCK_DOFS],
            damping_after: [0.0; BLOCK_DOFS],
            external_after: [0.0; BLOCK_DOFS],
        };
        let mut start = 0;
        while start < n {
            let end = (start + BLOCK).min(n);
            let i0 = first + start;
            self.predict_free_block(
                i0,
                &mut scratch,
                &mut u_next[start..end],
                &mut v_next[start..end],
                &mut accel[start..end],
                out,
            );
            start = end;
        }
    }

    /// One block of at most [`BLOCK`] nodes of [`NodeContext::predict_free_run`].
    #[inline(always)]
    fn predict_free_block(
        &self,
        i0: usize,
        t: &mut BlockScratch,
        u_next: &mut [[f64; 3]],
        v_next: &mut [[f64; 3]],
        accel: &mut [[f64; 3]],
        out: &mut ChunkResult,
    ) {
        let nb = u_next.len();
        let nd = 3 * nb;
        let nodes = i0..i0 + nb;
        // Per degree of freedom: its node's mass, inverse mass and α.
        for (k, i) in nodes.clone().enumerate() {
            let (m, w, a) = (self.mass[i], self.inv_mass[i], self.alpha_at(i));
            t.mass[3 * k..3 * k + 3].fill(m);
            t.inv_mass[3 * k..3 * k + 3].fill(w);
            t.alpha[3 * k..3 * k + 3].fill(a);
        }
        let u = &self.u[nodes.clone()].as_flattened()[..nd];
        let v = &self.v[nodes.clone()].as_flattened()[..nd];
        let f_int = &self.f_int[nodes.clone()].as_flattened()[..nd];
        // Forces known to be +0 everywhere are read from a block of zeros in cache, not
        // from memory: the same values, 48 of the 280 bytes a node moves.
        let f_damp = if self.damping_forces {
            &self.f_damp[nodes.clone()].as_flattened()[..nd]
        } else {
            &ZEROS[..nd]
        };
        let f_ext = if self.external_forces {
            &self.f_ext[nodes].as_flattened()[..nd]
        } else {
            &ZEROS[..nd]
        };
        let (mass, inv_mass, alpha, gravity) = (
            &t.mass[..nd],
            &t.inv_mass[..nd],
            &t.alpha[..nd],
            &t.gravity[..nd],
        );
        let un = &mut u_next.as_flattened_mut()[..nd];
        let vn = &mut v_next.as_flattened_mut()[..nd];
        let an = &mut accel.as_flattened_mut()[..nd];
        let (dt_v, dt_u, dt_prev) = (self.dt_v, self.dt_u, self.dt_prev);
        let half_prev = 0.5 * dt_prev;
        let half_u = 0.5 * dt_u;
        let span = dt_prev + dt_u;
        let uniform = self.uniform;
        // Each line is the operation of `predict_free` / the node pass, in its order.
        for j in 0..nd {
            let m = mass[j];
            let ext = f_ext[j] + m * gravity[j];
            let damp = f_damp[j] + alpha[j] * m * v[j];
            let force = ext - f_int[j] - damp;
            let vd = v[j] + dt_v * force * inv_mass[j];
            vn[j] = vd;
            un[j] = u[j] + dt_u * vd;
            let vt = if uniform {
                0.5 * (v[j] + vd)
            } else {
                (dt_u * v[j] + dt_prev * vd) / span
            };
            t.kinetic[j] = 0.5 * m * vt * vt;
            let b = half_prev * v[j];
            let a = half_u * vd;
            t.internal_before[j] = f_int[j] * b;
            t.damping_before[j] = damp * b;
            t.external_before[j] = ext * b;
            t.internal_after[j] = f_int[j] * a;
            t.damping_after[j] = damp * a;
            t.external_after[j] = ext * a;
            an[j] = (vd - v[j]) / dt_v;
        }
        // The sums, node by node from 0 as in `predict_free`, then the checks in order.
        let node_sum = |x: &[f64; BLOCK_DOFS], k: usize| {
            let mut s = 0.0;
            s += x[3 * k];
            s += x[3 * k + 1];
            s += x[3 * k + 2];
            s
        };
        for k in 0..nb {
            let parts = &mut out.parts;
            parts[0] += node_sum(&t.kinetic, k);
            parts[1] += node_sum(&t.internal_before, k);
            parts[2] += node_sum(&t.damping_before, k);
            parts[4] += node_sum(&t.external_before, k);
            parts[7] += node_sum(&t.internal_after, k);
            parts[8] += node_sum(&t.damping_after, k);
            parts[10] += node_sum(&t.external_after, k);
            let (ui, vi) = (&u_next[k], &v_next[k]);
            let vm = vi[0].abs().max(vi[1].abs()).max(vi[2].abs());
            out.check(
                i0 + k,
                vm,
                !vm.is_finite() || !ui.iter().all(|x| x.is_finite()),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::{ChunkResult, NodeContext};

    /// A value in (−1, 1) with all its bits in play, from a small linear congruential
    /// sequence (fixed seed: the test is reproducible).
    fn values(n: usize, seed: u64) -> Vec<f64> {
        let mut x = seed;
        (0..n)
            .map(|_| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((x >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
            })
            .collect()
    }

    fn triples(n: usize, seed: u64, scale: f64) -> Vec<[f64; 3]> {
        values(3 * n, seed)
            .chunks_exact(3)
            .map(|c| [scale * c[0], scale * c[1], scale * c[2]])
            .collect()
    }

    /// The nodal arrays of a test: masses, displacements, velocities and the three forces
    /// (the flags for damping and external forces set from whether those are given).
    struct Nodes<'a> {
        mass: &'a [f64],
        inv_mass: &'a [f64],
        none: &'a [u8],
        u: &'a [[f64; 3]],
        v: &'a [[f64; 3]],
        f_int: &'a [[f64; 3]],
        f_damp: &'a [[f64; 3]],
        f_ext: &'a [[f64; 3]],
        forces: bool,
    }

    /// A full step Δt of 10⁻⁴ s over `nodes`, none constrained, with gravity and α = 0.3.
    fn context<'a>(nodes: &Nodes<'a>) -> NodeContext<'a> {
        NodeContext {
            dt: 1e-4,
            dt_v: 1e-4,
            dt_u: 1e-4,
            dt_prev: 1e-4,
            uniform: true,
            t: 0.25,
            alpha: 0.3,
            node_alpha: None,
            gravity: [0.0, -9.81, 0.5],
            mass: nodes.mass,
            inv_mass: nodes.inv_mass,
            constrained: nodes.none,
            node_kind: nodes.none,
            fixed: nodes.none,
            prescribed: &[],
            prescribed_of: &[],
            u: nodes.u,
            v: nodes.v,
            f_int: nodes.f_int,
            f_damp: nodes.f_damp,
            f_ext: nodes.f_ext,
            damping_forces: nodes.forces,
            external_forces: nodes.forces,
        }
    }

    /// The block predictor gives bit for bit the node-by-node predictor's motion,
    /// acceleration, energy sums and velocity check, over runs that end inside a block,
    /// for full and shortened steps, with and without damping and external forces, with
    /// one α for the model and one per node.
    #[test]
    fn block_predictor_is_the_node_by_node_predictor_bit_for_bit() {
        // 75 nodes: two full blocks and a partial one; the run starts at node 3.
        let n = 78;
        let first = 3;
        let mass: Vec<f64> = values(n, 1).iter().map(|x| 2.0 + x).collect();
        let inv_mass: Vec<f64> = mass.iter().map(|m| 1.0 / m).collect();
        let node_alpha: Vec<f64> = values(n, 2).iter().map(|x| 0.5 + 0.4 * x).collect();
        let (u, v) = (triples(n, 3, 1e-3), triples(n, 4, 0.1));
        let (f_int, f_damp, f_ext) = (triples(n, 5, 1e3), triples(n, 6, 10.0), triples(n, 7, 50.0));
        let zeros = vec![[0.0; 3]; n];
        let none_u8 = vec![0u8; n];
        for (uniform, dt_prev, dt_u) in [(true, 1e-4, 1e-4), (false, 1e-4, 3.7e-5)] {
            for forces in [true, false] {
                for per_node_alpha in [false, true] {
                    let nodes = Nodes {
                        mass: &mass,
                        inv_mass: &inv_mass,
                        none: &none_u8,
                        u: &u,
                        v: &v,
                        f_int: &f_int,
                        f_damp: if forces { &f_damp } else { &zeros },
                        f_ext: if forces { &f_ext } else { &zeros },
                        forces,
                    };
                    let ctx = NodeContext {
                        dt_v: 0.5 * (dt_prev + dt_u),
                        dt_u,
                        dt_prev,
                        uniform,
                        node_alpha: per_node_alpha.then_some(node_alpha.as_slice()),
                        ..context(&nodes)
                    };
                    let m = n - first;
                    let (mut ub, mut vb, mut ab) =
                        (vec![[0.0; 3]; m], vec![[0.0; 3]; m], vec![[0.0; 3]; m]);
                    let mut block = ChunkResult::default();
                    ctx.predict_free_run(first, &mut ub, &mut vb, &mut ab, &mut block);
                    let mut one = ChunkResult::default();
                    for k in 0..m {
                        let i = first + k;
                        let (mut ui, mut vi) = ([0.0; 3], [0.0; 3]);
                        ctx.predict_free(i, &mut ui, &mut vi, &mut one.parts);
                        let ai: [f64; 3] = std::array::from_fn(|d| (vi[d] - v[i][d]) / ctx.dt_v);
                        let vm = vi[0].abs().max(vi[1].abs()).max(vi[2].abs());
                        one.check(i, vm, !vm.is_finite() || !ui.iter().all(|x| x.is_finite()));
                        let bits = |x: [f64; 3]| x.map(f64::to_bits);
                        assert_eq!(bits(ub[k]), bits(ui), "U of node {i}");
                        assert_eq!(bits(vb[k]), bits(vi), "V of node {i}");
                        assert_eq!(bits(ab[k]), bits(ai), "acceleration of node {i}");
                    }
                    assert_eq!(
                        block.parts.map(f64::to_bits),
                        one.parts.map(f64::to_bits),
                        "energy parts (uniform {uniform}, forces {forces})"
                    );
                    assert_eq!(block.vmax.to_bits(), one.vmax.to_bits());
                    assert_eq!(block.vmax_node, one.vmax_node);
                    assert!(!block.nonfinite);
                    assert!(block.parts[0] > 0.0 && block.vmax > 0.0);
                }
            }
        }
    }

    /// A non-finite velocity is reported at the first node that has one, as the node pass
    /// reports it.
    #[test]
    fn block_predictor_reports_the_first_non_finite_node() {
        let n = 40;
        let mass = vec![1.0; n];
        let inv_mass = vec![1.0; n];
        let u = vec![[0.0; 3]; n];
        let v = vec![[0.1; 3]; n];
        let mut f_int = vec![[1.0; 3]; n];
        f_int[33][1] = f64::INFINITY;
        f_int[37][0] = f64::NAN;
        let zeros = vec![[0.0; 3]; n];
        let none_u8 = vec![0u8; n];
        let nodes = Nodes {
            mass: &mass,
            inv_mass: &inv_mass,
            none: &none_u8,
            u: &u,
            v: &v,
            f_int: &f_int,
            f_damp: &zeros,
            f_ext: &zeros,
            forces: false,
        };
        let ctx = context(&nodes);
        let (mut ub, mut vb, mut ab) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
        let mut out = ChunkResult::default();
        ctx.predict_free_run(0, &mut ub, &mut vb, &mut ab, &mut out);
        assert!(out.nonfinite);
        assert_eq!(out.vmax_node, 33);
    }
}
