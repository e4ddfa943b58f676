//! One hex8 cube with symmetry rollers on three faces, driven through the explicit
//! driver by prescribed face displacements — the single-element material tests (W10).
//!
//! ```text
//!        z
//!        │  ┌──────┐
//!        │  │      │→ x = l face: prescribed u_x (and u_y on the y = l face for biaxial)
//!        │  │      │
//!        └──└──────┘── x     rollers: u_x = 0 on x = 0, u_y = 0 on y = 0, u_z = 0 on z = 0
//! ```

use dcfm::boundary::{MotionKind, Prescribed};
use dcfm::element::Integration;
use dcfm::load::TimeFunction;
use dcfm::material::Material;
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;
use dcfm::{DcfmError, Result};

/// Flanagan–Belytschko hourglass coefficient of the one-point element (the cube's
/// homogeneous strain excites no hourglass mode, so its value does not enter the result).
pub const HOURGLASS: f64 = 0.05;

/// A single fully integrated element; `velocities[d]` (m/s) is the constant velocity of
/// the face d = l for d = x, y (None: that face is free).
pub fn build(
    material: Material,
    l: f64,
    velocities: [Option<f64>; 2],
    beta: f64,
) -> Result<Simulation> {
    build_with(material, l, velocities, beta, Integration::Full)
}

/// [`build`] with the given integration rule (one-point: hourglass coefficient
/// [`HOURGLASS`]).
pub fn build_with(
    material: Material,
    l: f64,
    velocities: [Option<f64>; 2],
    beta: f64,
    integration: Integration,
) -> Result<Simulation> {
    let mesh = BoxMeshSpec::single("e", [0.0; 3], [l; 3], [1, 1, 1]).build("single element")?;
    let setup = RegionSetup {
        region: "e".into(),
        material,
        integration,
        hourglass: match integration {
            Integration::OnePoint => HOURGLASS,
            Integration::Full => 0.0,
        },
    };
    let mut model = Model::new(mesh, &[setup], "single element")?;
    for (face, mask) in [("e.xmin", 1u8), ("e.ymin", 2), ("e.zmin", 4)] {
        let nodes = model.mesh.node_sets[face].clone();
        model.constraints.fix(&nodes, mask);
    }
    for (d, face) in ["e.xmax", "e.ymax"].iter().enumerate() {
        if let Some(v) = velocities[d] {
            let nodes = model.mesh.node_sets[*face].clone();
            model
                .constraints
                .prescribe(Prescribed {
                    nodes,
                    dof: d,
                    kind: MotionKind::Velocity,
                    history: TimeFunction::Constant { value: v },
                })
                .map_err(|n| DcfmError::Mesh(format!("node {n} constrained twice")))?;
        }
    }
    model.damping.beta = beta;
    let dt = 0.8 * model.critical_step_with_damping();
    Simulation::new(model, dt, 0.9)
}

/// Integration-point state of the single element (point 0; all eight points of a fully
/// integrated element are equal under homogeneous strain).
pub fn point_state(sim: &Simulation) -> &[f64] {
    let g = &sim.model.groups[0];
    let stride = g.states().stride();
    &g.states().current()[..stride]
}
