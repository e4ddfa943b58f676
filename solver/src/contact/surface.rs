//! Point-to-surface contact, eqs. (16)–(22), in the leapfrog form.
//!
//! A node i of surface a in point-to-surface contact touches the point c of a face of
//! surface b with bilinear shape functions φⱼ(ξ, η) (eq. (16)). Its force Rᵢ acts on i and
//! −φⱼ Rᵢ on the face nodes j (statically equivalent to −Rᵢ applied at c). With the
//! correction U = Ū + Δt² w R the relative position dᵢ = x_c − xᵢ after the step is
//!
//! ```text
//!   dᵢ = d̄ᵢ − Σₖ Hᵢₖ Rₖ,   Hᵢₖ = Δt² (wᵢ δᵢₖ + Σⱼ φⱼ⁽ⁱ⁾ φⱼ⁽ᵏ⁾ wⱼ)        (17)–(18)
//! ```
//!
//! (the paper's H of eqs. (20)–(21) with Δt²/(2M) → Δt² w), summed over the face nodes j
//! shared by the faces of i and k. With the contact normal nᵢ (from i towards b: minus the
//! outward normal of the face at c, configuration at tⁿ):
//!
//! - ḡᵢ = d̄ᵢ·nᵢ − min(0, dᵢⁿ·nᵢ): the predicted gap, less any penetration present at tⁿ
//!   (held, not pushed out, so that contact forces never do positive work);
//! - stick (3 unknowns Rᵢ): (H R)ᵢ = ḡᵢ nᵢ + Pₜ(d̄ᵢ − dᵢⁿ) — eq. (20) for the normal part
//!   with Δ₃ = ḡᵢ nᵢ, eq. (21) for the tangential part with Δ₄ = Pₜ(d̄ᵢ − dᵢⁿ);
//! - slide (1 unknown λᵢ, Rᵢ = λᵢ(−nᵢ + μd t̂ᵢ), eq. (13)): nᵢ·(H R)ᵢ = ḡᵢ, the tangential
//!   row leaves the system;
//! - open (ḡᵢ ≥ 0, or λᵢ < 0 after a solve): Rᵢ = 0 (eq. (15)).
//!
//! The system is assembled as a sparse matrix and solved with faer: a sparse Cholesky of
//! the scalar m × m H for the three components at once while all closed nodes stick, a
//! sparse LU of the non-symmetric system once some slide. Starting
//! with every closed node sticking, nodes with λ < 0 are released and sticking nodes with
//! |T| > μs λ switch to sliding (t̂ = T/|T| of that solve); the loop repeats until nothing
//! changes; then open nodes that their neighbours' forces (through shared face nodes) would
//! push into surface b are added as sticking and the loop goes on. Every switch happens at
//! most once per node and step (open → stick, stick → slide, contact → released in
//! tension, never re-added), so it ends after at most 3m + 2 solves.
//!
//! Coupled friction can leave that solution inconsistent (a sliding node whose friction,
//! aimed by the stick solve, reverses its own slip once its neighbours slide too). A
//! projected Gauss–Seidel polish follows: each node in turn solves its own contact law
//! (the pair kernel with Hᵢᵢ/Δt² for w_a + w_b) given the others' forces, until no force
//! changes by more than 1e-12 of the largest; a node that slid in the step keeps μd for the
//! rest of it. On consistent solutions the first sweep changes nothing. Once the sweeps
//! stop switching modes they converge linearly, and slowly; Anderson acceleration
//! (`anderson.rs`) shortens that tail. The end state is always a sweep's own and satisfies
//! every node's law, so the forces do no positive work. No settling within 20,000 sweeps
//! is an error naming the interface and the step.

use std::collections::HashMap;

use faer::prelude::*;
use faer::sparse::{SparseColMat, Triplet};

use super::anderson::Anderson;
use super::geom::{
    add, axpy, dot, face_normal, face_point, face_shape, norm, scale, sub, tangential,
};
use super::pair::{solve_pair, PairInput, PairParams};
use super::search::{FaceGrid, FaceHit};
use super::{ContactStepInput, Interface, PairState, NONE};
use crate::error::{DcfmError, Result};

