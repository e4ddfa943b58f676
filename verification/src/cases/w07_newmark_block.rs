//! W7 — Newmark sliding block: a "rigid" block on a base whose acceleration is prescribed.
//!
//! Goal: point-to-point friction reproduces Newmark's rigid-plastic sliding block (yield
//! acceleration N g): the slip of a rectangular pulse and the per-cycle slip of one-way
//! sliding under a sine.
//!
//! ```text
//!     g ↓ (tilted by θ for one-way sliding)
//!     ┌────────┐ plate 2 × 2 × 0.02 m, 1000 kg, μs = μd
//!  ═══╧════════╧═══ base: x acceleration a_b(t) prescribed at every node, y and z fixed
//! ```
//!
//! Plate as in W6 (E 0.1 GPa, ν 0, β = 0.41 ms, ξ ≈ 1 at its first mode, so it moves as a
//! rigid body; gravity ramped over 10 ms), split pairs on a 2 × 2 m footprint, slip
//! threshold 100 m (pairs stay point-to-point). The base nodes are fully constrained
//! (w = 0: the base is the infinite-mass side of each pair).
//! 1. Rectangular pulse: horizontal base, μ = N = 0.2, a_b = A g for t0 = 0.2 s (A 0.5)
//!    starting at t_s = 0.05 s. Slip = x_plate − x_base at the end; slip ends when no pair
//!    slides any more.
//! 2. One-way sliding: gravity tilted by θ (sinθ = 0.125) and μ = 0.225/cosθ, so the yield
//!    acceleration is g(μ cosθ − sinθ) = 0.1 g downslope and g(μ cosθ + sinθ) = 0.35 g
//!    upslope, above the 0.3 g amplitude (never reached: one-way); a_b = 0.3 g sin(2π·1 Hz·t) along the slope.
//!    Slip per cycle = x_rel(2 s) − x_rel(1 s) (the sliding episode that starts at
//!    t ≈ 0.55 s runs past 1 s, so the first cycle is shorter; from the second on every
//!    cycle slides the same).
//!
//! Reference: docs/verification_references.md §W7: V²/(2Ng)(1 − N/A) = 0.14715 m, slip ends at A t0/N = 0.5 s
//! after the pulse start; one-way 0.17665 m per cycle (Newmark 1965).
//! Tolerance ±3 % (W7; the slip end ±3 % of 0.5 s).

use dcfm::boundary::{MotionKind, Prescribed};
use dcfm::contact::{ContactSystem, InterfaceSpec};
use dcfm::load::{Gravity, TimeFunction};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::Model;
use dcfm::stage::Simulation;
use dcfm::{DcfmError, Result};

use crate::models::contact_blocks::{block, centre_of_mass, elastic, region_nodes};
use crate::record::{CaseOutput, Check, Series};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W7 Newmark sliding block";

const SOURCE: &str = "docs/verification_references.md §W7 (Newmark 1965)";
const G: f64 = 9.81;
const PLATE: f64 = 0.02;
const BETA: f64 = 4.1e-4;
const RAMP: f64 = 0.01;
/// Rectangular pulse (A, t0 (s), N, start (s)).
const PULSE: (f64, f64, f64, f64) = (0.5, 0.2, 0.2, 0.05);

/// Build the plate on a base with prescribed x acceleration `base_acc` (m/s² × history),
/// gravity tilted by `sin_theta`, friction μ.
pub fn build(mu: f64, sin_theta: f64, base_acc: TimeFunction) -> Result<Simulation> {
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("base", [0.0; 3], [2.0, 2.0, 1.0], [2, 2, 1]),
            block("top", [0.0, 0.0, 1.0], [2.0, 2.0, PLATE], [2, 2, 1]),
        ],
        split: vec![["base".into(), "top".into()]],
        merge_tolerance: 1e-6,
    }
    .build("w07")?;
    let regions = [
        elastic("base", 1e6, 0.25, 1000.0)?,
        elastic("top", 1e8, 0.0, 1000.0 / (4.0 * PLATE))?,
    ];
    let mut model = Model::new(mesh, &regions, "w07")?;
    let base = region_nodes(&model.mesh, "base");
    model.constraints.fix(&base, 0b110);
    model
        .constraints
        .prescribe(Prescribed {
            nodes: base,
            dof: 0,
            kind: MotionKind::Acceleration,
            history: base_acc,
        })
        .map_err(|n| DcfmError::Mesh(format!("node {n} constrained twice")))?;
    let cos_theta = (1.0 - sin_theta * sin_theta).sqrt();
    model.gravity = Some(Gravity {
        acceleration: [G * sin_theta, 0.0, -G * cos_theta],
        history: TimeFunction::Table {
            times: vec![0.0, RAMP],
            values: vec![0.0, 1.0],
        },
    });
    let mut spec = InterfaceSpec::new("newmark", "top-base", "base-top", mu, mu, 0.0);
    spec.slip_threshold = Some(100.0);
    model.contact = Some(ContactSystem::new(&model.mesh, &[spec], "w07")?);
    model.damping.beta = BETA;
    let dt = 0.9 * model.critical_step_with_damping();
    Simulation::new(model, dt, 1.0)
}

