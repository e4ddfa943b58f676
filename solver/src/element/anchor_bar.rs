//! Anchor bars embedded in rock or concrete (paper §3 and its ref. [39], Xiao 1992: the
//! implicit anchor bar element whose stiffness is superposed on its host elements).
//!
//! Each bar is cut into segments where it crosses host element faces (and, optionally,
//! into pieces no longer than `segment_length`); the ends of a segment lie in one host
//! element, located by their natural coordinates (Newton inverse map of the trilinear hex).
//!
//! **Perfect bond** (default): a segment of length l along the unit vector t between host
//! points p and q has the axial strain ε = t·(u(q) − u(p))/l with u(ξ) = Σ N_a(ξ) u_a, the
//! force N = N₀ + EA (ε − εᵖ) of elastic–perfectly plastic steel (|N| ≤ f_y A, εᵖ grows by
//! the excess), and returns f_a = N t (N_a(q) − N_a(p)) to the host nodes — the internal
//! force ∂W/∂u_a of W = ½ EA l ε². N₀ is the pretension. The steel mass ρAl goes to the
//! host nodes through the shape functions.
//!
//! **Bond–slip** (`bond_stiffness` k_s given): the bar has its own nodes at the segment
//! ends, each with one axial displacement w_i and the steel mass of its half segments; a
//! bond spring k_s l_i (l_i the node's tributary length) ties w_i to the axial host
//! displacement t·u(p_i). The bar nodes are integrated by central difference in step with
//! the host ([`AnchorBars::commit`]). Pull-out of such a bar from a fixed host follows
//! N(x) = P sinh(λ(L − x))/sinh(λL), λ = √(k_s/EA) (VERIFICATION.md W11).
//!
//! Determinism: the perfect-bond pass works on the segments grouped by host element (the
//! reinforcement mats put many segments in every concrete element) in parallel phases
//! whose results do not depend on how rayon splits them
//! ([`AnchorBars::add_internal_forces`]): every host's segments' axial forces from its
//! nodes, read once, and its eight nodal forces summed over them in segment order, then
//! every host node's sum over its hosts in ascending order — the additions, in their
//! order, of a serial loop over the hosts. The bond–slip bars follow serially in input
//! order. So results do not depend on the number of threads.

use rayon::prelude::*;
use serde::Deserialize;

use crate::element::groups::SharedMut;
use crate::element::host_locate::{HostLocator, HostPoint};
use crate::element::lanes::{run_lane_work, F64s, LaneWork, Simd};
use crate::lanes8;
use crate::mesh::Mesh;

/// `[[anchors.bars]]`: one bar between two points.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct BarSpec {
    /// Name (histories, messages); default `bar<i>`.
    #[serde(default)]
    pub name: Option<String>,
    pub start: [f64; 3],
    pub end: [f64; 3],
    #[serde(flatten)]
    pub steel: SteelSpec,
}

/// Steel and bond of a bar or pattern.
#[derive(Clone, Debug, Deserialize, PartialEq)]
pub struct SteelSpec {
    /// Bar diameter (m); A = π d²/4.
    pub diameter: f64,
    /// Young's modulus (Pa).
    #[serde(default = "default_young")]
    pub young: f64,
    /// Yield stress f_y (Pa).
    pub yield_stress: f64,
    /// Steel density (kg/m³).
    #[serde(default = "default_density")]
    pub density: f64,
    /// Pretension (N): initial axial force (perfect bond), or a head force against a plate
    /// on the host (bond–slip).
    #[serde(default)]
    pub pretension: f64,
    /// Bond stiffness per length k_s (N/m per m): the bar gets its own nodes tied to the
    /// host by bond springs. Default: perfect bond.
    #[serde(default)]
    pub bond_stiffness: Option<f64>,
    /// Largest segment length (m); default: segments end at host element faces only.
    #[serde(default)]
    pub segment_length: Option<f64>,
}

fn default_young() -> f64 {
    200e9
}
fn default_density() -> f64 {
    7850.0
}

/// `[[anchors.patterns]]`: bars from every part of a face set into its elements.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PatternSpec {
    /// Name (histories); default `pattern<i>`.
    #[serde(default)]
    pub name: Option<String>,
    /// The face set the bars start from; they run along the inward normal (into the
    /// faces' own elements).
    pub face_set: String,
    /// Bar length (m).
    pub length: f64,
    /// One bar per `spacing`² of surface (m).
    pub spacing: f64,
    /// Depth of each bar's start below its face along the inward normal (m): 0 (the
    /// default) starts at the face, as a bolt does; a tie between the two reinforcement
    /// mats of a wall starts at the inner mat's cover.
    #[serde(default)]
    pub depth: f64,
    #[serde(flatten)]
    pub steel: SteelSpec,
}

/// `[anchors]`.
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct AnchorSection {
    #[serde(default)]
    pub bars: Vec<BarSpec>,
    #[serde(default)]
    pub patterns: Vec<PatternSpec>,
    #[serde(default)]
    pub mats: Vec<crate::element::anchor_mat::MatSpec>,
}

/// One segment of a perfectly bonded bar, inside one host element.
#[derive(Clone, Debug)]
pub struct Segment {
    pub bar: u32,
    pub host: u32,
    /// N_a(q) − N_a(p) over the host's eight nodes.
    pub g: [f64; 8],
    /// End points (reference) and the shape functions there.
    pub p: HostPoint,
    pub q: HostPoint,
    pub t: [f64; 3],
    pub length: f64,
    /// End points (reference).
    pub x: [[f64; 3]; 2],
    /// The host element's nodes.
    pub nodes: [u32; 8],
}

/// What the force pass reads of a perfect-bond segment, packed (built by
/// [`AnchorBars::finish`], in host order: see [`HostBlocks`]).
#[derive(Clone, Debug)]
struct SegmentKernel {
    /// Segment index in [`AnchorBars::segments`].
    segment: u32,
    g: [f64; 8],
    t: [f64; 3],
    length: f64,
    ea: f64,
    yield_force: f64,
    pretension: f64,
    /// Elongation t·(u(q) − u(p)) at installation ([`AnchorBars::install_at`]; 0 until
    /// then).
    reference: f64,
}

