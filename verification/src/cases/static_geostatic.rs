//! Static stage, in-situ stress: a laterally confined column under its own weight (and a
//! surcharge), and a given K0 field in a laterally fixed box, both through case files.
//!
//! Goal: (a) the gravity in-situ step gives σ_zz = −ρ g (H − z) and the uniaxial-strain
//! settlement u_z = −(ρg/M)(Hz − z²/2) (+ −(s/M) z under a surcharge s), for both
//! integrations, by the direct solve and by dynamic relaxation; (b) a K0 field set as
//! initial stress and equilibrated keeps σ_h/σ_v = K0 and σ_v = ρ g (H − z), and its
//! initial out-of-balance with the lumped gravity loads is reported (zero to round-off on
//! this mesh: the centroid stresses of a uniform column balance the lumped weights
//! exactly).
//!
//! ```text
//!   (a) 1 × 1 × 100 m, 20 elements       (b) 20 × 20 × 40 m, 4 × 4 × 8 elements,
//!       u_x = u_y = 0 everywhere             rollers on the four sides, base fixed,
//!       base fixed, top free (+ p)           K0 = (0.5, 0.7) from the top down
//! ```
//!
//! Reference: `analytic::ConfinedColumn` (equilibrium and uniaxial strain, exact at the
//! nodes of linear elements with the lumped = consistent weight; the element-centroid
//! stress is the exact value at the centroid). Tolerances: direct 1e-9 (round-off of a
//! sparse solve), relaxation 1e-6 of the top settlement (its out-of-balance tolerance is
//! 1e-10), K0 ratios ±1e-6 (issue #7).

use dcfm::case::parse_case;
use dcfm::model::Model;
use dcfm::stage::static_stage::{self, StaticResult};
use dcfm::Result;

use crate::analytic::ConfinedColumn;
use crate::record::{Check, CheckRow};

const SOURCE: &str = "uniaxial-strain column under self weight (equilibrium + Hooke)";
const H: f64 = 100.0;
const RHO: f64 = 2700.0;
const G: f64 = 9.81;

fn column_case(integration: &str, solver: &str, surcharge: f64) -> String {
    let load = if surcharge > 0.0 {
        format!("[[static.loads]]\nset = \"col.zmax\"\npressure = {surcharge}\n")
    } else {
        String::new()
    };
    format!(
        r#"[time]
end = 1e-3
[mesh]
[[mesh.blocks]]
name = "col"
origin = [0.0, 0.0, 0.0]
size = [1.0, 1.0, {H}]
divisions = [1, 1, 20]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = {RHO}
[[regions]]
name = "col"
material = "rock"
integration = "{integration}"
[loads.gravity]
acceleration = [0.0, 0.0, -{G}]
[static]
solver = "{solver}"
tolerance = 1e-10
predictor = false
{load}[[static.fixed]]
set = "col"
dofs = "xy"
[[static.fixed]]
set = "col.zmin"
dofs = "z"
[static.in_situ]
method = "gravity"
"#
    )
}

fn solve(text: &str, name: &str) -> Result<(Model, StaticResult)> {
    let case = parse_case(text, name, std::path::Path::new("."))?;
    let plan = case.static_plan.expect("static stage");
    static_stage::run(case.model, &plan)
}

/// Largest nodal settlement error / top settlement and largest centroid-stress error /
/// ρgH of a solved column.
fn column_errors(model: &Model, r: &StaticResult, surcharge: f64) -> (f64, f64) {
    let c = ConfinedColumn::new(H, RHO, G, 20e9, 0.25).expect("valid");
    let top = c.displacement(H).abs();
    let mut du: f64 = 0.0;
    for (i, x) in model.mesh.coords.iter().enumerate() {
        let exact = c.displacement(x[2]) + c.surcharge_displacement(surcharge, x[2]);
        du = du.max((r.u[i][2] - exact).abs() / top);
    }
    let mut ds: f64 = 0.0;
    for e in 0..model.n_elements() {
        let (_, s) = model.element_strain_stress(e, &r.u);
        let zc = model
            .mesh
            .element_coords(e)
            .iter()
            .map(|p| p[2])
            .sum::<f64>()
            / 8.0;
        ds = ds.max((s[2] - (c.stress(zc) - surcharge)).abs() / (RHO * G * H));
    }
    (du, ds)
}

