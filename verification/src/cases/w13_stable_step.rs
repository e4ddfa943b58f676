//! W13 — stable time step of hex8 with lumped mass.
//!
//! Goal: the element matrices have the right spectrum and the step the driver allows is
//! stable, while a step beyond the mesh's limit is caught as an instability.
//!
//! ```text
//!   (a) one free cube element of side h, full integration: Δt_crit = 2/ω_max of M⁻¹K
//!   (b) 6×6×6 uniform mesh, boundary fixed, random initial velocities, 3000 steps:
//!       one-point elements bounded at Δt = 0.99 h/c_p and caught as unstable at 1.25 h/c_p;
//!       fully integrated elements bounded at the default 0.9 h/c_p
//!   (c) selective mass scaling (w13_mass_scaling.rs): a thin slab's step lifted to its
//!       neighbours', stable there, the added mass transmitting a pulse as a point mass
//!   (d) the shared-mass bound (w13_shared_mass_step.rs): at most the exact critical step
//!       of a graded mesh, stable where the elements' own bound refuses
//! ```
//!
//! Reference: docs/verification_references.md §W13 (single-element bound 0.775 h/c_p; uniform mesh stable up
//! to h/c_p). Measured here: the h/c_p limit holds for one-point elements; with full 2×2×2
//! integration (ν = 0.25) the uniform mesh goes unstable from 0.96 h/c_p (bounded at 0.95),
//! which the default safety factor 0.9 covers. Tolerance: 1 % on 0.775; (b) pass/fail.

use nalgebra::DMatrix;

use dcfm::element::hex8_full::{internal_force, FullGeometry};
use dcfm::element::hex8_shape::NODE_XI;
use dcfm::element::lumped_mass::element_masses;
use dcfm::element::Integration;
use dcfm::material::{Elastic, Material, PointContext};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;
use dcfm::{DcfmError, Result};

use crate::record::{CaseOutput, Check};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W13 stable time step";

const SOURCE: &str = "docs/verification_references.md §W13";

/// 2/ω_max of a single free cube element (side h) times c_p/h.
pub fn single_element_bound() -> f64 {
    let h = 1.0;
    let el = Elastic::new("rock", 20e9, 0.25, 2700.0).expect("valid");
    let material = Material::Elastic(el);
    let x = NODE_XI.map(|p| p.map(|c| 0.5 * h * (c + 1.0)));
    let geo = FullGeometry::new(&x).expect("cube");
    let m = element_masses(&x, el.density);
    let ctx = PointContext {
        char_length: h,
        dt: 0.0,
        reads_damage: false,
    };
    let mut k = DMatrix::<f64>::zeros(24, 24);
    for col in 0..24 {
        let mut u = [[0.0; 3]; 8];
        u[col / 3][col % 3] = 1.0;
        let mut f = [[0.0; 3]; 8];
        internal_force(&geo, &material, &u, &[], &mut [], &ctx, &mut f);
        for row in 0..24 {
            k[(row, col)] = f[row / 3][row % 3];
        }
    }
    // Symmetric scaling M^{-1/2} K M^{-1/2}.
    let s = DMatrix::from_fn(24, 24, |r, c| k[(r, c)] / (m[r / 3] * m[c / 3]).sqrt());
    let eig = s.symmetric_eigen();
    let wmax = eig.eigenvalues.iter().fold(0.0f64, |a, &b| a.max(b)).sqrt();
    (2.0 / wmax) * el.p_wave_speed() / h
}

/// The model's critical step for one free unit cube times c_p/h (the solver's own power
/// iteration on the element kernel).
pub fn solver_cube_bound() -> Result<f64> {
    let mesh = BoxMeshSpec::single("c", [0.0; 3], [1.0; 3], [1, 1, 1]).build("w13")?;
    let el = Elastic::new("rock", 20e9, 0.25, 2700.0)?;
    let setup = RegionSetup {
        region: "c".into(),
        material: Material::Elastic(el),
        integration: Integration::Full,
        hourglass: 0.0,
    };
    let model = Model::new(mesh, &[setup], "w13")?;
    Ok(model.stable.critical * el.p_wave_speed())
}

/// Run a 6×6×6 mesh with fixed boundary at `courant` × h/c_p for `steps` steps from random
/// velocities; returns the ratio of the largest to the initial kinetic energy, or the error.
pub fn uniform_mesh_run(integration: Integration, courant: f64, steps: usize) -> Result<f64> {
    let mesh = BoxMeshSpec::single("m", [0.0; 3], [6.0; 3], [6, 6, 6]).build("w13")?;
    let setup = RegionSetup {
        region: "m".into(),
        material: Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0)?),
        integration,
        hourglass: 0.05,
    };
    let mut model = Model::new(mesh, &[setup], "w13")?;
    for face in ["m.xmin", "m.xmax", "m.ymin", "m.ymax", "m.zmin", "m.zmax"] {
        let nodes = model.mesh.node_sets[face].clone();
        model.constraints.fix(&nodes, 0b111);
    }
    let h_over_c = 1.0 / Elastic::new("rock", 20e9, 0.25, 2700.0)?.p_wave_speed();
    kinetic_growth(
        Simulation::new_unchecked(model, courant * h_over_c),
        12345,
        steps,
    )
}

/// Give the free DOFs of `sim` random velocities in [-0.5, 0.5) from `seed` (a 64-bit LCG)
/// and run `steps` undamped steps; returns the ratio of the largest to the first step's
/// kinetic energy, or the error that stopped the run.
pub fn kinetic_growth(mut sim: Simulation, mut seed: u64, steps: usize) -> Result<f64> {
    for (i, v) in sim.v.iter_mut().enumerate() {
        if sim.model.constraints.constrained[i] != 0 {
            continue;
        }
        for c in v.iter_mut() {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            *c = ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5;
        }
    }
    sim.restart_energy_account();
    sim.step()?;
    let k0 = sim.energies.kinetic;
    let mut kmax = k0;
    for _ in 1..steps {
        sim.step()?;
        kmax = kmax.max(sim.energies.kinetic);
    }
    Ok(kmax / k0)
}

/// Run W13.
pub fn run() -> Result<CaseOutput> {
    let mut check = Check::new(TITLE);
    check.relative(
        "single free cube: 2/ω_max · c_p/h (nalgebra eigensolver)",
        0.775,
        single_element_bound(),
        0.01,
        SOURCE,
    );
    check.relative(
        "single free cube: the model's critical step · c_p/h (element power iteration)",
        0.775,
        solver_cube_bound()?,
        0.01,
        SOURCE,
    );
    let stable = uniform_mesh_run(Integration::OnePoint, 0.99, 3000)?;
    check.within(
        "one-point mesh at 0.99 h/c_p: max/initial kinetic energy (bounded)",
        0.0,
        2.0,
        stable,
        SOURCE,
    );
    let caught = match uniform_mesh_run(Integration::OnePoint, 1.25, 3000) {
        Err(DcfmError::Unstable { .. }) => 1.0,
        _ => 0.0,
    };
    check.absolute(
        "one-point mesh at 1.25 h/c_p: instability detected (1 = yes)",
        1.0,
        caught,
        0.0,
        SOURCE,
    );
    let full = uniform_mesh_run(Integration::Full, 0.9, 3000)?;
    check.within(
        "full-integration mesh at 0.9 h/c_p (default): max/initial kinetic energy",
        0.0,
        2.0,
        full,
        SOURCE,
    );
    super::w13_mass_scaling::checks(&mut check)?;
    super::w13_shared_mass_step::checks(&mut check)?;
    Ok(check.finish().into())
}