/// The perfect-bond segments grouped by host element, and the buffers of the force pass
/// ([`AnchorBars::add_internal_forces`]), sized by [`AnchorBars::finish`] so that the step
/// loop allocates nothing. Kernels are the segments sorted by (host element, segment).
#[derive(Clone, Debug, Default)]
struct HostBlocks {
    /// Nodes of every host element, hosts in ascending element order.
    host_nodes: Vec<[u32; 8]>,
    /// Kernels of host h: `start[h]..start[h + 1]`.
    start: Vec<u32>,
    /// Kernel of every segment (the inverse of [`SegmentKernel::segment`]).
    kernel_of: Vec<u32>,
    /// Axial force and trial plastic strain of every kernel at the last pass.
    axial: Vec<(f64, f64)>,
    /// Forces on the eight nodes of every host at the last pass, the nodes in lanes
    /// (component d of node a: `[d][a]`).
    host_force: Vec<[F64s; 3]>,
    /// Distinct host nodes, ascending, with their entries (host, local node) in ascending
    /// host order: `entry_start[i]..entry_start[i + 1]` (CSR).
    scatter_nodes: Vec<u32>,
    entry_start: Vec<u32>,
    entry: Vec<(u32, u8)>,
    /// f_int of every host node with its hosts' forces added.
    sum: Vec<[f64; 3]>,
}

impl HostBlocks {
    /// Group `segments` by host (stably: segment order within a host) and build the
    /// node scatter.
    fn new(segments: &[Segment], bars: &[BarInfo]) -> (Self, Vec<SegmentKernel>) {
        let mut order: Vec<u32> = (0..segments.len() as u32).collect();
        order.sort_by_key(|&k| (segments[k as usize].host, k));
        let mut blocks = HostBlocks::default();
        let mut kernels = Vec::with_capacity(segments.len());
        let mut last_host = None;
        for &k in &order {
            let sg = &segments[k as usize];
            if last_host != Some(sg.host) {
                last_host = Some(sg.host);
                blocks.start.push(kernels.len() as u32);
                blocks.host_nodes.push(sg.nodes);
            }
            let info = &bars[sg.bar as usize];
            kernels.push(SegmentKernel {
                segment: k,
                g: sg.g,
                t: sg.t,
                length: sg.length,
                ea: info.ea,
                yield_force: info.yield_force,
                pretension: info.pretension,
                reference: 0.0,
            });
        }
        blocks.start.push(kernels.len() as u32);
        blocks.kernel_of = vec![0; segments.len()];
        for (kernel, s) in kernels.iter().enumerate() {
            blocks.kernel_of[s.segment as usize] = kernel as u32;
        }
        let mut pairs: Vec<(u32, u32, u8)> = Vec::with_capacity(8 * blocks.host_nodes.len());
        for (h, nodes) in blocks.host_nodes.iter().enumerate() {
            for (a, &n) in nodes.iter().enumerate() {
                pairs.push((n, h as u32, a as u8));
            }
        }
        pairs.sort_unstable();
        for (i, p) in pairs.iter().enumerate() {
            if blocks.scatter_nodes.last() != Some(&p.0) {
                blocks.scatter_nodes.push(p.0);
                blocks.entry_start.push(i as u32);
            }
        }
        blocks.entry_start.push(pairs.len() as u32);
        blocks.entry = pairs.iter().map(|&(_, h, a)| (h, a)).collect();
        blocks.sum = vec![[0.0; 3]; blocks.scatter_nodes.len()];
        blocks.axial = vec![(0.0, 0.0); kernels.len()];
        blocks.host_force = vec![[F64s::ZERO; 3]; blocks.host_nodes.len()];
        (blocks, kernels)
    }
}

/// Segments per parallel task of [`AnchorBars::history_values`].
const HISTORY_SEGMENTS_PER_TASK: usize = 8192;

/// Segments per rayon task of the segment phase, hosts per task of the host phase, host
/// nodes per task of the node phase: large enough to amortise the task, small enough to
/// balance two to a few threads.
const SEGMENTS_PER_TASK: usize = 1024;
const HOSTS_PER_TASK: usize = 128;
const NODES_PER_TASK: usize = 512;

/// A bond–slip bar: its own nodes.
#[derive(Clone, Debug)]
pub struct BondSlipBar {
    pub bar: u32,
    pub t: [f64; 3],
    /// Node positions (reference), hosts, tributary lengths, masses.
    pub x: Vec<[f64; 3]>,
    pub hosts: Vec<HostPoint>,
    pub bond: Vec<f64>,
    pub mass: Vec<f64>,
    /// Segment lengths (n − 1).
    pub lengths: Vec<f64>,
    /// Axial displacement w_i and half-step velocity of the nodes.
    pub w: Vec<f64>,
    /// Axial host displacement t·u(p_i) at installation ([`AnchorBars::install_at`]; 0
    /// for bars present from the start): the bond springs measure from it.
    pub host_reference: Vec<f64>,
    pub v: Vec<f64>,
    /// Internal forces on the nodes at the last internal-force pass.
    f: Vec<f64>,
    /// Axial force pulling the head (node 0) out of the host (N); with `plate` the host
    /// takes the reaction at the head.
    pub head_load: f64,
    pub plate: bool,
    /// First segment of this bar in the state arrays.
    first: usize,
}

/// Per-bar constants.
#[derive(Clone, Debug)]
pub struct BarInfo {
    pub name: String,
    /// Group for histories (the bar's own name or its pattern's).
    pub group: String,
    pub ea: f64,
    pub yield_force: f64,
    pub pretension: f64,
    /// Steel mass per length ρA (kg/m).
    pub mass_per_length: f64,
    pub start: [f64; 3],
    pub end: [f64; 3],
}

/// Which history group every anchor segment belongs to ([`AnchorBars::history_layout`]).
#[derive(Clone, Debug, Default)]
pub struct AnchorHistoryLayout {
    groups: usize,
    segment_group: Vec<u32>,
    segment_yield: Vec<f64>,
}

/// All the anchor bars of a model with their state.
#[derive(Clone, Debug, Default)]
pub struct AnchorBars {
    pub bars: Vec<BarInfo>,
    pub segments: Vec<Segment>,
    pub bond_slip: Vec<BondSlipBar>,
    /// Plastic strain of every segment (perfect-bond segments first, then the bond–slip
    /// bars' segments), committed and trial.
    plastic: Vec<f64>,
    plastic_trial: Vec<f64>,
    /// `plastic_trial` holds the trial strains of a force pass not yet committed (every
    /// entry: the pass writes them all), so that [`AnchorBars::commit`] takes them by a
    /// swap of the two buffers, without a copy.
    trial_pending: bool,
    /// Axial force of every segment at the last internal-force pass (N).
    pub force: Vec<f64>,
    /// Packed segment data in host order and the host blocks of the force pass.
    kernels: Vec<SegmentKernel>,
    blocks: HostBlocks,
}