/// Reusable buffers of the point-to-surface solve.
#[derive(Clone, Debug, Default)]
pub struct Scratch {
    pub(super) grid: FaceGrid,
    pub(super) active: Vec<Active>,
    h: Vec<(usize, usize, f64)>,
    by_master: Vec<(u32, usize, f64)>,
    triplets: Vec<Triplet<usize, usize, f64>>,
    /// Nodes whose force the last solve wrote.
    pub(super) touched: Vec<u32>,
    /// The system is the joint system of interfaces that meet (`joint.rs`): direct solves
    /// regularised ([`REGULARISATION`]), checked for constraints that cannot all hold
    /// ([`INCONSISTENT`]), polish settled on the nodes' net forces.
    pub(super) joint: bool,
    /// Diagonal term of the direct solves (0 unless `joint`).
    reg: f64,
    /// Net contact force per node of the previous polish sweep (`net_settled`).
    net_prev: Vec<[f64; 3]>,
    /// Row ranges of the sorted H list in the polish: row i is `h[row[i]..row[i + 1]]`.
    row: Vec<usize>,
    /// Anderson acceleration of the polish sweeps, with the forces before (x) and after
    /// (g) a sweep as flat vectors.
    anderson: Anderson,
    sweep_in: Vec<f64>,
    sweep_out: Vec<f64>,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Mode {
    Stick,
    Slide,
    Open,
}

/// One constraint of a contact system: a node in point-to-surface contact (its force on
/// `node`, −φⱼ times it on the face nodes) or, in the joint solve of interfaces that meet
/// (`joint.rs`), a node pair (the partner as a one-node "face", φ = (1, 0, 0, 0)).
#[derive(Clone, Copy, Debug)]
pub(super) struct Active {
    /// Interface (index in the model) and record (index in its `slaves`) it belongs to.
    pub(super) owner: usize,
    pub(super) slave: usize,
    pub(super) node: u32,
    pub(super) face: [u32; 4],
    pub(super) phi: [f64; 4],
    pub(super) n: [f64; 3],
    /// Predicted relative position d̄ (no force of this system).
    pub(super) dbar: [f64; 3],
    gbar: f64,
    rhs: [f64; 3],
    pub(super) dn: [f64; 3],
    mode: Mode,
    dir: [f64; 3],
    offset: usize,
    pub(super) r: [f64; 3],
    /// Released in tension during this step (never re-activated in the same step).
    released: bool,
    /// Nothing can move this node (H diagonal zero): no force.
    fixed: bool,
    /// (H R)ᵢ of the last solve.
    hr: [f64; 3],
    /// Has slid in this step.
    pub(super) slid: bool,
    /// Friction and, while bonded, cohesive strengths (eqs. (12)–(14)).
    params: PairParams,
    /// Cohesion intact (a bonded pair: holds its gap at tⁿ, carries tension up to its
    /// tensile capacity); lost for the rest of the step once broken.
    pub(super) bonded: bool,
}

/// One contact group given directly: the pure kernel behind [`solve`], public for tests and
/// benchmarks. `nodes[i] = (wᵢ, face nodes' w, φ, face node ids, nᵢ, d̄ᵢ, dᵢⁿ)`; returns
/// the forces Rᵢ and the final states (Stick, Sliding or Separated).
#[allow(clippy::type_complexity)]
pub fn solve_group(
    dt: f64,
    mu_s: f64,
    mu_d: f64,
    nodes: &[(
        f64,
        [f64; 4],
        [f64; 4],
        [u32; 4],
        [f64; 3],
        [f64; 3],
        [f64; 3],
    )],
) -> std::result::Result<Vec<([f64; 3], PairState)>, String> {
    // Inverse masses per node: the contact nodes are numbered after every face node (each
    // its own node, shared with nothing).
    let mut w_of: HashMap<u32, f64> = HashMap::new();
    let first = nodes
        .iter()
        .flat_map(|t| t.3)
        .filter(|&j| j != NONE)
        .max()
        .map_or(0, |j| j + 1);
    let params = PairParams {
        mu_s,
        mu_d,
        shear_capacity: 0.0,
        tensile_capacity: 0.0,
    };
    let mut active = Vec::with_capacity(nodes.len());
    for (i, &(w, wf, phi, face, n, dbar, dn)) in nodes.iter().enumerate() {
        for j in 0..4 {
            w_of.insert(face[j], wf[j]);
        }
        let node = first + i as u32;
        w_of.insert(node, w);
        active.push(Active::new(
            (0, i),
            node,
            face,
            phi,
            n,
            dbar,
            dn,
            params,
            false,
        ));
    }
    let mut scratch = Scratch {
        active,
        ..Default::default()
    };
    solve_active(&mut scratch, dt, &|j| w_of[&j])?;
    Ok(scratch.active.iter().map(|a| (a.r, a.state())).collect())
}

/// Forces on the four face nodes from the force `r` on the contact node: −φⱼ r. They sum
/// to −r and are statically equivalent to −r applied at x_c = Σ φⱼ xⱼ.
#[inline]
pub fn distribute(phi: &[f64; 4], r: [f64; 3]) -> [[f64; 3]; 4] {
    phi.map(|p| scale(-p, r))
}

impl Active {
    /// A constraint of record `owner = (interface, slave)` on `node` against the point
    /// Σ φⱼ x_face[j], with contact normal `n`, predicted relative position `dbar` = d̄,
    /// relative position at tⁿ `dn`, its strengths and whether its bond is intact.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn new(
        owner: (usize, usize),
        node: u32,
        face: [u32; 4],
        phi: [f64; 4],
        n: [f64; 3],
        dbar: [f64; 3],
        dn: [f64; 3],
        params: PairParams,
        bonded: bool,
    ) -> Active {
        let mut a = Active {
            owner: owner.0,
            slave: owner.1,
            node,
            face,
            phi,
            n,
            dbar,
            gbar: 0.0,
            rhs: [0.0; 3],
            dn,
            mode: Mode::Open,
            dir: [0.0; 3],
            offset: 0,
            r: [0.0; 3],
            released: false,
            fixed: false,
            hr: [0.0; 3],
            slid: false,
            params,
            bonded,
        };
        a.set_targets();
        a.mode = if bonded || a.gbar < 0.0 {
            Mode::Stick
        } else {
            Mode::Open
        };
        a
    }

    /// Gap to close and right-hand side of eqs. (20)–(21). The normal target is zero, or,
    /// where the node already penetrates at tⁿ (a change of contact face, the coupling of
    /// neighbours), that penetration: it is held, not pushed out, so that contact forces
    /// never do positive work; a bonded pair holds its gap at tⁿ whatever its sign (as
    /// `pair::solve_pair`).
    fn set_targets(&mut self) {
        let gap_old = dot(self.dn, self.n);
        let target = if self.bonded {
            gap_old
        } else {
            gap_old.min(0.0)
        };
        self.gbar = dot(self.dbar, self.n) - target;
        self.rhs = axpy(
            tangential(sub(self.dbar, self.dn), self.n),
            self.gbar,
            self.n,
        );
    }

