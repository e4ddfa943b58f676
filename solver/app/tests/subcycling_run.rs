//! `time.subcycling` through the run driver: the summary reports the levels, a run
//! stopped at a checkpoint and resumed ends bit-identical to an uninterrupted one, and
//! bad values or models it does not handle are refused by name.

use std::path::Path;

mod common;

use common::{fresh_dir, options, rock, run_text, Histories};
use dcfm::case::parse_case;
use dcfm_app::run::{run_case, RunOptions};

/// A 2 × 2 m bar along x: 4 slabs 0.5 m long, then 4 cubes of 2 m, fixed at x = 0,
/// pulled by gravity along x; subcycling `setting`, histories every step, checkpoints
/// every `every` steps, run to `end`.
fn graded_bar(setting: &str, every: u64, end: &str) -> String {
    format!(
        r#"title = "graded bar"
[time]
end = {end}
subcycling = {setting}
[output]
checkpoint_every = {every}
nodes = [0, 20, 35]
[mesh]
[[mesh.blocks]]
name = "fine"
origin = [0.0, 0.0, 0.0]
size = [2.0, 2.0, 2.0]
divisions = [4, 1, 1]
[[mesh.blocks]]
name = "coarse"
origin = [2.0, 0.0, 0.0]
size = [8.0, 2.0, 2.0]
divisions = [4, 1, 1]
{rock}[loads.gravity]
acceleration = [9.81, 0.0, -9.81]
"#,
        rock = rock(&["fine", "coarse"], "fine.xmin"),
    )
}