/// A bar's name and its history group.
pub struct BarNames {
    pub name: String,
    pub group: String,
}

/// Segments for VTU line output: end points, point pairs, axial force, plastic strain and
/// bar per line.
pub struct BarLines {
    pub points: Vec<[f64; 3]>,
    pub lines: Vec<[u32; 2]>,
    pub force: Vec<f64>,
    /// Committed plastic strain εᵖ of every line (0 until its segment yields).
    pub plastic_strain: Vec<f64>,
    pub bar: Vec<f64>,
}

/// Why a bar could not be built (as text; the case builder adds the field path).
pub type BarError = String;

/// The element holding `p` when only elements that may not host bars do (docs/anchors.md,
/// "Host elements": those inactive when the bars are installed).
fn inactive_host(locator: &HostLocator, mesh: &Mesh, p: &[f64; 3]) -> Option<u32> {
    if locator.locate(mesh, p).is_some() {
        return None;
    }
    locator.locate_any(mesh, p).map(|h| h.element)
}

/// The error of a bar point `p`, `from_start` m along the bar, held only by the inactive
/// element `e`.
fn inactive_message(p: &[f64; 3], from_start: f64, e: u32) -> BarError {
    format!(
        "runs at {p:?} ({from_start:.3} m from its start) through element {e} only, which is \
         not active when the bars are installed (excavated or not yet placed by the static \
         stage): a bar point needs an active host"
    )
}

