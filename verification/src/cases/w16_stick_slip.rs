//! W16 — stick–slip oscillator: a block on a moving belt, held by a spring.
//!
//! Goal: point-to-point friction with μs > μd reproduces the rigid stick–slip limit cycle
//! (period, minimum velocity, dissipation per cycle, slip onset at μs m g), and the energy
//! balance of a belt started impulsively closes (issue 12 items 4 and 7).
//!
//! ```text
//!            g ↓
//!  ┌─╱╲╱╲╱╲─┐ plate 0.2 × 0.2 × 0.01 m, 1 kg       spring k = 100 N/m acting on the
//!  │ fixed   ▭                                       plate's contact-plane nodes
//!  ════════════════════ belt → v0 = 0.1 m/s (every belt node, from t = 0)
//! ```
//!
//! Block: a plate 0.2 × 0.2 × 0.01 m of one element, ρ 2500 kg/m³ (m = 1 kg), E 10 MPa,
//! ν 0, stiffness-proportional damping β = 0.32 ms (ξ ≈ 1 at its first shear mode);
//! gravity ramped over 10 ms. Belt: the same footprint, 0.05 m thick, every node with x
//! velocity v0 prescribed (a jump from rest at t = 0), y and z fixed; split pairs, slip
//! threshold 100 m (the pairs stay point-to-point). μs = 0.6, μd = 0.4.
//! Why this block (docs/contact.md §8): an elastic block slips when its most loaded
//! contact node reaches μs N. Damping removes the vibration every re-stick excites
//! (undamped, the first slip starts at 0.64 μs m g); one element makes every pair a corner,
//! loaded alike by symmetry (a 2 × 2 footprint locks in unequal T/N at its corner, edge and
//! centre nodes when it sticks: onset 0.89 μs m g); a thin plate keeps the overturning
//! moment of the inertia force small.
//!
//! Spring: no point spring exists in the case format, so the driver applies one as nodal
//! loads updated before every step from Uⁿ (as the scheme treats an internal force): on the
//! block's contact-plane node i, F_i = −k w_i x̄ⁿ with x̄ = Σ w_j u_x,j and w_i the node's
//! contact area over the footprint — the rank-one stiffness k w wᵀ, energy ½ k x̄² (booked
//! as external work). Spring and friction both act in the contact plane, so they form no
//! tipping couple; the spring is relaxed at x̄ = 0.
//!
//! Closed form (rigid block, Coulomb friction; docs/verification_references.md §W16).
//! x: block displacement, ω = √(k/m), x_s = μs m g/k (the spring force that breaks the
//! stick), x_d = μd m g/k, ξ₀ = x_s − x_d.
//! - Stick: ẋ = v0 until k x = μs m g, i.e. x = x_s.
//! - Slip (belt faster than the block, friction +μd m g on it): m ẍ = −k x + μd m g, so
//!   ξ = x − x_d is harmonic with ξ(0) = ξ₀, ξ̇(0) = v0: ξ = A cos(ωτ − φ),
//!   A = √(ξ₀² + (v0/ω)²), tan φ = v0/(ω ξ₀). The relative velocity vanishes again where
//!   ξ̇ = v0 with ξ̈ > 0, i.e. ξ = −ξ₀ (energy: ξ² + ξ̇²/ω² = A²), at ωτ − φ = π + φ:
//!   t_slip = (π + 2φ)/ω. There k x = (2μd − μs) m g < μs m g: the block sticks again.
//! - Stick from x_d − ξ₀ to x_d + ξ₀ = x_s at v0: t_stick = 2ξ₀/v0.
//! - Period T = t_stick + t_slip; minimum velocity ẋ_min = −A ω (the block runs backwards);
//!   the block is back at x_s with ẋ = v0 after T, so its slip relative to the belt over a
//!   cycle is v0 T and the friction dissipates D = μd m g v0 T per cycle (static friction
//!   does no work while the block sticks).
//!
//! With v0 = 0.1 m/s, k = 100 N/m, m = 1 kg, g = 9.81 m/s²: ω = 10 rad/s, ξ₀ = 0.01962 m,
//! A = 0.0220215 m, φ = 0.471365 rad, t_slip = 0.408432 s, t_stick = 0.3924 s,
//! T = 0.800832 s, ẋ_min = −0.220215 m/s, D = 0.314247 J, slip onset force 5.886 N.
//!
//! Measured: slip onsets (the first step a pair slides after all stuck), the spring force
//! k x̄ there, the period between onsets, the block's centre-of-mass velocity minimum and
//! the interface's work (energies.contact) between onsets, over the cycles after the first
//! (the first slip starts from rest under a ramping load).
//! Tolerance ±2 % (period, minimum velocity, dissipation, onset force); energy residual
//! ≤ 1e-5 of the largest energy (impulsive start included; the residual is
//! (Δt²/8) Σ M|aⁿ|², 2e-7 measured; the account of the first step used to leave ¼ of the
//! belt's kinetic energy).

