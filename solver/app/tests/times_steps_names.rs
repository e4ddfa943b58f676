//! Issue 12 items 3, 5 and 6 through case files and the run driver: a run ends exactly
//! on its `end`, the stable step comes from the parts that move, and the VTU names the
//! regions of its `region` field.

use std::path::{Path, PathBuf};

mod common;

use common::Histories;
use dcfm::case::parse_case;
use dcfm_app::output::read_string_arrays;
use dcfm_app::run::RunSummary;

/// Two blocks side by side along x (regions "left" and "right"), `[[regions]]` listing
/// "right" first: the `region` field numbers regions in that order, not in block order.
const TWO_REGIONS: &str = r#"
title = "two regions"
[time]
end = 0.0003
[output]
vtu_every = 0
[mesh]
[[mesh.blocks]]
name = "left"
origin = [0.0, 0.0, 0.0]
size = [2.0, 1.0, 1.0]
divisions = [2, 1, 1]
[[mesh.blocks]]
name = "right"
origin = [2.0, 0.0, 0.0]
size = [1.0, 1.0, 1.0]
divisions = [1, 1, 1]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[materials.soft]
model = "elastic"
young = 2e9
poisson = 0.25
density = 2000.0
[[regions]]
name = "right"
material = "soft"
[[regions]]
name = "left"
material = "rock"
[[boundary.fixed]]
set = "left.xmin"
dofs = "xyz"
"#;

fn dir(name: &str) -> PathBuf {
    common::fresh_dir("tsn", name)
}

fn run(text: &str, out: &Path) -> RunSummary {
    common::run_text("case.toml", text, &common::options(out)).unwrap()
}

#[test]
fn region_field_numbers_regions_in_case_order_and_the_vtu_names_them() {
    let case = parse_case(TWO_REGIONS, "case.toml", Path::new(".")).unwrap();
    // The mesh orders its regions by block: left, right.
    assert_eq!(case.model.mesh.region_names, ["left", "right"]);
    let region_of_block: Vec<usize> = case
        .model
        .mesh
        .element_region
        .iter()
        .map(|&r| r as usize)
        .collect();
    let out = dir("regions");
    let s = run(TWO_REGIONS, &out);
    let last = out.join(format!("mesh_{:06}.vtu", s.steps));
    for file in [out.join("mesh_000000.vtu"), last] {
        let text = std::fs::read_to_string(&file).unwrap();
        let arrays = read_string_arrays(&text).expect("well-formed field data");
        assert_eq!(
            arrays,
            vec![(
                "region_names".to_string(),
                vec!["right".to_string(), "left".to_string()]
            )]
        );
        let region = common::vtu_field(&file, "region", true);
        assert_eq!(region.len(), 3);
        for (e, &r) in region.iter().enumerate() {
            // Block "left" (mesh region 0) is [[regions]] entry 1, "right" entry 0.
            let expect = if region_of_block[e] == 0 { 1.0 } else { 0.0 };
            assert_eq!(r, expect, "element {e}");
            assert_eq!(
                arrays[0].1[r as usize],
                case.model.mesh.region_names[region_of_block[e]]
            );
        }
    }
    let _ = std::fs::remove_dir_all(&out);
}

#[test]
fn a_region_named_twice_is_refused_at_its_field() {
    let text = TWO_REGIONS.replace(
        "[[regions]]\nname = \"left\"",
        "[[regions]]\nname = \"right\"\nmaterial = \"rock\"\n[[regions]]\nname = \"left\"",
    );
    let e = parse_case(&text, "two.toml", Path::new("."))
        .unwrap_err()
        .to_string();
    assert!(
        e.contains("two.toml") && e.contains("regions[1].name") && e.contains("regions[0]"),
        "{e}"
    );
}

/// A 1 m cube of 2 × 2 × 1 elements on a belt: a 2 cm layer of stiff elements under it
/// whose every node is driven (x) or fixed (y, z). BELT_DOFS: the DOFs of the belt's
/// nodes that are fixed besides the driven x.
const ON_A_BELT: &str = r#"
title = "block on a belt"
[time]
end = 0.001
[mesh]
[[mesh.blocks]]
name = "belt"
origin = [0.0, 0.0, -0.02]
size = [1.0, 1.0, 0.02]
divisions = [2, 2, 1]
[[mesh.blocks]]
name = "body"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 1.0]
divisions = [2, 2, 1]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[materials.steel]
model = "elastic"
young = 200e9
poisson = 0.3
density = 7800.0
[[regions]]
name = "body"
material = "rock"
[[regions]]
name = "belt"
material = "steel"
[[boundary.fixed]]
set = "belt"
dofs = "BELT_DOFS"
[[boundary.prescribed]]
set = "belt"
dof = "x"
kind = "velocity"
history = { type = "constant", value = 0.1 }
"#;

