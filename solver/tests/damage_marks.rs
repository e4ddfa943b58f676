//! The damaged-volume scan of a history row visits only the elements the force passes
//! marked as possibly damaged (`element::damage_marks`, issue 11). On a block of concrete
//! cracked in one corner (one-point and fully integrated, single and subcycled steps,
//! states in place and buffered), after every few steps: the marked scan gives the volumes
//! of a scan of every element bit for bit (per point and per element, thresholds 0.1 and
//! 0.5, and 0 where every element counts), every element with a damaged point is marked,
//! and part of the block is left unmarked (so the test sees the skipping). The marks
//! recomputed from restored states (a checkpoint's) give the same volumes.
//!
//! The scan also keeps, between rows, each element's answers (D_t, D_c at or above the
//! threshold) and reads again only the elements whose hardening the force kernel saw move
//! (`element::damage_scan`). Scanned every step like a history row, with one threshold and
//! measure, it matches a scan that reads every state bit for bit at every check, also
//! across a restore of the states.

mod common;

use dcfm::element::Integration;
use dcfm::material::Elastic;
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;

/// 12 × 6 × 4 elements of concrete, base fixed; the nodes with x < 3 m start at ±3 m/s
/// (random), the others at rest.
fn simulation(integration: Integration, subcycled: bool, in_place: bool) -> Simulation {
    let (nx, ny, nz) = (12usize, 6usize, 4usize);
    let mut mesh = BoxMeshSpec::single(
        "concrete",
        [0.0; 3],
        [nx as f64, ny as f64, nz as f64],
        [nx, ny, nz],
    )
    .build("damage-marks test")
    .unwrap();
    // Coarser elements beyond x = 6 m (they step at 2 Δt when subcycled).
    for x in mesh.coords.iter_mut() {
        if x[0] > 6.0 {
            x[0] = 6.0 + 2.0 * (x[0] - 6.0);
        }
    }
    let elastic = Elastic::new("concrete", 25e9, 0.17, 2450.0).unwrap();
    let material = common::damaging_concrete(elastic);
    let setup = RegionSetup {
        region: "concrete".to_string(),
        material,
        integration,
        hourglass: 0.05,
    };
    let mut model = Model::new(mesh, &[setup], "damage-marks test").unwrap();
    let base = model.mesh.node_sets["concrete.zmin"].clone();
    model.constraints.fix(&base, 0b111);
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = Simulation::new(model, dt, 0.9).unwrap();
    for g in &mut sim.model.groups {
        g.set_states_in_place(in_place);
    }
    let mut lcg = common::Lcg(0x05ee_dda3_a9e5_u64);
    let mut rand = move || lcg.centred();
    for (vel, x) in sim.v.iter_mut().zip(&sim.model.mesh.coords) {
        if x[0] < 3.0 && x[2] > 0.0 {
            *vel = [6.0 * rand(), 6.0 * rand(), 6.0 * rand()];
        }
    }
    sim.restart_energy_account();
    if subcycled {
        sim.enable_subcycling(2, 0.9).unwrap();
    }
    sim
}

fn bits(v: [f64; 3]) -> [u64; 3] {
    v.map(f64::to_bits)
}

/// The marked scan against the full scan on every group, for the thresholds and both
/// measures; returns (marked elements, elements with a damaged point, elements).
fn check_scans(sim: &Simulation, label: &str) -> (usize, usize, usize) {
    let (mut marked, mut damaged, mut n) = (0, 0, 0);
    for g in &sim.model.groups {
        for threshold in [0.0, 0.1, 0.5] {
            for per_element in [false, true] {
                assert_eq!(
                    bits(g.damaged_volume(threshold, per_element)),
                    bits(g.damaged_volume_scanning_all(threshold, per_element)),
                    "{label}: threshold {threshold}, per element {per_element}"
                );
            }
        }
        let states = g.states().current();
        let per = g.states().stride() * g.integration.points();
        for le in 0..g.len() {
            let has_damage = states[le * per..(le + 1) * per]
                .chunks_exact(g.states().stride())
                .any(|p| {
                    g.material
                        .tensile_and_compressive_damage(p)
                        .is_some_and(|(t, c)| t > 0.0 || c > 0.0)
                });
            damaged += has_damage as usize;
        }
        marked += g.marked_elements();
        n += g.len();
    }
    assert!(
        marked >= damaged,
        "{label}: {marked} marked < {damaged} damaged"
    );
    (marked, damaged, n)
}

#[test]
fn the_marked_scan_is_the_full_scan_bit_for_bit() {
    for integration in [Integration::Full, Integration::OnePoint] {
        for (subcycled, in_place) in [(false, true), (true, true), (false, false)] {
            let label = format!("{integration:?}, subcycled {subcycled}, in place {in_place}");
            let mut sim = simulation(integration, subcycled, in_place);
            let mut last = (0, 0, 0);
            for _ in 0..8 {
                sim.run_steps(10).unwrap();
                last = check_scans(&sim, &label);
            }
            let (marked, damaged, n) = last;
            assert!(damaged > 0, "{label}: the corner cracks");
            assert!(
                marked < n,
                "{label}: part of the block stays unmarked ({marked} of {n})"
            );
            // Marks recomputed from restored (a checkpoint's) states.
            let before: Vec<[u64; 3]> = sim
                .model
                .groups
                .iter()
                .map(|g| bits(g.damaged_volume(0.1, false)))
                .collect();
            for g in &mut sim.model.groups {
                let values = g.states().current().to_vec();
                g.restore_states(&values);
            }
            check_scans(&sim, &label);
            let after: Vec<[u64; 3]> = sim
                .model
                .groups
                .iter()
                .map(|g| bits(g.damaged_volume(0.1, false)))
                .collect();
            assert_eq!(before, after, "{label}: after a restore");
        }
    }
}

#[test]
fn kept_answers_are_the_states_bit_for_bit() {
    for integration in [Integration::Full, Integration::OnePoint] {
        for (subcycled, in_place) in [(false, true), (true, true), (false, false)] {
            for (threshold, per_element) in [(0.1, false), (0.5, true), (0.02, false)] {
                let label = format!(
                    "{integration:?}, subcycled {subcycled}, in place {in_place}, threshold \
                     {threshold}, per element {per_element}"
                );
                let mut sim = simulation(integration, subcycled, in_place);
                let mut grown = false;
                let mut first = None;
                for step in 1..=80 {
                    sim.run_steps(1).unwrap();
                    for (k, g) in sim.model.groups.iter().enumerate() {
                        // The history row, every step.
                        let row = g.damaged_volume(threshold, per_element);
                        if step % 4 == 0 {
                            assert_eq!(
                                bits(row),
                                bits(g.damaged_volume_scanning_all(threshold, per_element)),
                                "{label}: step {step}, group {k}"
                            );
                        }
                        if k == 0 {
                            grown |= first.is_some_and(|f: [f64; 3]| row[2] > f[2]);
                            first.get_or_insert(row);
                        }
                    }
                    if step == 40 {
                        for g in &mut sim.model.groups {
                            let values = g.states().current().to_vec();
                            g.restore_states(&values);
                        }
                    }
                }
                assert!(grown, "{label}: the damaged volume grows while scanned");
            }
        }
    }
}