    /// The bond breaks (for the rest of the step): contact without cohesion from now on.
    fn lose_bond(&mut self) {
        if self.bonded {
            self.bonded = false;
            self.set_targets();
        }
    }

    /// State of the constraint after the solve.
    pub(super) fn state(&self) -> PairState {
        match self.mode {
            Mode::Stick if self.bonded => PairState::Bonded,
            Mode::Stick => PairState::Stick,
            Mode::Slide => PairState::Sliding,
            Mode::Open => PairState::Separated,
        }
    }
}

/// Assemble Hᵢₖ = Δt² Σⱼ wⱼ eᵢ(j) eₖ(j) (sorted, merged) for the active set, summed over
/// the nodes j that constraints i and k share, with eᵢ = −1 on the contact node and φⱼ on
/// the face nodes (eqs. (17)–(18), written for any constraints that share nodes).
fn assemble_h(s: &mut Scratch, dt2: f64, w_node: &dyn Fn(u32) -> f64) {
    s.h.clear();
    s.by_master.clear();
    for (i, a) in s.active.iter().enumerate() {
        s.h.push((i, i, 0.0));
        s.by_master.push((a.node, i, -1.0));
        for j in 0..4 {
            if a.phi[j] != 0.0 && a.face[j] != NONE {
                s.by_master.push((a.face[j], i, a.phi[j]));
            }
        }
    }
    s.by_master.sort_unstable_by_key(|x| (x.0, x.1));
    let mut start = 0;
    while start < s.by_master.len() {
        let node = s.by_master[start].0;
        let mut end = start;
        while end < s.by_master.len() && s.by_master[end].0 == node {
            end += 1;
        }
        let w = w_node(node);
        if w != 0.0 {
            for p in start..end {
                for q in start..end {
                    let (_, i, fi) = s.by_master[p];
                    let (_, k, fk) = s.by_master[q];
                    s.h.push((i, k, dt2 * w * fi * fk));
                }
            }
        }
        start = end;
    }
    s.h.sort_by_key(|x| (x.0, x.1));
    let mut out = 0;
    for p in 0..s.h.len() {
        if out > 0 && s.h[out - 1].0 == s.h[p].0 && s.h[out - 1].1 == s.h[p].1 {
            s.h[out - 1].2 += s.h[p].2;
        } else {
            s.h[out] = s.h[p];
            out += 1;
        }
    }
    s.h.truncate(out);
}

/// Active-set loop over the H system, then the polish; fills `a.r` and `a.mode` of every
/// active constraint. Returns the number of direct solves and of polish sweeps. Also the
/// joint system of a group of interfaces (`joint.rs`, with `Scratch::joint` set).
pub(super) fn solve_active(
    s: &mut Scratch,
    dt: f64,
    w_node: &dyn Fn(u32) -> f64,
) -> std::result::Result<(usize, usize), String> {
    let iters = active_set(s, dt, w_node)?;
    if s.joint {
        // Forces far beyond what any constraint needs on its own come from constraints
        // that cannot all hold (a loop of pairs whose gap targets disagree): no solution
        // exists; the caller falls back to the sweeps.
        let mut alone: f64 = 0.0;
        for &(i, k, h) in &s.h {
            let a = &s.active[i];
            if i == k && h > 0.0 && !a.fixed {
                alone = alone.max(norm(a.rhs) / h);
            }
        }
        let fmax = s.active.iter().map(|a| norm(a.r)).fold(0.0, f64::max);
        if fmax > INCONSISTENT * alone {
            return Err(format!(
                "the direct solve gave forces {:.1e} times what any constraint needs alone \
                 (constraints that cannot all hold)",
                fmax / alone.max(f64::MIN_POSITIVE)
            ));
        }
    }
    let sweeps = polish(s, dt)?;
    Ok((iters, sweeps))
}

/// Relative Tikhonov term added to the diagonal of H in the direct solves of a joint
/// system (`Scratch::joint`): constraints that close a loop (three interfaces pairing three
/// coincident nodes) make H singular, with the force circulating round the loop as its
/// null space; the term picks the split of least norm. The polish then works on H itself.
const REGULARISATION: f64 = 1e-11;

/// Largest force of a joint system's direct solve, relative to the largest force that a
/// constraint would need on its own (|bᵢ|/Hᵢᵢ), beyond which its constraints are taken as
/// ones that cannot all hold.
const INCONSISTENT: f64 = 1e6;

