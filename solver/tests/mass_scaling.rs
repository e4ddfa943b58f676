//! Selective mass scaling (`dcfm::mass_scaling`, the case's `time.mass_scaling`):
//! (a) a thin slab that holds a bar's step back steps at the requested step with the mass
//!     (f − 1) ρ V_slab added, f = (Δt_min / Δt_slab)², and only its nodes heavier;
//! (b) the model is stable at the step it allows (10× the unscaled one): undamped free
//!     vibration stays bounded over 20,000 steps, while the unscaled model refuses that
//!     step and, forced to it, blows up;
//! (c) the added mass acts as a mass: a P pulse crossing the scaled slab is transmitted as
//!     through a point mass M = added mass between two rods, M dv/dt = 2Z (v_i − v)
//!     (Z = ρ c A; Graff, *Wave Motion in Elastic Solids*, 1975, §1.6: a mass at the
//!     junction of two rods), solved here by RK4;
//! (d) a region that would gain more than `max_added_fraction` of its mass is refused,
//!     naming the field, the region and the mass.

mod common;

use dcfm::mass_scaling::{apply_mass_scaling, MassScalingSettings};
use dcfm::model::Model;
use dcfm::stage::Simulation;

const YOUNG: f64 = 20e9;
const DENSITY: f64 = 2500.0;
/// Cross-section of the bar (2 m × 2 m, one element).
const AREA: f64 = 4.0;
const SLAB: f64 = 0.1;

fn wave_speed() -> f64 {
    (YOUNG / DENSITY).sqrt()
}

/// A free bar along x of `n` cubes 1 m long (cross-section 2 m × 2 m) with a slab
/// `SLAB` m thick as element `slab` (common::elastic_bar: ν = 0, a 1D wave).
fn bar(n: usize, slab: usize) -> Model {
    let mut lengths = vec![1.0; n];
    lengths[slab] = SLAB;
    common::elastic_bar(&lengths, YOUNG, DENSITY, "mass scaling bar")
}

/// The element of `model` whose nodes span x ∈ [a, b].
fn element_between(model: &Model, a: f64, b: f64) -> usize {
    (0..model.n_elements())
        .find(|&e| {
            let x = model.mesh.element_coords(e);
            let lo = x.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
            let hi = x.iter().map(|p| p[0]).fold(f64::NEG_INFINITY, f64::max);
            (lo - a).abs() < 1e-9 && (hi - b).abs() < 1e-9
        })
        .unwrap()
}

fn settings(min_element_step: f64, max_added_fraction: f64) -> MassScalingSettings {
    MassScalingSettings {
        min_element_step,
        max_added_fraction,
    }
}

#[test]
fn thin_slab_steps_at_the_requested_step_with_the_mass_it_needs() {
    let n = 40;
    let mut model = bar(n, 20);
    let slab = element_between(&model, 20.0, 20.0 + SLAB);
    let cube = element_between(&model, 0.0, 1.0);
    let (dt_slab, dt_cube) = (model.element_steps[slab], model.element_steps[cube]);
    // The slab holds the step back by about the thickness ratio.
    assert_eq!(model.stable.critical, dt_slab);
    assert!(dt_cube / dt_slab > 5.0, "{dt_cube} {dt_slab}");
    let mass_before = model.mass.clone();
    let total_before: f64 = mass_before.iter().sum();
    let summary = apply_mass_scaling(&mut model, &settings(dt_cube, 0.9), "bar").unwrap();
    let f = (dt_cube / dt_slab).powi(2);
    let slab_mass = DENSITY * SLAB * AREA;
    let added = (f - 1.0) * slab_mass;
    eprintln!("factor {f:.3}, added {added:.4e} kg: {summary:?}");
    assert_eq!(summary.elements, 1);
    assert_eq!(summary.by_region.len(), 1);
    assert!((summary.largest_factor - f).abs() < 1e-12 * f);
    assert!((summary.added_mass - added).abs() < 1e-9 * added);
    let total_mass = DENSITY * AREA * ((n - 1) as f64 + SLAB);
    assert!((summary.total_mass - total_mass).abs() < 1e-9 * total_mass);
    assert!((summary.added_fraction - added / total_mass).abs() < 1e-12);
    // The step: every element at or above the requested one, the critical step that one.
    assert_eq!(model.element_steps[slab], dt_cube);
    assert!((model.stable.critical / dt_cube - 1.0).abs() < 1e-9);
    // The nodal masses: the slab's eight nodes carry the added mass, an eighth each; the
    // others are unchanged bit for bit.
    let total_after: f64 = model.mass.iter().sum();
    assert!((total_after - total_before - added).abs() < 1e-9 * total_after);
    let slab_nodes = model.mesh.elements[slab];
    for (i, (&after, &before)) in model.mass.iter().zip(&mass_before).enumerate() {
        if slab_nodes.contains(&(i as u32)) {
            assert!(
                (after - before - added / 8.0).abs() < 1e-9 * after,
                "node {i}"
            );
        } else {
            assert_eq!(after.to_bits(), before.to_bits(), "node {i}");
        }
        assert_eq!(model.inv_mass[i], 1.0 / after);
    }
}

