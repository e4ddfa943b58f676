//! W14 — free-field boundaries: a laterally uniform model reproduces its own 1D column
//! everywhere, corners included, under all three components at once; a deep model
//! truncated below the ground surface, its free field continued up through the
//! overburden, matches the full-height model.
//!
//! ```text
//!  (a) z = 30 ┌────────────┐ free surface          (b) full        truncated
//!             │ soil 30 m  │ 1 m elements            ┌──────┐ 30    · · · · overburden
//!      z = 0  ├────────────┤                         │ soil │        · · · · (column
//!             │ rock 30 m  │ 3 m elements            ├──────┤ 0      · · · ·  and walls)
//!    z = −30  └────────────┘ viscous-spring base     │ rock │  −20 ┌──────┐ ← top coupled
//!     12 × 8 m in plan, free-field walls, x/y/z input  │      │      │ rock │   to the free field
//!                                                     └──────┘ −60  └──────┘
//! ```
//!
//! (c) Quiet transition: a 40 m rock cube settles under gravity in the static stage
//! (rollers on the sides, base fixed; a 8 m cavern excavated in the second variant), then
//! the dynamic stage starts with a viscous-spring base, free-field sides and zero input:
//! the static reactions load the boundaries and the springs are measured from the static
//! state, so nothing moves (≤ 1e-6 m/s over 2 s, VERIFICATION W14).
//!
//! Input: incident half-sine velocity pulses, x 0.01 m/s over 0.02 s (SV), y 0.006 m/s
//! over 0.03 s (SH), z 0.008 m/s over 0.015 s (P). Reference: the model's own reference
//! free-field column (a), the full-height model (b). Tolerance (docs/verification_references.md §W14):
//! every node within 2 % of the column at its depth (max |Δv| over time / max |v| of the
//! column), and the truncated model within 2 % of the full one at −30 m and −50 m.

use dcfm::case::parse_case;
use dcfm::stage::Simulation;
use dcfm::Result;

use crate::record::{Check, CheckRow};

/// Title of the case (the `case` of its rows).
pub const TITLE: &str = "W14 free-field boundaries";

const SOURCE: &str = "docs/verification_references.md §W14";

const MATERIALS: &str = r#"
[materials.rock]
model = "elastic"
young = 1.40625e10
poisson = 0.25
density = 2500.0
[materials.soil]
model = "elastic"
young = 4.68e8
poisson = 0.3
density = 2000.0
"#;

const INPUT: &str = r#"
[seismic]
quantity = "velocity"
definition = "incident"
x = { type = "half_sine", amplitude = 0.01, period = 0.02 }
y = { type = "half_sine", amplitude = 0.006, period = 0.03 }
z = { type = "half_sine", amplitude = 0.008, period = 0.015 }
"#;

/// (a): the largest |v_node − v_column(z)| over all nodes, components and time, relative
/// to the column's largest |v|, and the number of nodes compared.
fn uniform_model() -> Result<(f64, usize)> {
    let text = format!(
        r#"
[time]
end = 0.6
[mesh]
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, -30.0]
size = [12.0, 8.0, 30.0]
divisions = [4, 2, 10]
[[mesh.blocks]]
name = "soil"
origin = [0.0, 0.0, 0.0]
size = [12.0, 8.0, 30.0]
divisions = [4, 2, 30]
{MATERIALS}
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[[regions]]
name = "soil"
material = "soil"
integration = "full"
[[boundary.absorbing]]
set = "rock.zmin"
kind = "viscous_spring"
input = true
[boundary.free_field]
sides = [["rock.xmin", "soil.xmin"], ["rock.xmax", "soil.xmax"], ["rock.ymin", "soil.ymin"], ["rock.ymax", "soil.ymax"]]
{INPUT}
"#
    );
    let case = parse_case(&text, "w14a", std::path::Path::new("."))?;
    let mut sim = Simulation::new(case.model, case.dt, case.safety)?;
    let n = sim.model.mesh.n_nodes();
    let mut level = vec![0usize; n];
    {
        sim.step()?;
        let col = sim
            .model
            .boundaries
            .as_ref()
            .and_then(|b| b.reference_column())
            .expect("reference column");
        for (i, x) in sim.model.mesh.coords.iter().enumerate() {
            level[i] = col
                .level_at(x[2], 1e-6)
                .expect("every node at a column level");
        }
    }
    let (mut worst, mut peak) = (0.0f64, 0.0f64);
    let mut v_old = sim.v.clone();
    while sim.time < 0.6 {
        v_old.copy_from_slice(&sim.v);
        sim.step()?;
        let col = sim
            .model
            .boundaries
            .as_ref()
            .and_then(|b| b.reference_column())
            .expect("reference column");
        for i in 0..n {
            let vc = col.velocity(level[i]);
            for d in 0..3 {
                let vn = 0.5 * (v_old[i][d] + sim.v[i][d]);
                worst = worst.max((vn - vc[d]).abs());
                peak = peak.max(vc[d].abs());
            }
        }
    }
    Ok((worst / peak, n))
}