/// Projected Gauss–Seidel sweeps from the active-set solution until every constraint
/// satisfies its own contact law given the forces of the others (the rules of a pair,
/// `pair::solve_pair`, with Hᵢᵢ/Δt² in place of w_a + w_b). Where the active-set solution
/// is consistent — the usual case — the first sweep changes nothing. Where coupled friction
/// made it inconsistent (a sliding node whose friction would reverse its own slip) the
/// sweeps settle it, so that every sliding node ends with T along its slip and the forces
/// do no positive work. They stop when no force changes by more than 1e-12 of the largest,
/// or, in a joint system, when no node's net contact force does (the split of a loop's
/// forces is free: `joint.rs`).
///
/// **Acceleration.** While no constraint switches (its mode, its bond, its first slip) a
/// sweep is one fixed map G of the forces, and the sweeps are the fixed-point iteration
/// R ← G(R), linear in its convergence (≈ 0.967 per sweep on the Yingxiuwan meshes: a
/// joint solve took 445 sweeps on average at 4.0–4.2 s of the full mesh). Each sweep's
/// input is then the Anderson-accelerated iterate of the sweeps so far (`anderson.rs`,
/// depth 6), restarted at every switch; the stopping tests judge a sweep's output against
/// its input, so what is kept is a sweep's output, consistent with every law as before.
/// An extrapolation can cross a constraint's switching surface; after
/// [`ACCELERATED_SWITCHES`] switches that followed an accelerated iterate the sweeps go
/// on unaccelerated (on the CI mesh at 3.0–3.3 s, one joint solve cycled without that
/// limit and fell back to the interface sweeps). Measured (docs/benchmarks.md): polish
/// sweeps 590,185 → 59,337 on the full mesh at 4.0–4.2 s.
///
/// At most 20,000 sweeps, then the joint system falls back to the interface-by-interface
/// sweeps of `joint.rs`, whose every sweep solves pairs anew and which settle no better:
/// with 2,000, the Yingxiuwan full mesh at 15.0–15.045 s fell back in 134 of 299 group
/// steps (74 accepted unsettled) and its CI mesh at 3.0–3.3 s in 71 of 1,827; with 20,000,
/// 10 (8 unsettled) and 1 (none), in 10 % and 7 % less time (docs/benchmarks.md).
fn polish(s: &mut Scratch, dt: f64) -> std::result::Result<usize, String> {
    const MAX_SWEEPS: usize = 20000;
    let m = s.active.len();
    // Row ranges of the sorted H list.
    let row = &mut s.row;
    row.clear();
    row.resize(m + 1, 0);
    for &(i, _, _) in &s.h {
        row[i + 1] += 1;
    }
    for i in 0..m {
        row[i + 1] += row[i];
    }
    let fmax = s.active.iter().map(|a| norm(a.r)).fold(0.0, f64::max);
    s.net_prev.clear();
    s.anderson.reset(3 * m);
    // Switches that followed an accelerated iterate; past `ACCELERATED_SWITCHES` of them
    // the sweeps go on unaccelerated (an extrapolation that keeps crossing a constraint's
    // switching surface can cycle, where plain sweeps settle).
    let mut accelerated = false;
    let mut switches_after_acceleration = 0;
    for sweep in 1..=MAX_SWEEPS {
        let mut change: f64 = 0.0;
        let mut scale_f = fmax;
        // Whether a constraint changed its mode, lost its bond or slid for the first time:
        // the sweep is then another map than the last one's, and the acceleration restarts.
        let mut switched = false;
        let accelerating = switches_after_acceleration < ACCELERATED_SWITCHES;
        if accelerating {
            gather_forces(&s.active, &mut s.sweep_in);
        }
        for i in 0..m {
            if s.active[i].fixed {
                continue;
            }
            let mut hii = 0.0;
            let mut coupled = [0.0; 3];
            for &(_, k, h) in &s.h[s.row[i]..s.row[i + 1]] {
                if k == i {
                    hii = h;
                } else {
                    coupled = axpy(coupled, h, s.active[k].r);
                }
            }
            let a = &s.active[i];
            if a.mode == Mode::Open && !a.bonded && a.gbar - dot(coupled, a.n) >= 0.0 {
                // Still open: no force (an accelerated iterate may have put one there).
                let a = &mut s.active[i];
                change = change.max(norm(a.r));
                a.r = [0.0; 3];
                continue;
            }
            // A constraint that slid in this step keeps the kinetic coefficient for the
            // rest of the step: it sticks again only inside the μd cone (static/kinetic
            // switching between coupled nodes otherwise has no fixed point).
            let params = if a.slid {
                PairParams {
                    mu_s: a.params.mu_d,
                    ..a.params
                }
            } else {
                a.params
            };
            let state = if a.bonded {
                PairState::Bonded
            } else {
                PairState::Stick
            };
            // Local problem: relative position after the step d = (d̄ − Σₖ Hᵢₖ Rₖ) − Hᵢᵢ Rᵢ.
            let out = solve_pair(
                state,
                &params,
                &PairInput {
                    n: a.n,
                    w_sum: hii / (dt * dt),
                    dt,
                    rel_pred: sub(a.dbar, coupled),
                    rel_old: a.dn,
                },
            );
            let a = &mut s.active[i];
            change = change.max(norm(sub(out.r, a.r)));
            scale_f = scale_f.max(norm(out.r));
            a.r = out.r;
            let before = (a.mode, a.bonded, a.slid);
            if out.state != PairState::Bonded {
                a.lose_bond();
            }
            a.mode = match out.state {
                PairState::Sliding => {
                    a.slid = true;
                    Mode::Slide
                }
                PairState::Separated => Mode::Open,
                _ => Mode::Stick,
            };
            switched |= before != (a.mode, a.bonded, a.slid);
        }
        if change <= 1e-12 * scale_f.max(f64::MIN_POSITIVE) {
            return Ok(sweep);
        }
        if s.joint && net_settled(s, sweep == 1) {
            return Ok(sweep);
        }
        if switched {
            s.anderson.reset(3 * m);
            switches_after_acceleration += usize::from(accelerated);
            accelerated = false;
            continue;
        }
        if !accelerating {
            continue;
        }
        // The next sweep starts from the accelerated iterate (its own output is what
        // the stopping tests above judge, so the end state is always a sweep's).
        gather_forces(&s.active, &mut s.sweep_out);
        accelerated = s.anderson.step(&mut s.sweep_in, &s.sweep_out);
        if accelerated {
            for (a, x) in s.active.iter_mut().zip(s.sweep_in.chunks_exact(3)) {
                a.r = [x[0], x[1], x[2]];
            }
            if s.joint {
                record_net(s);
            }
        }
    }
    Err(format!(
        "friction of {m} coupled nodes did not settle in {MAX_SWEEPS} Gauss–Seidel sweeps"
    ))
}