#[test]
fn scaled_model_is_stable_at_the_step_it_allows() {
    let mut model = bar(30, 15);
    let cube = element_between(&model, 0.0, 1.0);
    let dt_cube = model.element_steps[cube];
    // Unscaled, the step of the scaled model is refused.
    let dt = 0.9 * dt_cube;
    assert!(model.time_step(Some(dt), 0.9).is_err());
    apply_mass_scaling(&mut model, &settings(dt_cube, 0.9), "bar").unwrap();
    let allowed = model.time_step(None, 0.9).unwrap();
    assert!((allowed / dt - 1.0).abs() < 1e-9, "{allowed} {dt}");
    // Undamped free vibration from a velocity field that excites the highest modes
    // (alternating signs node to node, all three directions), 20,000 steps: the scaled
    // model's energy stays bounded (the leapfrog's K + U oscillates by O(ω²Δt²) in the
    // highest modes, it does not grow); the unscaled model forced to the same step
    // grows without bound within a few hundred steps.
    let run = |model: Model| {
        let mut sim = Simulation::new_unchecked(model, dt);
        for (i, v) in sim.v.iter_mut().enumerate() {
            let s = if i % 2 == 0 { 1.0 } else { -1.0 };
            *v = [0.01 * s, 0.007 * s, -0.005 * s];
        }
        sim.restart_energy_account();
        sim.step().unwrap();
        let start = sim.energies.kinetic + sim.energies.internal;
        let mut largest: f64 = 1.0;
        for _ in 0..20_000 {
            if sim.step().is_err() {
                return f64::INFINITY;
            }
            let e = sim.energies.kinetic + sim.energies.internal;
            largest = largest.max(e / start);
        }
        largest
    };
    let scaled = run(model);
    let unscaled = run(bar(30, 15));
    eprintln!(
        "largest K + U over its start: scaled {scaled:.4}, unscaled at the same step {unscaled:e}"
    );
    assert!(scaled < 2.0, "energy grew to {scaled} of its start");
    assert!(
        unscaled > 1e3,
        "the unscaled model should not be stable: {unscaled}"
    );
}

/// Peak velocity of the pulse transmitted through a point mass `m` between two rods of
/// impedance `z`: M dv/dt = 2Z (v_i − v), v_i(t) = v0 sin²(π t / T), RK4 with 20,000 steps
/// over 3 T.
fn point_mass_transmission(m: f64, z: f64, period: f64, v0: f64) -> f64 {
    let incident = |t: f64| {
        if (0.0..period).contains(&t) {
            v0 * (std::f64::consts::PI * t / period).sin().powi(2)
        } else {
            0.0
        }
    };
    let rate = |t: f64, v: f64| 2.0 * z / m * (incident(t) - v);
    let steps = 20_000;
    let h = 3.0 * period / steps as f64;
    let (mut t, mut v, mut peak) = (0.0, 0.0f64, 0.0f64);
    for _ in 0..steps {
        let k1 = rate(t, v);
        let k2 = rate(t + 0.5 * h, v + 0.5 * h * k1);
        let k3 = rate(t + 0.5 * h, v + 0.5 * h * k2);
        let k4 = rate(t + h, v + h * k3);
        v += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
        t += h;
        peak = peak.max(v);
    }
    peak
}

