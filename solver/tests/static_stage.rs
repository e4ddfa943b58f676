//! The static stage through case files: every bad input of `[static]` gets an error naming
//! the file, the field, the value and what was expected; every failure of a step names the
//! step and where (node, coordinates, value); a run resumed after the static stage is
//! bit-identical; results do not depend on the number of threads.

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::checkpoint::{
    read_checkpoint, read_static_block, write_checkpoint, write_static_block,
};
use dcfm::stage::static_stage;

/// A rock box with a gallery (element set "gallery" = region), a lining block "lining"
/// above it placed by a step, gravity.
const CASE: &str = include_str!("fixtures/gallery_lining.toml");

fn err(text: &str) -> String {
    match parse_case(text, "case.toml", Path::new(".")) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e.to_string(),
    }
}

fn run_err(text: &str) -> String {
    let case = parse_case(text, "case.toml", Path::new(".")).unwrap();
    let plan = case.static_plan.unwrap();
    match static_stage::run(case.model, &plan) {
        Ok(_) => panic!("ran:\n{text}"),
        Err(e) => e.to_string(),
    }
}

#[test]
fn the_case_runs() {
    let case = parse_case(CASE, "case.toml", Path::new(".")).unwrap();
    let plan = case.static_plan.unwrap();
    assert_eq!(plan.initially_inactive.len(), 3);
    let (m, r) = static_stage::run(case.model, &plan).unwrap();
    assert_eq!(r.steps.len(), 3);
    assert!(r.out_of_balance.ratio < 1e-12);
    assert_eq!(r.active.iter().filter(|&&a| a).count(), m.n_elements() - 1);
    // Reactions at the base carry the weight of what is active (rock without the gallery,
    // and the lining).
    let rz: f64 = r.reactions.iter().map(|(_, f)| f[2]).sum();
    let weight = 2700.0 * 9.81 * (30.0 * 10.0 * 30.0 - 1000.0 + 30.0 * 10.0 * 2.0);
    assert!((rz - weight).abs() < 1e-8 * weight, "{rz} vs {weight}");
}

#[test]
fn bad_sets_and_sequences_are_named() {
    let e = err(&CASE.replace("excavate = [\"gallery\"]", "excavate = [\"cavern\"]"));
    assert!(
        e.contains("case.toml: static.steps[0].excavate[0] = \"cavern\"") && e.contains("gallery"),
        "{e}"
    );
    let twice = CASE.replace(
        "[[static.steps]]\nname = \"lining\"",
        "[[static.steps]]\nexcavate = [\"gallery\"]\n[[static.steps]]\nname = \"lining\"",
    );
    let e = err(&twice);
    assert!(
        e.contains("static.steps[1].excavate[0] = \"gallery\"") && e.contains("already removed"),
        "{e}"
    );
    let e = err(&format!(
        "{CASE}[[static.steps]]\nactivate = [\"lining\"]\n"
    ));
    assert!(
        e.contains("static.steps[2].activate[0] = \"lining\"") && e.contains("already active"),
        "{e}"
    );
    let e = err(&CASE.replace("[time]", "[output]\nelements = [4]\n[time]"));
    assert!(
        e.contains("output.elements[0] = 4") && e.contains("excavated"),
        "{e}"
    );
}