/// (b): velocity histories (all components) at z = −30 m and −50 m on the model's axis
/// (x = 6, y = 4), full or truncated.
fn deep_model(truncated: bool) -> Result<[Vec<[f64; 3]>; 2]> {
    let (blocks, top) = if truncated {
        (
            r#"
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, -60.0]
size = [12.0, 8.0, 40.0]
divisions = [4, 2, 20]
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[boundary.free_field]
sides = ["rock.xmin", "rock.xmax", "rock.ymin", "rock.ymax"]
top = "rock.zmax"
"#,
            r#"
[[seismic.overburden]]
thickness = 20.0
material = "rock"
divisions = 10
[[seismic.overburden]]
thickness = 30.0
material = "soil"
divisions = 30
"#,
        )
    } else {
        (
            r#"
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, -60.0]
size = [12.0, 8.0, 60.0]
divisions = [4, 2, 30]
[[mesh.blocks]]
name = "soil"
origin = [0.0, 0.0, 0.0]
size = [12.0, 8.0, 30.0]
divisions = [4, 2, 30]
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[[regions]]
name = "soil"
material = "soil"
integration = "full"
[boundary.free_field]
sides = [["rock.xmin", "soil.xmin"], ["rock.xmax", "soil.xmax"], ["rock.ymin", "soil.ymin"], ["rock.ymax", "soil.ymax"]]
"#,
            "",
        )
    };
    let text = format!(
        r#"
[time]
end = 0.7
[mesh]
{blocks}
{MATERIALS}
[node_sets.p30]
box = [[5.99, 3.99, -30.01], [6.01, 4.01, -29.99]]
[node_sets.p50]
box = [[5.99, 3.99, -50.01], [6.01, 4.01, -49.99]]
[[boundary.absorbing]]
set = "rock.zmin"
kind = "viscous_spring"
input = true
{INPUT}
{top}
"#
    );
    let case = parse_case(&text, "w14b", std::path::Path::new("."))?;
    // The same Δt for both models (the truncated one has no stiffer element).
    let mut sim = Simulation::new(case.model, 4.0e-4, case.safety)?;
    let probes = [
        sim.model.mesh.node_sets["p30"][0] as usize,
        sim.model.mesh.node_sets["p50"][0] as usize,
    ];
    let mut out: [Vec<[f64; 3]>; 2] = Default::default();
    while sim.time < 0.7 {
        let old = probes.map(|p| sim.v[p]);
        sim.step()?;
        for k in 0..2 {
            let p = probes[k];
            out[k].push(std::array::from_fn(|d| 0.5 * (old[k][d] + sim.v[p][d])));
        }
    }
    Ok(out)
}

