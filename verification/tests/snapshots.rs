//! insta snapshots of rounded derived scalars of verified runs (peak values, energies,
//! error norms) — never raw arrays. Each snapshot records a result that the analytic suite
//! checks against its reference; the snapshot guards it against unnoticed drift.

use dcfm::element::Integration;
use dcfm_verification::cases::{
    contact_drop_bounce, energy_conservation, patch_test, w01_wave_pulses, w06_incline,
    w10_plastic_damage,
};
use dcfm_verification::models::column::{ColumnSetup, TopEnd, Wave};

fn r4(x: f64) -> String {
    format!("{x:.4e}")
}

#[test]
fn w01_p_free_scalars() {
    let m = w01_wave_pulses::measure(&ColumnSetup::w1(Wave::P, TopEnd::Free)).unwrap();
    insta::assert_yaml_snapshot!(
        "w01_p_free",
        vec![
            ("mid_peak_stress_pa", r4(m.mid_peak_stress)),
            ("mid_peak_time_s", r4(m.mid_peak_time)),
            ("mid_net_displacement_m", r4(m.mid_net_displacement)),
            ("top_peak_velocity_m_s", r4(m.top_peak_velocity)),
            ("top_displacement_m", r4(m.top_displacement)),
        ]
    );
}

#[test]
fn w01_s_fixed_scalars() {
    let m = w01_wave_pulses::measure(&ColumnSetup::w1(Wave::S, TopEnd::Fixed)).unwrap();
    insta::assert_yaml_snapshot!(
        "w01_s_fixed",
        vec![
            ("mid_peak_stress_pa", r4(m.mid_peak_stress)),
            ("top_peak_stress_pa", r4(m.top_peak_stress))
        ]
    );
}

#[test]
fn energy_means() {
    let (scheme, _) = energy_conservation::measure(Integration::OnePoint, 2000).unwrap();
    insta::assert_yaml_snapshot!(
        "energy_one_point_2000_steps",
        vec![r4(scheme[0]), r4(scheme[1])]
    );
}

#[test]
fn patch_errors_are_round_off() {
    let (s, f) = patch_test::measure(Integration::Full).unwrap();
    insta::assert_yaml_snapshot!("patch_full_below_1e-12", vec![s < 1e-12, f < 1e-12]);
}

#[test]
fn w10_tension_scalars() {
    let (s, d, g) = w10_plastic_damage::tension(1.0).unwrap();
    insta::assert_yaml_snapshot!(
        "w10_tension_l1",
        vec![
            ("stress_at_1_over_b_pa", r4(s)),
            ("damage_at_1_over_b", r4(d)),
            ("plastic_dissipation_j_m3", r4(g))
        ]
    );
}

#[test]
fn w06_incline_slide_scalars() {
    let m = w06_incline::measure(30.0, 0.5, 0.4, false, 1.0).unwrap();
    insta::assert_yaml_snapshot!(
        "w06_slide_30deg_pairs",
        vec![
            ("x_m", r4(m.x)),
            ("v_m_s", r4(m.v)),
            ("friction_work_per_kg", r4(m.friction_work / m.mass)),
            ("sliding_pairs", m.sliding_pairs.to_string()),
        ]
    );
}

#[test]
fn drop_bounce_state_counts() {
    let m = contact_drop_bounce::measure(1.5).unwrap();
    insta::assert_yaml_snapshot!(
        "drop_bounce",
        vec![
            ("separations", m.separations.to_string()),
            ("recontacts", m.recontacts.to_string()),
            (
                "final_normal_force_over_weight",
                format!("{:.4}", m.final_normal_force / (9.81 * m.mass))
            ),
        ]
    );
}
