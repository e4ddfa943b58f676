//! Multi-time-step integration (`stage::subcycling`, issue 11 item 3):
//! (a) on a mesh of equal elements subcycling changes nothing, bit for bit;
//! (b) a P pulse crossing from thin slabs into elements 4× longer in a free bar (ν = 0,
//!     a 1D wave in a 3D mesh) is reflected by less than 1 % of its amplitude, and arrives
//!     in the coarse part when the single-step run and c t say;
//! (c) undamped free vibration of a graded box with a velocity field that excites its
//!     highest modes conserves K + U (exact strain energy) at the synchronous steps and
//!     does not grow (stability);
//! results are bit-identical on 1 and 2 threads; unhandled models are refused by name.

mod common;

use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;

const YOUNG: f64 = 20e9;
const DENSITY: f64 = 2500.0;

fn wave_speed() -> f64 {
    (YOUNG / DENSITY).sqrt()
}

/// A bar along x (common::elastic_bar) with element lengths `lengths` (m).
fn bar(lengths: &[f64]) -> Model {
    common::elastic_bar(lengths, YOUNG, DENSITY, "subcycling bar")
}

/// The bar `lengths` with a right-going P pulse (common::launch_right_going_pulse).
fn pulse_run(lengths: &[f64], max_level: Option<u8>, x0: f64, w: f64, v0: f64) -> Simulation {
    let model = bar(lengths);
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = Simulation::new(model, dt, 0.9).unwrap();
    common::launch_right_going_pulse(&mut sim, wave_speed(), x0, w, v0);
    if let Some(l) = max_level {
        sim.enable_subcycling(l, 0.9).unwrap();
    }
    sim
}

/// 200 slabs 0.5 m long (x ∈ [0, 100]) then 100 cubes 2 m (x ∈ [100, 300]).
fn graded_lengths() -> Vec<f64> {
    let mut l = vec![0.5; 200];
    l.extend(vec![2.0; 100]);
    l
}

/// Largest |v_x| over the nodes with x in [a, b].
fn max_velocity(sim: &Simulation, a: f64, b: f64) -> f64 {
    sim.model
        .mesh
        .coords
        .iter()
        .zip(&sim.v)
        .filter(|(x, _)| x[0] >= a && x[0] <= b)
        .map(|(_, v)| v[0].abs())
        .fold(0.0, f64::max)
}

fn bits(v: &[[f64; 3]]) -> Vec<u64> {
    v.iter().flatten().map(|x| x.to_bits()).collect()
}

#[test]
fn equal_elements_are_bit_identical_with_subcycling() {
    let lengths = vec![1.0; 60];
    let mut off = pulse_run(&lengths, None, 15.0, 10.0, 0.1);
    let mut on = pulse_run(&lengths, Some(3), 15.0, 10.0, 0.1);
    let s = on.subcycling().unwrap().clone();
    assert_eq!(s.nodes_per_level[0], on.u.len() as u64, "{s:?}");
    for _ in 0..400 {
        off.step().unwrap();
        on.step().unwrap();
    }
    assert_eq!(bits(&off.u), bits(&on.u));
    assert_eq!(bits(&off.v), bits(&on.v));
    assert_eq!(off.energies, on.energies);
}

#[test]
fn graded_bar_levels_and_savings() {
    let sim = pulse_run(&graded_lengths(), Some(3), 20.0, 20.0, 0.1);
    let s = sim.subcycling().unwrap();
    // The cubes' own step is at least 4 times the slabs' (lengths 2 m and 0.5 m): the
    // cubes step at 4 Δt, the nodes between the parts (and their element) at Δt.
    assert_eq!(s.elements_per_level, vec![201, 0, 99, 0], "{s:?}");
    assert_eq!(s.nodes_per_level, vec![4 * 201, 0, 4 * 100, 0], "{s:?}");
    assert!((s.element_update_fraction - (201.0 + 99.0 / 4.0) / 300.0).abs() < 1e-12);
}