#[test]
fn bad_values_are_named() {
    let cases = [
        ("solver = \"direct\"", "solver = \"direct\"\ntolerance = 2.0", "static.tolerance = 2"),
        ("solver = \"direct\"", "solver = \"direct\"\nmax_iterations = 0", "static.max_iterations = 0"),
        ("solver = \"direct\"", "solver = \"gauss\"", "solver"),
        ("solver = \"direct\"", "solver = \"direct\"\nlinear_solver = \"lu\"", "linear_solver"),
        ("solver = \"direct\"", "solver = \"direct\"\nfactor_memory_limit = -2.0", "static.factor_memory_limit = -2"),
        ("solver = \"direct\"", "solver = \"direct\"\ncg_tolerance = 0.0", "static.cg_tolerance = 0"),
        ("solver = \"direct\"", "solver = \"direct\"\ncg_max_iterations = 0", "static.cg_max_iterations = 0"),
        (
            "name = \"gallery\"\nexcavate",
            "name = \"gallery\"\nsubsteps = 0\nexcavate",
            "static.steps[0].substeps = 0",
        ),
        ("method = \"gravity\"", "method = \"k0\"\nground_surface = 40.0", "static.in_situ.k0 = missing"),
        ("method = \"gravity\"", "method = \"k0\"\nk0 = 0.5", "static.in_situ.ground_surface = missing"),
        ("method = \"gravity\"", "method = \"k0\"\nground_surface = 10.0\nk0 = 0.5", "static.in_situ.ground_surface = 10"),
        ("method = \"gravity\"", "method = \"k0\"\nground_surface = 40.0\nk0 = -0.5", "static.in_situ.k0 = [-0.5, -0.5]"),
        ("method = \"gravity\"", "method = \"k0\"\nground_surface = 40.0\nk0 = 0.5\nunit_weight = -1.0", "static.in_situ.unit_weight = -1"),
        ("method = \"gravity\"", "method = \"k0\"\nground_surface = 40.0\nk0 = 0.5\nsurface_pressure = -3.0", "static.in_situ.surface_pressure = -3"),
        (
            "method = \"gravity\"",
            "method = \"k0\"\nground_surface = 40.0\nk0 = 0.5\n[[static.in_situ.layers]]\nbottom = 20.0\n[[static.in_situ.layers]]\nbottom = 25.0",
            "static.in_situ.layers[1].bottom = 25",
        ),
        (
            "method = \"gravity\"",
            "method = \"k0\"\nground_surface = 40.0\nk0 = 0.5\n[[static.in_situ.layers]]\nunit_weight = 2e4\n[[static.in_situ.layers]]\nbottom = 5.0",
            "static.in_situ.layers[0].bottom = missing",
        ),
        ("method = \"gravity\"", "method = \"table\"\ntable = [[40.0, 0.0, 1.0], [50.0, 1e6, 1.0]]", "static.in_situ.table[1]"),
        ("method = \"gravity\"", "method = \"table\"\ntable = [[40.0, -1.0, 1.0]]", "static.in_situ.table[0] = [40.0, -1.0, 1.0]"),
        ("method = \"gravity\"", "method = \"table\"\ntable = [[40.0, 1.0]]", "static.in_situ.table[0] = [40.0, 1.0]"),
        ("method = \"gravity\"", "method = \"gravity\"\nk0 = 0.5", "static.in_situ.k0 = given"),
        ("method = \"gravity\"", "method = \"magic\"", "method"),
    ];
    for (from, to, expect) in cases {
        let e = err(&CASE.replacen(from, to, 1));
        assert!(e.contains("case.toml") && e.contains(expect), "{to}: {e}");
    }
    let no_gravity = CASE.replace("[loads.gravity]\nacceleration = [0.0, 0.0, -9.81]\n", "");
    let e = err(&no_gravity);
    assert!(
        e.contains("static.in_situ.method = \"gravity\"") && e.contains("[loads.gravity]"),
        "{e}"
    );
    let e = err(&no_gravity.replace(
        "method = \"gravity\"",
        "method = \"k0\"\nground_surface = 40.0\nk0 = 0.5",
    ));
    assert!(e.contains("static.in_situ.unit_weight = missing"), "{e}");
    // Loads.
    let load = |l: &str| CASE.replace("[static.in_situ]", &format!("{l}\n[static.in_situ]"));
    let e = err(&load(
        "[[static.loads]]\nset = \"top.zmax\"\nforce = [0.0, 0.0, 1.0]\npressure = 1.0",
    ));
    assert!(
        e.contains("static.loads[0]") && e.contains("exactly one"),
        "{e}"
    );
    let e = err(&load("[[static.loads]]\nset = \"all\"\npressure = 1.0"));
    assert!(
        e.contains("static.loads[0].set = \"all\"") && e.contains("face set"),
        "{e}"
    );
    let e = err(&load(
        "[[static.loads]]\nset = \"top.zmax\"\ntraction = [0.0, nan, 1.0]",
    ));
    assert!(e.contains("static.loads[0].traction"), "{e}");
    let e = err(&load("[[static.fixed]]\nset = \"bottom\"\ndofs = \"xw\""));
    assert!(e.contains("static.fixed[0].dofs = \"xw\""), "{e}");
    let e = err(&load("[[static.fixed]]\nset = \"nowhere\"\ndofs = \"x\""));
    assert!(e.contains("static.fixed[0].set = \"nowhere\""), "{e}");
}