#[test]
fn subcycled_run_reports_levels_and_resumes_bit_identically() {
    let dir = fresh_dir("subcycling", "resume");
    let case = graded_bar("{ max_level = 3 }", 8, "0.02");
    let full = run_text("g.toml", &case, &options(&dir.join("full"))).unwrap();
    let s = full.subcycling.clone().expect("subcycling in the summary");
    assert_eq!(s.max_level, 3);
    // The cubes (own step between 2 and 4 × the slabs') step at 2 Δt, except the one
    // touching the slabs; the nodes of the slabs (and of the fixed end) at Δt.
    assert_eq!(s.elements_per_level, vec![5, 3, 0, 0], "{s:?}");
    assert_eq!(s.nodes_per_level, vec![20, 16, 0, 0], "{s:?}");
    assert!(
        full.energy_residual_relative < 1e-2,
        "{}",
        full.energy_residual_relative
    );
    // Interrupted at a shorter end, resumed to the full end.
    let short = case.replace("end = 0.02", "end = 0.011");
    run_text("g.toml", &short, &options(&dir.join("part"))).unwrap();
    let resume = RunOptions {
        resume: true,
        ..options(&dir.join("part"))
    };
    let resumed = run_text("g.toml", &case, &resume).unwrap();
    assert!(resumed
        .resumed_from_step
        .is_some_and(|s| s > 0 && s % 8 == 0));
    assert_eq!(full.steps, resumed.steps);
    let a = std::fs::read_to_string(dir.join("full/histories.csv")).unwrap();
    let b = std::fs::read_to_string(dir.join("part/histories.csv")).unwrap();
    assert_eq!(a, b, "histories differ after resuming a subcycled run");
    // The same case without subcycling differs (the option does something) but agrees
    // closely in its end energies.
    let off = run_text(
        "g.toml",
        &graded_bar("\"off\"", 8, "0.02"),
        &options(&dir.join("off")),
    )
    .unwrap();
    assert!(off.subcycling.is_none());
    let c = std::fs::read_to_string(dir.join("off/histories.csv")).unwrap();
    assert_ne!(a, c);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn bad_subcycling_settings_are_refused_by_name() {
    for (setting, field) in [
        ("{ max_level = 9 }", "time.subcycling.max_level"),
        ("{ max_level = 0 }", "time.subcycling.max_level"),
        ("{ max_level = 2.5 }", "time.subcycling.max_level"),
        ("{ levels = 2 }", "time.subcycling.levels"),
        ("\"on\"", "time.subcycling"),
        ("3", "time.subcycling"),
    ] {
        let err = parse_case(&graded_bar(setting, 8, "0.01"), "g.toml", Path::new("."))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains(field) && err.contains("g.toml"),
            "{setting}: {err}"
        );
    }
    // Checkpoints between synchronous steps (the cycle is 2 steps).
    let dir = fresh_dir("subcycling", "bad");
    let case = parse_case(
        &graded_bar("{ max_level = 3 }", 5, "0.01"),
        "g.toml",
        Path::new("."),
    )
    .unwrap();
    let err = run_case(case, &options(&dir)).unwrap_err().to_string();
    assert!(err.contains("output.checkpoint_every"), "{err}");
    // Stiffness-proportional damping: refused, not run wrong.
    let damped = graded_bar("{ max_level = 3 }", 8, "0.01") + "[damping]\nbeta = 1e-5\n";
    let case = parse_case(&damped, "g.toml", Path::new(".")).unwrap();
    let err = run_case(case, &options(&dir)).unwrap_err().to_string();
    assert!(
        err.contains("time.subcycling") && err.contains("β"),
        "{err}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The graded bar cut at x = 2 m between its slabs and its cubes by a frictional contact
/// interface, the cubes pressed onto the slabs by gravity along −x: every node of both
/// surfaces steps at Δt (so the cubes' face at the cut does, which the element levels alone
/// would step at 2 Δt), and the subcycled run follows the single-step one.
#[test]
fn contact_nodes_stay_on_the_finest_step() {
    let dir = fresh_dir("subcycling", "contact");
    let case = |setting: &str| {
        graded_bar(setting, 8, "0.02")
            .replace("[mesh]\n", "[mesh]\nsplit = [[\"fine\", \"coarse\"]]\n")
            .replace(
                "acceleration = [9.81, 0.0, -9.81]",
                "acceleration = [-9.81, 0.0, 0.0]",
            )
            + "[[interfaces]]\nname = \"cut\"\nsurface_a = \"coarse-fine\"\n\
               surface_b = \"fine-coarse\"\nmu_s = 0.5\nmu_d = 0.4\ncohesion = 0.0\n"
    };
    let run = |setting: &str, name: &str| {
        run_text("c.toml", &case(setting), &options(&dir.join(name))).unwrap()
    };
    let on = run("{ max_level = 3 }", "on");
    let off = run("\"off\"", "off");
    assert!(off.subcycling.is_none());
    assert!(
        on.energies.contact > 0.0,
        "the cut must take contact forces"
    );
    let s = on.subcycling.clone().unwrap();
    // 20 nodes of the slabs and 4 of the cubes' face at the cut at Δt; 16 cube nodes at 2 Δt.
    assert_eq!(s.nodes_per_level, vec![24, 16, 0, 0], "{s:?}");
    assert_eq!(s.elements_per_level, vec![5, 3, 0, 0], "{s:?}");
    // Row by row (the same full steps; the last rows differ in time: the subcycled run
    // takes no shortened last step), every history column within 5 % of its range in the
    // single-step run for the displacements — the energies (columns 1–8: kinetic … residual) within 5 % of the
    // largest energy, the external work (the friction work at the cut is 1e-4 of it).
    let a = Histories::read(&dir.join("on")).rows;
    let Histories { header, rows: b } = Histories::read(&dir.join("off"));
    // Velocities and accelerations of a coarse node are those of its own (longer) step,
    // at another time: compared are the energies and the displacements along the bar
    // (the lateral ones, Poisson's, are 1/20 of these and differ by up to 6 % of their
    // range).
    let rows = a.len().min(b.len()) - 1;
    assert!(rows > 100);
    for col in 0..b[0].len() {
        let name = &header[col];
        if !((1..=8).contains(&col) || name.ends_with("_ux")) {
            continue;
        }
        let range = if (1..=8).contains(&col) {
            b.iter().map(|r| r[5].abs()).fold(0.0, f64::max)
        } else {
            b.iter().map(|r| r[col].abs()).fold(0.0, f64::max)
        };
        for k in 0..rows {
            let (x, y) = (a[k][col], b[k][col]);
            assert!(
                (x - y).abs() <= 0.05 * range || (x.is_nan() && y.is_nan()),
                "column {col} row {k}: subcycled {x}, single {y} (range {range})"
            );
        }
    }
    assert!(
        on.energy_residual_relative < 1e-2,
        "{}",
        on.energy_residual_relative
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// The graded bar with an anchor bar inside its last cube (x 8.5 → 9.5 m, 0.1 m in
/// diameter): the nodes of that host cube step at Δt (its faces at x = 8 and 10 m, which
/// the element levels alone would step at 2 Δt), so the bar's forces only reach nodes that
/// update at every step; the subcycled run follows the single-step one.
#[test]
fn anchor_hosts_stay_on_the_finest_step() {
    let dir = fresh_dir("subcycling", "anchor");
    let case = |setting: &str| {
        graded_bar(setting, 8, "0.02")
            + "[[anchors.bars]]\nname = \"bolt\"\nstart = [8.5, 1.0, 1.0]\n\
               end = [9.5, 1.0, 1.0]\ndiameter = 0.1\nyield_stress = 400e6\n\
               [[anchors.bars]]\nname = \"slip\"\nstart = [8.5, 0.5, 0.5]\n\
               end = [9.5, 0.5, 0.5]\ndiameter = 0.1\nyield_stress = 400e6\n\
               bond_stiffness = 1e9\nsegment_length = 0.25\n"
    };
    let run = |setting: &str, name: &str| {
        run_text("a.toml", &case(setting), &options(&dir.join(name))).unwrap()
    };
    let on = run("{ max_level = 3 }", "on");
    let off = run("\"off\"", "off");
    assert!(off.subcycling.is_none());
    let s = on
        .subcycling
        .clone()
        .expect("anchors are stepped, not refused");
    // The bond–slip bar's stiff springs set the model's Δt, so the elements are coarse
    // against it: at Δt only the fixed end's 4 nodes and the host cube's 8 (its faces at
    // x = 8 and 10 m); the other slab nodes (16) at 2 Δt, the nodes at x = 4 and 6 m at 8 Δt.
    assert_eq!(s.nodes_per_level, vec![12, 16, 0, 8], "{s:?}");
    // Elements at the period of their finest node: the first slab, the cube at x 6–8 m and
    // the host cube every step; the other slabs and the cube at x 2–4 m every 2 steps; the
    // cube at x 4–6 m every 8.
    assert_eq!(s.elements_per_level, vec![3, 4, 0, 1], "{s:?}");
    let on_histories = Histories::read(&dir.join("on"));
    let (a, b) = (&on_histories.rows, Histories::read(&dir.join("off")).rows);
    let rows = a.len().min(b.len()) - 1;
    assert!(rows > 100);
    // Row by row (the same full steps), each column's largest difference from the
    // single-step run over the scale `scale`. Measured: energies ≤ 0.5 % of the largest
    // energy, displacements along the bar ≤ 3 % of their range, the bond–slip bar's force
    // 5.5 % (12.9 % when its host nodes are left to step at 8 Δt), the perfectly bonded
    // bolt's 11.6 % — the strain of one 2 m element next to the cube stepping at 8 Δt, a
    // high-frequency quantity like the velocities there (4 %).
    let worst = |col: usize, scale: f64| {
        (0..rows)
            .map(|k| (a[k][col] - b[k][col]).abs())
            .fold(0.0, f64::max)
            / scale
    };
    let range = |col: usize| b.iter().map(|r| r[col].abs()).fold(0.0, f64::max);
    let column = |name: &str| on_histories.index(name);
    let largest_energy = (1..=8).map(range).fold(0.0, f64::max);
    for (col, name) in on_histories.header.iter().enumerate().take(9).skip(1) {
        let w = worst(col, largest_energy);
        assert!(w <= 0.02, "{name}: {w:.4} of the largest energy");
    }
    for name in ["node20_ux", "node35_ux"] {
        let col = column(name);
        let w = worst(col, range(col));
        assert!(w <= 0.05, "{name}: {w:.4} of its range");
    }
    for (name, limit) in [
        ("anchor_slip_max_force", 0.08),
        ("anchor_bolt_max_force", 0.15),
    ] {
        let col = column(name);
        assert!(range(col) > 0.0, "{name}: the bar must carry a force");
        let w = worst(col, range(col));
        assert!(w <= limit, "{name}: {w:.4} of its range");
    }
    assert!(
        on.energy_residual_relative < 1e-2,
        "{}",
        on.energy_residual_relative
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// `dcfm check`'s wall-time estimate of a subcycled case is timed subcycled, over whole
/// cycles, and reports the levels the run will use.
#[test]
fn the_estimate_of_a_subcycled_case_runs_subcycled_over_whole_cycles() {
    use dcfm_app::estimate::estimate_wall_time;
    let case = graded_bar("{ max_level = 3 }", 8, "0.02");
    let w = estimate_wall_time(parse_case(&case, "g.toml", Path::new(".")).unwrap()).unwrap();
    let s = w.subcycling.expect("levels in the estimate");
    assert_eq!(s.elements_per_level, vec![5, 3, 0, 0], "{s:?}");
    // The node levels reach 1: a cycle of 2 steps, timed whole.
    assert!(
        w.steps_timed >= 3 && w.steps_timed.is_multiple_of(2),
        "{}",
        w.steps_timed
    );
    let off = graded_bar("\"off\"", 8, "0.02");
    let w = estimate_wall_time(parse_case(&off, "g.toml", Path::new(".")).unwrap()).unwrap();
    assert!(w.subcycling.is_none());
}
