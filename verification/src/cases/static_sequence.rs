//! Static stage: excavation sequences, activation and the hand-over to the dynamic stage.
//!
//! 1. Path independence (linear elastic): excavating two sets in one step or in two steps
//!    ends in the same state (the release forces are the whole out-of-balance of the
//!    remaining body, so the end state is its unique equilibrium): ≤ 1e-8 of the largest
//!    displacement and stress.
//! 2. Activation: a 2 m concrete block placed on a 20 m rock column that has settled under
//!    its weight (lateral rollers). Placed weightless it stays stress-free although its
//!    base has moved (stress ≤ 1e-8 of the rock's); with its weight, its stress is its own
//!    weight only, σ_zz = −ρ_c g (h_c − z) (uniaxial column), and the rock settles by
//!    −(ρ_c g h_c / M_r) z more (`analytic::ConfinedColumn`). Both for a conforming mesh
//!    (shared nodes: the element reference displacement) and for a split mesh with a bonded
//!    contact interface (the pair's reference offset; direct solve with ties, and the
//!    dynamic relaxation with the DCFM pairs).
//! 3. Quiet transition (W14): after the static stage (gravity, a gallery excavated), the
//!    dynamic stage with zero input stays at rest — peak velocity ≤ 1e-6 m/s over 2 s — with
//!    the static supports kept, and with the base support freed in the dynamic stage (its
//!    static reactions handed over as loads).

use dcfm::case::parse_case;
use dcfm::model::Model;
use dcfm::stage::static_stage::{self, StaticResult};
use dcfm::Result;

use crate::analytic::ConfinedColumn;
use crate::record::{Check, CheckRow};

fn solve(text: &str, name: &str) -> Result<(Model, StaticResult)> {
    let case = parse_case(text, name, std::path::Path::new("."))?;
    let plan = case.static_plan.expect("static stage");
    static_stage::run(case.model, &plan)
}

fn sequence_case(steps: &str) -> String {
    format!(
        r#"[time]
end = 1e-3
[mesh]
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, 0.0]
size = [40.0, 10.0, 40.0]
divisions = [8, 2, 8]
[[mesh.blocks]]
name = "a"
region = "rock"
origin = [40.0, 0.0, 20.0]
size = [10.0, 10.0, 10.0]
divisions = [2, 2, 2]
[[mesh.blocks]]
name = "b"
region = "rock"
origin = [40.0, 0.0, 10.0]
size = [10.0, 10.0, 10.0]
divisions = [2, 2, 2]
[[mesh.blocks]]
name = "fill"
region = "rock"
origin = [40.0, 0.0, 0.0]
size = [10.0, 10.0, 10.0]
divisions = [2, 2, 2]
[[mesh.blocks]]
name = "cap"
region = "rock"
origin = [40.0, 0.0, 30.0]
size = [10.0, 10.0, 10.0]
divisions = [2, 2, 2]
[[mesh.blocks]]
name = "side"
region = "rock"
origin = [50.0, 0.0, 0.0]
size = [20.0, 10.0, 40.0]
divisions = [4, 2, 8]
[node_sets.all]
box = [[-1.0, -1.0, -1.0], [71.0, 11.0, 41.0]]
[node_sets.x0]
box = [[-0.001, -1.0, -1.0], [0.001, 11.0, 41.0]]
[node_sets.x1]
box = [[69.999, -1.0, -1.0], [70.001, 11.0, 41.0]]
[node_sets.bottom]
box = [[-1.0, -1.0, -0.001], [71.0, 11.0, 0.001]]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "rock"
material = "rock"
integration = "one_point"
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[static]
solver = "direct"
[[static.fixed]]
set = "all"
dofs = "y"
[[static.fixed]]
set = "x0"
dofs = "x"
[[static.fixed]]
set = "x1"
dofs = "x"
[[static.fixed]]
set = "bottom"
dofs = "xyz"
[static.in_situ]
method = "gravity"
{steps}"#
    )
}

