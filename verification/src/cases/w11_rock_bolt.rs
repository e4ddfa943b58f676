//! W11 — rock bolt: an anchor bar superposed on its host elements (paper §3, ref. [39]).
//!
//! ```text
//!   z = 6 ┌───┐  ← u_z = ε·6 (uniaxial stress field imposed exactly)
//!         │ │ │  rock prism 1.5 × 1.5 × 6 m, E = 20 GPa, ν = 0.25, 3 × 3 × 12 hex8
//!         │ │ │  φ28 bar on the axis, A = 6.1575 cm², E = 200 GPa, f_y = 400 MPa
//!   z = 0 └───┘
//! ```
//!
//! (a) Perfect bond: reaction / imposed shortening = composite stiffness (E_r A_r + E_b A_b)/L
//!     = 7518.5 MN/m with A_r the prism less the bar (the bar is superposed on a full
//!     prism here: 7520.5 MN/m, 0.027 % above), bar EA/L = 20.525 MN/m, bar share 0.273 %.
//!     The reaction comes from the solver's internal-force pass on the exact field.
//! (b) Yield: at ε = 1 % the bar carries f_y A = 246.30 kN.
//! (c) Pull-out of a bond–slip bar (k_s = 2e8 N/m per m, 0.1 m segments) from a fixed host
//!     under P = 100 kN at the head, run to rest by the explicit solver with mass damping:
//!     head stiffness EA λ tanh(λL) = 156.94 MN/m, λ = √(k_s/EA) = 1.2744 /m, and
//!     N(x) = P sinh(λ(L − x))/sinh(λL) at x = 0.5, 1, 2 m.
//! (d) Critical step of a bar of 0.5 m segments alone: l/c = 0.5/√(E/ρ) = 99.06 µs; the
//!     model's step with the bar is below both the bar's and the host's.
//!
//! Reference: docs/verification_references.md §W11. Tolerance ±1 % (N(x) within 1 % of P).

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::Simulation;
use dcfm::Result;

use crate::record::{Check, CheckRow};

const SOURCE: &str = "docs/verification_references.md §W11";
const E_BAR: f64 = 200e9;
const DIAMETER: f64 = 0.028;
const LENGTH: f64 = 6.0;

fn area() -> f64 {
    0.25 * std::f64::consts::PI * DIAMETER * DIAMETER
}

/// The prism case with an optional `[anchors]` text.
fn prism_case(anchors: &str, extra: &str) -> String {
    format!(
        r#"
[time]
end = 1.0
[mesh]
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, 0.0]
size = [1.5, 1.5, 6.0]
divisions = [3, 3, 12]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "rock"
material = "rock"
{extra}
{anchors}
"#
    )
}

fn bar(extra: &str) -> String {
    format!(
        "[[anchors.bars]]\nname = \"bolt\"\nstart = [0.75, 0.75, 0.0]\nend = [0.75, 0.75, 6.0]\ndiameter = {DIAMETER}\nyoung = {E_BAR}\nyield_stress = 400e6\n{extra}\n"
    )
}

/// Reaction at the top for the exact uniaxial-stress field of strain `eps` (z).
fn top_reaction(case_text: &str, eps: f64) -> Result<(f64, Option<f64>)> {
    let case = parse_case(case_text, "w11.toml", Path::new("."))?;
    let mut sim = Simulation::new_unchecked(case.model, case.dt);
    for (u, x) in sim.u.iter_mut().zip(&sim.model.mesh.coords) {
        *u = [
            -0.25 * eps * (x[0] - 0.75),
            -0.25 * eps * (x[1] - 0.75),
            eps * x[2],
        ];
    }
    sim.internal_forces();
    let f = sim.internal_force();
    let top: f64 = sim
        .model
        .mesh
        .coords
        .iter()
        .zip(f)
        .filter(|(x, _)| (x[2] - LENGTH).abs() < 1e-9)
        .map(|(_, f)| f[2])
        .sum();
    let bar_force = sim
        .model
        .anchors
        .as_ref()
        .map(|a| a.force.iter().copied().fold(0.0, f64::max));
    Ok((top, bar_force))
}