/// The body alone: the same elements without the belt.
const BODY_ALONE: &str = r#"
title = "body"
[time]
end = 0.001
[mesh]
[[mesh.blocks]]
name = "body"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 1.0]
divisions = [2, 2, 1]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "body"
material = "rock"
"#;

fn region_of(case: &dcfm::case::Case, e: usize) -> String {
    let m = &case.model;
    m.groups[m.element_location[e].0 as usize].name.clone()
}

#[test]
fn elements_whose_nodes_are_all_prescribed_do_not_limit_the_step() {
    let driven = parse_case(
        &ON_A_BELT.replace("BELT_DOFS", "yz"),
        "belt.toml",
        Path::new("."),
    )
    .unwrap();
    let alone = parse_case(BODY_ALONE, "body.toml", Path::new(".")).unwrap();
    // The body's elements set the step, exactly as without the belt.
    assert_eq!(driven.model.stable.critical, alone.model.stable.critical);
    assert_eq!(region_of(&driven, driven.model.stable.element), "body");
    assert_eq!(driven.dt, alone.dt);
    // The P-wave bound of a 0.5 × 0.5 × 1 m rock element: Δt ≤ L/c_p with L ≤ 0.5 m.
    let c = (20e9 * 0.75 / (1.25 * 0.5) / 2700.0f64).sqrt();
    assert!(driven.model.stable.critical <= 0.5 / c * (1.0 + 1e-12));
    // The belt's elements are 2 cm thick, of steel: without the prescription of y and z
    // their nodes move in those directions and a belt element limits the step, 50 times
    // smaller.
    let free = parse_case(
        &ON_A_BELT.replace(
            "[[boundary.fixed]]\nset = \"belt\"\ndofs = \"BELT_DOFS\"\n",
            "",
        ),
        "belt.toml",
        Path::new("."),
    )
    .unwrap();
    assert_eq!(region_of(&free, free.model.stable.element), "belt");
    assert!(free.model.stable.critical < 0.1 * alone.model.stable.critical);
    // A partly prescribed element keeps its own limit: y fixed only.
    let partly = parse_case(
        &ON_A_BELT.replace("BELT_DOFS", "y"),
        "belt.toml",
        Path::new("."),
    )
    .unwrap();
    assert_eq!(partly.model.stable, free.model.stable);
}

#[test]
fn dcfm_check_names_the_element_of_the_parts_that_move() {
    let dir = dir("check");
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("belt.toml");
    std::fs::write(&path, ON_A_BELT.replace("BELT_DOFS", "yz")).unwrap();
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_dcfm"))
        .arg("check")
        .arg(&path)
        .output()
        .unwrap();
    let text =
        String::from_utf8_lossy(&out.stdout).to_string() + &String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{text}");
    let case = parse_case(
        &ON_A_BELT.replace("BELT_DOFS", "yz"),
        "belt.toml",
        Path::new("."),
    )
    .unwrap();
    let e = case.model.stable.element;
    assert!(
        text.contains(&format!("(element {e} in region 'body'")),
        "{text}"
    );
    assert!(
        text.contains("4 elements with every node prescribed"),
        "{text}"
    );
    let _ = std::fs::remove_dir_all(&dir);
}

/// A free 1 m cube (2 × 2 × 2 elements, no support) falling under gravity with Δt =
/// 1e-4 s: no stress, every node moves as a point mass under constant acceleration. The
/// leapfrog from rest (V^{−½} = 0) then gives exactly u(t) = −g(½t² + ½Δt·t), including
/// over a shortened last step h whose velocity increment is ½(Δt + h) g (module docs of
/// stage::dynamic); any other increment misses it by O(hΔt g).
const FALLING: &str = r#"
title = "free fall"
[time]
end = END
dt = 1e-4
[output]
vtu_every = 4
nodes = [0]
[mesh]
[[mesh.blocks]]
name = "b"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 1.0]
divisions = [2, 2, 2]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "b"
material = "rock"
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
"#;