fn k0_case(integration: &str, in_situ: &str) -> String {
    format!(
        r#"[time]
end = 1e-3
[mesh]
[[mesh.blocks]]
name = "box"
origin = [0.0, 0.0, -40.0]
size = [20.0, 20.0, 40.0]
divisions = [4, 4, 8]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = {RHO}
[[regions]]
name = "box"
material = "rock"
integration = "{integration}"
[loads.gravity]
acceleration = [0.0, 0.0, -{G}]
[static]
solver = "direct"
[[static.fixed]]
set = "box.xmin"
dofs = "x"
[[static.fixed]]
set = "box.xmax"
dofs = "x"
[[static.fixed]]
set = "box.ymin"
dofs = "y"
[[static.fixed]]
set = "box.ymax"
dofs = "y"
[[static.fixed]]
set = "box.zmin"
dofs = "xyz"
[static.in_situ]
{in_situ}
"#
    )
}

/// Run the geostatic checks.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("Static stage: geostatic states");
    for integ in ["full", "one_point"] {
        let (m, r) = solve(&column_case(integ, "direct", 0.0), "column.toml")?;
        let (du, ds) = column_errors(&m, &r, 0.0);
        check
            .absolute(
                &format!("gravity column, {integ}, direct: max |u_z − exact| / top settlement"),
                0.0,
                du,
                1e-9,
                SOURCE,
            )
            .absolute(
                &format!("gravity column, {integ}, direct: max |σ_zz − exact| / ρgH"),
                0.0,
                ds,
                1e-9,
                SOURCE,
            );
        let (m, r) = solve(&column_case(integ, "direct", 2e6), "column.toml")?;
        let (du, ds) = column_errors(&m, &r, 2e6);
        check
            .absolute(
                &format!("column + 2 MPa surcharge, {integ}: max |u_z − exact| / top settlement"),
                0.0,
                du,
                1e-9,
                SOURCE,
            )
            .absolute(
                &format!("column + 2 MPa surcharge, {integ}: max |σ_zz − exact| / ρgH"),
                0.0,
                ds,
                1e-9,
                SOURCE,
            );
    }
    let (m, r) = solve(&column_case("full", "relaxation", 0.0), "column.toml")?;
    let (du, ds) = column_errors(&m, &r, 0.0);
    check
        .absolute(
            "gravity column, full, relaxation: max |u_z − exact| / top settlement",
            0.0,
            du,
            1e-6,
            SOURCE,
        )
        .absolute(
            "gravity column, full, relaxation: max |σ_zz − exact| / ρgH",
            0.0,
            ds,
            1e-6,
            SOURCE,
        );
    // K0 field, given by layers (γ = ρg of the material) and by a table.
    let layered = "method = \"k0\"\nground_surface = 0.0\nk0 = [0.5, 0.7]";
    let gamma = RHO * G;
    let table = format!(
        "method = \"table\"\ntable = [[0.0, 0.0, 0.5, 0.7], [-40.0, {}, 0.5, 0.7]]",
        gamma * 40.0
    );
    for (integ, how, text) in [
        ("full", "k0", layered.to_string()),
        ("one_point", "k0", layered.to_string()),
        ("full", "table", table),
    ] {
        let (m, r) = solve(&k0_case(integ, &text), "k0.toml")?;
        let (mut ex, mut ey, mut ez): (f64, f64, f64) = (0.0, 0.0, 0.0);
        for e in 0..m.n_elements() {
            let (_, s) = m.element_strain_stress(e, &r.u);
            let zc = m.mesh.element_coords(e).iter().map(|p| p[2]).sum::<f64>() / 8.0;
            ex = ex.max((s[0] / s[2] - 0.5).abs());
            ey = ey.max((s[1] / s[2] - 0.7).abs());
            ez = ez.max((s[2] + gamma * (-zc)).abs() / (gamma * 40.0));
        }
        let src = "the given field (equilibrated)";
        check
            .absolute(
                &format!("K0 box, {integ}, {how}: max |σ_xx/σ_zz − 0.5|"),
                0.0,
                ex,
                1e-6,
                src,
            )
            .absolute(
                &format!("K0 box, {integ}, {how}: max |σ_yy/σ_zz − 0.7|"),
                0.0,
                ey,
                1e-6,
                src,
            )
            .absolute(
                &format!("K0 box, {integ}, {how}: max |σ_zz + ρg(−z)| / ρgH"),
                0.0,
                ez,
                1e-6,
                src,
            )
            .absolute(
                &format!("K0 box, {integ}, {how}: initial out-of-balance ratio of the field"),
                0.0,
                r.initial_field_out_of_balance.map_or(f64::NAN, |o| o.ratio),
                1e-9,
                "centroid stresses of a uniform column balance the lumped weights",
            );
    }
    Ok(check.finish())
}
