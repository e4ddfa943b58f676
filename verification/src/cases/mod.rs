//! Registered verification cases: one file per case, each with a header giving its goal,
//! sketch, boundary conditions, parameters, reference and tolerance.

use dcfm::Result;

use crate::record::CheckRow;

pub mod convergence_w01;
pub mod energy_conservation;
pub mod patch_test;
pub mod w01_wave_pulses;
pub mod w10_plastic_damage;
pub mod w13_stable_step;

/// A registered case: name and the function that runs it.
pub struct Case {
    pub id: &'static str,
    pub run: fn() -> Result<Vec<CheckRow>>,
}

/// Every case the runner executes, in report order.
pub fn all() -> Vec<Case> {
    vec![
        Case {
            id: "W1",
            run: w01_wave_pulses::run,
        },
        Case {
            id: "W1-conv",
            run: convergence_w01::run,
        },
        Case {
            id: "patch",
            run: patch_test::run,
        },
        Case {
            id: "energy",
            run: energy_conservation::run,
        },
        Case {
            id: "W10",
            run: w10_plastic_damage::run,
        },
        Case {
            id: "W13",
            run: w13_stable_step::run,
        },
    ]
}