#[test]
fn plate_with_hole_inputs_are_named() {
    let base = "[time]\nend = 1.0\n[mesh.plate_with_hole]\nradius = 1.0\nhalf_width = 10.0\nthickness = 1.0\ndivisions_radial = 4\n[materials.rock]\nmodel = \"elastic\"\nyoung = 1e9\npoisson = 0.2\ndensity = 2000.0\n[[regions]]\nname = \"plate\"\nmaterial = \"rock\"\n[[regions]]\nname = \"hole\"\nmaterial = \"rock\"\n";
    parse_case(base, "case.toml", Path::new(".")).unwrap();
    let e = err(&base.replace("half_width = 10.0", "half_width = 0.5"));
    assert!(
        e.contains("case.toml: mesh.plate_with_hole.half_width = 0.5"),
        "{e}"
    );
    let e = err(&base.replace("thickness = 1.0", "thickness = 1.0\ndivisions_around = 6"));
    assert!(
        e.contains("mesh.plate_with_hole.divisions_around = 6"),
        "{e}"
    );
    let e = err(&base.replace("[time]", "[[mesh.blocks]]\nname=\"b\"\norigin=[0.0,0.0,0.0]\nsize=[1.0,1.0,1.0]\ndivisions=[1,1,1]\n[time]"));
    assert!(e.contains("case.toml"), "{e}");
}

#[test]
fn step_failures_name_the_step_and_the_place() {
    // Relaxation cut short: names the step, the node, its coordinates and the force.
    let e = run_err(&CASE.replace(
        "solver = \"direct\"",
        "solver = \"relaxation\"\nmax_iterations = 5\npredictor = false",
    ));
    assert!(
        e.contains("static stage, step 0 'in-situ (gravity)'")
            && e.contains("did not converge in 5 iterations")
            && e.contains("at node")
            && e.contains(" N along "),
        "{e}"
    );
    // No support: the body can move.
    let free = CASE
        .replace(
            "[static.in_situ]",
            "[[static.fixed]]\nset = \"all\"\ndofs = \"y\"\n[static.in_situ]",
        )
        .replace("method = \"gravity\"", "method = \"none\"");
    let e = run_err(&free);
    assert!(
        e.contains("is not restrained")
            && e.contains("translate along")
            && e.contains("static.fixed"),
        "{e}"
    );
}

#[test]
fn direct_solve_refuses_a_bond_that_breaks() {
    // A lining block bonded to the rock top by a weak interface, hanging below a support:
    // its weight pulls the bond apart.
    let text = r#"
[time]
end = 0.01
[mesh]
split = [["rock", "block"]]
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, 2.0]
size = [2.0, 2.0, 2.0]
divisions = [1, 1, 1]
[[mesh.blocks]]
name = "block"
origin = [0.0, 0.0, 0.0]
size = [2.0, 2.0, 2.0]
divisions = [1, 1, 1]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[[regions]]
name = "block"
material = "rock"
integration = "full"
[[interfaces]]
name = "bond"
surface_a = "rock-block"
surface_b = "block-rock"
mu_s = 0.6
mu_d = 0.5
cohesion = 1.0
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[static]
[[static.fixed]]
set = "rock.zmax"
dofs = "xyz"
[static.in_situ]
method = "gravity"
"#;
    let e = run_err(text);
    assert!(
        e.contains("interface 'bond'")
            && e.contains("beyond its strength")
            && e.contains("relaxation"),
        "{e}"
    );
}

