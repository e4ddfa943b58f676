//! W8 — cohesive bond: tensile debonding, no tension afterwards, recompression, and the
//! shear strength cA + μs N falling to μd N at the first slip.
//!
//! Goal: the bond-slip law of eqs. (12)–(15) on a real mesh: cohesion c over the control
//! area A, lost for ever at the first separation or slide (paper §2).
//!
//! ```text
//!        ┌──────┐ plate 0.5 × 0.5 × 0.02 m (one element), loads on its bottom nodes
//!   ═════╧══════╧═════ base (fixed), bonded split interface, A = 0.25 m² (4 × 0.0625)
//! ```
//!
//! Loads act on the four interface nodes of the plate (surface a), 1/4 each, so every
//! pair sees exactly its share (no overturning moment, no wave in the plate); the plate
//! (E 1 GPa, ν 0, ρ 2400, β = 44 µs ≈ 2/ω₁ against ringing) only rides along.
//! 1. Tension: F = 10⁶ t N (+z) until t = 0.0505 s, then −50 kN (compression) held.
//! 2. Shear: N = 50 kN compressive (ramped over 10 ms, held), shear S = 10⁶ (t − 0.02) N
//!    along x from t = 0.02 s.
//!
//! Parameters: c = 0.2 MPa (tensile strength = c), μs 0.6, μd 0.45.
//! Reference (docs/verification_references.md §W8): cA = 50 kN, debond at t = 0.05 s; tensile capacity
//! zero afterwards; recompression transmits the 50 kN; slip starts at cA + μs N = 80 kN
//! (t = 0.1 s), the resistance falls to μd N = 22.5 kN.
//! The four pairs carry equal loads; should round-off let some debond or slip a few steps
//! before the others, the rest follow once they carry the whole load, so the sliding
//! resistance is averaged over the steps where every pair slides.
//! Tolerance: ±1 % on forces, debond and slip times within 2Δt of the reference (the
//! bond law itself is exact, W9); zero tension after debonding (absolute 1e-9 N).

use dcfm::contact::{ContactSystem, InterfaceSpec};
use dcfm::load::{NodalLoad, TimeFunction};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::Model;
use dcfm::stage::Simulation;
use dcfm::Result;

use crate::models::contact_blocks::{block, elastic, interface_forces, region_nodes};
use crate::record::{CaseOutput, Check};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W8 cohesive bond";

const SOURCE: &str = "docs/verification_references.md §W8 (paper §2, eqs. (12)–(15))";

/// What the two W8 runs measured.
#[derive(Clone, Copy, Debug, Default)]
pub struct BondMeasures {
    /// First time a pair separated (s) and the largest tension Σ(−λ) before it (N).
    pub debond_time: f64,
    pub peak_tension: f64,
    /// Steps from the first separation until no pair is bonded any more.
    pub debond_steps: f64,
    /// Largest tension Σ(−λ) once no pair is bonded (N).
    pub tension_after: f64,
    /// Mean Σλ over [0.1, 0.15] s after recompression (N).
    pub recompression: f64,
    /// Shear load at the first slide (N) and mean |ΣT| over the 5 ms after it, over the
    /// steps in which every pair slides (N).
    pub slip_load: f64,
    pub slip_time: f64,
    pub sliding_resistance: f64,
    /// Mean Σλ over the same window (N).
    pub sliding_normal: f64,
    pub dt: f64,
}

pub fn build(loads: Vec<([f64; 3], TimeFunction)>) -> Result<Simulation> {
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [0.5, 0.5, 0.5], [1, 1, 1]),
            block("top", [0.0, 0.0, 0.5], [0.5, 0.5, 0.02], [1, 1, 1]),
        ],
        split: vec![["base".into(), "top".into()]],
        merge_tolerance: 1e-6,
    }
    .build("w08")?;
    let regions = [
        elastic("base", 1e6, 0.0, 2400.0)?,
        elastic("top", 1e9, 0.0, 2400.0)?,
    ];
    let mut model = Model::new(mesh, &regions, "w08")?;
    let base = region_nodes(&model.mesh, "base");
    model.constraints.fix(&base, 0b111);
    let spec = InterfaceSpec::new("bond", "top-base", "base-top", 0.6, 0.45, 0.2e6);
    let contact = ContactSystem::new(&model.mesh, &[spec], "w08")?;
    let a_nodes: Vec<u32> = contact.pairs(0).iter().map(|p| p.0).collect();
    model.contact = Some(contact);
    for (force, history) in loads {
        model.nodal_loads.push(NodalLoad {
            nodes: a_nodes.clone(),
            force: force.map(|f| 0.25 * f),
            history,
        });
    }
    model.damping.beta = 4.4e-5;
    let dt = 0.9 * model.critical_step_with_damping();
    Simulation::new(model, dt, 1.0)
}