impl AnchorBars {
    /// The host elements of every bar (perfect-bond segments and bond–slip bar nodes), with
    /// repeats: the elements whose nodes take the bars' forces.
    pub fn host_elements(&self) -> impl Iterator<Item = u32> + '_ {
        self.segments.iter().map(|s| s.host).chain(
            self.bond_slip
                .iter()
                .flat_map(|b| b.hosts.iter().map(|h| h.element)),
        )
    }

    /// Add one straight bar from `a` to `b`, cut at the faces of the elements `locator`
    /// holds; `group` names its history group.
    pub fn add_bar(
        &mut self,
        mesh: &Mesh,
        locator: &HostLocator,
        names: BarNames,
        [a, b]: [[f64; 3]; 2],
        steel: &SteelSpec,
    ) -> Result<(), BarError> {
        let BarNames { name, group } = names;
        let len = (0..3).map(|d| (b[d] - a[d]).powi(2)).sum::<f64>().sqrt();
        if !(len.is_finite() && len > 0.0) {
            return Err(format!("start and end must differ (length {len} m)"));
        }
        let t: [f64; 3] = std::array::from_fn(|d| (b[d] - a[d]) / len);
        let (cuts, hosts) = locator
            .cut(mesh, &a, &b, steel.segment_length)
            .map_err(|s| {
                let p: [f64; 3] = std::array::from_fn(|d| a[d] + s * (b[d] - a[d]));
                match inactive_host(locator, mesh, &p) {
                    Some(e) => inactive_message(&p, s * len, e),
                    None => format!("leaves the mesh at {p:?} ({:.3} m from its start)", s * len),
                }
            })?;
        let at = |s: f64| -> [f64; 3] { std::array::from_fn(|d| a[d] + s * (b[d] - a[d])) };
        let area = 0.25 * std::f64::consts::PI * steel.diameter * steel.diameter;
        let bar = self.bars.len() as u32;
        self.bars.push(BarInfo {
            name,
            group,
            ea: steel.young * area,
            yield_force: steel.yield_stress * area,
            pretension: steel.pretension,
            mass_per_length: steel.density * area,
            start: a,
            end: b,
        });
        let locate = |e: u32, s: f64| {
            locator.locate_in(mesh, e, &at(s), 1e-6).ok_or_else(|| {
                let p = at(s);
                match inactive_host(locator, mesh, &p) {
                    Some(h) => inactive_message(&p, s * len, h),
                    None => format!(
                        "could not locate the point at {:.3} m in element {e}",
                        s * len
                    ),
                }
            })
        };
        match steel.bond_stiffness {
            None => {
                for (w, &h) in cuts.windows(2).zip(&hosts) {
                    let (p, q) = (locate(h, w[0])?, locate(h, w[1])?);
                    self.segments.push(Segment {
                        bar,
                        host: h,
                        g: std::array::from_fn(|k| q.n[k] - p.n[k]),
                        p,
                        q,
                        t,
                        length: (w[1] - w[0]) * len,
                        x: [at(w[0]), at(w[1])],
                        nodes: mesh.elements[h as usize],
                    });
                }
            }
            Some(ks) => {
                let n = cuts.len();
                let lengths: Vec<f64> = cuts.windows(2).map(|w| (w[1] - w[0]) * len).collect();
                let mut host_points = Vec::with_capacity(n);
                for (i, &s) in cuts.iter().enumerate() {
                    let h = hosts[i.min(hosts.len() - 1)];
                    host_points.push(locate(h, s)?);
                }
                let trib: Vec<f64> = (0..n)
                    .map(|i| {
                        0.5 * (if i > 0 { lengths[i - 1] } else { 0.0 }
                            + if i + 1 < n { lengths[i] } else { 0.0 })
                    })
                    .collect();
                self.bond_slip.push(BondSlipBar {
                    bar,
                    t,
                    x: cuts.iter().map(|&s| at(s)).collect(),
                    hosts: host_points,
                    bond: trib.iter().map(|l| ks * l).collect(),
                    mass: trib.iter().map(|l| steel.density * area * l).collect(),
                    lengths,
                    w: vec![0.0; n],
                    host_reference: vec![0.0; n],
                    v: vec![0.0; n],
                    f: vec![0.0; n],
                    head_load: steel.pretension,
                    plate: true,
                    first: 0,
                });
            }
        }
        Ok(())
    }

    /// Size the state arrays once every bar is added.
    pub fn finish(&mut self) {
        let mut n = self.segments.len();
        for b in self.bond_slip.iter_mut() {
            b.first = n;
            n += b.lengths.len();
        }
        self.plastic = vec![0.0; n];
        self.plastic_trial = vec![0.0; n];
        self.force = vec![0.0; n];
        let (blocks, kernels) = HostBlocks::new(&self.segments, &self.bars);
        self.blocks = blocks;
        self.kernels = kernels;
    }

    /// Install the bars in the deformed configuration `u` (host displacements): from now
    /// on they measure the host's displacement from `u`, so a bar grouted into rock that
    /// has already moved carries only its pretension until the rock moves further (bolts
    /// installed after the excavation, the static stage's displacements handed to the
    /// dynamic stage). The bars' own state (plastic strains, bond–slip nodes) is kept.
    pub fn install_at(&mut self, mesh: &Mesh, u: &[[f64; 3]]) {
        let axial = |host: u32, w: &[f64; 8], t: &[f64; 3]| {
            let conn = mesh.elements[host as usize];
            (0..8)
                .map(|a| {
                    let ua = u[conn[a] as usize];
                    w[a] * (t[0] * ua[0] + t[1] * ua[1] + t[2] * ua[2])
                })
                .sum::<f64>()
        };
        for k in self.kernels.iter_mut() {
            let s = &self.segments[k.segment as usize];
            k.reference = axial(s.host, &s.g, &s.t);
        }
        for b in self.bond_slip.iter_mut() {
            b.host_reference = b
                .hosts
                .iter()
                .map(|h| axial(h.element, &h.n, &b.t))
                .collect();
        }
    }

    /// Number of bars.
    pub fn len(&self) -> usize {
        self.bars.len()
    }

    pub fn is_empty(&self) -> bool {
        self.bars.is_empty()
    }

    /// Per history group, in order of first appearance: (group, bars, total length in m,
    /// steel mass in kg) — what `dcfm check` reports.
    pub fn group_totals(&self) -> Vec<(String, usize, f64, f64)> {
        let mut out: Vec<(String, usize, f64, f64)> = Vec::new();
        for b in &self.bars {
            let len = (0..3)
                .map(|d| (b.end[d] - b.start[d]).powi(2))
                .sum::<f64>()
                .sqrt();
            let k = match out.iter().position(|g| g.0 == b.group) {
                Some(k) => k,
                None => {
                    out.push((b.group.clone(), 0, 0.0, 0.0));
                    out.len() - 1
                }
            };
            out[k].1 += 1;
            out[k].2 += len;
            out[k].3 += len * b.mass_per_length;
        }
        out
    }

    /// Steel mass of the perfectly bonded segments, added to their host nodes (half of a
    /// segment to each end, spread by the shape functions).
    pub fn add_host_masses(&self, mesh: &Mesh, mass: &mut [f64]) {
        for s in &self.segments {
            let m = self.bars[s.bar as usize].mass_per_length * s.length;
            let conn = mesh.elements[s.host as usize];
            for a in 0..8 {
                mass[conn[a] as usize] += 0.5 * m * (s.p.n[a] + s.q.n[a]);
            }
        }
    }

    /// Add the bars' internal forces for host displacements `u` to `f_int` (the lead's
    /// internal-force pass calls this after the element colours). Plastic strains are
    /// trial values until [`AnchorBars::commit`].
    ///
    /// Perfect bond, in parallel phases over buffers sized by [`AnchorBars::finish`]:
    /// 1. every host element h (its own kernels only): its nodes' displacements read once,
    ///    then for each of its segments k in ascending order ε = t·(u(q) − u(p))/l, N and
    ///    the trial εᵖ ([`elastic_plastic`]), and (N t)_k (N_a(q) − N_a(p)) added to the
    ///    host's eight nodal forces;
    /// 2. every host node n: f_int(n) + the forces of its hosts in ascending order, then
    ///    written back to f_int;
    /// 3. the axial forces and trial plastic strains copied into segment order.
    ///
    /// Each node receives exactly the additions, in exactly the order, of a serial loop
    /// over the segments in input order, however rayon splits the work: the forces are
    /// the same bit for bit on any number of threads.
    pub fn add_internal_forces(&mut self, mesh: &Mesh, u: &[[f64; 3]], f_int: &mut [[f64; 3]]) {
        let nseg = self.segments.len();
        let blocks = &mut self.blocks;
        // 1. Every host: its nodes' displacements gathered once, then its segments in
        // segment order (kernels are sorted by host): each segment's axial force and trial
        // plastic strain from them, and its N t (N_a(q) − N_a(p)) added to the host's
        // nodal forces — the additions of a serial loop, in its order.
        {
            let plastic = &self.plastic[..nseg];
            let axial = SharedMut(blocks.axial.as_mut_ptr());
            let (kernels, start, host_nodes) = (&self.kernels, &blocks.start, &blocks.host_nodes);
            blocks
                .host_force
                .par_chunks_mut(HOSTS_PER_TASK)
                .enumerate()
                .for_each(|(c, out)| {
                    run_lane_work(HostForces {
                        kernels,
                        start,
                        host_nodes,
                        plastic,
                        u,
                        axial,
                        first: c * HOSTS_PER_TASK,
                        out,
                    })
                });
        }
        // 2. Every host node's sum over its hosts in ascending order.
        {
            let (scatter_nodes, entry_start, entry) =
                (&blocks.scatter_nodes, &blocks.entry_start, &blocks.entry);
            let host_force = &blocks.host_force;
            let f_in: &[[f64; 3]] = f_int;
            blocks
                .sum
                .par_iter_mut()
                .enumerate()
                .with_min_len(NODES_PER_TASK)
                .for_each(|(i, sum)| {
                    let mut f = f_in[scatter_nodes[i] as usize];
                    for &(h, a) in &entry[entry_start[i] as usize..entry_start[i + 1] as usize] {
                        let v = &host_force[h as usize];
                        for d in 0..3 {
                            f[d] += v[d][a as usize];
                        }
                    }
                    *sum = f;
                });
            for (&n, f) in blocks.scatter_nodes.iter().zip(&blocks.sum) {
                f_int[n as usize] = *f;
            }
        }
        // 3. The axial forces and trial plastic strains in segment order.
        {
            let (kernel_of, axial) = (&blocks.kernel_of, &blocks.axial);
            self.force[..nseg]
                .par_iter_mut()
                .zip(self.plastic_trial[..nseg].par_iter_mut())
                .zip(kernel_of.par_iter())
                .with_min_len(SEGMENTS_PER_TASK)
                .for_each(|((force, trial), &k)| {
                    (*force, *trial) = axial[k as usize];
                });
        }
        for bi in 0..self.bond_slip.len() {
            let info = &self.bars[self.bond_slip[bi].bar as usize];
            let (ea, fy) = (info.ea, info.yield_force);
            let first = self.bond_slip[bi].first;
            let nseg = self.bond_slip[bi].lengths.len();
            // Axial forces of the bar's own segments.
            for s in 0..nseg {
                let b = &self.bond_slip[bi];
                let eps = (b.w[s + 1] - b.w[s]) / b.lengths[s];
                let (n, ep) = elastic_plastic(self.plastic[first + s], ea, fy, 0.0, eps);
                self.plastic_trial[first + s] = ep;
                self.force[first + s] = n;
            }
            let b = &mut self.bond_slip[bi];
            for i in 0..b.w.len() {
                // Bar node: −N of the segment it starts, +N of the one it ends.
                let mut fi = 0.0;
                if i < nseg {
                    fi -= self.force[first + i];
                }
                if i > 0 {
                    fi += self.force[first + i - 1];
                }
                let h = &b.hosts[i];
                let conn = mesh.elements[h.element as usize];
                let mut uh = 0.0;
                for a in 0..8 {
                    let ua = u[conn[a] as usize];
                    uh += h.n[a] * (b.t[0] * ua[0] + b.t[1] * ua[1] + b.t[2] * ua[2]);
                }
                let bond = b.bond[i] * (b.w[i] - (uh - b.host_reference[i]));
                fi += bond;
                b.f[i] = fi;
                // The host takes −bond along t (and the plate reaction at the head).
                let mut fh = -bond;
                if i == 0 && b.plate {
                    fh -= b.head_load;
                }
                for a in 0..8 {
                    let f = &mut f_int[conn[a] as usize];
                    for d in 0..3 {
                        f[d] += fh * b.t[d] * h.n[a];
                    }
                }
            }
        }
        self.trial_pending = true;
    }

    /// End of a step: commit the plastic strains and advance the bond–slip bars' own nodes
    /// by central difference with mass-proportional damping `alpha` (the model's α):
    /// velocity increment `dt_v` (½(Δt⁻ + h), Δt for full steps), then displacement
    /// increment `h` × velocity (stage::dynamic, variable step).
    pub fn commit(&mut self, dt_v: f64, h: f64, alpha: f64) {
        // The pass wrote every trial strain: the buffers change roles, and the next pass
        // overwrites the old committed strains left in `plastic_trial`. Without a pass
        // since the last commit there is nothing to take.
        if std::mem::take(&mut self.trial_pending) {
            std::mem::swap(&mut self.plastic, &mut self.plastic_trial);
        }
        for b in self.bond_slip.iter_mut() {
            for i in 0..b.w.len() {
                // The head load pulls node 0 out (against t).
                let ext = if i == 0 { -b.head_load } else { 0.0 };
                let m = b.mass[i];
                b.v[i] += dt_v * (ext - b.f[i] - alpha * m * b.v[i]) / m;
                b.w[i] += h * b.v[i];
            }
        }
    }

    /// Gershgorin bound on the largest eigenvalue of M^{-1/2} K_bars M^{-1/2} (host masses
    /// `mass`, the bar nodes' own masses): by Weyl's inequality the model's ω²_max is at
    /// most the elements' ω²_max plus this, so 2/√(ω²_h + ω²_b) is a stable step.
    pub fn omega_squared_bound(&self, mesh: &Mesh, mass: &[f64]) -> f64 {
        let mut row = vec![0.0f64; 3 * mesh.n_nodes()];
        let mut worst = 0.0f64;
        for s in &self.segments {
            let info = &self.bars[s.bar as usize];
            let k = info.ea / s.length;
            let conn = mesh.elements[s.host as usize];
            let gs: f64 = (0..8)
                .map(|b| s.g[b].abs() / mass[conn[b] as usize].sqrt())
                .sum();
            let ts: f64 = s.t.iter().map(|v| v.abs()).sum();
            for a in 0..8 {
                let n = conn[a] as usize;
                for i in 0..3 {
                    row[3 * n + i] += k * s.g[a].abs() / mass[n].sqrt() * gs * s.t[i].abs() * ts;
                }
            }
        }
        for b in &self.bond_slip {
            let info = &self.bars[b.bar as usize];
            let n = b.w.len();
            // The bar's own axial chain: its exact largest eigenvalue (Sturm bisection, an
            // upper bound); the bond springs by Gershgorin, added by Weyl.
            let chain = chain_max_eigenvalue(info.ea, &b.lengths, &b.mass);
            let mut bond_worst = 0.0f64;
            for i in 0..n {
                let mi = b.mass[i];
                let mut r = 0.0;
                // Bond spring: its own diagonal and the coupling to the host nodes.
                let h = &b.hosts[i];
                let conn = mesh.elements[h.element as usize];
                let ts: f64 = b.t.iter().map(|v| v.abs()).sum();
                let hs: f64 = (0..8).map(|a| h.n[a] / mass[conn[a] as usize].sqrt()).sum();
                r += b.bond[i] / mi + b.bond[i] / mi.sqrt() * hs * ts;
                bond_worst = bond_worst.max(r);
                for a in 0..8 {
                    let nn = conn[a] as usize;
                    for d in 0..3 {
                        row[3 * nn + d] += b.bond[i] * h.n[a] / mass[nn].sqrt()
                            * b.t[d].abs()
                            * (1.0 / mi.sqrt() + hs * ts);
                    }
                }
            }
            worst = worst.max(chain + bond_worst);
        }
        row.into_iter().fold(worst, f64::max)
    }

    /// History values: per group, the largest axial force (N) and the number of yielded
    /// segments, in the order of [`AnchorBars::history_names`].
    pub fn history_names(&self) -> Vec<String> {
        let mut out = Vec::new();
        for g in self.groups() {
            out.push(format!("anchor_{g}_max_force"));
            out.push(format!("anchor_{g}_yielded_segments"));
        }
        out
    }

    fn groups(&self) -> Vec<String> {
        let mut g: Vec<String> = Vec::new();
        for b in &self.bars {
            if !g.contains(&b.group) {
                g.push(b.group.clone());
            }
        }
        g
    }

    /// Bar of every segment in the state arrays.
    fn segment_bars(&self) -> Vec<u32> {
        let mut out: Vec<u32> = self.segments.iter().map(|s| s.bar).collect();
        for b in &self.bond_slip {
            out.extend(std::iter::repeat_n(b.bar, b.lengths.len()));
        }
        out
    }

    /// The group of every segment in the state arrays, worked out once before the step
    /// loop so that [`AnchorBars::history_values`] allocates nothing.
    pub fn history_layout(&self) -> AnchorHistoryLayout {
        let groups = self.groups();
        let bars = self.segment_bars();
        let segment_group = bars
            .iter()
            .map(|&b| {
                let name = &self.bars[b as usize].group;
                groups.iter().position(|g| g == name).unwrap_or(0) as u32
            })
            .collect();
        let segment_yield = bars
            .iter()
            .map(|&b| self.bars[b as usize].yield_force)
            .collect();
        AnchorHistoryLayout {
            groups: groups.len(),
            segment_group,
            segment_yield,
        }
    }

    /// Append the history values to `row`, in the order of
    /// [`AnchorBars::history_names`].
    pub fn history_values(&self, layout: &AnchorHistoryLayout, row: &mut Vec<f64>) {
        // Fixed chunks of segments in parallel, each with its groups' pairs (max, yielded);
        // maxima and counts do not depend on the order they are combined in (a zero
        // maximum is written as +0).
        let groups = layout.groups;
        let n_chunks = layout
            .segment_group
            .len()
            .div_ceil(HISTORY_SEGMENTS_PER_TASK);
        let partial: Vec<Vec<f64>> = (0..n_chunks)
            .into_par_iter()
            .map(|c| {
                let mut pairs = vec![0.0f64; 2 * groups];
                let start = c * HISTORY_SEGMENTS_PER_TASK;
                let end = (start + HISTORY_SEGMENTS_PER_TASK).min(layout.segment_group.len());
                for k in start..end {
                    let g = layout.segment_group[k] as usize;
                    pairs[2 * g] = pairs[2 * g].max(self.force[k]);
                    if self.plastic[k] != 0.0
                        && self.force[k].abs() >= layout.segment_yield[k] * (1.0 - 1e-12)
                    {
                        pairs[2 * g + 1] += 1.0;
                    }
                }
                pairs
            })
            .collect();
        let base = row.len();
        row.resize(base + 2 * groups, 0.0);
        let pairs = &mut row[base..];
        for p in &partial {
            for g in 0..groups {
                pairs[2 * g] = pairs[2 * g].max(p[2 * g]);
                pairs[2 * g + 1] += p[2 * g + 1];
            }
        }
        for g in 0..groups {
            if pairs[2 * g] == 0.0 {
                pairs[2 * g] = 0.0;
            }
        }
    }

    /// Segment end points (reference), axial forces and plastic strains, for VTU line
    /// output: (points, lines as point pairs, force, plastic strain and bar per line).
    pub fn lines(&self) -> BarLines {
        let mut pts = Vec::new();
        let mut lines = Vec::new();
        let mut bars = Vec::new();
        for s in &self.segments {
            let p = pts.len() as u32;
            pts.extend(s.x);
            lines.push([p, p + 1]);
            bars.push(s.bar as f64);
        }
        for b in &self.bond_slip {
            let p0 = pts.len() as u32;
            pts.extend(&b.x);
            for s in 0..b.lengths.len() as u32 {
                lines.push([p0 + s, p0 + s + 1]);
                bars.push(b.bar as f64);
            }
        }
        BarLines {
            points: pts,
            lines,
            force: self.force.clone(),
            plastic_strain: self.plastic.clone(),
            bar: bars,
        }
    }

    /// State for checkpoints: plastic strains, then every bond–slip node's w and v.
    pub fn state(&self) -> Vec<f64> {
        let mut s = self.plastic.clone();
        for b in &self.bond_slip {
            s.extend(&b.w);
            s.extend(&b.v);
        }
        s
    }

    /// Restore [`AnchorBars::state`]; false when the length does not match.
    pub fn restore_state(&mut self, s: &[f64]) -> bool {
        let n: usize =
            self.plastic.len() + self.bond_slip.iter().map(|b| 2 * b.w.len()).sum::<usize>();
        if s.len() != n {
            return false;
        }
        let k = self.plastic.len();
        self.plastic.copy_from_slice(&s[..k]);
        self.plastic_trial.copy_from_slice(&s[..k]);
        self.trial_pending = false;
        let mut at = k;
        for b in self.bond_slip.iter_mut() {
            let n = b.w.len();
            b.w.copy_from_slice(&s[at..at + n]);
            b.v.copy_from_slice(&s[at + n..at + 2 * n]);
            at += 2 * n;
        }
        true
    }
}