/// Reflection at the fine/coarse boundary and arrival in the coarse part.
#[test]
fn pulse_crosses_fine_coarse_boundary() {
    let c = wave_speed();
    let (x0, w, v0) = (45.0, 40.0, 0.1);
    let probe_x = 250.0;
    let lengths = graded_lengths();
    let mut out = Vec::new();
    for level in [None, Some(3)] {
        let mut sim = pulse_run(&lengths, level, x0, w, v0);
        // Reflected: at t = 85/c the incident pulse (x ∈ [110, 150]) has left the fine
        // part and a wave reflected at x = 100 would lie in x ∈ [50, 90].
        let dt = sim.dt;
        let cycle = sim.cycle_steps();
        let n_refl = ((85.0 / c / dt).round() as u64).div_ceil(cycle) * cycle;
        sim.run_steps(n_refl).unwrap();
        let reflected = max_velocity(&sim, 0.0, 95.0);
        // Arrival at x = 250 (a node of the coarse part): the time its displacement, from
        // −(v0/c) w/2 ahead of the pulse to 0 behind it, is half-way (linear between
        // steps), c t exactly: (250 − x0)/c.
        let probe = sim
            .model
            .mesh
            .coords
            .iter()
            .position(|x| (x[0] - probe_x).abs() < 1e-9)
            .unwrap();
        let half = -(v0 / c) * 0.25 * w;
        let mut arrival = f64::NAN;
        let mut transmitted = 0.0f64;
        let (mut t_prev, mut u_prev) = (sim.time, sim.u[probe][0]);
        while sim.time < 240.0 / c {
            sim.step().unwrap();
            let u = sim.u[probe][0];
            if arrival.is_nan() && u >= half {
                arrival = t_prev + (half - u_prev) / (u - u_prev) * (sim.time - t_prev);
            }
            (t_prev, u_prev) = (sim.time, u);
            if sim.on_grid() {
                transmitted = transmitted.max(max_velocity(&sim, 110.0, 280.0));
            }
        }
        out.push((reflected, arrival, transmitted, cycle as f64 * dt));
    }
    let (r_single, a_single, t_single, _) = out[0];
    let (r_sub, a_sub, t_sub, cycle_dt) = out[1];
    let exact = (probe_x - x0) / c;
    eprintln!(
        "reflected/incident: single {:.3e}, subcycled {:.3e}; transmitted peak/incident: \
         single {:.4}, subcycled {:.4}; arrival at x = {probe_x}: single {:.6e} s, \
         subcycled {:.6e} s, c t {:.6e} s (cycle {:.3e} s)",
        r_single / v0,
        r_sub / v0,
        t_single / v0,
        t_sub / v0,
        a_single,
        a_sub,
        exact,
        cycle_dt
    );
    assert!(r_sub < 0.01 * v0, "reflected {r_sub:e} of {v0}");
    assert!(r_single < 0.01 * v0, "reflected {r_single:e} of {v0}");
    // The transmitted pulse keeps its amplitude (the bar's impedance is uniform).
    assert!((t_sub - v0).abs() < 0.02 * v0, "transmitted {t_sub}");
    // Arrival as in the single-step run: no later than c t by more than the single-step
    // run's own (dispersion) lag plus a tenth of a cycle, and within 0.5 % of c t.
    assert!(
        (a_sub - exact).abs() <= (a_single - exact).abs() + 0.1 * cycle_dt,
        "{a_sub} {a_single} {exact}"
    );
    assert!((a_sub - exact).abs() < 0.005 * exact, "{a_sub} vs {exact}");
}

/// A 12 × 3 × 3 box with x-spacing from 0.5 to 4 m (y, z: 4 m) and random velocities.
fn graded_box(max_level: Option<u8>) -> Simulation {
    let elastic = Material::Elastic(Elastic::new("rock", YOUNG, 0.25, DENSITY).unwrap());
    graded_box_of(elastic, 1.0, max_level)
}

/// [`graded_box`] of `material`, the random velocities scaled by `speed` (m/s).
fn graded_box_of(material: Material, speed: f64, max_level: Option<u8>) -> Simulation {
    let xs = [0.5, 0.5, 0.5, 0.5, 1.0, 1.0, 2.0, 2.0, 4.0, 4.0, 4.0, 4.0];
    let n = xs.len();
    let mut mesh = BoxMeshSpec::single("rock", [0.0; 3], [n as f64, 12.0, 12.0], [n, 3, 3])
        .build("graded box")
        .unwrap();
    let mut edge = vec![0.0; n + 1];
    for k in 0..n {
        edge[k + 1] = edge[k] + xs[k];
    }
    for x in mesh.coords.iter_mut() {
        x[0] = edge[x[0].round() as usize];
    }
    let setup = RegionSetup {
        region: "rock".to_string(),
        material,
        integration: Integration::Full,
        hourglass: 0.05,
    };
    let model = Model::new(mesh, &[setup], "graded box").unwrap();
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = Simulation::new(model, dt, 0.9).unwrap();
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut rand = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
    for v in sim.v.iter_mut() {
        *v = [speed * rand(), speed * rand(), speed * rand()];
    }
    sim.restart_energy_account();
    if let Some(l) = max_level {
        sim.enable_subcycling(l, 0.9).unwrap();
    }
    sim
}

