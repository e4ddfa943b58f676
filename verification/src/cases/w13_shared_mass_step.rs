//! W13 (d) — the shared-mass bound on the critical step (`time.stable_step =
//! "shared_mass"`, solver/src/element/shared_mass_step.rs).
//!
//! ```text
//!   a 6×5×5 box graded along every axis (cells 0.3–1.6 m), interior nodes jittered, base
//!   fixed, fully integrated elastic hex8:
//!   (1) the shared-mass step ≤ 2/ω_max of the assembled M⁻¹K (dense eigensolve, nalgebra)
//!   (2) the driver runs at that step (safety 1), which the elements' own bound refuses,
//!       20,000 undamped steps from random velocities: bounded
//!   (3) at 1.05 × the exact critical step the same run is caught as unstable
//! ```
//!
//! Reference: the Irons–Treharne bound holds for any split of the nodal masses among the
//! elements (docs/verification_references.md §W13); the exact ω_max is the independent
//! reference. Tolerance: (1) none beyond round-off (1e-12); (2), (3) pass/fail.

use dcfm::dense_spectrum::omega_max_squared;
use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup, StepBound};
use dcfm::stage::Simulation;
use dcfm::{DcfmError, Result};

use crate::record::Check;

const SOURCE: &str = "docs/verification_references.md §W13";

/// The graded box, its base fixed, with the step bounded by `bound`.
fn graded_box(bound: StepBound) -> Result<Model> {
    let mut mesh = BoxMeshSpec::single("g", [0.0; 3], [6.0, 5.0, 5.0], [6, 5, 5]).build("w13")?;
    let planes = [
        vec![0.0, 1.6, 1.9, 3.5, 3.8, 5.4, 7.0],
        vec![0.0, 1.5, 1.8, 3.4, 4.9, 6.5],
        vec![0.0, 0.3, 1.9, 3.5, 3.8, 5.4],
    ];
    let last = [6, 5, 5];
    for (k, p) in mesh.coords.iter_mut().enumerate() {
        let index: [usize; 3] = std::array::from_fn(|d| p[d].round() as usize);
        let interior = (0..3).all(|d| index[d] > 0 && index[d] < last[d]);
        for d in 0..3 {
            let jitter = if interior {
                0.05 * ((k as f64) * (1.3 + 0.7 * d as f64)).sin()
            } else {
                0.0
            };
            p[d] = planes[d][index[d]] + jitter;
        }
    }
    let setup = RegionSetup {
        region: "g".into(),
        material: Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0)?),
        integration: Integration::Full,
        hourglass: 0.0,
    };
    let mut model = Model::new(mesh, &[setup], "w13")?;
    let base = model.mesh.node_sets["g.zmin"].clone();
    model.constraints.fix(&base, 0b111);
    model.step_bound = bound;
    model.refresh_stable_step();
    Ok(model)
}

/// Largest over initial kinetic energy over `steps` undamped steps of `dt` from random
/// velocities, through the driver's checked constructor (`safety` 1); the error if the
/// driver refuses the step or the run goes unstable.
fn free_run(model: Model, dt: f64, steps: usize, checked: bool) -> Result<f64> {
    let sim = if checked {
        Simulation::new(model, dt, 1.0)?
    } else {
        Simulation::new_unchecked(model, dt)
    };
    super::w13_stable_step::kinetic_growth(sim, 2718281828, steps)
}

/// The shared-mass checks, added to W13's.
pub fn checks(check: &mut Check) -> Result<()> {
    let own = graded_box(StepBound::Element)?;
    let shared = graded_box(StepBound::SharedMass)?;
    let (dt_own, dt_shared) = (own.stable.critical, shared.stable.critical);
    let exact = 2.0 / omega_max_squared(&shared).sqrt();
    check.within(
        "graded box: shared-mass step / exact 2/ω_max of the assembled M⁻¹K (a bound: ≤ 1)",
        0.0,
        1.0 + 1e-12,
        dt_shared / exact,
        SOURCE,
    );
    check.within(
        "graded box: shared-mass step / the elements' own bound (≥ 1)",
        1.0,
        10.0,
        dt_shared / dt_own,
        SOURCE,
    );
    let refused = match own.time_step(Some(dt_shared), 1.0) {
        Err(DcfmError::TimeStepTooLarge { .. }) => 1.0,
        _ => 0.0,
    };
    check.absolute(
        "graded box: the elements' own bound refuses the shared-mass step (1 = yes)",
        1.0,
        refused,
        0.0,
        SOURCE,
    );
    let bounded = free_run(shared, dt_shared, 20_000, true)?;
    check.within(
        "graded box at the shared-mass step, 20,000 undamped steps: max/initial kinetic energy",
        0.0,
        2.0,
        bounded,
        SOURCE,
    );
    let caught = match free_run(
        graded_box(StepBound::SharedMass)?,
        1.05 * exact,
        20_000,
        false,
    ) {
        Err(DcfmError::Unstable { .. }) => 1.0,
        _ => 0.0,
    };
    check.absolute(
        "graded box at 1.05 × the exact critical step: instability detected (1 = yes)",
        1.0,
        caught,
        0.0,
        SOURCE,
    );
    Ok(())
}