/// Writing the static block and the dynamic checkpoint, then reading both into a model
/// freshly built from the case, gives a run that continues bit-identically.
#[test]
fn resume_after_the_static_stage_is_bit_identical() {
    let case = parse_case(CASE, "case.toml", Path::new(".")).unwrap();
    let plan = case.static_plan.clone().unwrap();
    let (model, r) = static_stage::run(case.model, &plan).unwrap();
    let mut sim = static_stage::start_dynamic(model, &r, case.dt, case.safety).unwrap();
    sim.run_steps(5).unwrap();
    let mut bytes = Vec::new();
    write_static_block(&mut bytes, &r, &sim.model).unwrap();
    write_checkpoint(&mut bytes, &sim).unwrap();
    sim.run_steps(20).unwrap();

    let fresh = parse_case(CASE, "case.toml", Path::new(".")).unwrap();
    let mut model = fresh.model;
    let (restored, offset) = read_static_block(&bytes, "ckpt", &mut model, &plan).unwrap();
    let restored = restored.unwrap();
    assert_eq!(restored.u, r.u);
    assert_eq!(restored.reactions, r.reactions);
    let mut sim2 = static_stage::start_dynamic(model, &restored, fresh.dt, fresh.safety).unwrap();
    read_checkpoint(&bytes[offset..], "ckpt", &mut sim2).unwrap();
    sim2.run_steps(20).unwrap();
    assert_eq!(sim.u, sim2.u);
    assert_eq!(sim.v, sim2.v);
    assert_eq!(sim.energies.internal, sim2.energies.internal);
    // Without a static block: (None, 0) and the model untouched.
    let plain = parse_case(CASE, "case.toml", Path::new(".")).unwrap();
    let mut m = plain.model;
    let (none, off) = read_static_block(&bytes[offset..], "ckpt", &mut m, &plan).unwrap();
    assert!(none.is_none() && off == 0);
}

/// The static stage (direct and relaxation) gives the same bits on 1 and 2 threads.
#[test]
fn static_results_do_not_depend_on_threads() {
    for solver in ["direct", "relaxation"] {
        let text = CASE.replace(
            "solver = \"direct\"",
            &format!("solver = \"{solver}\"\ntolerance = 1e-8"),
        );
        let run = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let case = parse_case(&text, "case.toml", Path::new(".")).unwrap();
                let plan = case.static_plan.unwrap();
                static_stage::run(case.model, &plan).unwrap().1
            })
        };
        let (a, b) = (run(1), run(2));
        assert_eq!(a.u, b.u, "{solver}");
        assert_eq!(a.reactions, b.reactions, "{solver}");
    }
}

/// The explicit step over groups with an initial strain (K0 field) and element references
/// (placed elements) gives the same bits on 1 and 2 threads.
#[test]
fn dynamic_steps_after_a_k0_stage_do_not_depend_on_threads() {
    let text = CASE.replace(
        "method = \"gravity\"",
        "method = \"k0\"\nground_surface = 40.0\nk0 = [0.8, 0.6]",
    );
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let case = parse_case(&text, "case.toml", Path::new(".")).unwrap();
            let plan = case.static_plan.clone().unwrap();
            let (model, r) = static_stage::run(case.model, &plan).unwrap();
            assert!(model.groups.iter().any(|g| g.initial_strain.is_some()));
            assert!(model.groups.iter().any(|g| g.reference.is_some()));
            let mut sim = static_stage::start_dynamic(model, &r, case.dt, case.safety).unwrap();
            // A kick so that every element strains.
            for v in sim.v.iter_mut() {
                v[0] += 0.01;
            }
            sim.restart_energy_account();
            sim.run_steps(30).unwrap();
            (sim.u.clone(), sim.energies.internal)
        })
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.0, b.0);
    assert_eq!(a.1, b.1);
}