/// (c): peak nodal velocity over 2 s of the dynamic stage after the static stage, with
/// zero input, with or without a cavern excavated in the static stage.
fn quiet_transition(cavern: bool) -> Result<f64> {
    let (blocks, regions, steps) = if cavern {
        (
            r#"
[[mesh.blocks]]
name = "below"
region = "rock"
origin = [0.0, 0.0, 0.0]
size = [40.0, 40.0, 16.0]
divisions = [5, 5, 2]
[[mesh.blocks]]
name = "above"
region = "rock"
origin = [0.0, 0.0, 24.0]
size = [40.0, 40.0, 16.0]
divisions = [5, 5, 2]
[[mesh.blocks]]
name = "west"
region = "rock"
origin = [0.0, 0.0, 16.0]
size = [16.0, 40.0, 8.0]
divisions = [2, 5, 1]
[[mesh.blocks]]
name = "east"
region = "rock"
origin = [24.0, 0.0, 16.0]
size = [16.0, 40.0, 8.0]
divisions = [2, 5, 1]
[[mesh.blocks]]
name = "south"
region = "rock"
origin = [16.0, 0.0, 16.0]
size = [8.0, 16.0, 8.0]
divisions = [1, 2, 1]
[[mesh.blocks]]
name = "north"
region = "rock"
origin = [16.0, 24.0, 16.0]
size = [8.0, 16.0, 8.0]
divisions = [1, 2, 1]
[[mesh.blocks]]
name = "cavern"
origin = [16.0, 16.0, 16.0]
size = [8.0, 8.0, 8.0]
divisions = [1, 1, 1]
"#,
            r#"
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[[regions]]
name = "cavern"
material = "rock"
integration = "full"
"#,
            r#"
[[static.steps]]
name = "cavern"
excavate = ["cavern"]
"#,
        )
    } else {
        (
            r#"
[[mesh.blocks]]
name = "cube"
region = "rock"
origin = [0.0, 0.0, 0.0]
size = [40.0, 40.0, 40.0]
divisions = [5, 5, 5]
"#,
            r#"
[[regions]]
name = "rock"
material = "rock"
integration = "full"
"#,
            "",
        )
    };
    let text = format!(
        r#"
[time]
end = 2.0
[mesh]
{blocks}
{MATERIALS}
{regions}
[node_sets.base]
box = [[-1.0, -1.0, -0.001], [41.0, 41.0, 0.001]]
[node_sets.x_sides]
box = [[-0.001, -1.0, 0.001], [0.001, 41.0, 41.0]]
[node_sets.x_far]
box = [[39.999, -1.0, 0.001], [40.001, 41.0, 41.0]]
[node_sets.y_sides]
box = [[-1.0, -0.001, 0.001], [41.0, 0.001, 41.0]]
[node_sets.y_far]
box = [[-1.0, 39.999, 0.001], [41.0, 40.001, 41.0]]
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[[boundary.absorbing]]
set = "outer.zmin"
kind = "viscous_spring"
input = true
[boundary.free_field]
sides = ["outer.xmin", "outer.xmax", "outer.ymin", "outer.ymax"]
[seismic]
quantity = "velocity"
definition = "incident"
x = {{ type = "constant", value = 0.0 }}
profile_at = [0.0, 0.0]
[static]
solver = "direct"
[[static.fixed]]
set = "base"
dofs = "xyz"
[[static.fixed]]
set = "x_sides"
dofs = "x"
[[static.fixed]]
set = "x_far"
dofs = "x"
[[static.fixed]]
set = "y_sides"
dofs = "y"
[[static.fixed]]
set = "y_far"
dofs = "y"
[static.in_situ]
method = "gravity"
{steps}
"#
    );
    let case = parse_case(&text, "w14c", std::path::Path::new("."))?;
    let plan = case.static_plan.clone().expect("a static stage");
    let (model, result) = dcfm::stage::static_stage::run(case.model, &plan)?;
    let mut sim = dcfm::stage::static_stage::start_dynamic(model, &result, case.dt, case.safety)?;
    let mut peak = 0.0f64;
    while sim.time < 2.0 {
        sim.step()?;
        for v in &sim.v {
            peak = peak.max(v[0].abs().max(v[1].abs()).max(v[2].abs()));
        }
    }
    Ok(peak)
}

/// Run W14.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new(TITLE);
    let (worst, n) = uniform_model()?;
    check.within(
        &format!("laterally uniform model: max |v − v_column| / max |v_column| over all {n} nodes, x/y/z"),
        0.0,
        0.02,
        worst,
        SOURCE,
    );
    let full = deep_model(false)?;
    let truncated = deep_model(true)?;
    for (k, depth) in ["−30 m", "−50 m"].iter().enumerate() {
        let peak = full[k].iter().flatten().fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = full[k]
            .iter()
            .zip(&truncated[k])
            .flat_map(|(a, b)| (0..3).map(move |d| (a[d] - b[d]).abs()))
            .fold(0.0f64, f64::max);
        check.within(
            &format!("model truncated at −20 m vs full height: max |Δv| / max |v| at {depth}"),
            0.0,
            0.02,
            diff / peak,
            SOURCE,
        );
    }
    for (cavern, name) in [(false, "without"), (true, "with")] {
        check.within(
            &format!("static → dynamic, zero input, {name} a cavern: peak velocity over 2 s (m/s)"),
            0.0,
            1e-6,
            quiet_transition(cavern)?,
            SOURCE,
        );
    }
    Ok(check.finish())
}
