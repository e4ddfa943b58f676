//! Excavated and not yet placed elements, and the nodes only they touch, are flagged in the
//! VTU (`active` on cells and points): the static stage's gallery-and-lining case.

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::static_stage;
use dcfm_app::output::activity::activity_fields;

/// A rock box (3 × 1 × 3 elements of 10 m) with a gallery element excavated by a step and
/// a lining of 3 elements on its top placed by the next (tests/static_stage.rs).
const CASE: &str = include_str!("../../tests/fixtures/gallery_lining.toml");

#[test]
fn excavated_cells_and_dormant_nodes_are_flagged() {
    let case = parse_case(CASE, "case.toml", Path::new(".")).unwrap();
    let mut plan = case.static_plan.unwrap();
    let gallery = case.model.mesh.region_index("gallery").unwrap();
    let lining = case.model.mesh.region_index("lining").unwrap();
    let region = case.model.mesh.element_region.clone();
    let top_of_lining: Vec<usize> = (0..case.model.mesh.n_nodes())
        .filter(|&n| case.model.mesh.coords[n][2] > 31.0)
        .collect();
    assert_eq!(top_of_lining.len(), 8);
    // Stop after the excavation: the gallery is gone, the lining not yet placed.
    plan.steps.truncate(1);
    let (model, _) = static_stage::run(case.model, &plan).unwrap();
    let (cells, points) = activity_fields(&model);
    for (e, &r) in region.iter().enumerate() {
        let expected = if r as usize == gallery || r as usize == lining {
            0.0
        } else {
            1.0
        };
        assert_eq!(cells[e], expected, "element {e} of region {r}");
    }
    for (n, &p) in points.iter().enumerate() {
        let expected = if top_of_lining.contains(&n) { 0.0 } else { 1.0 };
        assert_eq!(p, expected, "node {n} at {:?}", model.mesh.coords[n]);
    }
}

/// The run's summary counts the elements the dynamic stage computes: the excavated
/// gallery element is in `elements`, not in `active_elements`, and the element-update
/// rate is steps × active elements per second.
#[test]
fn summary_counts_the_active_elements() {
    let out = std::env::temp_dir().join(format!("dcfm-activity-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&out);
    let opts = dcfm_app::run::RunOptions {
        out: out.clone(),
        progress: false,
        ..Default::default()
    };
    let case = parse_case(CASE, "case.toml", Path::new(".")).unwrap();
    let s = dcfm_app::run::run_case(case, &opts).unwrap();
    assert_eq!(
        s.active_elements + 1,
        s.elements,
        "{} of {}",
        s.active_elements,
        s.elements
    );
    let rate = s.steps_per_s * s.active_elements as f64;
    assert!((s.element_updates_per_s - rate).abs() <= 1e-9 * rate);
    let _ = std::fs::remove_dir_all(&out);
}