/// Regions with different Rayleigh α (so the nodes carry their own α) and an excavation
/// that leaves nodes without any active element (dormant, no mass): the dynamic stage's
/// damping work and energy balance stay finite. The nodal α was Σ α_e M_e,a / M_a = 0/0 at
/// the dormant nodes, which made the damping and input work NaN from the first step.
#[test]
fn damping_energy_is_finite_with_dormant_nodes_and_regional_damping() {
    let text = CASE
        .replace(
            "name = \"rock\"\nmaterial = \"rock\"\nintegration = \"full\"",
            "name = \"rock\"\nmaterial = \"rock\"\nintegration = \"full\"\ndamping = { alpha = 0.6 }",
        )
        .replace(
            "name = \"lining\"\nactivate = [\"lining\"]",
            "name = \"lining\"\nexcavate = [\"lining\"]",
        );
    let case = parse_case(&text, "case.toml", Path::new(".")).unwrap();
    let plan = case.static_plan.clone().unwrap();
    let (model, r) = static_stage::run(case.model, &plan).unwrap();
    assert!(model.mass.contains(&0.0), "no dormant node");
    let mut sim = static_stage::start_dynamic(model, &r, case.dt, case.safety).unwrap();
    // A kick on the free x DOFs of the nodes with mass.
    for i in 0..sim.v.len() {
        if sim.model.mass[i] > 0.0 && sim.model.constraints.constrained[i] & 1 == 0 {
            sim.v[i][0] += 0.01;
        }
    }
    sim.restart_energy_account();
    sim.run_steps(200).unwrap();
    let e = &sim.energies;
    assert!(
        e.damping.is_finite() && e.damping > 0.0,
        "damping work {}",
        e.damping
    );
    assert!(e.input.is_finite(), "input work {}", e.input);
    let rel = e.relative_residual();
    assert!(
        rel.is_finite() && rel < 1e-3,
        "relative energy residual {rel}"
    );
}

/// A wall standing on a base (one body) and an inner block placed on the base beside the
/// wall, with interfaces "seat" (inner block on the base) and "joint" (inner block
/// against the wall). `joint` adds the joint interface; `bond_step` holds it out of
/// contact until a last step that bonds it.
fn inner_block_case(joint: bool, bond_step: bool) -> String {
    let mut text = String::from(
        r#"
[time]
end = 0.01
[mesh]
split = [["base", "inner"], ["wall", "inner"]]
[[mesh.blocks]]
name = "base"
origin = [0.0, 0.0, 0.0]
size = [2.0, 1.0, 1.0]
divisions = [2, 1, 1]
[[mesh.blocks]]
name = "wall"
origin = [0.0, 0.0, 1.0]
size = [1.0, 1.0, 2.0]
divisions = [1, 1, 2]
[[mesh.blocks]]
name = "inner"
origin = [1.0, 0.0, 1.0]
size = [1.0, 1.0, 1.0]
divisions = [1, 1, 1]
[node_sets.all]
box = [[-1.0, -1.0, -1.0], [3.0, 2.0, 4.0]]
[node_sets.bottom]
box = [[-1.0, -1.0, -0.001], [3.0, 2.0, 0.001]]
[materials.rock]
model = "elastic"
young = 1e9
poisson = 0.25
density = 2700.0
[materials.concrete]
model = "elastic"
young = 30e9
poisson = 0.2
density = 2400.0
[[regions]]
name = "base"
material = "rock"
integration = "full"
[[regions]]
name = "wall"
material = "rock"
integration = "full"
[[regions]]
name = "inner"
material = "concrete"
integration = "full"
[[interfaces]]
name = "seat"
surface_a = "inner-base"
surface_b = "base-inner"
mu_s = 0.6
mu_d = 0.5
cohesion = 1e9
"#,
    );
    if joint {
        text.push_str(
            "[[interfaces]]\nname = \"joint\"\nsurface_a = \"inner-wall\"\nsurface_b = \"wall-inner\"\n\
             mu_s = 0.6\nmu_d = 0.5\ncohesion = 1e9\n",
        );
    }
    text.push_str(
        r#"[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[[boundary.fixed]]
set = "bottom"
dofs = "xyz"
[[boundary.fixed]]
set = "all"
dofs = "y"
[static]
solver = "direct"
[static.in_situ]
method = "gravity"
[[static.steps]]
name = "inner block"
activate = ["inner"]
"#,
    );
    if bond_step {
        text.push_str("[[static.steps]]\nname = \"joint bonded\"\nbond = [\"joint\"]\n");
    }
    text
}

