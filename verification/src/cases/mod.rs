//! Registered verification cases: one file per case, each with a header giving its goal,
//! sketch, boundary conditions, parameters, reference and tolerance.

use dcfm::Result;

use crate::record::CheckRow;

pub mod contact_bonded_monolithic;
pub mod contact_drop_bounce;
pub mod convergence_w01;
pub mod energy_conservation;
pub mod patch_test;
pub mod w01_wave_pulses;
pub mod w02_absorbing;
pub mod w03_site_response;
pub mod w05_bar_impact;
pub mod w06_incline;
pub mod w07_newmark_block;
pub mod w08_cohesive_bond;
pub mod w09_pair_step;
pub mod w10_plastic_damage;
pub mod w11_rock_bolt;
pub mod w13_stable_step;
pub mod w14_free_field;
pub mod w15_arias;
pub mod w15_butterworth;
pub mod w15_integration;
pub mod w15_records;
pub mod w15_response_spectrum;
pub mod w15_synthetic;

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
            id: "W2",
            run: w02_absorbing::run,
        },
        Case {
            id: "W3",
            run: w03_site_response::run,
        },
        Case {
            id: "W14",
            run: w14_free_field::run,
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
            id: "W11",
            run: w11_rock_bolt::run,
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
            id: "W15a",
            run: w15_response_spectrum::run,
        },
        Case {
            id: "W15b",
            run: w15_arias::run,
        },
        Case {
            id: "W15c",
            run: w15_butterworth::run,
        },
        Case {
            id: "W15d",
            run: w15_integration::run,
        },
        Case {
            id: "W15e",
            run: w15_records::run,
        },
        Case {
            id: "W15f",
            run: w15_synthetic::run,
        },
    ]
}
