//! Probes by place, by set and by name (issue 12 item 1), contact state in the histories
//! (item 2) and the diagnosis of an instability (issue 13 item 3), through case files and
//! the application's run driver.

use std::path::Path;

mod common;

use common::Histories;
use dcfm::case::parse_case;
use dcfm::error::DcfmError;
use dcfm::stage::Simulation;

/// A 2 m cube of 2 × 2 × 2 elements (nodes on the 1 m grid), fixed at its base, pushed on
/// its top, with Rayleigh damping `alpha` (1/s), no field files and `probes` in `[output]`.
fn damped_block(probes: &str, alpha: &str) -> String {
    common::elastic_block(
        "block",
        "0.0005",
        2.0,
        &format!(
            "{}[damping]\nalpha = {alpha}\n[output]\nvtu_every = 0\n{probes}\n",
            common::TOP_RAMP
        ),
    )
}

fn block(probes: &str) -> String {
    damped_block(probes, "0.0")
}

fn err(text: &str) -> String {
    match parse_case(text, "block.toml", Path::new(".")) {
        Ok(_) => panic!("accepted: {text}"),
        Err(e) => e.to_string(),
    }
}

/// Run `text` and return its histories.csv.
fn run_histories(text: &str, name: &str) -> Histories {
    let dir = common::fresh_dir("probes", name);
    common::run_text("case.toml", text, &common::options(&dir)).unwrap();
    let h = Histories::read(&dir);
    let _ = std::fs::remove_dir_all(&dir);
    h
}

#[test]
fn a_point_probe_takes_the_nearest_node_and_reports_its_distance() {
    let text = block(
        "[[output.probes]]\nname = \"crest\"\nat = [1.9, 0.1, 2.0]\n\
         [[output.element_probes]]\nname = \"core\"\nat = [0.5, 1.5, 0.5]",
    );
    let case = parse_case(&text, "block.toml", Path::new(".")).unwrap();
    let p = &case.probes.nodes[0];
    assert_eq!(p.label, "crest");
    assert_eq!(p.nodes.len(), 1);
    let n = p.nodes[0] as usize;
    assert_eq!(case.model.mesh.coords[n], [2.0, 0.0, 2.0]);
    // √(0.1² + 0.1²) = 0.14142 m, reported with the node.
    assert!(p.found.contains("1.4142e-1 m"), "{}", p.found);
    let e = case.probes.elements[0].elements[0] as usize;
    let x = case.model.mesh.element_coords(e);
    for d in 0..3 {
        let lo = x.iter().map(|c| c[d]).fold(f64::INFINITY, f64::min);
        let hi = x.iter().map(|c| c[d]).fold(f64::NEG_INFINITY, f64::max);
        assert!(lo <= [0.5, 1.5, 0.5][d] && [0.5, 1.5, 0.5][d] <= hi);
    }
    assert!(case
        .probes
        .describe()
        .iter()
        .any(|l| l.contains("crest") && l.contains("output.probes[0]")));
}

#[test]
fn named_columns_read_the_same_values_as_node_and_element_ids() {
    // The same node and element, once by id (`node{n}_…`, `elem{e}_…`) and once by name.
    let named = block(
        "[[output.probes]]\nname = \"crest\"\nat = [2.0, 2.0, 2.0]\n\
         [[output.element_probes]]\nname = \"core\"\nat = [1.5, 1.5, 1.5]",
    );
    let case = parse_case(&named, "block.toml", Path::new(".")).unwrap();
    let (n, e) = (
        case.probes.nodes[0].nodes[0],
        case.probes.elements[0].elements[0],
    );
    let by_id = block(&format!("nodes = [{n}]\nelements = [{e}]"));
    let a = run_histories(&named, "named");
    let b = run_histories(&by_id, "by-id");
    for (x, y) in [
        ("crest_ux", format!("node{n}_ux")),
        ("crest_az", format!("node{n}_az")),
    ]
    .into_iter()
    .chain([("core_szz", format!("elem{e}_szz"))])
    {
        let (cx, cy) = (a.column(x), b.column(&y));
        assert!(cx.iter().any(|v| *v != 0.0), "{x} stays zero");
        assert_eq!(cx, cy, "{x} against {y}");
    }
}

