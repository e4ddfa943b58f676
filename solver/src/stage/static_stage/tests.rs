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

/// Exploration: Kirsch (VERIFICATION.md W4) through the stage, printed.
#[test]
#[ignore]
fn kirsch_explore() {
    use crate::mesh::generators::PlateWithHoleSpec;
    for k0 in [0.5, 1.0, 1.5] {
        for (integ, around, radial, grading, b) in [
            (Integration::Full, 128, 80, 10.0, 200.0),
            (Integration::Full, 128, 100, 30.0, 400.0),
            (Integration::Full, 128, 120, 60.0, 800.0),
            (Integration::Full, 256, 160, 30.0, 400.0),
        ] {
            let (a, p) = (10.0, 10e6);
            let mut spec = PlateWithHoleSpec::new(a, b, 1.0, radial);
            spec.axis = "y".into();
            spec.divisions_around = around;
            spec.grading = grading;
            let mesh = spec.build("k").unwrap();
            let el = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
            let setups: Vec<RegionSetup> = ["hole", "plate"]
                .iter()
                .map(|r| RegionSetup {
                    region: r.to_string(),
                    material: Material::Elastic(el),
                    integration: integ,
                    hourglass: 0.05,
                })
                .collect();
            let m = Model::new(mesh, &setups, "k").unwrap();
            let n = m.mesh.n_nodes();
            let mut c = Constraints::new(n);
            let all: Vec<u32> = (0..n as u32).collect();
            c.fix(&all, 0b010);
            for (x, z, mask) in [(0.0, b, 1u8), (0.0, -b, 1), (b, 0.0, 4), (-b, 0.0, 4)] {
                let nodes: Vec<u32> = (0..n as u32)
                    .filter(|&i| {
                        let q = m.mesh.coords[i as usize];
                        (q[0] - x).abs() < 1e-9 && (q[2] - z).abs() < 1e-9
                    })
                    .collect();
                c.fix(&nodes, mask);
            }
            let mut plan = StaticPlan::new(c);
            let q = k0 * p;
            plan.in_situ = InSitu::Field {
                profile: StressProfile::Layers {
                    ground_surface: 1e3,
                    surface_pressure: p,
                    layers: vec![Layer {
                        bottom: f64::NEG_INFINITY,
                        unit_weight: Some(0.0),
                        k0: [k0, 0.25 * (1.0 + k0)],
                    }],
                },
                solver: StepSolver::Direct,
                convergence: Convergence::default(),
            };
            let faces = |name: &str| m.mesh.face_sets[name].clone();
            plan.loads = vec![
                StaticLoad::Pressure {
                    faces: faces("plate.xmin"),
                    pressure: q,
                },
                StaticLoad::Pressure {
                    faces: faces("plate.xmax"),
                    pressure: q,
                },
                StaticLoad::Pressure {
                    faces: faces("plate.zmin"),
                    pressure: p,
                },
                StaticLoad::Pressure {
                    faces: faces("plate.zmax"),
                    pressure: p,
                },
            ];
            plan.steps = vec![StaticStep {
                name: "hole".into(),
                excavate: vec![ElementSet {
                    name: "hole".into(),
                    elements: m.mesh.element_sets["hole"].clone(),
                }],
                activate: vec![],
                solver: StepSolver::Direct,
                substeps: 1,
                convergence: Convergence::default(),
            }];
            let t0 = std::time::Instant::now();
            let (m, r) = run(m, &plan).unwrap();
            let du = r.displacement_since_in_situ();
            let find = |x: f64, z: f64| -> u32 {
                (0..n as u32)
                    .filter(|&i| {
                        let q = m.mesh.coords[i as usize];
                        (q[0] - x).abs() < 1e-9 && (q[2] - z).abs() < 1e-9
                    })
                    .collect::<Vec<_>>()[0]
            };
            let side = find(a, 0.0);
            let crown = find(0.0, a);
            let g = el.mu;
            let exact = |cos2: f64| a / (4.0 * g) * ((p + q) + (p - q) * (3.0 - 4.0 * 0.25) * cos2);
            let ur_side = -du[side as usize][0];
            let ur_crown = -du[crown as usize][2];
            // Stress: elements of the first two plate rings touching the wall node's ray.
            let wall_stress = |node: u32, comp: usize| -> (f64, f64) {
                let xw = m.mesh.coords[node as usize];
                let dir = [xw[0] / a, xw[2] / a];
                let mut rings: Vec<(f64, f64, usize)> = Vec::new();
                for e in 0..m.n_elements() {
                    if m.element_location[e].0 == u32::MAX {
                        continue;
                    }
                    let x = m.mesh.element_coords(e);
                    let c = [
                        x.iter().map(|p| p[0]).sum::<f64>() / 8.0,
                        x.iter().map(|p| p[2]).sum::<f64>() / 8.0,
                    ];
                    let rr = (c[0] * c[0] + c[1] * c[1]).sqrt();
                    let cosang = (c[0] * dir[0] + c[1] * dir[1]) / rr;
                    if cosang > (std::f64::consts::PI / around as f64 * 1.01).cos() && rr < 3.0 * a
                    {
                        let (_, s) = m.element_strain_stress(e, &r.u);
                        rings.push((rr, -s[comp], e));
                    }
                }
                rings.sort_by(|x, y| x.0.total_cmp(&y.0));
                let s1 = 0.5 * (rings[0].1 + rings[1].1);
                let r1 = 0.5 * (rings[0].0 + rings[1].0);
                let s2 = 0.5 * (rings[2].1 + rings[3].1);
                let r2 = 0.5 * (rings[2].0 + rings[3].0);
                (s1, s1 + (s1 - s2) * (r1 - a) / (r2 - r1))
            };
            let (s_side, s_side_x) = wall_stress(side, 2);
            let (s_crown, s_crown_x) = wall_stress(crown, 0);
            println!(
                "K0 {k0} {integ:?} {around}x{radial}: u side {:.4} mm ({:.4}) crown {:.4} mm ({:.4}); σθθ side {:.3} / extrap {:.3} MPa ({}) crown {:.3} / {:.3} ({}); {:.1}s",
                ur_side * 1e3,
                exact(-1.0) * 1e3,
                ur_crown * 1e3,
                exact(1.0) * 1e3,
                s_side / 1e6,
                s_side_x / 1e6,
                (3.0 * p - q) / 1e6,
                s_crown / 1e6,
                s_crown_x / 1e6,
                (3.0 * q - p) / 1e6,
                t0.elapsed().as_secs_f64()
            );
        }
    }
}
