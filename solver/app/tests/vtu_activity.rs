//! Excavated and not yet placed elements, and the nodes only they touch, are flagged in the
//! VTU (`active` on cells and points): the static stage's gallery-and-lining case.

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::static_stage;
use dcfm_app::output::activity::activity_fields;

/// A rock box (3 × 1 × 3 elements of 10 m) with a gallery element excavated by a step and
/// a lining of 3 elements on its top placed by the next (tests/static_stage.rs).
const CASE: &str = r#"
[time]
end = 0.01
[mesh]
[[mesh.blocks]]
name = "base"
region = "rock"
origin = [0.0, 0.0, 0.0]
size = [30.0, 10.0, 10.0]
divisions = [3, 1, 1]
[[mesh.blocks]]
name = "left"
region = "rock"
origin = [0.0, 0.0, 10.0]
size = [10.0, 10.0, 10.0]
divisions = [1, 1, 1]
[[mesh.blocks]]
name = "gallery"
region = "gallery"
origin = [10.0, 0.0, 10.0]
size = [10.0, 10.0, 10.0]
divisions = [1, 1, 1]
[[mesh.blocks]]
name = "right"
region = "rock"
origin = [20.0, 0.0, 10.0]
size = [10.0, 10.0, 10.0]
divisions = [1, 1, 1]
[[mesh.blocks]]
name = "top"
region = "rock"
origin = [0.0, 0.0, 20.0]
size = [30.0, 10.0, 10.0]
divisions = [3, 1, 1]
[[mesh.blocks]]
name = "lining"
region = "lining"
origin = [0.0, 0.0, 30.0]
size = [30.0, 10.0, 2.0]
divisions = [3, 1, 1]
[node_sets.all]
box = [[-1.0, -1.0, -1.0], [31.0, 11.0, 33.0]]
[node_sets.bottom]
box = [[-1.0, -1.0, -0.001], [31.0, 11.0, 0.001]]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[[regions]]
name = "gallery"
material = "rock"
integration = "full"
[[regions]]
name = "lining"
material = "rock"
integration = "full"
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[[boundary.fixed]]
set = "bottom"
dofs = "xyz"
[[boundary.fixed]]
set = "all"
dofs = "y"
[static]
solver = "direct"
[static.in_situ]
method = "gravity"
[[static.steps]]
name = "gallery"
excavate = ["gallery"]
[[static.steps]]
name = "lining"
activate = ["lining"]
"#;

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
