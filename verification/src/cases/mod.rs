//! Registered verification cases: one file per case, each with a header giving its goal,
//! sketch, boundary conditions, parameters, reference and tolerance.

use dcfm::Result;

use crate::record::CheckRow;

pub mod contact_bonded_monolithic;
pub mod contact_drop_bounce;
pub mod convergence_w01;
pub mod energy_conservation;
pub mod patch_test;
pub mod static_geostatic;
pub mod static_relaxation;
pub mod static_sequence;
pub mod w01_wave_pulses;
pub mod w04_kirsch;
pub mod w05_bar_impact;
pub mod w06_incline;
pub mod w07_newmark_block;
pub mod w08_cohesive_bond;
pub mod w09_pair_step;
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
        Case {
            id: "W5",
            run: w05_bar_impact::run,
        },
        Case {
            id: "W6",
            run: w06_incline::run,
        },
        Case {
            id: "W7",
            run: w07_newmark_block::run,
        },
        Case {
            id: "W8",
            run: w08_cohesive_bond::run,
        },
        Case {
            id: "W9",
            run: w09_pair_step::run,
        },
        Case {
            id: "bonded",
            run: contact_bonded_monolithic::run,
        },
        Case {
            id: "drop",
            run: contact_drop_bounce::run,
        },
        Case {
            id: "W4",
            run: w04_kirsch::run,
        },
        Case {
            id: "static-geo",
            run: static_geostatic::run,
        },
        Case {
            id: "static-DR",
            run: static_relaxation::run,
        },
        Case {
            id: "static-seq",
            run: static_sequence::run,
        },
    ]
}
