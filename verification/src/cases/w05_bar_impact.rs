//! W5 — impact of two identical elastic bars, and of a bar against a rigid wall.
//!
//! Goal: point-to-point contact (eqs. (5)–(15)) transmits the impact force of 1D wave
//! theory, for the right duration, and lets the bars separate when the contact would pull.
//!
//! ```text
//!   striker  v0 = 1 m/s →        target (at rest, or fixed = rigid wall)
//!   ┌────────────────────┐┌────────────────────┐
//!   │ x ∈ [0, 2] m       ││ x ∈ [2, 4] m       │   1 × 1 m² section, h = 6.25 mm
//!   └────────────────────┘└────────────────────┘
//!                  split interface "striker-target" (a) / "target-striker" (b)
//! ```
//!
//! BCs: none (ν = 0, so the free lateral faces give a uniaxial-stress bar with
//! c = √(E/ρ)); rigid-wall variant: every node of the target fixed (w = 0).
//! Parameters: E 30 GPa, ν 0, ρ 2400 kg/m³ (c 3535.53 m/s), A 1 m², L 2 m, 320 elements per
//! bar, frictionless contact without cohesion (μs = μd = 0, c = 0), Δt = 0.9 Δt_crit.
//! Reference (docs/verification_references.md §W5, 1D wave theory): contact force ρcAv0/2 = 4.2426 MN for
//! 2L/c = 1.1314 ms, then the striker rests and the target moves at v0 (impulse 4800 N·s);
//! against a rigid wall ρcAv0 = 8.485 MN (8.485 MPa on 1 m²) and rebound −v0.
//! Measured: the interface force Σλ of the four pairs each step; the plateau is its time
//! average over the contact (the lumped-mass mesh rings around the plateau, Gibbs
//! oscillation of the discrete step front, so the peak is not a fair measure); duration
//! = steps with Σλ > 0; momenta and energies from the nodal masses and half-step velocities.
//! Mesh: the impulse deficit (momentum left in the striker by the dispersed wave tail) is
//! about one step of contact force and falls with h: 0.47 % at 80, 0.29 % at 160, 0.18 % at
//! 320 elements per bar (wall rebound 0.94 %, 0.58 %, 0.36 %), hence 320.
//! Tolerances (W5): plateau ±3 %, duration ±2Δt, momentum ±0.5 %, energy ±2 %; energy
//! residual (W12) ≤ 2 % of the largest energy.

use dcfm::contact::{ContactSystem, InterfaceSpec};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::Model;
use dcfm::stage::Simulation;
use dcfm::Result;

use crate::models::contact_blocks::{
    block, centre_of_mass, elastic, interface_forces, region_nodes,
};
use crate::record::{CaseOutput, Check, Series};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W5 bar impact";

const SOURCE: &str = "docs/verification_references.md §W5 (1D wave theory)";
const E: f64 = 30e9;
const RHO: f64 = 2400.0;
const L: f64 = 2.0;
const V0: f64 = 1.0;

/// What one impact measured.
#[derive(Clone, Debug, Default)]
pub struct ImpactMeasures {
    /// Time-averaged interface force over the contact (N).
    pub plateau: f64,
    /// Contact duration (s).
    pub duration: f64,
    /// Impulse ∫Σλ dt (N·s).
    pub impulse: f64,
    /// Striker and target centre-of-mass velocities at the end (m/s).
    pub striker_velocity: f64,
    pub target_velocity: f64,
    /// Mass of one bar (kg).
    pub bar_mass: f64,
    /// Kinetic + strain energy at the end (J).
    pub final_energy: f64,
    /// Initial kinetic energy (J).
    pub initial_energy: f64,
    /// Largest |energy residual| / largest energy over the run.
    pub energy_residual: f64,
    pub dt: f64,
    /// Time of every step (s) and the interface force Σλ then (N), for the plot.
    pub times: Vec<f64>,
    pub forces: Vec<f64>,
}

/// Build the two bars; `wall`: the target is fixed (rigid wall).
pub fn build(elements_per_bar: usize, wall: bool) -> Result<Simulation> {
    let mesh = BoxMeshSpec {
        blocks: vec![
            block("striker", [0.0; 3], [L, 1.0, 1.0], [elements_per_bar, 1, 1]),
            block(
                "target",
                [L, 0.0, 0.0],
                [L, 1.0, 1.0],
                [elements_per_bar, 1, 1],
            ),
        ],
        split: vec![["striker".into(), "target".into()]],
        merge_tolerance: 1e-6,
    }
    .build("w05")?;
    let regions = [
        elastic("striker", E, 0.0, RHO)?,
        elastic("target", E, 0.0, RHO)?,
    ];
    let mut model = Model::new(mesh, &regions, "w05")?;
    let striker = region_nodes(&model.mesh, "striker");
    let target = region_nodes(&model.mesh, "target");
    if wall {
        model.constraints.fix(&target, 0b111);
    }
    model.initial_velocity.push((striker, [V0, 0.0, 0.0]));
    let spec = InterfaceSpec::new("impact", "striker-target", "target-striker", 0.0, 0.0, 0.0);
    model.contact = Some(ContactSystem::new(&model.mesh, &[spec], "w05")?);
    let dt = 0.9 * model.stable.critical;
    Simulation::new(model, dt, 1.0)
}

