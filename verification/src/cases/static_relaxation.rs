//! Static stage: dynamic relaxation against the direct solve on the same elastic model
//! (issue #7: ≤ 1e-6 relative displacement), and a plastic-damage step that only the
//! relaxation can solve.
//!
//! ```text
//!   30 × 10 × 30 m rock box (6 × 2 × 6 elements), gallery 10 × 10 × 10 m in the middle
//!   (through the thickness); rollers on the sides, base fixed, gravity, then the gallery
//!   excavated in one step (release in 4 substeps for the relaxation).
//! ```
//!
//! Reference: the direct solve of the same model (sparse Cholesky, out-of-balance 1e-14):
//! the relaxation must reach the same equilibrium. Tolerance 1e-6 of the largest
//! displacement, with the relaxation's out-of-balance tolerance at 1e-11 (its displacement
//! error is the out-of-balance times the compliance, ~κ × ratio).
//!
//! Plastic-damage: a 1 × 1 × 4 m column with free sides pressed on top by 20 MPa (above
//! f_c0 = 13 MPa, below f_c = 24.1 MPa: hardening): the direct solve refuses the step (the
//! material yields), the relaxation converges with σ_zz = −p in every element (statics)
//! and a compressive damage D_c > 0.

use dcfm::case::parse_case;
use dcfm::model::Model;
use dcfm::stage::static_stage::{self, StaticResult};
use dcfm::Result;

use crate::record::{Check, CheckRow};

fn gallery_case(solver: &str, extra: &str) -> String {
    let block = |name: &str, region: &str, o: [f64; 3], s: [f64; 3], d: [usize; 3]| {
        format!(
            "[[mesh.blocks]]\nname = \"{name}\"\nregion = \"{region}\"\norigin = {o:?}\nsize = {s:?}\ndivisions = {d:?}\n"
        )
    };
    let mut blocks = String::new();
    blocks += &block(
        "base",
        "rock",
        [0.0, 0.0, 0.0],
        [30.0, 10.0, 10.0],
        [6, 2, 2],
    );
    blocks += &block(
        "left",
        "rock",
        [0.0, 0.0, 10.0],
        [10.0, 10.0, 10.0],
        [2, 2, 2],
    );
    blocks += &block(
        "gallery",
        "gallery",
        [10.0, 0.0, 10.0],
        [10.0, 10.0, 10.0],
        [2, 2, 2],
    );
    blocks += &block(
        "right",
        "rock",
        [20.0, 0.0, 10.0],
        [10.0, 10.0, 10.0],
        [2, 2, 2],
    );
    blocks += &block(
        "top",
        "rock",
        [0.0, 0.0, 20.0],
        [30.0, 10.0, 10.0],
        [6, 2, 2],
    );
    format!(
        r#"[time]
end = 1e-3
[mesh]
{blocks}
[node_sets.all]
box = [[-1.0, -1.0, -1.0], [31.0, 11.0, 31.0]]
[node_sets.xsides]
box = [[-0.001, -1.0, -1.0], [0.001, 11.0, 31.0]]
[node_sets.xsides2]
box = [[29.999, -1.0, -1.0], [30.001, 11.0, 31.0]]
[node_sets.bottom]
box = [[-1.0, -1.0, -0.001], [31.0, 11.0, 0.001]]
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
name = "gallery"
material = "rock"
integration = "full"
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[static]
solver = "{solver}"
tolerance = 1e-11
{extra}
[[static.fixed]]
set = "all"
dofs = "y"
[[static.fixed]]
set = "xsides"
dofs = "x"
[[static.fixed]]
set = "xsides2"
dofs = "x"
[[static.fixed]]
set = "bottom"
dofs = "xyz"
[static.in_situ]
method = "gravity"
[[static.steps]]
name = "gallery"
excavate = ["gallery"]
substeps = 4
"#
    )
}

fn solve(text: &str) -> Result<(Model, StaticResult)> {
    let case = parse_case(text, "gallery.toml", std::path::Path::new("."))?;
    let plan = case.static_plan.expect("static stage");
    static_stage::run(case.model, &plan)
}

