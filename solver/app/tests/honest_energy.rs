//! Honest energy (issue 12 item 4): the work of a prescribed velocity that jumps at t = 0
//! is booked exactly (no constant residual of ¼ of the kinetic energy it injects), and
//! summary.json's initial kinetic energy is the one of histories.csv's row at t = 0, the
//! initial velocities' ½ M |V|² (docs/ARCHITECTURE.md, "Energy accounting").

use std::path::{Path, PathBuf};

use dcfm::case::parse_case;
use dcfm_app::run::{run_case, RunOptions, RunSummary};

fn out_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("dcfm-energy-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// Run `text`; returns the summary, summary.json and histories.csv (header, rows).
fn run(text: &str, name: &str) -> (RunSummary, serde_json::Value, Vec<String>, Vec<Vec<f64>>) {
    let dir = out_dir(name);
    let case = parse_case(text, "case.toml", Path::new(".")).unwrap();
    let summary = run_case(
        case,
        &RunOptions {
            out: dir.clone(),
            resume: false,
            progress: false,
            ..Default::default()
        },
    )
    .unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("summary.json")).unwrap()).unwrap();
    let csv = std::fs::read_to_string(dir.join("histories.csv")).unwrap();
    let _ = std::fs::remove_dir_all(&dir);
    let mut lines = csv.lines();
    let header = lines
        .next()
        .unwrap()
        .split(',')
        .map(|s| s.to_string())
        .collect();
    let rows = lines
        .map(|l| l.split(',').map(|x| x.parse().unwrap()).collect())
        .collect();
    (summary, json, header, rows)
}

fn col(header: &[String], name: &str) -> usize {
    header
        .iter()
        .position(|h| h == name)
        .unwrap_or_else(|| panic!("no column {name}"))
}

/// A belt 0.1 × 0.1 × 0.02 m (ρ 1000: 0.2 kg) whose every node starts at v0 = 0.1 m/s
/// along x at t = 0 (a jump from rest), under an elastic block resting on it through a
/// frictionless split interface. GRAVITY: the block's weight.
const BELT: &str = r#"
title = "belt started impulsively"
[time]
end = 0.004
[output]
vtu_every = 0
history_every = 1
[mesh]
split = [["block", "belt"]]
[[mesh.blocks]]
name = "belt"
origin = [0.0, 0.0, 0.0]
size = [0.1, 0.1, 0.02]
divisions = [2, 2, 1]
[[mesh.blocks]]
name = "block"
origin = [0.0, 0.0, 0.02]
size = [0.1, 0.1, 0.05]
divisions = [2, 2, 1]
[materials.belt]
model = "elastic"
young = 1e7
poisson = 0.25
density = 1000.0
[materials.block]
model = "elastic"
young = 1e7
poisson = 0.25
density = 2000.0
[[regions]]
name = "belt"
material = "belt"
integration = "full"
[[regions]]
name = "block"
material = "block"
integration = "full"
[[boundary.fixed]]
set = "belt"
dofs = "yz"
[[boundary.prescribed]]
set = "belt"
dof = "x"
kind = "velocity"
history = { type = "constant", value = 0.1 }
[[interfaces]]
name = "belt"
surface_a = "block-belt"
surface_b = "belt-block"
mu_s = 0.0
mu_d = 0.0
cohesion = 0.0
GRAVITY
"#;

#[test]
fn a_belt_started_impulsively_books_the_kinetic_energy_it_injects_as_input() {
    // Belt mass 0.1 × 0.1 × 0.02 × 1000 = 0.2 kg: it injects ½ m v0² = 1e-3 J.
    let injected = 0.5 * 0.2 * 0.1f64.powi(2);
    let (summary, _, header, rows) = run(&BELT.replace("GRAVITY", ""), "belt");
    let (t, k, input, res) = (
        col(&header, "time"),
        col(&header, "kinetic"),
        col(&header, "input"),
        col(&header, "residual"),
    );
    let last = rows.last().unwrap();
    assert!(
        (last[k] - injected).abs() <= 1e-12 * injected,
        "kinetic {} J, expected {injected} J",
        last[k]
    );
    assert!(
        (last[input] - injected).abs() <= 1e-12 * injected,
        "input work {} J, expected the injected {injected} J",
        last[input]
    );
    assert_eq!(rows[0][t], 0.0);
    assert_eq!(rows[0][k], 0.0, "the belt is at rest before t = 0");
    // Every row from the second full step on (the row of t⁰ itself carries the scheme's
    // kinetic energy ½ M (v0/2)² of the jump, with V⁰ = ½(V^{−½} + V^{½})).
    for r in &rows[2..] {
        assert!(
            r[res].abs() <= 1e-6 * injected,
            "residual {} J at t = {} s (¼ of the injected energy would be {} J)",
            r[res],
            r[t],
            0.25 * injected
        );
    }
    assert!(
        summary.energy_residual_relative <= 1e-6,
        "summary residual {:.3e} relative",
        summary.energy_residual_relative
    );
    assert_eq!(summary.energies.initial_kinetic, 0.0);
}

#[test]
fn the_summarys_initial_kinetic_energy_is_the_row_at_t0_and_half_m_v_squared() {
    let text = std::fs::read_to_string(
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/w05_bar_impact.toml"),
    )
    .unwrap()
    .replace("end = 3e-3", "end = 2e-4");
    // Striker 2 × 1 × 1 m, ρ 2400 kg/m³, v0 = 1 m/s: ½ m v0² = 2400 J.
    let closed_form = 0.5 * (2.0 * 1.0 * 1.0 * 2400.0) * 1.0f64.powi(2);
    let (summary, json, header, rows) = run(&text, "w05");
    let (t, k) = (col(&header, "time"), col(&header, "kinetic"));
    assert_eq!(rows[0][t], 0.0);
    let initial = json["energies"]["initial_kinetic"].as_f64().unwrap();
    assert!(
        (initial - closed_form).abs() <= 1e-9 * closed_form,
        "summary.json initial kinetic {initial} J, ½ m v0² = {closed_form} J"
    );
    assert!(
        (rows[0][k] - closed_form).abs() <= 1e-9 * closed_form,
        "histories.csv kinetic at t = 0: {} J, ½ m v0² = {closed_form} J",
        rows[0][k]
    );
    assert_eq!(initial, rows[0][k]);
    assert_eq!(summary.energies.initial_kinetic, initial);
    // The contact acts from the first step on; the balance still closes.
    assert!(
        summary.energy_residual_relative <= 1e-2,
        "residual {:.3e}",
        summary.energy_residual_relative
    );
}