/// The peak x-velocity at x = `probe` of a right-going pulse (width `w`, centred at `x0`,
/// amplitude `v0`) through the bar, mass scaled to `scale_to` when given.
fn transmitted_peak(scale_to: Option<f64>, x0: f64, w: f64, v0: f64, probe: f64) -> f64 {
    let mut model = bar(120, 60);
    if let Some(dt) = scale_to {
        apply_mass_scaling(&mut model, &settings(dt, 0.9), "bar").unwrap();
    }
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = Simulation::new(model, dt, 0.9).unwrap();
    let c = wave_speed();
    common::launch_right_going_pulse(&mut sim, c, x0, w, v0);
    let nodes: Vec<usize> = (0..sim.u.len())
        .filter(|&i| (sim.model.mesh.coords[i][0] - probe).abs() < 1e-9)
        .collect();
    assert_eq!(nodes.len(), 4);
    // Until the pulse has passed the probe, before the end's reflection comes back.
    let mut peak = 0.0f64;
    while sim.time < (probe - x0 + w) / c {
        sim.step().unwrap();
        for &i in &nodes {
            peak = peak.max(sim.v[i][0]);
        }
    }
    peak
}

#[test]
fn added_mass_transmits_a_pulse_as_a_point_mass_between_two_rods() {
    let (x0, w, v0) = (25.0, 20.0, 0.1);
    let probe = 90.0 + SLAB;
    let c = wave_speed();
    let model = bar(120, 60);
    let dt_cube = model.element_steps[element_between(&model, 0.0, 1.0)];
    let dt_slab = model.element_steps[element_between(&model, 60.0, 60.0 + SLAB)];
    // The rods on either side of the slab carry the slab's own 0.1 m: the point mass is
    // the added mass (f − 1) ρ V_slab.
    let f = (dt_cube / dt_slab).powi(2);
    let m = (f - 1.0) * DENSITY * SLAB * AREA;
    let z = DENSITY * c * AREA;
    let expected = point_mass_transmission(m, z, w / c, v0);
    let unscaled = transmitted_peak(None, x0, w, v0, probe);
    let scaled = transmitted_peak(Some(dt_cube), x0, w, v0, probe);
    eprintln!(
        "factor {f:.2}, point mass {m:.4e} kg (τ = M/2Z = {:.3e} s, pulse {:.3e} s): \
         transmitted peak / incident: unscaled {:.4}, scaled {:.4}, point mass (RK4) {:.4}",
        m / (2.0 * z),
        w / c,
        unscaled / v0,
        scaled / v0,
        expected / v0
    );
    // The physical slab passes the pulse; the scaled one holds it back as the mass says.
    assert!((unscaled / v0 - 1.0).abs() < 0.01, "{unscaled}");
    assert!(
        expected / v0 < 0.95,
        "the test's mass must matter: {expected}"
    );
    assert!(
        (scaled - expected).abs() < 0.02 * v0,
        "{scaled} vs {expected}"
    );
}

#[test]
fn too_much_added_mass_is_refused_by_name() {
    let mut model = bar(40, 20);
    let dt_cube = model.element_steps[element_between(&model, 0.0, 1.0)];
    let err = apply_mass_scaling(&mut model, &settings(dt_cube, 0.05), "bar.toml")
        .unwrap_err()
        .to_string();
    eprintln!("{err}");
    for part in [
        "bar.toml",
        "time.mass_scaling.min_element_step",
        "max_added_fraction = 0.05",
        "region rock",
        "1 elements",
    ] {
        assert!(err.contains(part), "{part} not in: {err}");
    }
    // Nothing was changed.
    assert!(model.mass_factor.is_empty());
    assert!(model.mass_scaling.is_none());
    for (s, bad) in [
        (settings(-1.0, 0.05), "min_element_step"),
        (settings(f64::NAN, 0.05), "min_element_step"),
        (settings(dt_cube, 0.0), "max_added_fraction"),
        (settings(dt_cube, f64::INFINITY), "max_added_fraction"),
    ] {
        let err = apply_mass_scaling(&mut model, &s, "bar.toml")
            .unwrap_err()
            .to_string();
        assert!(err.contains(bad), "{bad} not in: {err}");
    }
    // A step below every element's adds nothing and changes nothing.
    let before = model.mass.clone();
    let s = apply_mass_scaling(&mut model, &settings(1e-9, 0.05), "bar.toml").unwrap();
    assert_eq!(s.elements, 0);
    assert_eq!(s.added_mass, 0.0);
    assert_eq!(model.mass, before);
}
