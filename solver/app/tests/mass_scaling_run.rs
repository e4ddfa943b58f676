//! `time.mass_scaling` through the case file and the run driver: the summary reports the
//! elements made heavier and the mass added, the run steps at the requested step, a run
//! stopped at a checkpoint and resumed ends bit-identical to an uninterrupted one, and bad
//! values are refused by name.

use std::path::Path;

mod common;

use common::{fresh_dir, options, rock, run_text};
use dcfm::case::parse_case;
use dcfm_app::run::RunOptions;

/// A 2 × 2 m bar along x: 4 cubes of 1 m, a slab 0.25 m thick, 4 cubes of 1 m; fixed at
/// x = 0, pulled by gravity along x; mass scaling `setting`, checkpoints every 10 steps.
fn bar_with_slab(setting: &str, end: &str) -> String {
    format!(
        r#"title = "bar with a thin slab"
[time]
end = {end}
mass_scaling = {setting}
[output]
checkpoint_every = 10
nodes = [0, 20, 35]
[mesh]
[[mesh.blocks]]
name = "left"
origin = [0.0, 0.0, 0.0]
size = [4.0, 2.0, 2.0]
divisions = [4, 1, 1]
[[mesh.blocks]]
name = "slab"
origin = [4.0, 0.0, 0.0]
size = [0.25, 2.0, 2.0]
divisions = [1, 1, 1]
[[mesh.blocks]]
name = "right"
origin = [4.25, 0.0, 0.0]
size = [4.0, 2.0, 2.0]
divisions = [4, 1, 1]
{rock}[loads.gravity]
acceleration = [9.81, 0.0, -9.81]
"#,
        rock = rock(&["left", "slab", "right"], "left.xmin"),
    )
}

/// The own steps of the slab and of a cube of the unscaled bar (s).
fn own_steps() -> (f64, f64) {
    let case = parse_case(&bar_with_slab("\"off\"", "0.01"), "b.toml", Path::new(".")).unwrap();
    let m = &case.model;
    let slab = m.groups.iter().find(|g| g.name == "slab").unwrap().elements[0] as usize;
    let cube = m.groups.iter().find(|g| g.name == "left").unwrap().elements[0] as usize;
    assert_eq!(m.stable.critical, m.element_steps[slab]);
    (m.element_steps[slab], m.element_steps[cube])
}

#[test]
fn scaled_run_reports_the_added_mass_and_resumes_bit_identically() {
    let dir = fresh_dir("mass_scaling", "resume");
    let (dt_slab, dt_cube) = own_steps();
    assert!(dt_cube / dt_slab > 2.0, "{dt_slab} {dt_cube}");
    let setting = format!("{{ min_element_step = {dt_cube:e}, max_added_fraction = 20.0 }}");
    let case = bar_with_slab(&setting, "0.02");
    let full = run_text("b.toml", &case, &options(&dir.join("full"))).unwrap();
    let s = full
        .mass_scaling
        .clone()
        .expect("mass scaling in the summary");
    let f = (dt_cube / dt_slab).powi(2);
    let slab_mass = 2700.0 * 0.25 * 4.0;
    assert_eq!(s.elements, 1);
    assert_eq!(s.by_region.len(), 1);
    assert_eq!(s.by_region[0].region, "slab");
    assert!((s.added_mass - (f - 1.0) * slab_mass).abs() < 1e-9 * s.added_mass);
    assert!((s.by_region[0].added_fraction - (f - 1.0)).abs() < 1e-9 * f);
    // The step: safety × the cubes' own step, where the slab held it at its own before.
    assert!(
        (full.dt / (0.9 * dt_cube) - 1.0).abs() < 1e-12,
        "{}",
        full.dt
    );
    assert!(
        full.energy_residual_relative < 1e-2,
        "{}",
        full.energy_residual_relative
    );
    // Interrupted at a shorter end, resumed to the full end: the same histories.
    let short = case.replace("end = 0.02", "end = 0.011");
    run_text("b.toml", &short, &options(&dir.join("part"))).unwrap();
    let resume = RunOptions {
        resume: true,
        ..options(&dir.join("part"))
    };
    let resumed = run_text("b.toml", &case, &resume).unwrap();
    assert!(resumed.resumed_from_step.is_some_and(|s| s > 0));
    assert_eq!(full.steps, resumed.steps);
    let a = std::fs::read_to_string(dir.join("full/histories.csv")).unwrap();
    let b = std::fs::read_to_string(dir.join("part/histories.csv")).unwrap();
    assert_eq!(a, b, "histories differ after resuming a mass-scaled run");
    // Without the option the summary has no mass scaling and the step is the slab's.
    let off = run_text(
        "b.toml",
        &bar_with_slab("\"off\"", "0.002"),
        &options(&dir.join("off")),
    )
    .unwrap();
    assert!(off.mass_scaling.is_none());
    assert!((off.dt / (0.9 * dt_slab) - 1.0).abs() < 1e-12, "{}", off.dt);
    let summary = std::fs::read_to_string(dir.join("full/summary.json")).unwrap();
    assert!(summary.contains("\"mass_scaling\""), "{summary}");
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_mass_scaling_settings_are_refused_by_name() {
    let (_, dt_cube) = own_steps();
    for (setting, field) in [
        (
            "{ min_element_step = -1e-4 }",
            "time.mass_scaling.min_element_step",
        ),
        (
            "{ min_element_step = \"1e-4\" }",
            "time.mass_scaling.min_element_step",
        ),
        (
            "{ max_added_fraction = 0.1 }",
            "time.mass_scaling.min_element_step",
        ),
        (
            "{ min_element_step = 1e-4, max_added_fraction = 0.0 }",
            "time.mass_scaling.max_added_fraction",
        ),
        (
            "{ min_element_step = 1e-4, target = 2 }",
            "time.mass_scaling.target",
        ),
        ("\"on\"", "time.mass_scaling"),
        ("1e-4", "time.mass_scaling"),
    ] {
        let err = parse_case(&bar_with_slab(setting, "0.01"), "b.toml", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(field) && err.contains("b.toml"),
            "{setting}: {err}"
        );
    }
    // The default fraction (5 % of a region's mass) refuses the slab's factor.
    let setting = format!("{{ min_element_step = {dt_cube:e} }}");
    let err = parse_case(&bar_with_slab(&setting, "0.01"), "b.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        err.contains("region slab") && err.contains("max_added_fraction = 0.05"),
        "{err}"
    );
}
