//! Tests of the static stage on small models with closed-form answers.

use super::*;
use crate::element::Integration;
use crate::load::{Gravity, TimeFunction};
use crate::material::{Elastic, Material};
use crate::mesh::BoxMeshSpec;
use crate::model::RegionSetup;

fn column(integration: Integration, nz: usize, h: f64) -> Model {
    let mesh = BoxMeshSpec::single("col", [0.0; 3], [1.0, 1.0, h], [1, 1, nz])
        .build("t")
        .unwrap();
    let el = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
    let setup = RegionSetup {
        region: "col".into(),
        material: Material::Elastic(el),
        integration,
        hourglass: 0.05,
    };
    let mut m = Model::new(mesh, &[setup], "t").unwrap();
    m.gravity = Some(Gravity {
        acceleration: [0.0, 0.0, -9.81],
        history: TimeFunction::Constant { value: 1.0 },
    });
    m
}

fn column_plan(m: &Model, solver: StepSolver) -> StaticPlan {
    let mut c = Constraints::new(m.mesh.n_nodes());
    let all: Vec<u32> = (0..m.mesh.n_nodes() as u32).collect();
    c.fix(&all, 0b011);
    c.fix(&m.mesh.node_sets["col.zmin"], 0b100);
    let mut plan = StaticPlan::new(c);
    plan.in_situ = InSitu::Gravity {
        solver,
        convergence: Convergence {
            tolerance: 1e-10,
            max_iterations: 200_000,
        },
    };
    plan
}

/// Uniaxial strain under self weight: σ_zz = −ρ g (H − z), u_z = −(ρ g / M)(H z − z²/2),
/// M = λ + 2μ; nodal values exact for linear elements with the lumped (= consistent) load.
#[test]
fn gravity_column_direct_matches_closed_form() {
    for integ in [Integration::Full, Integration::OnePoint] {
        let h = 100.0;
        let m = column(integ, 20, h);
        let plan = column_plan(&m, StepSolver::Direct);
        let (m, r) = run(m, &plan).unwrap();
        let el = *m.groups[0].material.elastic();
        let rg = 2700.0 * 9.81;
        let mut worst: f64 = 0.0;
        let top = rg / el.p_modulus() * h * h / 2.0;
        for (i, x) in m.mesh.coords.iter().enumerate() {
            let z = x[2];
            let exact = -(rg / el.p_modulus()) * (h * z - z * z / 2.0);
            worst = worst.max((r.u[i][2] - exact).abs() / top);
        }
        assert!(worst < 1e-9, "{integ:?}: {worst:e}");
        for e in 0..m.n_elements() {
            let (_, s) = m.element_strain_stress(e, &r.u);
            let zc = m.mesh.element_coords(e).iter().map(|p| p[2]).sum::<f64>() / 8.0;
            let exact = -rg * (h - zc);
            assert!(
                (s[2] - exact).abs() < 1e-8 * rg * h,
                "{integ:?} {e}: {} vs {exact}",
                s[2]
            );
        }
        assert!(r.out_of_balance.ratio < 1e-12);
    }
}

#[test]
fn relaxation_matches_direct_on_the_column() {
    let h = 50.0;
    let m = column(Integration::Full, 10, h);
    let plan = column_plan(&m, StepSolver::Direct);
    let (_, direct) = run(m, &plan).unwrap();
    let m = column(Integration::Full, 10, h);
    let mut plan = column_plan(&m, StepSolver::Relaxation);
    plan.relaxation.predictor = false;
    let (_, relaxed) = run(m, &plan).unwrap();
    let umax = direct.u.iter().map(|u| u[2].abs()).fold(0.0, f64::max);
    let err = direct
        .u
        .iter()
        .zip(&relaxed.u)
        .map(|(a, b)| (a[2] - b[2]).abs())
        .fold(0.0, f64::max);
    assert!(
        err <= 1e-6 * umax,
        "{err:e} of {umax:e}; {} iterations",
        relaxed.steps[0].iterations
    );
}