/// Net contact force of every node of the system (Σᵢ −eᵢ(j) Rᵢ, `assemble_h`) against the
/// previous sweep's: whether none changed by more than 1e-12 of the largest force (always
/// false on the `first` sweep, which records them).
fn net_settled(s: &mut Scratch, first: bool) -> bool {
    let mut change: f64 = 0.0;
    let mut fmax = s.active.iter().map(|a| norm(a.r)).fold(0.0, f64::max);
    let Scratch {
        by_master,
        active,
        net_prev,
        ..
    } = s;
    for_each_net(by_master, active, |g, net| {
        if first {
            net_prev.push(net);
        } else {
            change = change.max(norm(sub(net, net_prev[g])));
            net_prev[g] = net;
        }
        fmax = fmax.max(norm(net));
    });
    !first && change <= NET_TOLERANCE * fmax.max(f64::MIN_POSITIVE)
}

/// The constraints' forces Rᵢ as one flat vector.
fn gather_forces(active: &[Active], out: &mut Vec<f64>) {
    out.clear();
    out.extend(active.iter().flat_map(|a| a.r));
}

/// Net contact forces recorded as the previous sweep's, without a comparison (the
/// accelerated iterate replaced the last sweep's forces).
fn record_net(s: &mut Scratch) {
    let Scratch {
        by_master,
        active,
        net_prev,
        ..
    } = s;
    for_each_net(by_master, active, |g, net| net_prev[g] = net);
}

/// Calls `f(g, net)` for the g-th node of the system (in the node order of `by_master`)
/// with its net contact force Σᵢ −eᵢ(j) Rᵢ.
fn for_each_net(
    by_master: &[(u32, usize, f64)],
    active: &[Active],
    mut f: impl FnMut(usize, [f64; 3]),
) {
    let mut g = 0;
    let mut start = 0;
    while start < by_master.len() {
        let node = by_master[start].0;
        let mut net = [0.0; 3];
        let mut end = start;
        while end < by_master.len() && by_master[end].0 == node {
            let (_, i, e) = by_master[end];
            net = axpy(net, -e, active[i].r);
            end += 1;
        }
        f(g, net);
        g += 1;
        start = end;
    }
}

/// Mode switches after accelerated iterates past which a polish goes on with plain sweeps.
const ACCELERATED_SWITCHES: usize = 64;

/// Largest change of a node's net contact force between two polish sweeps of a joint
/// system, relative to the largest force, at which the polish stops: the tolerance of the
/// joint sweeps (`joint.rs`).
const NET_TOLERANCE: f64 = 1e-10;

/// All closed nodes stick: (H R)ᵢ = bᵢ with the scalar, symmetric positive definite H acting
/// on each component, so one sparse Cholesky factorisation of the m × m matrix H solves the
/// three components at once. Returns false (nothing written) if H is not positive definite.
fn stick_solve(s: &mut Scratch, m: usize) -> bool {
    s.triplets.clear();
    for &(i, k, h) in &s.h {
        let (ai, ak) = (&s.active[i], &s.active[k]);
        if ai.mode == Mode::Stick && ak.mode == Mode::Stick && ai.offset >= ak.offset {
            let h = if i == k { h + s.reg } else { h };
            s.triplets
                .push(Triplet::new(ai.offset / 3, ak.offset / 3, h));
        }
    }
    let Ok(mat) = SparseColMat::<usize, f64>::try_new_from_triplets(m, m, &s.triplets) else {
        return false;
    };
    let Ok(llt) = mat.sp_cholesky(faer::Side::Lower) else {
        return false;
    };
    let mut rhs = Mat::<f64>::zeros(m, 3);
    for a in &s.active {
        if a.mode == Mode::Stick {
            for d in 0..3 {
                rhs[(a.offset / 3, d)] = a.rhs[d];
            }
        }
    }
    llt.solve_in_place(rhs.as_mut());
    if (0..m).any(|i| (0..3).any(|d| !rhs[(i, d)].is_finite())) {
        return false;
    }
    for a in s.active.iter_mut() {
        a.r = match a.mode {
            Mode::Stick => [0, 1, 2].map(|d| rhs[(a.offset / 3, d)]),
            _ => [0.0; 3],
        };
    }
    true
}

