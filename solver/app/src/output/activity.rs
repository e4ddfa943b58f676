//! Which cells and points of the mesh take part in the model at an output step: elements
//! excavated by the static stage or not yet placed are in the mesh (the VTU keeps one
//! connectivity for every frame) but not in any element group, and a node that only such
//! elements touch is dormant. The VTU flags both (`active` on cells and points, `region`
//! −1 on inactive cells), so that ParaView's *Threshold* on `active` ≥ 1 shows the model
//! as it is.

use dcfm::model::Model;

/// `(cells, points)`: 1 for an active element (a node of one), 0 otherwise, one value per
/// mesh element (node).
pub fn activity_fields(model: &Model) -> (Vec<f64>, Vec<f64>) {
    let mut cells = vec![0.0; model.n_elements()];
    let mut points = vec![0.0; model.mesh.n_nodes()];
    for g in &model.groups {
        for (&e, conn) in g.elements.iter().zip(&g.conn) {
            cells[e as usize] = 1.0;
            for &n in conn {
                points[n as usize] = 1.0;
            }
        }
    }
    (cells, points)
}