#[test]
fn a_mean_over_a_set_is_the_mean_of_its_members() {
    let each = block(
        "[[output.probes]]\nname = \"top\"\nset = \"b.zmax\"\n\
         [[output.element_probes]]\nname = \"all\"\nset = \"b\"",
    );
    let mean = block(
        "[[output.probes]]\nname = \"top\"\nset = \"b.zmax\"\nreduce = \"mean\"\n\
         [[output.element_probes]]\nname = \"all\"\nset = \"b\"\nreduce = \"mean\"",
    );
    let case = parse_case(&each, "block.toml", Path::new(".")).unwrap();
    assert_eq!(case.probes.nodes.len(), 9, "3 × 3 nodes on the top");
    assert_eq!(case.probes.elements.len(), 8);
    let a = run_histories(&each, "each");
    let b = run_histories(&mean, "mean");
    let node_labels: Vec<String> = case.probes.nodes.iter().map(|p| p.label.clone()).collect();
    let element_labels: Vec<String> = case
        .probes
        .elements
        .iter()
        .map(|p| p.label.clone())
        .collect();
    for (q, members, group) in [
        ("ux", &node_labels, "top"),
        ("uz", &node_labels, "top"),
        ("sxx", &element_labels, "all"),
        ("szz", &element_labels, "all"),
    ] {
        let m = b.column(&format!("{group}_{q}"));
        let cols: Vec<Vec<f64>> = members
            .iter()
            .map(|l| a.column(&format!("{l}_{q}")))
            .collect();
        // Equal volumes: the volume mean is the plain mean.
        for (row, &mv) in m.iter().enumerate() {
            let plain = cols.iter().map(|c| c[row]).sum::<f64>() / cols.len() as f64;
            assert!(
                (mv - plain).abs() <= 1e-9 * plain.abs().max(1e-30),
                "{group}_{q} row {row}: {mv} against {plain}"
            );
        }
        assert!(m.iter().any(|v| *v != 0.0));
    }
}

#[test]
fn bad_probes_are_refused_at_their_field() {
    for (probes, field, expect) in [
        (
            "[[output.probes]]\nname = \"far\"\nat = [5.0, 5.0, 5.0]",
            "output.probes[0].at",
            "inside the model",
        ),
        (
            "[[output.probes]]\nname = \"a\"\nnode = 1\n[[output.probes]]\nname = \"a\"\nnode = 2",
            "output.probes[1].name",
            "output.probes[0] has it",
        ),
        (
            "nodes = [3]\n[[output.probes]]\nname = \"a\"\nnode = 3",
            "output.probes[0]",
            "output.nodes[0] already probes it",
        ),
        (
            "[[output.probes]]\nname = \"a\"\nset = \"b.zmx\"",
            "output.probes[0].set",
            "did you mean 'b.zmax'",
        ),
        (
            "[[output.probes]]\nname = \"a\"",
            "output.probes[0]",
            "exactly one of",
        ),
        (
            "[[output.probes]]\nname = \"a\"\nnode = 1\nat = [0.0, 0.0, 0.0]",
            "output.probes[0]",
            "exactly one of",
        ),
        (
            "[[output.probes]]\nname = \"a\"\nnode = 1\nreduce = \"mean\"",
            "output.probes[0].reduce",
            "only with set",
        ),
        (
            "[[output.probes]]\nname = \"a b\"\nnode = 1",
            "output.probes[0].name",
            "letters, digits",
        ),
        (
            "[[output.element_probes]]\nname = \"x\"\nelement = 0\nset = \"b\"",
            "output.element_probes[0]",
            "exactly one of at = [x, y, z], element = ID",
        ),
        (
            "[[output.element_probes]]\nname = \"x\"\nelement = 0\nreduce = \"mean\"",
            "output.element_probes[0].reduce",
            "only with set",
        ),
        (
            "[[output.element_probes]]\nname = \"x\"\nat = [0.0, 0.0, -1.0]",
            "output.element_probes[0].at",
            "inside the model",
        ),
        (
            "[[output.element_probes]]\nname = \"x\"\nset = \"rock\"",
            "output.element_probes[0].set",
            "an element set or a region",
        ),
        (
            "[[output.element_probes]]\nname = \"x\"\nelement = 8",
            "output.element_probes[0].element",
            "below 8",
        ),
    ] {
        let m = err(&block(probes));
        assert!(
            m.contains("block.toml") && m.contains(field) && m.contains(expect),
            "{probes}: {m}"
        );
    }
}