/// Run one impact to t = 3 ms (the contact ends at 1.13 ms) and measure it.
pub fn measure(elements_per_bar: usize, wall: bool) -> Result<ImpactMeasures> {
    let mut sim = build(elements_per_bar, wall)?;
    let striker = region_nodes(&sim.model.mesh, "striker");
    let target = region_nodes(&sim.model.mesh, "target");
    let mut m = ImpactMeasures {
        dt: sim.dt,
        initial_energy: sim.energies.kinetic,
        ..Default::default()
    };
    let (mut t_on, mut t_off) = (None, None);
    let (mut max_res, mut max_scale) = (0.0f64, 0.0f64);
    while sim.time < 3e-3 {
        sim.step()?;
        let (f, _, _) = interface_forces(&sim, 0);
        // The force of step n acts over [tⁿ, tⁿ⁺¹]: plotted at tⁿ.
        m.times.push(sim.time - sim.dt);
        m.forces.push(f);
        if f > 0.0 && t_off.is_none() {
            t_on.get_or_insert(sim.time - sim.dt);
            m.impulse += f * sim.dt;
        } else if t_on.is_some() && t_off.is_none() {
            t_off = Some(sim.time - sim.dt);
        }
        max_res = max_res.max(sim.energies.residual().abs());
        max_scale = max_scale.max(sim.energies.scale());
    }
    let t_on = t_on.unwrap_or(0.0);
    m.duration = t_off.unwrap_or(sim.time) - t_on;
    m.plateau = m.impulse / m.duration;
    let (ms, _, vs) = centre_of_mass(&sim, &striker);
    let (_, _, vt) = centre_of_mass(&sim, &target);
    m.bar_mass = ms;
    m.striker_velocity = vs[0];
    m.target_velocity = vt[0];
    m.final_energy = sim.energies.kinetic + sim.energies.internal;
    m.energy_residual = max_res / max_scale;
    Ok(m)
}

/// Run W5: two bars, and the striker against a rigid wall.
pub fn run() -> Result<CaseOutput> {
    let mut check = Check::new(TITLE);
    let c = (E / RHO).sqrt();
    let t_c = 2.0 * L / c;
    let f_bars = RHO * c * 1.0 * V0 / 2.0;
    let m = measure(320, false)?;
    let p0 = m.bar_mass * V0;
    let reference = m
        .times
        .iter()
        .map(|&t| if (0.0..t_c).contains(&t) { f_bars } else { 0.0 })
        .collect();
    let series = vec![Series::new(
        TITLE,
        "two bars: interface force",
        ("time (s)", "contact force Σλ (N)"),
        m.times.clone(),
        m.forces.clone(),
        Some(reference),
    )];
    check
        .relative(
            "bars: plateau force ρcAv0/2 (N)",
            f_bars,
            m.plateau,
            0.03,
            SOURCE,
        )
        .absolute(
            "bars: contact duration 2L/c (s)",
            t_c,
            m.duration,
            2.0 * m.dt,
            SOURCE,
        )
        .relative("bars: impulse ρALv0 (N·s)", p0, m.impulse, 0.005, SOURCE)
        .relative(
            "bars: target momentum after (N·s)",
            p0,
            m.bar_mass * m.target_velocity,
            0.005,
            SOURCE,
        )
        .absolute(
            "bars: striker momentum after / ρALv0",
            0.0,
            m.striker_velocity / V0,
            0.005,
            SOURCE,
        )
        .relative(
            "bars: target kinetic energy ½mv0² (J)",
            m.initial_energy,
            0.5 * m.bar_mass * m.target_velocity.powi(2),
            0.02,
            SOURCE,
        )
        .relative(
            "bars: kinetic + strain energy after (J)",
            m.initial_energy,
            m.final_energy,
            0.02,
            SOURCE,
        )
        .within(
            "bars: W12 energy residual / largest energy",
            -0.02,
            0.02,
            m.energy_residual,
            "docs/verification_references.md §W12",
        );
    let w = measure(320, true)?;
    check
        .relative(
            "wall: plateau force ρcAv0 (N)",
            2.0 * f_bars,
            w.plateau,
            0.03,
            SOURCE,
        )
        .absolute(
            "wall: contact duration 2L/c (s)",
            t_c,
            w.duration,
            2.0 * w.dt,
            SOURCE,
        )
        .relative(
            "wall: rebound velocity −v0 (m/s)",
            -V0,
            w.striker_velocity,
            0.005,
            SOURCE,
        )
        .relative(
            "wall: kinetic + strain energy after (J)",
            w.initial_energy,
            w.final_energy,
            0.02,
            SOURCE,
        )
        .within(
            "wall: W12 energy residual / largest energy",
            -0.02,
            0.02,
            w.energy_residual,
            "docs/verification_references.md §W12",
        );
    Ok(CaseOutput {
        rows: check.finish(),
        series,
    })
}