#[test]
fn a_run_ends_exactly_on_an_end_that_is_not_a_multiple_of_the_step() {
    let (dt, g) = (1e-4, 9.81);
    for (end, steps) in [(1.037e-3, 11u64), (1e-5, 1), (1.2e-3, 12)] {
        let out = dir(&format!("end-{end}"));
        let s = run(&FALLING.replace("END", &end.to_string()), &out);
        assert_eq!(s.steps, steps, "end {end}");
        assert_eq!(s.end_time, end, "summary end_time for end {end}");
        assert_eq!(s.end_requested, end);
        let last = end - (steps - 1) as f64 * dt;
        assert!((s.last_dt - last).abs() < 1e-15, "{} vs {last}", s.last_dt);
        let json: serde_json::Value =
            serde_json::from_str(&std::fs::read_to_string(out.join("summary.json")).unwrap())
                .unwrap();
        assert_eq!(json["end_time"].as_f64(), Some(end));
        let h = Histories::read(&out);
        let row = h.rows.last().unwrap();
        assert_eq!(row[0], end, "last histories row for end {end}");
        assert_eq!(h.rows.len() as u64, steps + 1);
        // The closed form of the leapfrog under constant acceleration.
        let uz = row[h.index("node0_uz")];
        let exact = -g * (0.5 * end * end + 0.5 * dt * end);
        assert!(
            (uz - exact).abs() <= 1e-9 * exact.abs(),
            "end {end}: u_z = {uz:e}, closed form {exact:e}"
        );
        // Frames every 4 steps on the step grid, the last one on the end.
        let pvd = dcfm_app::output::PvdCollection::resume(&out.join("case.pvd")).unwrap();
        let times: Vec<f64> = pvd.entries().iter().map(|e| e.time).collect();
        let mut expect: Vec<f64> = (0..steps)
            .filter(|k| k % 4 == 0)
            .map(|k| k as f64 * dt)
            .collect();
        expect.push(end);
        assert_eq!(times.len(), expect.len(), "{times:?} vs {expect:?}");
        for (t, e) in times.iter().zip(&expect) {
            assert!((t - e).abs() <= 1e-12 * dt, "{times:?} vs {expect:?}");
        }
        assert_eq!(*times.last().unwrap(), end);
        let _ = std::fs::remove_dir_all(&out);
    }
}

#[test]
fn a_shortened_last_step_keeps_the_energy_balance() {
    // The balance residual of a run ending with a shortened step is of the order of that
    // of the runs of full steps around it.
    let residual = |end: f64| {
        let out = dir(&format!("energy-{end}"));
        let s = run(&FALLING.replace("END", &end.to_string()), &out);
        let _ = std::fs::remove_dir_all(&out);
        (s.energy_residual.abs(), s.energies.external.abs())
    };
    let (short, work) = residual(1.037e-3);
    let (full_before, _) = residual(1.0e-3);
    let (full_after, _) = residual(1.1e-3);
    assert!(work > 0.0);
    assert!(
        short <= 2.0 * full_before.max(full_after) + 1e-12 * work,
        "residual {short:e} against {full_before:e} and {full_after:e} (work {work:e})"
    );
}

/// W5 (cases/w05_bar_impact.toml): stopped in the middle of the impact at an end that is
/// not a multiple of Δt, the shortened last step keeps the faces together — the contact
/// force of that step closes the gap over h·½(Δt + h), not Δt² — and carries the 1D
/// contact force ρ c v0 / 2 (a quarter of it on the corner node).
#[test]
fn a_shortened_last_step_keeps_contact_closed_with_the_impact_force() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/w05_bar_impact.toml");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("end = 3e-3", "end = 5.06e-4")
        .replace("vtu_every = 100", "vtu_every = 0")
        .replace(
            "nodes = [0, 80, 647, 403]",
            "nodes = [647]\n[[output.probes]]\nname = \"hit\"\nat = [2.0, 0.0, 0.0]",
        );
    let out = dir("impact");
    let s = run(&text, &out);
    assert_eq!(s.end_time, 5.06e-4);
    assert!(
        s.last_dt < 0.9 * s.dt && s.last_dt > 0.1 * s.dt,
        "a shortened last step: {} of {}",
        s.last_dt,
        s.dt
    );
    let h = Histories::read(&out);
    let _ = std::fs::remove_dir_all(&out);
    let theory = 0.25 * 2400.0 * (30e9f64 / 2400.0).sqrt() * 1.0 / 2.0;
    let n = h.rows.len();
    for row in [&h.rows[n - 2], &h.rows[n - 1]] {
        // The probe takes node 80, the striker's corner; node 647 is its split twin.
        let (a, b) = (row[h.index("hit_ux")], row[h.index("node647_ux")]);
        assert!(a > 1e-4, "the striker has moved: {a:e}");
        assert!(
            (a - b).abs() <= 1e-9 * a,
            "t = {}: faces at {a:e} and {b:e}",
            row[0]
        );
        assert_ne!(row[h.index("hit_contact_state")], 3.0, "separated");
        let f = row[h.index("hit_normal_force")];
        assert!(
            (f / theory - 1.0).abs() < 0.1,
            "t = {}: normal force {f:.4e} N against {theory:.4e} N",
            row[0]
        );
    }
}