fn activation_case(split: bool, solver: &str, concrete_density: f64) -> String {
    let (split_line, interface) = if split {
        (
            "split = [[\"rock\", \"concrete\"]]",
            "[[interfaces]]\nname = \"bond\"\nsurface_a = \"rock-concrete\"\nsurface_b = \"concrete-rock\"\nmu_s = 0.8\nmu_d = 0.6\ncohesion = 1e6\n",
        )
    } else {
        ("", "")
    };
    format!(
        r#"[time]
end = 1e-3
[mesh]
{split_line}
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, 0.0]
size = [2.0, 2.0, 20.0]
divisions = [1, 1, 10]
[[mesh.blocks]]
name = "concrete"
origin = [0.0, 0.0, 20.0]
size = [2.0, 2.0, 2.0]
divisions = [1, 1, 2]
[node_sets.all]
box = [[-1.0, -1.0, -1.0], [3.0, 3.0, 23.0]]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[materials.concrete]
model = "elastic"
young = 25e9
poisson = 0.2
density = {concrete_density}
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[[regions]]
name = "concrete"
material = "concrete"
integration = "full"
{interface}
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[static]
solver = "{solver}"
tolerance = 1e-10
predictor = false
[[static.fixed]]
set = "all"
dofs = "xy"
[[static.fixed]]
set = "rock.zmin"
dofs = "z"
[static.in_situ]
method = "gravity"
solver = "direct"
[[static.steps]]
name = "place the concrete"
activate = ["concrete"]
"#
    )
}

/// (max displacement difference, max stress difference) relative to the largest values,
/// over the active nodes and elements (a dormant node keeps the displacement it had when
/// its last element went, which depends on the sequence and means nothing).
fn state_difference(ma: &Model, a: &StaticResult, mb: &Model, b: &StaticResult) -> (f64, f64) {
    let mut active = vec![false; ma.mesh.n_nodes()];
    for g in &ma.groups {
        for c in &g.conn {
            for &n in c {
                active[n as usize] = true;
            }
        }
    }
    let (mut du, mut scale): (f64, f64) = (0.0, 0.0);
    for i in (0..active.len()).filter(|&i| active[i]) {
        for k in 0..3 {
            du = du.max((a.u[i][k] - b.u[i][k]).abs());
            scale = scale.max(a.u[i][k].abs());
        }
    }
    let (mut ds, mut smax): (f64, f64) = (0.0, 0.0);
    for e in 0..ma.n_elements() {
        if ma.element_location[e].0 == u32::MAX {
            continue;
        }
        let (_, sa) = ma.element_strain_stress(e, &a.u);
        let (_, sb) = mb.element_strain_stress(e, &b.u);
        for k in 0..6 {
            ds = ds.max((sa[k] - sb[k]).abs());
            smax = smax.max(sa[k].abs());
        }
    }
    (du / scale, ds / smax)
}

/// The activation checks of one variant.
fn activation(check: &mut Check, split: bool, solver: &str) -> Result<()> {
    let name = format!(
        "{} mesh, {solver}",
        if split {
            "split + bonded interface"
        } else {
            "conforming"
        }
    );
    let g = 9.81;
    // Weightless: stays stress-free.
    let (m, r) = solve(&activation_case(split, solver, 1e-9), "activation.toml")?;
    let concrete = m
        .groups
        .iter()
        .position(|g| g.name == "concrete")
        .expect("region");
    let mut smax: f64 = 0.0;
    for le in 0..m.groups[concrete].len() {
        let (_, s) = m.groups[concrete].strain_stress_of(le, &r.u);
        smax = smax.max(s.iter().fold(0.0, |a, v| a.max(v.abs())));
    }
    let rock_scale = 2700.0 * g * 20.0;
    check.absolute(
        &format!("{name}: weightless concrete placed on the settled rock: max |σ| / ρgH_rock"),
        0.0,
        smax / rock_scale,
        1e-8,
        "stress-free placement in the deformed configuration",
    );
    // With its weight.
    let rho_c = 2400.0;
    let (m, r) = solve(&activation_case(split, solver, rho_c), "activation.toml")?;
    let cc = ConfinedColumn::new(2.0, rho_c, g, 25e9, 0.2).expect("valid");
    let rock = ConfinedColumn::new(20.0, 2700.0, g, 20e9, 0.25).expect("valid");
    let mut es: f64 = 0.0;
    for (le, &e) in m.groups[concrete].elements.iter().enumerate() {
        let (_, s) = m.groups[concrete].strain_stress_of(le, &r.u);
        let zc = m
            .mesh
            .element_coords(e as usize)
            .iter()
            .map(|p| p[2])
            .sum::<f64>()
            / 8.0;
        es = es.max((s[2] - cc.stress(zc - 20.0)).abs() / (rho_c * g * 2.0));
    }
    let du = r.displacement_since_in_situ();
    let surcharge = rho_c * g * 2.0;
    let mut eu: f64 = 0.0;
    let scale = rock.surcharge_displacement(surcharge, 20.0).abs();
    for (i, x) in m.mesh.coords.iter().enumerate() {
        let in_rock = m
            .groups
            .iter()
            .any(|g| g.name == "rock" && g.conn.iter().any(|c| c.contains(&(i as u32))));
        if in_rock {
            eu = eu.max((du[i][2] - rock.surcharge_displacement(surcharge, x[2])).abs() / scale);
        }
    }
    let tol = if solver == "direct" { 1e-8 } else { 1e-5 };
    check
        .absolute(
            &format!("{name}: concrete σ_zz against its own weight, max error / ρ_c g h_c"),
            0.0,
            es,
            tol,
            "uniaxial column under its own weight",
        )
        .absolute(
            &format!("{name}: rock settlement under the concrete, max error / top value"),
            0.0,
            eu,
            tol,
            "uniaxial column under a surcharge ρ_c g h_c",
        );
    Ok(())
}

