//! External loads of the static stage, as nodal forces on the active model:
//!
//! - gravity: M_a g h_g(0) on the lumped masses of the active elements — the body force the
//!   explicit model applies at t = 0 (row-sum lumping gives the consistent ∫ρ g N_a dV);
//! - the nodal loads of the dynamic model at t = 0 (`[loads.nodal]` × h(0));
//! - the static loads of the plan (nodal forces, pressure and traction on face sets), which
//!   stay on in the dynamic stage: pressure p gives −p ∫ φⱼ n dA, traction t gives
//!   t ∫ φⱼ dA at the face nodes (exact for bilinear faces), on faces of active elements.

use super::plan::StaticLoad;
use crate::contact::geom::{face_nodal_area_vectors, face_nodal_areas};
use crate::mesh::Face;
use crate::model::Model;

/// Add the loads of the dynamic model at t = 0 (gravity on the current masses, nodal
/// loads) to `f`.
pub fn add_model_loads(model: &Model, f: &mut [[f64; 3]]) {
    if let Some(g) = &model.gravity {
        let h = g.history.value(0.0);
        for (fi, &m) in f.iter_mut().zip(&model.mass) {
            for d in 0..3 {
                fi[d] += m * g.acceleration[d] * h;
            }
        }
    }
    for load in &model.nodal_loads {
        let h = load.history.value(0.0);
        for &i in &load.nodes {
            for d in 0..3 {
                f[i as usize][d] += load.force[d] * h;
            }
        }
    }
}

/// Add the static loads (`StaticPlan::loads`) to `f`, face loads only on faces whose
/// element is active.
pub fn add_static_loads(model: &Model, loads: &[StaticLoad], active: &[bool], f: &mut [[f64; 3]]) {
    let face_x = |face: &Face| -> ([u32; 4], [[f64; 3]; 4]) {
        let nodes = model.mesh.face_nodes(*face);
        (nodes, nodes.map(|a| model.mesh.coords[a as usize]))
    };
    for load in loads {
        match load {
            StaticLoad::Nodal { nodes, force } => {
                for &i in nodes {
                    for d in 0..3 {
                        f[i as usize][d] += force[d];
                    }
                }
            }
            StaticLoad::Pressure { faces, pressure } => {
                for face in faces.iter().filter(|fc| active[fc.element as usize]) {
                    let (nodes, x) = face_x(face);
                    let (vecs, _) = face_nodal_area_vectors(&x);
                    for j in 0..4 {
                        for d in 0..3 {
                            f[nodes[j] as usize][d] -= pressure * vecs[j][d];
                        }
                    }
                }
            }
            StaticLoad::Traction { faces, traction } => {
                for face in faces.iter().filter(|fc| active[fc.element as usize]) {
                    let (nodes, x) = face_x(face);
                    let areas = face_nodal_areas(&x);
                    for j in 0..4 {
                        for d in 0..3 {
                            f[nodes[j] as usize][d] += traction[d] * areas[j];
                        }
                    }
                }
            }
        }
    }
}

/// The gravity acceleration magnitude |g h_g(0)| of the model (0 without gravity).
pub fn gravity_magnitude(model: &Model) -> f64 {
    model.gravity.as_ref().map_or(0.0, |g| {
        let h = g.history.value(0.0);
        g.acceleration.iter().map(|a| a * a).sum::<f64>().sqrt() * h.abs()
    })
}