/// Sticking (3 unknowns) and sliding (1 unknown) nodes together: the non-symmetric system
/// of eqs. (20)–(21) with the sliding rows of (21) removed, sparse LU. Returns false if it
/// is singular.
fn general_solve(s: &mut Scratch, size: usize) -> bool {
    s.triplets.clear();
    for &(i, k, h) in &s.h {
        let (ai, ak) = (&s.active[i], &s.active[k]);
        let (oi, ok) = (ai.offset, ak.offset);
        let h = if i == k { h + s.reg } else { h };
        match (ai.mode, ak.mode) {
            (Mode::Open, _) | (_, Mode::Open) => {}
            (Mode::Stick, Mode::Stick) => {
                for d in 0..3 {
                    s.triplets.push(Triplet::new(oi + d, ok + d, h));
                }
            }
            (Mode::Stick, Mode::Slide) => {
                for d in 0..3 {
                    s.triplets.push(Triplet::new(oi + d, ok, h * ak.dir[d]));
                }
            }
            (Mode::Slide, Mode::Stick) => {
                for d in 0..3 {
                    s.triplets.push(Triplet::new(oi, ok + d, h * ai.n[d]));
                }
            }
            (Mode::Slide, Mode::Slide) => {
                s.triplets.push(Triplet::new(oi, ok, h * dot(ai.n, ak.dir)));
            }
        }
    }
    let mut rhs = Mat::<f64>::zeros(size, 1);
    for a in &s.active {
        match a.mode {
            Mode::Stick => {
                for d in 0..3 {
                    rhs[(a.offset + d, 0)] = a.rhs[d];
                }
            }
            Mode::Slide => rhs[(a.offset, 0)] = a.gbar,
            Mode::Open => {}
        }
    }
    let Ok(mat) = SparseColMat::<usize, f64>::try_new_from_triplets(size, size, &s.triplets) else {
        return false;
    };
    let Ok(lu) = mat.sp_lu() else {
        return false;
    };
    lu.solve_in_place(rhs.as_mut());
    if (0..size).any(|i| !rhs[(i, 0)].is_finite()) {
        return false;
    }
    for a in s.active.iter_mut() {
        a.r = match a.mode {
            Mode::Stick => [0, 1, 2].map(|d| rhs[(a.offset + d, 0)]),
            Mode::Slide => scale(rhs[(a.offset, 0)], a.dir),
            Mode::Open => [0.0; 3],
        };
    }
    true
}

/// H restricted to the active set is singular (more constraints than free masses: e.g.
/// fully constrained nodes of a pressing on one free face node). The direct solve is left
/// to the Gauss–Seidel polish, which handles a semi-definite H: start from R = 0.
fn singular_fallback(s: &mut Scratch, iter: usize) -> usize {
    for a in s.active.iter_mut() {
        a.r = [0.0; 3];
        a.released = false;
        a.mode = if (a.bonded || a.gbar < 0.0) && !a.fixed {
            Mode::Stick
        } else {
            Mode::Open
        };
    }
    iter
}

fn active_set(
    s: &mut Scratch,
    dt: f64,
    w_node: &dyn Fn(u32) -> f64,
) -> std::result::Result<usize, String> {
    let m = s.active.len();
    // Nodes that nothing can move get no force.
    assemble_h(s, dt * dt, w_node);
    let mut diag: f64 = 0.0;
    for &(i, k, h) in &s.h {
        if i == k {
            diag = diag.max(h);
            if h <= 0.0 {
                let a = &mut s.active[i];
                a.mode = Mode::Open;
                a.fixed = true;
                a.bonded = false;
            }
        }
    }
    s.reg = if s.joint { REGULARISATION * diag } else { 0.0 };
    let max_iter = 3 * m + 2;
    for iter in 1..=max_iter {
        let mut size = 0;
        for a in s.active.iter_mut() {
            a.offset = size;
            a.r = [0.0; 3];
            size += match a.mode {
                Mode::Stick => 3,
                Mode::Slide => 1,
                Mode::Open => 0,
            };
        }
        if size == 0 {
            return Ok(iter);
        }
        let solved = s.active.iter().all(|a| a.mode != Mode::Slide) && stick_solve(s, size / 3);
        if !solved && !general_solve(s, size) {
            return Ok(singular_fallback(s, iter));
        }
        let mut changed = false;
        for a in s.active.iter_mut() {
            if a.mode == Mode::Open {
                continue;
            }
            // The checks of eqs. (12)–(15), as `pair::solve_pair`.
            let lambda = -dot(a.r, a.n);
            let t = tangential(a.r, a.n);
            let tm = norm(t);
            if lambda < 0.0 {
                if a.bonded && (tm * tm + lambda * lambda).sqrt() <= a.params.tensile_capacity {
                    continue;
                }
                a.lose_bond();
                a.mode = Mode::Open;
                a.r = [0.0; 3];
                a.released = true;
                changed = true;
                continue;
            }
            if a.mode == Mode::Stick {
                let mu = if a.slid { a.params.mu_d } else { a.params.mu_s };
                let cohesion = if a.bonded {
                    a.params.shear_capacity
                } else {
                    0.0
                };
                if tm > (mu * lambda + cohesion) * (1.0 + 1e-12) {
                    a.lose_bond();
                    a.mode = Mode::Slide;
                    a.slid = true;
                    a.dir = axpy(scale(-1.0, a.n), a.params.mu_d / tm, t);
                    changed = true;
                }
            }
        }
        if changed {
            continue;
        }
        // Open nodes that the forces of their neighbours (through shared face nodes) would
        // push into surface b come into contact.
        for a in s.active.iter_mut() {
            a.hr = [0.0; 3];
        }
        for &(i, k, h) in &s.h {
            let rk = s.active[k].r;
            s.active[i].hr = axpy(s.active[i].hr, h, rk);
        }
        for a in s.active.iter_mut() {
            if a.mode == Mode::Open && !a.released && !a.fixed && a.gbar - dot(a.hr, a.n) < 0.0 {
                a.mode = Mode::Stick;
                changed = true;
            }
        }
        if changed {
            continue;
        }
        return Ok(iter);
    }
    Err(format!(
        "active set did not settle in {max_iter} solves ({m} nodes)"
    ))
}

