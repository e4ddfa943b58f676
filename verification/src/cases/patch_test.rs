//! Constant-strain patch test (Irons; MacNeal & Harder 1985 form A) for both integrations.
//!
//! Goal: a distorted patch of hex8 elements represents a linear displacement field exactly:
//! every element's stress equals E0 : ε of the field and the internal force at the free
//! interior node vanishes.
//!
//! ```text
//!   2×2×2 patch of the unit cube, every node moved by up to 12 % of h (interior node too);
//!   u = a + G x imposed at all nodes
//! ```
//!
//! Reference: the imposed field (exact). Tolerance: 1e-10 relative (round-off).

use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;
use dcfm::Result;

use crate::record::{CaseOutput, Check};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "Patch test (constant strain)";

const SOURCE: &str = "exact linear field (patch test, MacNeal & Harder 1985)";

/// Largest relative stress error over the elements and the interior-node force relative
/// to the largest nodal force, for one integration rule.
pub fn measure(integration: Integration) -> Result<(f64, f64)> {
    let mut mesh = BoxMeshSpec::single("patch", [0.0; 3], [1.0; 3], [2, 2, 2]).build("patch")?;
    // Deterministic distortion: every node except the outer corners moves.
    for (i, x) in mesh.coords.iter_mut().enumerate() {
        let corner = x.iter().all(|c| *c == 0.0 || *c == 1.0);
        if corner {
            continue;
        }
        let s = i as f64;
        for (d, c) in x.iter_mut().enumerate() {
            let on_face = *c == 0.0 || *c == 1.0;
            if !on_face {
                *c += 0.12 * 0.5 * ((1.7 * s + 2.3 * d as f64).sin());
            }
        }
    }
    let elastic = Elastic::new("rock", 20e9, 0.25, 2700.0)?;
    let setup = RegionSetup {
        region: "patch".into(),
        material: Material::Elastic(elastic),
        integration,
        hourglass: 0.1,
    };
    let model = Model::new(mesh, &[setup], "patch")?;
    let dt = 0.5 * model.stable.critical;
    let mut sim = Simulation::new(model, dt, 0.9)?;
    let g = [
        [1e-4, 2e-5, -3e-5],
        [4e-5, -2e-4, 1e-5],
        [-1e-5, 3e-5, 5e-5],
    ];
    let a = [1e-3, -2e-3, 5e-4];
    for (i, x) in sim.model.mesh.coords.clone().iter().enumerate() {
        for r in 0..3 {
            sim.u[i][r] = a[r] + (0..3).map(|c| g[r][c] * x[c]).sum::<f64>();
        }
    }
    let eps = [
        g[0][0],
        g[1][1],
        g[2][2],
        g[0][1] + g[1][0],
        g[1][2] + g[2][1],
        g[2][0] + g[0][2],
    ];
    let exact = elastic.stress(&eps);
    let smax = exact.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut stress_err = 0.0f64;
    for e in 0..sim.model.n_elements() {
        let (_, s) = sim.model.element_strain_stress(e, &sim.u);
        for k in 0..6 {
            stress_err = stress_err.max((s[k] - exact[k]).abs() / smax);
        }
    }
    sim.internal_forces();
    let f = sim.internal_force();
    let fmax = f.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
    // The interior node is the only node with all coordinates strictly inside.
    let interior = sim
        .model
        .mesh
        .coords
        .iter()
        .position(|x| x.iter().all(|c| *c > 0.0 && *c < 1.0))
        .expect("patch has an interior node");
    let fi = f[interior].iter().fold(0.0f64, |m, v| m.max(v.abs())) / fmax;
    Ok((stress_err, fi))
}

/// Run the patch test for both integration rules.
pub fn run() -> Result<CaseOutput> {
    let mut check = Check::new(TITLE);
    for (name, integ) in [
        ("one-point + hourglass", Integration::OnePoint),
        ("full 2×2×2", Integration::Full),
    ] {
        let (s, f) = measure(integ)?;
        check
            .absolute(
                &format!("{name}: max stress error / max stress"),
                0.0,
                s,
                1e-10,
                SOURCE,
            )
            .absolute(
                &format!("{name}: interior-node force / max nodal force"),
                0.0,
                f,
                1e-10,
                SOURCE,
            );
    }
    Ok(check.finish().into())
}