fn quiet_case(free_base: bool) -> String {
    let boundary = if free_base {
        "[[boundary.fixed]]\nset = \"all\"\ndofs = \"y\"\n[[boundary.fixed]]\nset = \"x0\"\ndofs = \"x\"\n[[boundary.fixed]]\nset = \"x1\"\ndofs = \"x\"\n[[boundary.fixed]]\nset = \"corner\"\ndofs = \"x\"\n"
    } else {
        "[[boundary.fixed]]\nset = \"all\"\ndofs = \"y\"\n[[boundary.fixed]]\nset = \"x0\"\ndofs = \"x\"\n[[boundary.fixed]]\nset = \"x1\"\ndofs = \"x\"\n[[boundary.fixed]]\nset = \"bottom\"\ndofs = \"xyz\"\n"
    };
    sequence_case("[[static.steps]]\nname = \"gallery\"\nexcavate = [\"a\"]\n")
        .replace(
            "[static]\n",
            &format!("[node_sets.corner]\nnodes = [0]\n{boundary}[static]\n"),
        )
        .replace("end = 1e-3", "end = 2.0")
}

/// Run the sequence, activation and hand-over checks.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("Static stage: sequences, activation, hand-over");
    let one = sequence_case("[[static.steps]]\nname = \"both\"\nexcavate = [\"a\", \"b\"]\n");
    let two = sequence_case(
        "[[static.steps]]\nname = \"upper\"\nexcavate = [\"a\"]\n[[static.steps]]\nname = \"lower\"\nexcavate = [\"b\"]\n",
    );
    let (ma, a) = solve(&one, "one.toml")?;
    let (mb, b) = solve(&two, "two.toml")?;
    let (du, ds) = state_difference(&ma, &a, &mb, &b);
    let src = "uniqueness of the linear elastic equilibrium";
    check
        .absolute(
            "excavation in one step vs two: max |Δu| / max |u|",
            0.0,
            du,
            1e-8,
            src,
        )
        .absolute(
            "excavation in one step vs two: max |Δσ| / max |σ|",
            0.0,
            ds,
            1e-8,
            src,
        );
    activation(&mut check, false, "direct")?;
    activation(&mut check, true, "direct")?;
    activation(&mut check, true, "relaxation")?;
    // Quiet transition.
    for free_base in [false, true] {
        let case = parse_case(
            &quiet_case(free_base),
            "quiet.toml",
            std::path::Path::new("."),
        )?;
        let plan = case.static_plan.as_ref().expect("static stage").clone();
        let (model, r) = static_stage::run(case.model, &plan)?;
        let mut sim = static_stage::start_dynamic(model, &r, case.dt, case.safety)?;
        let steps = (case.end / case.dt).ceil() as u64;
        let mut vmax: f64 = 0.0;
        for _ in 0..steps {
            sim.step()?;
            for v in &sim.v {
                vmax = vmax.max((v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt());
            }
        }
        check.absolute(
            &format!(
                "static → dynamic with zero input, {}: peak velocity over 2 s (m/s)",
                if free_base {
                    "base support freed (reactions as loads)"
                } else {
                    "static supports kept"
                }
            ),
            0.0,
            vmax,
            1e-6,
            "W14 quiet transition",
        );
    }
    Ok(check.finish())
}
