//! W13, selective mass scaling (`time.mass_scaling`, `dcfm::mass_scaling`): a step held
//! back by one thin element is lifted by making that element heavier, the model is stable
//! at the step it then allows, and the added mass acts as a mass.
//!
//! ```text
//!   a free bar along x, 2 m × 2 m, of 1 m cells with one slab 0.1 m thick, E 20 GPa, ν 0
//!   (a 1D P wave), ρ 2500, fully integrated; mass scaling to the cells' own step:
//!   (a) the slab's density × f = (Δt_cell/Δt_slab)², the critical step = Δt_cell,
//!       the added mass (f − 1) ρ V_slab;
//!   (b) 20,000 undamped steps at 0.9 Δt_cell from alternating nodal velocities (the
//!       highest modes): bounded; the unscaled bar forced to that step blows up;
//!   (c) a sin² P pulse (20 m long) through the scaled slab: the transmitted peak is that of
//!       a point mass M = (f − 1) ρ V_slab between two rods (analytic::point_mass_junction:
//!       the rods on either side carry the slab's own 0.1 m), the unscaled slab passes it.
//! ```
//!
//! Tolerances: 1e-9 on the step and the added mass (round-off); 2 % of the incident
//! amplitude on the transmitted peak (the 1 m cells' dispersion on a 20 m pulse and the
//! sampling of the peak at the steps); (b) pass/fail.

use dcfm::element::Integration;
use dcfm::mass_scaling::{apply_mass_scaling, MassScalingSettings};
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;
use dcfm::Result;

use crate::analytic::point_mass_junction::peak_transmitted;
use crate::analytic::{HalfSinePulse1D, PulseShape};
use crate::record::Check;

const SOURCE: &str = "docs/verification_references.md §W13 (mass scaling)";
const YOUNG: f64 = 20e9;
const DENSITY: f64 = 2500.0;
const AREA: f64 = 4.0;
const SLAB: f64 = 0.1;

/// The bar of `n` cells with the slab as element `slab` (x from 0).
fn bar(n: usize, slab: usize) -> Result<Model> {
    let mut mesh = BoxMeshSpec::single("rock", [0.0; 3], [n as f64, 2.0, 2.0], [n, 1, 1])
        .build("W13 mass scaling")?;
    let mut edge = vec![0.0; n + 1];
    for k in 0..n {
        edge[k + 1] = edge[k] + if k == slab { SLAB } else { 1.0 };
    }
    for x in mesh.coords.iter_mut() {
        x[0] = edge[x[0].round() as usize];
    }
    let setup = RegionSetup {
        region: "rock".into(),
        material: Material::Elastic(Elastic::new("rock", YOUNG, 0.0, DENSITY)?),
        integration: Integration::Full,
        hourglass: 0.05,
    };
    Model::new(mesh, &[setup], "W13 mass scaling")
}

/// (the slab's own step, a cell's own step) of the unscaled bar.
fn own_steps(model: &Model, slab: usize) -> (f64, f64) {
    let (mut dt_slab, mut dt_cell) = (f64::NAN, f64::INFINITY);
    for e in 0..model.n_elements() {
        let x = model.mesh.element_coords(e);
        let lo = x.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
        if (lo - slab as f64).abs() < 1e-9 {
            dt_slab = model.element_steps[e];
        } else {
            dt_cell = dt_cell.min(model.element_steps[e]);
        }
    }
    (dt_slab, dt_cell)
}

fn scale(model: &mut Model, step: f64) -> Result<dcfm::mass_scaling::MassScalingSummary> {
    let settings = MassScalingSettings {
        min_element_step: step,
        max_added_fraction: 1.0,
    };
    apply_mass_scaling(model, &settings, "W13")
}

/// Largest (K + U) over its value after the first step, over `steps` undamped steps of Δt
/// `dt` from alternating nodal velocities; infinite when the run stops as unstable.
fn free_vibration(model: Model, dt: f64, steps: usize) -> f64 {
    let mut sim = Simulation::new_unchecked(model, dt);
    for (i, v) in sim.v.iter_mut().enumerate() {
        let s = if i % 2 == 0 { 1.0 } else { -1.0 };
        *v = [0.01 * s, 0.007 * s, -0.005 * s];
    }
    sim.restart_energy_account();
    if sim.step().is_err() {
        return f64::INFINITY;
    }
    let start = sim.energies.kinetic + sim.energies.internal;
    let mut largest = 1.0f64;
    for _ in 0..steps {
        if sim.step().is_err() {
            return f64::INFINITY;
        }
        largest = largest.max((sim.energies.kinetic + sim.energies.internal) / start);
    }
    largest
}