/// Where a node in point-to-surface contact touches surface b in one step: the closest
/// facing face (`search.rs`), its shape functions φ at the contact point c, the contact
/// normal n (minus the outward normal of the face at c) and dⁿ = x_c − xᵢ, all on the
/// configuration at tⁿ.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Touch {
    face: u32,
    xi: f64,
    eta: f64,
    phi: [f64; 4],
    n: [f64; 3],
    dn: [f64; 3],
}

/// The contact search of one interface for one step, found once and used by every solve of
/// that step (the sweeps of a joint solve, `joint.rs`, and of an interface with both pairs
/// and point-to-surface nodes, `mod.rs`).
///
/// What the search depends on: the positions at tⁿ (reference coordinates + Uⁿ) of the
/// nodes in point-to-surface contact and of the faces of surface b, each node's activation
/// offset δ₀ and normal, which faces of b are active, and which nodes are in point-to-surface
/// contact. None of these changes within a step: the predictor Ū^{n+1} and the contact
/// forces of the step enter only d̄ᵢ, never the choice of face, ξ, η, n or dⁿ; records are
/// restored to the start of the step between sweeps, and switches to point-to-surface
/// contact (large slip) and activation (`activity.rs`) happen between steps. So the search
/// is keyed by the `compute` call it was made in ([`StepFaces::stamp`]) and redone, without
/// any caller's help, by the first solve of the next call.
#[derive(Clone, Debug, Default)]
pub(crate) struct StepFaces {
    /// The `ContactSystem::compute` call (its stamp, ≥ 1) the search belongs to; 0: none.
    stamp: u64,
    /// Capture distance of the search (the gap recorded for a node that touches no face).
    capture: f64,
    /// Indexed like `Interface::slaves`: the face touched by each node in point-to-surface
    /// contact, `None` for a node that touches none or is not in that mode.
    touches: Vec<Option<Touch>>,
    /// Indexed like `Interface::slaves`: a pair (point-to-point) whose node or partner is a
    /// node of the point-to-surface system (a node with a touch or a node of its face), so
    /// that its force and the system's change each other within the step.
    coupled: Vec<bool>,
    /// Buffer: the nodes of the point-to-surface system, sorted.
    nodes: Vec<u32>,
}

impl StepFaces {
    /// Whether pair record `k` shares a node with the point-to-surface system of the
    /// `compute` call `stamp` (true when no search of that call is stored: nothing known).
    pub(crate) fn coupled(&self, stamp: u64, k: usize) -> bool {
        self.stamp != stamp || self.coupled.get(k).copied().unwrap_or(true)
    }
}

/// The contact search of `iface` for the `compute` call `stamp` (kept in `iface.faces`):
/// done on the first call of the step, the stored result returned on the later ones.
pub(super) fn step_faces(
    iface: &mut Interface,
    inp: &ContactStepInput,
    stamp: u64,
    grid: &mut FaceGrid,
) {
    if iface.faces.stamp == stamp && stamp != 0 {
        return;
    }
    let cur = |k: u32| -> [f64; 3] {
        let k = k as usize;
        add(inp.coords[k], inp.u_old[k])
    };
    // The faces of b binned over the configuration at tⁿ (`search.rs`).
    grid.rebuild(&iface.b_faces, &iface.b_face_active, iface.b_face_size, cur);
    let cache = &mut iface.faces;
    cache.stamp = stamp;
    cache.capture = grid.capture();
    cache.touches.clear();
    cache.touches.resize(iface.slaves.len(), None);
    // Closest facing face for each node in point-to-surface contact.
    for (sl, touch) in iface.slaves.iter().zip(cache.touches.iter_mut()) {
        if !sl.surface || !sl.active {
            continue;
        }
        // The node's position with its activation offset δ₀ (zero unless it was placed
        // against a surface that had already moved).
        let p = add(cur(sl.node), sl.rel0);
        let Some(FaceHit { face: fi, xi, eta }) = grid.closest(p, sl.normal, &iface.b_faces, cur)
        else {
            continue;
        };
        let x = iface.b_faces[fi as usize].map(cur);
        let n = scale(-1.0, face_normal(&x, xi, eta).unwrap_or([0.0; 3]));
        let phi = face_shape(xi, eta);
        let (xc, _, _) = face_point(&x, xi, eta);
        *touch = Some(Touch {
            face: fi,
            xi,
            eta,
            phi,
            n,
            dn: sub(xc, p),
        });
    }
    // The pairs that share a node with the system.
    cache.nodes.clear();
    for (sl, touch) in iface.slaves.iter().zip(&cache.touches) {
        if let Some(t) = touch {
            cache.nodes.push(sl.node);
            cache
                .nodes
                .extend_from_slice(&iface.b_faces[t.face as usize]);
        }
    }
    cache.nodes.sort_unstable();
    cache.nodes.dedup();
    let nodes = &cache.nodes;
    cache.coupled.clear();
    cache.coupled.extend(iface.slaves.iter().map(|sl| {
        !sl.surface
            && sl.partner != NONE
            && (nodes.binary_search(&sl.node).is_ok() || nodes.binary_search(&sl.partner).is_ok())
    }));
}