use dcfm::boundary::{MotionKind, Prescribed};
use dcfm::contact::{ContactSystem, InterfaceSpec};
use dcfm::load::{Gravity, NodalLoad, TimeFunction};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::Model;
use dcfm::stage::Simulation;
use dcfm::{DcfmError, Result};

use crate::models::contact_blocks::{block, centre_of_mass, elastic, region_nodes};
use crate::record::{CaseOutput, Check, Series};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W16 stick-slip oscillator";

const SOURCE: &str = "docs/verification_references.md §W16 (rigid stick-slip oscillator)";
const G: f64 = 9.81;
/// Belt velocity (m/s).
pub const V0: f64 = 0.1;
/// Spring stiffness (N/m).
pub const K: f64 = 100.0;
/// Block mass (kg).
pub const MASS: f64 = 1.0;
/// Static and dynamic friction coefficients.
pub const MU_S: f64 = 0.6;
pub const MU_D: f64 = 0.4;
/// Block size (m): footprint and height.
const SIZE: [f64; 3] = [0.2, 0.2, 0.01];
/// Elements of the block.
const DIV: [usize; 3] = [1, 1, 1];
/// Block Young's modulus (Pa): shear deflection under μs m g is 3e-7 m, 0.002 % of ξ₀.
const YOUNG: f64 = 1e7;
/// Stiffness-proportional damping of the block (s): ξ = βω₁/2 ≈ 1 at its first shear mode
/// ω₁ = √2 c_s/h = 6325 rad/s (c_s = 44.7 m/s, h = 0.01 m; as W6).
pub const BETA: f64 = 3.2e-4;
/// Gravity ramp (s).
const RAMP: f64 = 0.01;
/// Simulated time (s): the first slip and four full cycles.
const END: f64 = 3.6;
/// A slip counts as an onset after every pair stuck this long (s): shorter sticks are
/// the chatter of an undamped block (a tenth of t_stick).
const MIN_STICK: f64 = 0.04;

/// The closed form of the rigid stick–slip limit cycle.
#[derive(Clone, Copy, Debug)]
pub struct Reference {
    pub period: f64,
    pub stick_time: f64,
    pub slip_time: f64,
    pub min_velocity: f64,
    pub dissipation: f64,
    pub onset_force: f64,
}

/// The closed form for belt speed `v0`, stiffness `k`, mass `m`, friction `mu_s`, `mu_d`
/// (module documentation).
pub fn reference(v0: f64, k: f64, m: f64, mu_s: f64, mu_d: f64) -> Reference {
    let w = (k / m).sqrt();
    let xi0 = (mu_s - mu_d) * m * G / k;
    let amp = (xi0 * xi0 + (v0 / w).powi(2)).sqrt();
    let phi = (v0 / (w * xi0)).atan();
    let slip_time = (std::f64::consts::PI + 2.0 * phi) / w;
    let stick_time = 2.0 * xi0 / v0;
    let period = slip_time + stick_time;
    Reference {
        period,
        stick_time,
        slip_time,
        min_velocity: -amp * w,
        dissipation: mu_d * m * G * v0 * period,
        onset_force: mu_s * m * G,
    }
}

/// What a run measured.
#[derive(Clone, Debug, Default)]
pub struct Measured {
    /// Slip onsets, the first step a pair slides after every pair stuck for at least
    /// `MIN_STICK`: (time (s), spring force k x̄ (N), interface work up to then (J)).
    pub onsets: Vec<(f64, f64, f64)>,
    /// After each onset, the first step every pair slides: (time (s), spring force (N)).
    pub full_slides: Vec<(f64, f64)>,
    /// Minimum centre-of-mass velocity (m/s) between the last two onsets.
    pub min_velocity: f64,
    /// Largest |energy residual| / largest energy over the run.
    pub residual: f64,
    /// History: time, spring force, block velocity, whether a pair slides.
    pub times: Vec<f64>,
    pub sliding: Vec<bool>,
    pub forces: Vec<f64>,
    pub velocities: Vec<f64>,
}