/// Plastic-damage elements commit their state only when evaluated: the hardening
/// variables κ_t, κ_c (irreversible, never decreasing) of every element never decrease
/// from one fine step to the next, while the coarse elements (4 m, computed every 4 steps)
/// do damage. Committing the pending buffer of an element that was not evaluated (a plain
/// swap) would bring back its state of an earlier evaluation and fail this.
#[test]
fn plastic_damage_states_commit_at_evaluations_only() {
    let elastic = Elastic::new("concrete", YOUNG, 0.25, DENSITY).unwrap();
    let material = common::damaging_concrete(elastic);
    let mut sim = graded_box_of(material, 4.0, Some(3));
    let s = sim.subcycling().unwrap().clone();
    assert!(s.elements_per_level[2] > 0, "{s:?}");
    let kappa = |sim: &Simulation| -> Vec<[f64; 2]> {
        sim.model.groups[0]
            .element_damage_fields()
            .unwrap()
            .iter()
            .map(|f| [f[3], f[4]])
            .collect()
    };
    let coarse: Vec<usize> = (0..sim.model.groups[0].len())
        .filter(|&le| {
            let e = sim.model.groups[0].elements[le] as usize;
            sim.model
                .mesh
                .element_coords(e)
                .iter()
                .all(|x| x[0] >= 8.0 - 1e-9)
        })
        .collect();
    let mut before = kappa(&sim);
    for _ in 0..400 {
        sim.step().unwrap();
        let now = kappa(&sim);
        for (le, (a, b)) in before.iter().zip(&now).enumerate() {
            assert!(
                b[0] >= a[0] && b[1] >= a[1],
                "element {le}: kappa went from {a:?} to {b:?} at step {}",
                sim.step
            );
        }
        before = now;
    }
    let damaged = coarse
        .iter()
        .filter(|&&le| before[le][0] > 0.0 || before[le][1] > 0.0)
        .count();
    assert!(
        damaged > 0,
        "no coarse element yielded: the test does not test"
    );
}

/// Σ ½ M V^{−}·V^{+} over every node's step around a synchronous step n, plus the exact
/// strain energy U(Uⁿ): the energy the leapfrog conserves exactly in linear free
/// vibration (`stage::energy`), the node's own step for a coarse node.
fn modified_energy(sim: &mut Simulation) -> f64 {
    let strain = sim.elastic_strain_energy();
    let before = sim.v.clone();
    sim.step().unwrap();
    let kinetic: f64 = before
        .iter()
        .zip(&sim.v)
        .zip(&sim.model.mass)
        .map(|((a, b), m)| 0.5 * m * (a[0] * b[0] + a[1] * b[1] + a[2] * b[2]))
        .sum();
    kinetic + strain
}

#[test]
fn graded_box_conserves_energy_in_free_vibration() {
    let mut results = Vec::new();
    for level in [None, Some(3)] {
        let mut sim = graded_box(level);
        let cycle = sim.cycle_steps();
        let e0 = modified_energy(&mut sim);
        sim.run_steps(cycle - 1).unwrap();
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let mut last = 0.0;
        let mut samples = Vec::new();
        while sim.step < 200_000 {
            let e = modified_energy(&mut sim) / e0;
            sim.run_steps(cycle - 1).unwrap();
            lo = lo.min(e);
            hi = hi.max(e);
            last = e;
            if sim.step % 20_000 < cycle {
                samples.push(e);
            }
        }
        eprintln!("level {level:?}: E/E0 every 20000 steps {samples:?}");
        results.push((lo, hi, last, sim.energies.relative_residual(), cycle));
    }
    eprintln!("energy (E/E0 min, max, last, balance residual, cycle): {results:?}");
    let (lo, hi, last, residual, cycle) = results[1];
    assert!(cycle >= 4, "the coarse part steps at ≥ 4 Δt");
    assert!(hi - lo < 0.01, "E/E0 in [{lo}, {hi}]");
    assert!(last < 1.01, "growth: {last}");
    // The running balance (`stage::energy`) is off by Σ (H²/8) M |a|², large for a field of
    // the highest modes: no larger than with single steps.
    assert!(residual <= results[0].3, "balance residual {residual}");
}

#[test]
fn subcycled_results_do_not_depend_on_threads() {
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut sim = graded_box(Some(3));
            sim.run_steps(301).unwrap();
            (bits(&sim.u), bits(&sim.v), sim.energies)
        })
    };
    assert_eq!(run(1), run(2));
}

#[test]
fn bad_max_level_is_refused() {
    let model = bar(&[1.0; 4]);
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = Simulation::new(model, dt, 0.9).unwrap();
    let err = sim.enable_subcycling(9, 0.9).unwrap_err().to_string();
    assert!(err.contains("time.subcycling.max_level"), "{err}");
    assert!(sim.enable_subcycling(0, 0.9).is_err());
}