/// Point-to-surface contact of every node of `iface` in that mode, for one step (`stamp`:
/// the `compute` call, which keys the contact search, [`StepFaces`]).
pub(super) fn solve(
    iface: &mut Interface,
    inp: &ContactStepInput,
    stamp: u64,
    r: &mut [[f64; 3]],
    s: &mut Scratch,
) -> Result<()> {
    s.touched.clear();
    s.active.clear();
    s.joint = false;
    step_faces(iface, inp, stamp, &mut s.grid);
    for si in 0..iface.slaves.len() {
        if let Some(a) = constraint(iface, 0, si, inp, r) {
            s.active.push(a);
        }
    }
    if s.active.iter().all(|a| a.mode == Mode::Open) {
        for a in &s.active {
            let sl = &mut iface.slaves[a.slave];
            sl.state = PairState::Separated;
            sl.gap = a.gbar;
            sl.normal_force = 0.0;
            sl.tangential = [0.0; 3];
            sl.slip = add(sl.slip, tangential(sub(a.rhs, scale(a.gbar, a.n)), a.n));
        }
        return Ok(());
    }
    let w = inp.inv_mass;
    solve_active(s, inp.dt, &|j| w[j as usize]).map_err(|message| DcfmError::Contact {
        interface: iface.name.clone(),
        message: format!(
            "step {} (t = {:.6e} s): point-to-surface: {message}",
            inp.step, inp.time
        ),
    })?;
    // Forces: Rᵢ on the node, −φⱼ Rᵢ on the face nodes.
    for a in &s.active {
        apply_force(a, r, &mut s.touched);
    }
    for a in &s.active {
        record(&mut iface.slaves[a.slave], a, inp, r);
    }
    Ok(())
}

/// The constraint of record `si` of `iface` (interface number `owner`) if it is a node in
/// point-to-surface contact that touches a face of b in this step (the search of
/// [`step_faces`], done before), with d̄ from the predictor and the forces already in `r`.
/// A node that touches no face is recorded as separated, with the capture distance as its
/// gap.
pub(super) fn constraint(
    iface: &mut Interface,
    owner: usize,
    si: usize,
    inp: &ContactStepInput,
    r: &[[f64; 3]],
) -> Option<Active> {
    let dt2 = inp.dt * inp.dt;
    let capture = iface.faces.capture;
    let sl = &mut iface.slaves[si];
    if !sl.surface || !sl.active {
        return None;
    }
    let Some(Touch {
        face: fi,
        xi,
        eta,
        phi,
        n,
        dn,
    }) = iface.faces.touches[si]
    else {
        sl.face = NONE;
        sl.state = PairState::Separated;
        sl.gap = capture;
        sl.normal_force = 0.0;
        sl.tangential = [0.0; 3];
        return None;
    };
    let face = iface.b_faces[fi as usize];
    let pred = |k: u32| -> [f64; 3] {
        let k = k as usize;
        add(
            inp.coords[k],
            axpy(inp.u_pred[k], dt2 * inp.inv_mass[k], r[k]),
        )
    };
    let xbar = face.map(pred);
    let cbar = (0..4).fold([0.0; 3], |acc, j| axpy(acc, phi[j], xbar[j]));
    let dbar = sub(cbar, add(pred(sl.node), sl.rel0));
    sl.face = fi;
    sl.xi = [xi, eta];
    sl.gap_start = dot(dn, n);
    let params = PairParams {
        mu_s: iface.mu_s,
        mu_d: iface.mu_d,
        shear_capacity: 0.0,
        tensile_capacity: 0.0,
    };
    let mut a = Active::new((owner, si), sl.node, face, phi, n, dbar, dn, params, false);
    a.slid = sl.slid;
    Some(a)
}

/// Adds the force of a solved constraint to `r`: Rᵢ on its node, −φⱼ Rᵢ on its face nodes
/// (a pair's partner: −Rᵢ), and lists the nodes in `touched`.
pub(super) fn apply_force(a: &Active, r: &mut [[f64; 3]], touched: &mut Vec<u32>) {
    if a.mode == Mode::Open {
        return;
    }
    let i = a.node as usize;
    r[i] = add(r[i], a.r);
    touched.push(a.node);
    for (j, f) in distribute(&a.phi, a.r).into_iter().enumerate() {
        if a.phi[j] != 0.0 && a.face[j] != NONE {
            let k = a.face[j] as usize;
            r[k] = add(r[k], f);
            touched.push(a.face[j]);
        }
    }
}

/// The record of a node in point-to-surface contact after its solve, from the corrected
/// positions (`r` complete): gap, slip increment, forces, state.
pub(super) fn record(
    sl: &mut super::SlaveNode,
    a: &Active,
    inp: &ContactStepInput,
    r: &[[f64; 3]],
) {
    let dt2 = inp.dt * inp.dt;
    let corr = |k: u32| -> [f64; 3] {
        let k = k as usize;
        add(
            inp.coords[k],
            axpy(inp.u_pred[k], dt2 * inp.inv_mass[k], r[k]),
        )
    };
    let c = (0..4).fold([0.0; 3], |acc, j| axpy(acc, a.phi[j], corr(a.face[j])));
    let d = sub(c, add(corr(a.node), sl.rel0));
    let dslip = tangential(sub(d, a.dn), a.n);
    sl.gap = dot(d, a.n);
    sl.slip = add(sl.slip, dslip);
    let lambda = -dot(a.r, a.n);
    sl.normal_force = if a.mode == Mode::Open { 0.0 } else { lambda };
    sl.force = a.r;
    sl.slid |= a.slid;
    sl.tangential = tangential(a.r, a.n);
    sl.state = a.state();
    if sl.state == PairState::Sliding {
        sl.acc_slip += norm(dslip);
    }
}