/// The block: size (m), elements, Young's modulus (Pa), stiffness-proportional damping
/// β (s); its density makes the mass `MASS`.
#[derive(Clone, Copy, Debug)]
pub struct BlockSpec {
    pub size: [f64; 3],
    pub divisions: [usize; 3],
    pub young: f64,
    pub beta: f64,
}

/// The case's block: a plate 0.2 × 0.2 × 0.01 m, one element, E 10 MPa, β = `BETA`.
pub const PLATE: BlockSpec = BlockSpec {
    size: SIZE,
    divisions: DIV,
    young: YOUNG,
    beta: BETA,
};

/// Where the spring acts on the block.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Attachment {
    /// Every contact-plane node, weighted by its contact area (no tipping couple).
    ContactPlane,
    /// Only the contact-plane nodes of the block's rear edge x = 0 (an edge-loaded block).
    RearEdge,
}

/// Build block `b` on the belt with the spring at `attachment`; returns the simulation,
/// the spring's nodes and their weights w_i (Σ w_i = 1).
pub fn build(b: BlockSpec, attachment: Attachment) -> Result<(Simulation, Vec<u32>, Vec<f64>)> {
    let mesh = BoxMeshSpec {
        blocks: vec![
            block(
                "belt",
                [0.0; 3],
                [b.size[0], b.size[1], 0.05],
                [b.divisions[0], b.divisions[1], 1],
            ),
            block("block", [0.0, 0.0, 0.05], b.size, b.divisions),
        ],
        split: vec![["block".into(), "belt".into()]],
        merge_tolerance: 1e-9,
    }
    .build("w16")?;
    let density = MASS / (b.size[0] * b.size[1] * b.size[2]);
    let regions = [
        elastic("belt", 1e6, 0.25, 1000.0)?,
        elastic("block", b.young, 0.0, density)?,
    ];
    let mut model = Model::new(mesh, &regions, "w16")?;
    let belt = region_nodes(&model.mesh, "belt");
    model.constraints.fix(&belt, 0b110);
    model
        .constraints
        .prescribe(Prescribed {
            nodes: belt,
            dof: 0,
            kind: MotionKind::Velocity,
            history: TimeFunction::Constant { value: V0 },
        })
        .map_err(|n| DcfmError::Mesh(format!("node {n} constrained twice")))?;
    model.gravity = Some(Gravity {
        acceleration: [0.0, 0.0, -G],
        history: TimeFunction::Table {
            times: vec![0.0, RAMP],
            values: vec![0.0, 1.0],
        },
    });
    let mut spec = InterfaceSpec::new("belt", "block-belt", "belt-block", MU_S, MU_D, 0.0);
    spec.slip_threshold = Some(100.0);
    let contact = ContactSystem::new(&model.mesh, &[spec], "w16")?;
    // The spring's nodes: the block's side of every pair, weighted by contact area.
    let block_nodes = region_nodes(&model.mesh, "block");
    let mut nodes = Vec::new();
    let mut weights = Vec::new();
    for (a, b, area, _) in contact.pairs(0) {
        let n = if block_nodes.binary_search(&a).is_ok() {
            a
        } else {
            b
        };
        if attachment == Attachment::RearEdge && model.mesh.coords[n as usize][0] > 1e-9 {
            continue;
        }
        nodes.push(n);
        weights.push(area);
    }
    let total: f64 = weights.iter().sum();
    weights.iter_mut().for_each(|w| *w /= total);
    model.contact = Some(contact);
    for &n in &nodes {
        model.nodal_loads.push(NodalLoad {
            nodes: vec![n],
            force: [0.0; 3],
            history: TimeFunction::Constant { value: 1.0 },
        });
    }
    model.damping.beta = b.beta;
    let dt = 0.9 * model.critical_step_with_damping();
    Ok((Simulation::new(model, dt, 1.0)?, nodes, weights))
}