/// The peak x-velocity at x = `probe` of the right-going `pulse` (its front at x = `front`
/// at t = 0) through `model`, until the pulse has passed the probe.
fn transmitted_peak(model: Model, pulse: &HalfSinePulse1D, front: f64, probe: f64) -> Result<f64> {
    let dt = model.time_step(None, 0.9)?;
    let mut sim = Simulation::new(model, dt, 0.9)?;
    let c = pulse.speed;
    // The pulse left x = 0 at −front/c: u and V^{−½} of the incident wave there.
    let t0 = front / c;
    for i in 0..sim.u.len() {
        let x = sim.model.mesh.coords[i][0];
        sim.u[i] = [pulse.displacement(x, t0), 0.0, 0.0];
        sim.v[i] = [pulse.velocity(x, t0 - 0.5 * dt), 0.0, 0.0];
    }
    sim.restart_energy_account();
    let nodes: Vec<usize> = (0..sim.u.len())
        .filter(|&i| (sim.model.mesh.coords[i][0] - probe).abs() < 1e-9)
        .collect();
    let mut peak = 0.0f64;
    while sim.time < (probe - front) / c + 2.0 * pulse.period {
        sim.step()?;
        for &i in &nodes {
            peak = peak.max(sim.v[i][0]);
        }
    }
    Ok(peak)
}

/// The mass-scaling rows of W13.
pub fn checks(check: &mut Check) -> Result<()> {
    // (a) the step and the added mass.
    let (n, slab) = (40, 20);
    let mut model = bar(n, slab)?;
    let (dt_slab, dt_cell) = own_steps(&model, slab);
    let f = (dt_cell / dt_slab).powi(2);
    let summary = scale(&mut model, dt_cell)?;
    check.relative(
        "bar with a slab 1/10 of its cells, mass-scaled to the cells' step: critical step / the cells' own step",
        1.0,
        model.stable.critical / dt_cell,
        1e-9,
        SOURCE,
    );
    check.relative(
        "the same: added mass (kg) against (f − 1) ρ V_slab",
        (f - 1.0) * DENSITY * SLAB * AREA,
        summary.added_mass,
        1e-9,
        SOURCE,
    );
    // (b) stability at the step the scaling allows.
    let dt = 0.9 * dt_cell;
    let scaled = free_vibration(model, dt, 20_000);
    check.within(
        "scaled bar at 0.9× the cells' step (10× the slab's), 20,000 undamped steps: max/initial K + U (bounded)",
        0.0,
        2.0,
        scaled,
        SOURCE,
    );
    let unscaled = free_vibration(bar(n, slab)?, dt, 20_000);
    check.absolute(
        "unscaled bar forced to that step: instability (1 = energy beyond 10⁶× or the run stopped)",
        1.0,
        if unscaled > 1e6 { 1.0 } else { 0.0 },
        0.0,
        SOURCE,
    );
    // (c) a pulse through the scaled slab.
    let (n, slab) = (120, 60);
    let c = (YOUNG / DENSITY).sqrt();
    let length = 20.0;
    let pulse = HalfSinePulse1D::new(0.1, length / c, c, DENSITY)
        .expect("valid pulse")
        .with_shape(PulseShape::SineSquared);
    let (front, probe) = (35.0, 90.0 + SLAB);
    let mut scaled = bar(n, slab)?;
    let (dt_slab, dt_cell) = own_steps(&scaled, slab);
    scale(&mut scaled, dt_cell)?;
    let mass = ((dt_cell / dt_slab).powi(2) - 1.0) * DENSITY * SLAB * AREA;
    let tau = mass / (2.0 * DENSITY * c * AREA);
    let expected = peak_transmitted(tau, pulse.period);
    check.absolute(
        "P pulse (sin², 20 m) through the scaled slab: transmitted peak / incident against a point mass between two rods",
        expected,
        transmitted_peak(scaled, &pulse, front, probe)? / pulse.v0,
        0.02,
        SOURCE,
    );
    check.absolute(
        "the same pulse through the unscaled slab: transmitted peak / incident (passes whole)",
        1.0,
        transmitted_peak(bar(n, slab)?, &pulse, front, probe)? / pulse.v0,
        0.02,
        SOURCE,
    );
    Ok(())
}