/// Relative displacement plate − base along x, and whether a pair slides.
fn relative(sim: &Simulation, plate: &[u32], base: &[u32]) -> (f64, bool) {
    let (_, up, _) = centre_of_mass(sim, plate);
    let ub = sim.u[base[0] as usize][0];
    let (_, s) = sim.model.contact.as_ref().expect("contact").state_counts(0);
    let (p, _) = sim.model.contact.as_ref().expect("contact").state_counts(0);
    (up[0] - ub, p[2] + s[2] > 0)
}

/// Newmark's rigid-plastic slip |x_block − x_base| at time τ after the start of a
/// rectangular base pulse A g of duration t0, yield acceleration N g (N < A): relative
/// acceleration (A − N) g during the pulse, −N g after it until the relative velocity
/// vanishes at τ = A t0/N.
pub fn newmark_pulse_slip(a: f64, t0: f64, n: f64, tau: f64) -> f64 {
    let rise = |t: f64| 0.5 * (a - n) * G * t * t;
    if tau <= 0.0 {
        0.0
    } else if tau <= t0 {
        rise(tau)
    } else {
        let s = tau.min(a * t0 / n) - t0;
        rise(t0) + (a - n) * G * t0 * s - 0.5 * n * G * s * s
    }
}

/// The rectangular-pulse run: (|slip| (m), time from the pulse start to the end of
/// sliding (s), and the slip history (time, |slip|) at every step).
pub fn pulse_history() -> Result<(f64, f64, Vec<f64>, Vec<f64>)> {
    let (a, t0, n, ts) = PULSE;
    let mut sim = build(
        n,
        0.0,
        TimeFunction::Pulse {
            amplitude: a * G,
            duration: t0,
            start: ts,
        },
    )?;
    let plate = region_nodes(&sim.model.mesh, "top");
    let base = region_nodes(&sim.model.mesh, "base");
    let mut last_slide = 0.0;
    let (mut times, mut slips) = (Vec::new(), Vec::new());
    while sim.time < ts + 0.8 {
        sim.step()?;
        let (rel, sliding) = relative(&sim, &plate, &base);
        if sliding {
            last_slide = sim.time;
        }
        times.push(sim.time);
        slips.push(rel.abs());
    }
    Ok((
        relative(&sim, &plate, &base).0.abs(),
        last_slide - ts,
        times,
        slips,
    ))
}

/// Rectangular pulse: (|slip| (m), time from the pulse start to the end of sliding (s)).
pub fn measure_pulse() -> Result<(f64, f64)> {
    let (slip, end, _, _) = pulse_history()?;
    Ok((slip, end))
}

/// One-way sliding: slip between t = 1 s and t = 2 s (m).
pub fn measure_one_way() -> Result<f64> {
    let sin_theta = 0.125;
    let mu = 0.225 / (1.0f64 - sin_theta * sin_theta).sqrt();
    let mut sim = build(
        mu,
        sin_theta,
        TimeFunction::Sine {
            amplitude: 0.3 * G,
            frequency: 1.0,
            phase: 0.0,
        },
    )?;
    let plate = region_nodes(&sim.model.mesh, "top");
    let base = region_nodes(&sim.model.mesh, "base");
    let mut x1 = 0.0;
    while sim.time < 2.0 - 0.5 * sim.dt {
        sim.step()?;
        if (sim.time - 1.0).abs() < 0.5 * sim.dt {
            x1 = relative(&sim, &plate, &base).0;
        }
    }
    Ok(relative(&sim, &plate, &base).0 - x1)
}

/// Run W7.
pub fn run() -> Result<CaseOutput> {
    let mut ch = Check::new(TITLE);
    let (slip, t_end, times, slips) = pulse_history()?;
    let (a, t0, n, ts) = PULSE;
    let reference = times
        .iter()
        .map(|&t| newmark_pulse_slip(a, t0, n, t - ts))
        .collect();
    let series = vec![Series::new(
        TITLE,
        "rectangular pulse: slip of the block on the base",
        ("time (s)", "|slip| (m)"),
        times,
        slips,
        Some(reference),
    )];
    ch.relative(
        "pulse: slip V²/(2Ng)(1 − N/A) (m)",
        0.14715,
        slip,
        0.03,
        SOURCE,
    )
    .relative(
        "pulse: slip ends A t0/N after the pulse start (s)",
        0.5,
        t_end,
        0.03,
        SOURCE,
    );
    let per_cycle = measure_one_way()?;
    ch.relative(
        "one-way: slip per cycle (m)",
        0.17665,
        per_cycle,
        0.03,
        SOURCE,
    );
    Ok(CaseOutput {
        rows: ch.finish(),
        series,
    })
}