/// Run block `b` to `END` with the spring at `attachment`, and measure.
pub fn measure(b: BlockSpec, attachment: Attachment) -> Result<Measured> {
    let (mut sim, nodes, weights) = build(b, attachment)?;
    let n_pairs = sim.model.contact.as_ref().map_or(0, |c| c.pairs(0).len());
    let block = region_nodes(&sim.model.mesh, "block");
    let first_load = sim.model.nodal_loads.len() - nodes.len();
    let mut out = Measured::default();
    let mut stuck_since: Option<f64> = None;
    let mut awaiting_full = false;
    let mut v_min = f64::INFINITY;
    while sim.time < END {
        // Spring force from Uⁿ on the contact-plane nodes.
        let xbar: f64 = nodes
            .iter()
            .zip(&weights)
            .map(|(&n, w)| w * sim.u[n as usize][0])
            .sum();
        for (k, w) in weights.iter().enumerate() {
            sim.model.nodal_loads[first_load + k].force = [-K * w * xbar, 0.0, 0.0];
        }
        let t = sim.time;
        sim.step()?;
        let (p, _) = sim.model.contact.as_ref().expect("contact").state_counts(0);
        let (stuck, sliding, all_sliding) = (p[1] == n_pairs, p[2] > 0, p[2] == n_pairs);
        if sliding && stuck_since.is_some_and(|t0| t - t0 >= MIN_STICK) {
            out.onsets.push((t, K * xbar, sim.energies.contact));
            if out.onsets.len() >= 2 {
                out.min_velocity = v_min;
            }
            v_min = f64::INFINITY;
            awaiting_full = true;
        }
        if awaiting_full && all_sliding {
            out.full_slides.push((t, K * xbar));
            awaiting_full = false;
        }
        stuck_since = match (stuck, stuck_since) {
            (true, Some(t0)) => Some(t0),
            (true, None) => Some(t),
            (false, _) => None,
        };
        // From the second step on: the row of t⁰ carries the belt's jump (V⁰ = v0/2).
        if sim.step > 1 {
            out.residual = out
                .residual
                .max(sim.energies.residual().abs() / sim.energies.scale().max(f64::MIN_POSITIVE));
        }
        let (_, _, v) = centre_of_mass(&sim, &block);
        v_min = v_min.min(v[0]);
        out.times.push(sim.time);
        out.sliding.push(sliding);
        out.forces.push(K * xbar);
        out.velocities.push(v[0]);
    }
    Ok(out)
}

/// Run W16.
pub fn run() -> Result<CaseOutput> {
    let r = reference(V0, K, MASS, MU_S, MU_D);
    let m = measure(PLATE, Attachment::ContactPlane)?;
    let mut ch = Check::new(TITLE);
    let n = m.onsets.len();
    if n < 3 {
        return Err(DcfmError::Mesh(format!(
            "W16: {n} slip onsets in {END} s, at least 3 expected"
        )));
    }
    // Cycles after the first slip (which starts from rest under the gravity ramp).
    let cycles = &m.onsets[1..];
    let c = (cycles.len() - 1) as f64;
    let period = (cycles[cycles.len() - 1].0 - cycles[0].0) / c;
    let dissipation = (cycles[cycles.len() - 1].2 - cycles[0].2) / c;
    let onset = cycles.iter().map(|o| o.1).fold(f64::INFINITY, f64::min);
    ch.relative("period T (s)", r.period, period, 0.02, SOURCE)
        .relative(
            "minimum velocity −Aω (m/s)",
            r.min_velocity,
            m.min_velocity,
            0.02,
            SOURCE,
        )
        .relative(
            "dissipation per cycle μd m g v0 T (J)",
            r.dissipation,
            dissipation,
            0.02,
            SOURCE,
        )
        .relative(
            "smallest slip-onset spring force μs m g (N)",
            r.onset_force,
            onset,
            0.02,
            SOURCE,
        )
        .absolute(
            "energy residual / largest energy (belt started impulsively)",
            0.0,
            m.residual,
            1e-5,
            "docs/verification_references.md §W12",
        );
    let series = vec![Series::new(
        TITLE,
        "spring force k x̄ of the block on the belt",
        ("time (s)", "spring force (N)"),
        m.times.clone(),
        m.forces.clone(),
        None,
    )];
    Ok(CaseOutput {
        rows: ch.finish(),
        series,
    })
}
