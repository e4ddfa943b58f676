//! Selective mass scaling (`dcfm::mass_scaling`, the case's `time.mass_scaling`):
//! (a) a thin slab that holds a bar's step back steps at the requested step with the mass
//!     (f − 1) ρ V_slab added, f = (Δt_min / Δt_slab)², and only its nodes heavier;
//! (b) a region that would gain more than `max_added_fraction` of its mass is refused,
//!     naming the field, the region and the mass; bad values are refused.
//! The stability at the scaled step and the added mass's effect on a wave (a point mass
//! between two rods) are checked by the verification case W13
//! (verification/src/cases/w13_mass_scaling.rs), shown in the report.

mod common;

use dcfm::mass_scaling::{apply_mass_scaling, MassScalingSettings};
use dcfm::model::Model;

const YOUNG: f64 = 20e9;
const DENSITY: f64 = 2500.0;
/// Cross-section of the bar (2 m × 2 m, one element).
const AREA: f64 = 4.0;
const SLAB: f64 = 0.1;

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