/// (static result, joint interface index, the model) of a case.
fn run_inner(text: &str) -> (static_stage::StaticResult, dcfm::model::Model) {
    let case = parse_case(text, "case.toml", Path::new(".")).unwrap();
    let plan = case.static_plan.unwrap();
    let (m, r) = static_stage::run(case.model, &plan).unwrap();
    (r, m)
}

#[test]
fn an_interface_bonded_by_a_later_step_lets_both_sides_settle_first() {
    let (held, m) = run_inner(&inner_block_case(true, true));
    let (free, _) = run_inner(&inner_block_case(false, false));
    let (tied, mt) = run_inner(&inner_block_case(true, false));
    let c = m.contact.as_ref().unwrap();
    let k = c.interface_index("joint").unwrap();
    let pairs = c.pairs(k);
    assert_eq!(pairs.len(), 4);
    // Bonded at the end, at rest in the offset the sides reached on their own: the
    // displacements are those of the case without the joint (the bond step adds no force).
    assert_eq!(c.state_counts(k).0, [4, 0, 0, 0]);
    let scale = free.u.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
    assert!(scale > 0.0);
    for (a, b) in held.u.iter().zip(&free.u) {
        for d in 0..3 {
            assert!((a[d] - b[d]).abs() <= 1e-9 * scale, "{a:?} vs {b:?}");
        }
    }
    // The inner block settles relative to the wall after its placement (its nodes start at
    // rest at 0, the wall's where the in-situ step left them): mean vertical movement of
    // the joint's nodes of a relative to their partners since the in-situ step.
    let slip = |r: &static_stage::StaticResult| -> f64 {
        let rel = |u: &[[f64; 3]]| -> f64 {
            pairs
                .iter()
                .map(|&(a, b, _, _)| u[a as usize][2] - u[b as usize][2])
                .sum::<f64>()
                / 4.0
        };
        rel(&r.u) - rel(&r.u_in_situ)
    };
    assert!(slip(&held) < -1e-3 * scale, "slip {}", slip(&held));
    // Bonded from its placement instead, the joint holds the sides together (no slip) and
    // changes the displacements.
    let ct = mt.contact.as_ref().unwrap();
    assert_eq!(
        ct.state_counts(ct.interface_index("joint").unwrap()).0,
        [4, 0, 0, 0]
    );
    assert!(slip(&tied).abs() <= 1e-9 * scale, "slip {}", slip(&tied));
    let diff = tied
        .u
        .iter()
        .zip(&free.u)
        .flat_map(|(a, b)| (0..3).map(move |d| (a[d] - b[d]).abs()));
    assert!(diff.fold(0.0f64, f64::max) > 1e-3 * scale);
}

#[test]
fn bond_lists_name_interfaces_once() {
    let base = inner_block_case(true, false);
    let e = err(&format!("{base}[[static.steps]]\nbond = [\"jiont\"]\n"));
    assert!(
        e.contains("static.steps[1].bond[0]") && e.contains("jiont") && e.contains("seat, joint"),
        "{e}"
    );
    let e = err(&format!(
        "{base}[[static.steps]]\nbond = [\"joint\"]\n[[static.steps]]\nbond = [\"joint\"]\n"
    ));
    assert!(
        e.contains("static.steps[2].bond[0]") && e.contains("already bonded by static.steps[1]"),
        "{e}"
    );
}