/// W5 (cases/w05_bar_impact.toml, 80 elements per bar): 1D theory gives the contact
/// pressure ρ c v0 / 2 = 4.2426 MPa on the 1 m² face for 2L/c = 1.1314 ms, after which the
/// bars part.
#[test]
fn contact_state_and_forces_of_a_probe_node_follow_the_bar_impact() {
    let path = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../cases/w05_bar_impact.toml");
    let text = std::fs::read_to_string(path)
        .unwrap()
        .replace("end = 3e-3", "end = 2e-3")
        .replace("vtu_every = 100", "vtu_every = 0")
        .replace(
            "nodes = [0, 80, 647, 403]",
            "[[output.probes]]\nname = \"hit\"\nat = [2.0, 0.0, 0.0]",
        );
    let h = run_histories(&text, "w05");
    let t = h.column("time");
    let state = h.column("hit_contact_state");
    let normal = h.column("hit_normal_force");
    let areas: Vec<Vec<f64>> = ["bonded", "stick", "slide", "separated"]
        .iter()
        .map(|k| h.column(&format!("area_{k}_impact")))
        .collect();
    let contact_end = 2.0 * 2.0 / (30e9f64 / 2400.0).sqrt();
    let mut plateau = Vec::new();
    for (row, &ti) in t.iter().enumerate() {
        let total: f64 = areas.iter().map(|a| a[row]).sum();
        assert!(
            (total - 1.0).abs() < 1e-12,
            "t = {ti}: areas sum to {total}"
        );
        if ti > 0.2 * contact_end && ti < 0.8 * contact_end {
            assert!(state[row] != 3.0, "t = {ti}: separated during the impact");
            assert!(
                areas[3][row] == 0.0,
                "t = {ti}: separated area during the impact"
            );
            plateau.push(normal[row]);
        }
        if ti > 1.3 * contact_end {
            assert_eq!(state[row], 3.0, "t = {ti}: still in contact");
            assert_eq!(areas[3][row], 1.0);
            assert_eq!(normal[row], 0.0);
        }
    }
    // The corner node carries a quarter of the face (control area 0.25 m²).
    let mean = plateau.iter().sum::<f64>() / plateau.len() as f64;
    let theory = 0.25 * 2400.0 * (30e9f64 / 2400.0).sqrt() * 1.0 / 2.0;
    assert!(
        (mean / theory - 1.0).abs() < 0.03,
        "plateau {mean:.4e} N against {theory:.4e} N"
    );
}

/// Step until the run stops; the cause of its instability.
fn cause_of_blow_up(mut sim: Simulation) -> String {
    for _ in 0..200_000 {
        match sim.step() {
            Ok(()) => {}
            Err(DcfmError::Unstable { cause, .. }) => return cause,
            Err(e) => panic!("{e}"),
        }
    }
    panic!("no instability in 200 000 steps")
}

#[test]
fn a_step_above_the_element_limit_is_named_as_the_cause() {
    let case = parse_case(&block(""), "block.toml", Path::new(".")).unwrap();
    let dt = 3.0 * case.model.stable.critical;
    let cause = cause_of_blow_up(Simulation::new_unchecked(case.model, dt));
    assert!(
        cause.contains("above the stable step") && cause.contains("elements' limit"),
        "{cause}"
    );
}

#[test]
fn a_step_above_the_damped_limit_names_rayleigh_damping() {
    let undamped = parse_case(&block(""), "block.toml", Path::new(".")).unwrap();
    // ξ = 0.75 at ω_max = 2/Δt: the damped limit is (√(1 + ξ²) − ξ) = 0.5 of the undamped.
    let omega = 2.0 / undamped.model.critical_step();
    let alpha = 1.5 * omega;
    let text = damped_block("", &format!("{alpha:e}"));
    let case = parse_case(&text, "block.toml", Path::new(".")).unwrap();
    let ratio = case.model.critical_step_with_damping() / case.model.critical_step();
    assert!((ratio - 0.5).abs() < 1e-12, "{ratio}");
    let dt = 0.9 * case.model.critical_step();
    let cause = cause_of_blow_up(Simulation::new_unchecked(case.model, dt));
    assert!(
        cause.contains("above the stable step") && cause.contains("Rayleigh damping"),
        "{cause}"
    );
}