/// Phase 1 of [`AnchorBars::add_internal_forces`] for the hosts `first..first +
/// out.len()`, compiled for the CPU's widest vectors ([`run_lane_work`]): per host, its
/// nodes' displacements with the eight nodes in lanes, then per segment k, in order,
/// w_a = t·u_a for the eight nodes at once, the elongation Σ_a g_a w_a summed over a in
/// order, N and the trial εᵖ ([`elastic_plastic`]), and N t_d g_a added to the host's
/// forces, component d with the nodes in lanes. Each lane performs the IEEE operations of
/// the scalar loop (`du += g_a (t₀u_a0 + t₁u_a1 + t₂u_a2)` from 0, `f_ad += (N t_d) g_a`
/// from 0) in its order, so the forces are the same bits.
struct HostForces<'a> {
    kernels: &'a [SegmentKernel],
    start: &'a [u32],
    host_nodes: &'a [[u32; 8]],
    plastic: &'a [f64],
    u: &'a [[f64; 3]],
    /// Axial force and trial εᵖ per kernel; this pass writes its hosts' kernels only.
    axial: SharedMut<(f64, f64)>,
    first: usize,
    out: &'a mut [[F64s; 3]],
}

impl LaneWork for HostForces<'_> {
    type Output = ();
    #[inline(always)]
    fn run<S: Simd>(self, _simd: S) {
        for (j, force) in self.out.iter_mut().enumerate() {
            let h = self.first + j;
            let nodes = &self.host_nodes[h];
            let u = self.u;
            let ux = lanes8!(a => u[nodes[a] as usize][0]);
            let uy = lanes8!(a => u[nodes[a] as usize][1]);
            let uz = lanes8!(a => u[nodes[a] as usize][2]);
            let mut f = [F64s::ZERO; 3];
            for k in self.start[h] as usize..self.start[h + 1] as usize {
                let s = &self.kernels[k];
                let t = s.t;
                let g = F64s(s.g);
                let w = F64s::splat(t[0]) * ux + F64s::splat(t[1]) * uy + F64s::splat(t[2]) * uz;
                let gw = g * w;
                let mut du = 0.0;
                for a in 0..8 {
                    du += gw[a];
                }
                du -= s.reference;
                let (n, ep) = elastic_plastic(
                    self.plastic[s.segment as usize],
                    s.ea,
                    s.yield_force,
                    s.pretension,
                    du / s.length,
                );
                // SAFETY: kernel k belongs to host h alone (start is ascending), and every
                // host is visited once.
                unsafe { *self.axial.at(k) = (n, ep) };
                for d in 0..3 {
                    f[d] = f[d] + F64s::splat(n * t[d]) * g;
                }
            }
            *force = f;
        }
    }
}