/// Run both W8 loadings.
pub fn measure() -> Result<BondMeasures> {
    let mut m = BondMeasures::default();
    // 1. Tension, then recompression.
    let mut sim = build(vec![(
        [0.0, 0.0, 1.0],
        TimeFunction::Table {
            times: vec![0.0, 0.0505, 0.0506, 1.0],
            values: vec![0.0, 50_500.0, -50_000.0, -50_000.0],
        },
    )])?;
    m.dt = sim.dt;
    let (mut sum, mut count) = (0.0, 0usize);
    let mut debonded = false;
    while sim.time < 0.15 {
        sim.step()?;
        let (lam, _, c) = interface_forces(&sim, 0);
        if !debonded {
            if c[3] > 0 {
                debonded = true;
                m.debond_time = sim.time - sim.dt;
            } else {
                m.peak_tension = m.peak_tension.max(-lam);
            }
        }
        if debonded && c[0] > 0 {
            m.debond_steps += 1.0;
        } else if debonded {
            m.tension_after = m.tension_after.max(-lam);
        }
        if sim.time > 0.1 {
            sum += lam;
            count += 1;
        }
    }
    m.recompression = sum / count.max(1) as f64;
    // 2. Shear under 50 kN.
    let mut sim = build(vec![
        (
            [0.0, 0.0, -1.0],
            TimeFunction::Table {
                times: vec![0.0, 0.01],
                values: vec![0.0, 50_000.0],
            },
        ),
        (
            [1.0, 0.0, 0.0],
            TimeFunction::Ramp {
                rate: 1e6,
                start: 0.02,
            },
        ),
    ])?;
    let (mut sum, mut count, mut sum_n) = (0.0, 0usize, 0.0);
    let mut t_slip = None;
    while sim.time < 0.2 {
        sim.step()?;
        let (lam, t, c) = interface_forces(&sim, 0);
        match t_slip {
            None if c[2] > 0 => {
                let t0 = sim.time - sim.dt;
                t_slip = Some(t0);
                m.slip_time = t0;
                m.slip_load = 1e6 * (t0 - 0.02);
            }
            Some(t0) if sim.time - sim.dt <= t0 + 5e-3 && c[0] + c[1] == 0 => {
                sum += (t[0] * t[0] + t[1] * t[1]).sqrt();
                sum_n += lam;
                count += 1;
            }
            _ => {}
        }
        if t_slip.is_some_and(|t0| sim.time > t0 + 6e-3) {
            break;
        }
    }
    m.sliding_resistance = sum / count.max(1) as f64;
    m.sliding_normal = sum_n / count.max(1) as f64;
    Ok(m)
}

/// Run W8.
pub fn run() -> Result<CaseOutput> {
    let m = measure()?;
    let mut ch = Check::new(TITLE);
    let tol_t = 2.0 * m.dt;
    ch.absolute(
        "tension: debond time (s)",
        0.05,
        m.debond_time,
        tol_t,
        SOURCE,
    )
    .relative(
        "tension: peak tension cA (N)",
        50e3,
        m.peak_tension,
        0.01,
        SOURCE,
    )
    .absolute(
        "tension once no pair is bonded (N)",
        0.0,
        m.tension_after,
        1e-9,
        SOURCE,
    )
    .relative(
        "recompression: mean normal force (N)",
        50e3,
        m.recompression,
        0.01,
        SOURCE,
    )
    .relative(
        "shear: load at first slip cA + μs N (N)",
        80e3,
        m.slip_load,
        0.01,
        SOURCE,
    )
    .absolute(
        "shear: first slip time (s)",
        0.1,
        m.slip_time,
        tol_t,
        SOURCE,
    )
    .relative(
        "shear: sliding resistance μd N (N)",
        22.5e3,
        m.sliding_resistance,
        0.01,
        SOURCE,
    )
    .relative(
        "shear: normal force while sliding (N)",
        50e3,
        m.sliding_normal,
        0.01,
        SOURCE,
    )
    .relative(
        "shear: |ΣT| / Σλ while sliding = μd",
        0.45,
        m.sliding_resistance / m.sliding_normal,
        0.01,
        SOURCE,
    );
    Ok(ch.finish().into())
}