/// Run W11.
pub fn run() -> Result<Vec<CheckRow>> {
    let mut check = Check::new("W11 rock bolt");
    // (a) Composite stiffness.
    let eps = 1e-5;
    let delta = eps * LENGTH;
    let (with_bar, bar_force) = top_reaction(&prism_case(&bar(""), ""), eps)?;
    let (rock_only, _) = top_reaction(&prism_case("", ""), eps)?;
    check.relative(
        "composite stiffness (MN/m), perfect bond",
        7518.5,
        with_bar / delta / 1e6,
        0.01,
        SOURCE,
    );
    check.relative(
        "bar EA/L (MN/m): reaction with the bar less without",
        20.525,
        (with_bar - rock_only) / delta / 1e6,
        0.01,
        SOURCE,
    );
    check.relative(
        "bar share of the load (%)",
        0.273,
        100.0 * bar_force.unwrap_or(0.0) / with_bar,
        0.01,
        SOURCE,
    );
    // (b) Yield.
    let (yielded, force) = top_reaction(&prism_case(&bar(""), ""), 0.01)?;
    let (rock_yield, _) = top_reaction(&prism_case("", ""), 0.01)?;
    let fy_a = 400e6 * area();
    check.relative(
        "yielded bar force at ε = 1 % (kN) = f_y A",
        fy_a / 1e3,
        force.unwrap_or(0.0) / 1e3,
        0.01,
        SOURCE,
    );
    check.relative(
        "yielded bar: reaction with the bar less without (kN)",
        fy_a / 1e3,
        (yielded - rock_yield) / 1e3,
        0.01,
        SOURCE,
    );
    // (c) Pull-out with bond slip.
    let ks = 2e8;
    let ea = E_BAR * area();
    let lambda = (ks / ea).sqrt();
    check.relative("λ = √(k_s/EA) (1/m)", 1.2744, lambda, 0.01, SOURCE);
    let text = prism_case(
        &bar(&format!("bond_stiffness = {ks}\nsegment_length = 0.1")),
        "[[boundary.fixed]]\nset = \"rock\"\ndofs = \"xyz\"\n[damping]\nalpha = 8000.0",
    );
    let case = parse_case(&text, "w11_pullout.toml", Path::new("."))?;
    let mut sim = Simulation::new(case.model, case.dt, case.safety)?;
    let p = 100e3;
    {
        let b = &mut sim.model.anchors.as_mut().expect("anchors").bond_slip[0];
        b.head_load = p;
        b.plate = false;
    }
    sim.run_steps(4000)?;
    let anchors = sim.model.anchors.as_ref().expect("anchors");
    let b = &anchors.bond_slip[0];
    check.relative(
        "pull-out head stiffness P/|w(0)| (MN/m)",
        156.94,
        p / b.w[0].abs() / 1e6,
        0.01,
        SOURCE,
    );
    let first = anchors.segments.len();
    for x in [0.5, 1.0, 2.0] {
        // The segment whose middle is nearest x, compared at its middle.
        let mut s0 = 0.0;
        let mut best = (f64::INFINITY, 0.0, 0.0);
        for (s, l) in b.lengths.iter().enumerate() {
            let mid = s0 + 0.5 * l;
            if (mid - x).abs() < best.0 - 1e-12 {
                best = ((mid - x).abs(), mid, anchors.force[first + s]);
            }
            s0 += l;
        }
        let xm = best.1;
        let exact = p * (lambda * (LENGTH - xm)).sinh() / (lambda * LENGTH).sinh();
        check.absolute(
            &format!("pull-out N({xm:.2} m)/P against sinh(λ(L−x))/sinh(λL)"),
            exact / p,
            best.2 / p,
            0.01,
            SOURCE,
        );
    }
    // (d) Critical step of 0.5 m segments.
    let text = prism_case(&bar("bond_stiffness = 1.0\nsegment_length = 0.5"), "");
    let case = parse_case(&text, "w11_step.toml", Path::new("."))?;
    let a = case.model.anchors.as_ref().expect("anchors");
    let dt_bar = 2.0
        / a.omega_squared_bound(&case.model.mesh, &case.model.mass)
            .sqrt();
    let c = (E_BAR / 7850.0f64).sqrt();
    check.relative(
        "critical step of 0.5 m bar segments (µs) = l/c",
        0.5 / c * 1e6,
        dt_bar * 1e6,
        0.01,
        SOURCE,
    );
    let host_only = parse_case(&prism_case("", ""), "w11_host.toml", Path::new("."))?;
    check.within(
        "model critical step with the bar ≤ min(bar, host) (1 = yes)",
        0.5,
        1.5,
        f64::from(u8::from(
            case.model.stable.critical <= dt_bar.min(host_only.model.stable.critical),
        )),
        SOURCE,
    );
    Ok(check.finish())
}