/// Elastic–perfectly plastic axial force for axial strain `eps` from the committed plastic
/// strain `ep`, stiffness `ea`, yield force `yield_force` and pretension `n0`: N = n0 +
/// EA (ε − εᵖ) if |N| ≤ f_y A, else ±f_y A with εᵖ grown by the excess (module docs).
/// Returns (N, trial εᵖ).
#[inline(always)]
fn elastic_plastic(ep: f64, ea: f64, yield_force: f64, n0: f64, eps: f64) -> (f64, f64) {
    let trial = n0 + ea * (eps - ep);
    if trial.abs() <= yield_force {
        (trial, ep)
    } else {
        let n = yield_force * trial.signum();
        (n, ep + (trial - n) / ea)
    }
}

/// Largest eigenvalue of M^{-1/2} K M^{-1/2} of a free chain of axial bar segments
/// (stiffness EA/l_s between nodes of lumped mass m_i): Sturm-sequence bisection on the
/// symmetric tridiagonal matrix, returning the upper end of the final bracket (Wilkinson,
/// The Algebraic Eigenvalue Problem, §5.37).
pub fn chain_max_eigenvalue(ea: f64, lengths: &[f64], mass: &[f64]) -> f64 {
    let n = mass.len();
    if n < 2 {
        return 0.0;
    }
    let k: Vec<f64> = lengths.iter().map(|l| ea / l).collect();
    let diag: Vec<f64> = (0..n)
        .map(|i| {
            let left = if i > 0 { k[i - 1] } else { 0.0 };
            let right = if i + 1 < n { k[i] } else { 0.0 };
            (left + right) / mass[i]
        })
        .collect();
    let off: Vec<f64> = (0..n - 1)
        .map(|i| -k[i] / (mass[i] * mass[i + 1]).sqrt())
        .collect();
    // Eigenvalues below x.
    let below = |x: f64| {
        let mut count = 0;
        let mut d = 1.0;
        for i in 0..n {
            let b2 = if i > 0 { off[i - 1] * off[i - 1] } else { 0.0 };
            d = diag[i] - x - if i > 0 { b2 / d } else { 0.0 };
            if d == 0.0 {
                d = -f64::EPSILON * (diag[i].abs() + x.abs()).max(f64::MIN_POSITIVE);
            }
            if d < 0.0 {
                count += 1;
            }
        }
        count
    };
    let mut hi = (0..n)
        .map(|i| {
            diag[i]
                + if i > 0 { off[i - 1].abs() } else { 0.0 }
                + if i + 1 < n { off[i].abs() } else { 0.0 }
        })
        .fold(0.0, f64::max);
    let mut lo = 0.0;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if below(mid) == n {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::anchor_mat::mat_bars;
    use crate::element::anchor_pattern::pattern_points;
    use crate::mesh::box_generator::BoxMeshSpec;

    fn steel(pretension: f64) -> SteelSpec {
        SteelSpec {
            diameter: 0.025,
            young: 200e9,
            yield_stress: 335e6,
            density: 7850.0,
            pretension,
            bond_stiffness: None,
            segment_length: None,
        }
    }

    /// The commit takes the trial strains of the last force pass (perfect-bond and
    /// bond–slip segments alike) and nothing else: a second commit without a pass changes
    /// nothing, and a pass reads the committed strains, not the trial ones of an earlier
    /// pass (two passes at one displacement without a commit between give the same
    /// forces and trial strains) — along a path that yields, unloads and yields again.
    #[test]
    fn commit_takes_the_last_pass_trial_strains() {
        let mesh = BoxMeshSpec::single("b", [0.0; 3], [4.0, 4.0, 4.0], [4, 4, 4])
            .build("test")
            .unwrap();
        let locator = HostLocator::new(&mesh, |_| true);
        let mut bars = AnchorBars::default();
        for (k, (ends, bond)) in [
            ([[0.3, 0.4, 0.5], [3.6, 3.1, 3.4]], None),
            ([[0.2, 3.7, 0.6], [3.5, 0.3, 3.3]], Some(2e8)),
        ]
        .into_iter()
        .enumerate()
        {
            let names = BarNames {
                name: format!("b{k}"),
                group: "g".into(),
            };
            let spec = SteelSpec {
                bond_stiffness: bond,
                ..steel(0.0)
            };
            bars.add_bar(&mesh, &locator, names, ends, &spec).unwrap();
        }
        bars.finish();
        assert!(!bars.bond_slip.is_empty() && !bars.segments.is_empty());
        let n = bars.plastic.len();
        let zero = vec![[0.0; 3]; mesh.n_nodes()];
        bars.install_at(&mesh, &zero);
        let field = |a: f64| -> Vec<[f64; 3]> {
            mesh.coords
                .iter()
                .map(|x| [a * x[0], a * (x[1] + 0.3 * x[2]), a * x[2]])
                .collect()
        };
        let committed = |b: &AnchorBars| b.state()[..n].to_vec();
        let mut yielded = [false; 2];
        for (step, a) in [4e-3, 4e-3, 0.0, -4e-3, 1e-3].into_iter().enumerate() {
            let u = field(a);
            // The bond–slip bar's own nodes stretched along it, beyond yield at |a| = 4e-3.
            for b in bars.bond_slip.iter_mut() {
                for (i, w) in b.w.iter_mut().enumerate() {
                    *w = 2.0 * a * i as f64;
                }
            }
            let before = committed(&bars);
            let mut f1 = vec![[0.0; 3]; mesh.n_nodes()];
            bars.add_internal_forces(&mesh, &u, &mut f1);
            let (force1, trial1) = (bars.force.clone(), bars.plastic_trial.clone());
            let mut f2 = vec![[0.0; 3]; mesh.n_nodes()];
            bars.add_internal_forces(&mesh, &u, &mut f2);
            assert!(f1 == f2, "step {step}: a second pass reads other strains");
            assert!(
                bars.force == force1 && bars.plastic_trial == trial1,
                "step {step}"
            );
            assert_eq!(
                committed(&bars),
                before,
                "step {step}: a pass commits nothing"
            );
            bars.commit(0.0, 0.0, 0.0);
            assert_eq!(
                committed(&bars),
                trial1,
                "step {step}: the pass's trial strains"
            );
            bars.commit(0.0, 0.0, 0.0);
            assert_eq!(
                committed(&bars),
                trial1,
                "step {step}: a commit without a pass"
            );
            let first = bars.bond_slip[0].first;
            yielded[0] |= trial1[..first].iter().any(|&e| e != 0.0);
            yielded[1] |= trial1[first..].iter().any(|&e| e != 0.0);
        }
        assert_eq!(
            yielded,
            [true, true],
            "the path yields segments of both kinds"
        );
    }

    /// The parallel pass (on a two-thread pool, several tasks per phase) gives, bit for
    /// bit, the axial forces and trial plastic strains of the serial loop over the
    /// segments in input order written out from the module docs (ε = t·(u(q) − u(p))/l
    /// less the installation elongation, N = N₀ + EA (ε − εᵖ) clipped at ±f_y A) and the
    /// host forces of the serial loop over the hosts in ascending order (each host's
    /// f_a = Σ N t g_a over its segments in input order, added to its nodes) — added to
    /// host forces already non-zero (the element pass), with some segments yielding; and
    /// the host forces of the plain loop over the segments within rounding.
    #[test]
    fn parallel_pass_matches_the_serial_loops() {
        let mesh = BoxMeshSpec::single("b", [0.0; 3], [12.0, 12.0, 6.0], [12, 12, 6])
            .build("test")
            .unwrap();
        let locator = HostLocator::new(&mesh, |_| true);
        let mut bars = AnchorBars::default();
        let mut add = |k: usize, ends: [[f64; 3]; 2], pre: f64| {
            let names = BarNames {
                name: format!("b{k}"),
                group: "g".into(),
            };
            bars.add_bar(&mesh, &locator, names, ends, &steel(pre))
                .unwrap();
        };
        let mut k = 0;
        for side in ["b.zmax", "b.xmin"] {
            for ends in mat_bars(&mesh, &mesh.face_sets[side], 0.05, 0.1).unwrap() {
                add(k, ends, 0.0);
                k += 1;
            }
        }
        for (p, n) in pattern_points(&mesh, &mesh.face_sets["b.zmax"], 0.5) {
            add(k, [p, std::array::from_fn(|d| p[d] + 3.0 * n[d])], 2e4);
            k += 1;
        }
        bars.finish();
        // Several tasks in each phase.
        let (segments, hosts, nodes) = (
            bars.segments.len(),
            bars.blocks.host_nodes.len(),
            bars.blocks.scatter_nodes.len(),
        );
        assert!(segments > 3 * SEGMENTS_PER_TASK, "{segments} segments");
        assert!(hosts > 3 * HOSTS_PER_TASK, "{hosts} hosts");
        assert!(nodes > NODES_PER_TASK, "{nodes} host nodes");
        // Installed in a slightly deformed state, then strained up to 4e-3 > f_y/E.
        let field = |x: &[f64; 3], a: f64| -> [f64; 3] {
            [
                a * (x[0] * x[2]).sin(),
                a * (0.7 * x[1] + x[0]).cos(),
                a * x[0] * x[1] * 0.1,
            ]
        };
        let u0: Vec<[f64; 3]> = mesh.coords.iter().map(|x| field(x, 1e-5)).collect();
        bars.install_at(&mesh, &u0);
        let u: Vec<[f64; 3]> = mesh.coords.iter().map(|x| field(x, 4e-3)).collect();
        let f0: Vec<[f64; 3]> = mesh
            .coords
            .iter()
            .map(|x| [x[0] * 1e3 + 0.1, -x[1] * 7e2, x[2] * 3.3e2 + 1.0 / 3.0])
            .collect();

        // The serial references: segments in input order, then hosts in ascending order.
        let mut f_seg = f0.clone();
        let mut force_ref = vec![0.0; bars.segments.len()];
        let mut trial_ref = vec![0.0; bars.segments.len()];
        for (k, s) in bars.segments.iter().enumerate() {
            let conn = mesh.elements[s.host as usize];
            let mut du = 0.0;
            for a in 0..8 {
                let ua = u[conn[a] as usize];
                du += s.g[a] * (s.t[0] * ua[0] + s.t[1] * ua[1] + s.t[2] * ua[2]);
            }
            du -= bars.kernels[bars.blocks.kernel_of[k] as usize].reference;
            let info = &bars.bars[s.bar as usize];
            let ep = bars.plastic[k];
            let trial = info.pretension + info.ea * (du / s.length - ep);
            let (n, ep_new) = if trial.abs() <= info.yield_force {
                (trial, ep)
            } else {
                let n = info.yield_force * trial.signum();
                (n, ep + (trial - n) / info.ea)
            };
            force_ref[k] = n;
            trial_ref[k] = ep_new;
            for a in 0..8 {
                for d in 0..3 {
                    f_seg[conn[a] as usize][d] += n * s.t[d] * s.g[a];
                }
            }
        }
        let mut f_ref = f0.clone();
        let mut hosts: Vec<u32> = bars.segments.iter().map(|s| s.host).collect();
        hosts.sort_unstable();
        hosts.dedup();
        for &host in &hosts {
            let mut fh = [[0.0; 3]; 8];
            for (k, s) in bars.segments.iter().enumerate() {
                if s.host == host {
                    let nt = [0, 1, 2].map(|d| force_ref[k] * s.t[d]);
                    for a in 0..8 {
                        for d in 0..3 {
                            fh[a][d] += nt[d] * s.g[a];
                        }
                    }
                }
            }
            let conn = mesh.elements[host as usize];
            for a in 0..8 {
                for d in 0..3 {
                    f_ref[conn[a] as usize][d] += fh[a][d];
                }
            }
        }
        let yielded = trial_ref.iter().filter(|&&e| e != 0.0).count();
        assert!(
            yielded > 0 && yielded < bars.segments.len(),
            "{yielded} yielded"
        );

        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(2)
            .build()
            .unwrap();
        let mut f = f0.clone();
        pool.install(|| bars.add_internal_forces(&mesh, &u, &mut f));
        assert!(
            f == f_ref,
            "host forces differ from the serial loop over the hosts"
        );
        let scale = f_seg.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        for (a, b) in f.iter().flatten().zip(f_seg.iter().flatten()) {
            assert!(
                (a - b).abs() <= 1e-13 * scale,
                "host force {a} against {b} from the loop over the segments"
            );
        }
        assert!(bars.force == force_ref, "axial forces differ");
        assert!(
            bars.plastic_trial == trial_ref,
            "trial plastic strains differ"
        );
    }
}