/// max |u_a − u_b| / max |u_a|.
fn difference(a: &StaticResult, b: &StaticResult) -> f64 {
    let scale = a.u.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    let d =
        a.u.iter()
            .zip(&b.u)
            .flat_map(|(x, y)| (0..3).map(move |k| (x[k] - y[k]).abs()))
            .fold(0.0f64, f64::max);
    d / scale
}

fn pd_column(solver: &str) -> String {
    format!(
        r#"[time]
end = 1e-3
[mesh]
[[mesh.blocks]]
name = "col"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, 4.0]
divisions = [1, 1, 4]
[materials.concrete]
model = "plastic_damage"
young = 31027e6
poisson = 0.2
density = 2400.0
[materials.concrete.plastic_damage]
ft0 = 2.9e6
fc0 = 13e6
fc = 24.1e6
gt = 200.0
gc = 1e4
[[regions]]
name = "col"
material = "concrete"
integration = "full"
[node_sets.corner]
nodes = [0]
[node_sets.edge]
nodes = [1]
[static]
solver = "{solver}"
tolerance = 1e-9
[[static.fixed]]
set = "col.zmin"
dofs = "z"
[[static.fixed]]
set = "corner"
dofs = "xy"
[[static.fixed]]
set = "edge"
dofs = "y"
[[static.loads]]
set = "col.zmax"
pressure = 20e6
[static.in_situ]
method = "none"
[[static.steps]]
name = "load"
"#
    )
}

/// Run the relaxation checks.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("Static stage: dynamic relaxation");
    let (_, direct) = solve(&gallery_case("direct", ""))?;
    let src = "the direct solve of the same model";
    for (name, extra) in [
        (
            "kinetic damping, mass scaling",
            "damping = \"kinetic\"\npredictor = false",
        ),
        (
            "viscous damping, mass scaling",
            "damping = \"viscous\"\npredictor = false",
        ),
        (
            "kinetic damping, physical masses",
            "damping = \"kinetic\"\nmass_scaling = false\npredictor = false",
        ),
        (
            "direct elastic predictor + kinetic",
            "damping = \"kinetic\"",
        ),
    ] {
        let (_, dr) = solve(&gallery_case("relaxation", extra))?;
        let iters: usize = dr.steps.iter().map(|s| s.iterations).sum();
        check.absolute(
            &format!("gallery, {name} ({iters} iterations): max |u_DR − u_direct| / max |u|"),
            0.0,
            difference(&direct, &dr),
            1e-6,
            src,
        );
    }
    // Plastic-damage column: the direct solve refuses, the relaxation converges.
    let refused = solve(&pd_column("direct")).err().map(|e| e.to_string());
    let named = refused
        .as_deref()
        .is_some_and(|m| m.contains("not linear") && m.contains("relaxation"));
    check.absolute(
        "plastic-damage column: the direct solve refuses the yielding step (1 = refused with the reason)",
        1.0,
        if named { 1.0 } else { 0.0 },
        0.0,
        "the direct solve is exact for linear steps only",
    );
    let (m, r) = solve(&pd_column("relaxation"))?;
    let mut err: f64 = 0.0;
    for e in 0..m.n_elements() {
        let (_, s) = m.element_strain_stress(e, &r.u);
        err = err.max((s[2] + 20e6).abs() / 20e6);
    }
    check.absolute(
        "plastic-damage column, relaxation: max |σ_zz + p| / p",
        0.0,
        err,
        1e-6,
        "statics: σ_zz = −p in a column with free sides",
    );
    let dc = m.groups[0]
        .element_damage_fields()
        .map_or(0.0, |d| d.iter().map(|x| x[2]).fold(0.0, f64::max));
    check.within(
        "plastic-damage column, relaxation: compressive damage D_c (hardening: 0 < D_c < 1)",
        1e-6,
        1.0,
        dc,
        "20 MPa lies between f_c0 = 13 MPa and f_c = 24.1 MPa",
    );
    Ok(check.finish())
}
