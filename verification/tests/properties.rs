//! Property tests of the hex8 element and the assembly (issue #2, item 10):
//! Σ f_int = 0 for any displacement field; a rigid translation gives zero internal force;
//! lumped masses sum to ρV; hourglass modes vanish for linear fields; results are
//! bit-identical for 1 and 2 threads.

use proptest::prelude::*;

use dcfm::element::hex8_full::{self, FullGeometry};
use dcfm::element::hex8_shape::{volume, NODE_XI};
use dcfm::element::hex8_uniform::{self, UniformGeometry};
use dcfm::element::lumped_mass::element_masses;
use dcfm::element::Integration;
use dcfm::material::{Elastic, Material, PointContext};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;

fn material() -> Material {
    Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap())
}

/// A random but valid hex8: the unit cube with corners moved by up to 15 %.
fn element() -> impl Strategy<Value = [[f64; 3]; 8]> {
    proptest::collection::vec(-0.15f64..0.15, 24).prop_map(|d| {
        std::array::from_fn(|a| std::array::from_fn(|i| 0.5 * (NODE_XI[a][i] + 1.0) + d[3 * a + i]))
    })
}

fn field() -> impl Strategy<Value = [[f64; 3]; 8]> {
    proptest::collection::vec(-1e-3f64..1e-3, 24)
        .prop_map(|d| std::array::from_fn(|a| std::array::from_fn(|i| d[3 * a + i])))
}

fn forces(x: &[[f64; 3]; 8], u: &[[f64; 3]; 8], integration: Integration) -> [[f64; 3]; 8] {
    let m = material();
    let ctx = PointContext {
        char_length: 1.0,
        dt: 1e-4,
        reads_damage: false,
    };
    let mut f = [[0.0; 3]; 8];
    match integration {
        Integration::OnePoint => {
            let g = UniformGeometry::new(x, m.elastic(), 0.1).unwrap();
            hex8_uniform::internal_force(&g, &m, u, &[], &mut [], &ctx, &mut f);
        }
        Integration::Full => {
            let g = FullGeometry::new(x).unwrap();
            hex8_full::internal_force(&g, &m, u, &[], &mut [], &ctx, &mut f);
        }
    }
    f
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn internal_forces_sum_to_zero(x in element(), u in field(), full in any::<bool>()) {
        let integ = if full { Integration::Full } else { Integration::OnePoint };
        let f = forces(&x, &u, integ);
        let scale = f.iter().flatten().fold(0.0f64, |m, v| m.max(v.abs())).max(1.0);
        for i in 0..3 {
            let s: f64 = f.iter().map(|r| r[i]).sum();
            prop_assert!(s.abs() <= 1e-10 * scale, "Σf_{} = {} (scale {})", i, s, scale);
        }
    }

    #[test]
    fn rigid_translation_gives_no_force(x in element(), t in proptest::array::uniform3(-1.0f64..1.0), full in any::<bool>()) {
        let integ = if full { Integration::Full } else { Integration::OnePoint };
        let u = [t; 8];
        let f = forces(&x, &u, integ);
        for v in f.iter().flatten() {
            prop_assert!(v.abs() <= 1e-12 * 20e9, "force {}", v);
        }
    }

    #[test]
    fn lumped_mass_sums_to_rho_v(x in element(), rho in 100.0f64..10_000.0) {
        let m: f64 = element_masses(&x, rho).iter().sum();
        prop_assert!((m - rho * volume(&x)).abs() <= 1e-12 * m);
    }

    #[test]
    fn hourglass_modes_vanish_for_linear_fields(x in element(), g in proptest::collection::vec(-1e-3f64..1e-3, 12)) {
        let geo = UniformGeometry::new(&x, material().elastic(), 0.1).unwrap();
        let u: [[f64; 3]; 8] = std::array::from_fn(|a| std::array::from_fn(|i| g[9 + i] + (0..3).map(|j| g[3 * i + j] * x[a][j]).sum::<f64>()));
        let q = geo.hourglass_modes(&u);
        for v in q.iter().flatten() {
            prop_assert!(v.abs() <= 1e-15, "q = {}", v);
        }
    }
}

fn run_with_threads(threads: usize) -> (Vec<[f64; 3]>, f64) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mesh = BoxMeshSpec::single("b", [0.0; 3], [12.0, 12.0, 12.0], [12, 12, 12])
            .build("t")
            .unwrap();
        let setups: Vec<RegionSetup> = vec![RegionSetup {
            region: "b".into(),
            material: material(),
            integration: Integration::OnePoint,
            hourglass: 0.05,
        }];
        let mut model = Model::new(mesh, &setups, "t").unwrap();
        let base = model.mesh.node_sets["b.zmin"].clone();
        model.constraints.fix(&base, 0b111);
        model.damping.beta = 1e-5;
        let top = model.mesh.node_sets["b.zmax"].clone();
        model.initial_velocity.push((top, [0.1, -0.05, 0.02]));
        let dt = 0.8 * model.critical_step_with_damping();
        let mut sim = Simulation::new(model, dt, 0.9).unwrap();
        sim.run_steps(200).unwrap();
        (sim.u.clone(), sim.energies.internal)
    })
}

#[test]
fn results_are_bit_identical_for_one_and_two_threads() {
    let (u1, e1) = run_with_threads(1);
    let (u2, e2) = run_with_threads(2);
    assert!(u1.iter().flatten().any(|v| *v != 0.0));
    assert_eq!(u1, u2);
    assert_eq!(e1.to_bits(), e2.to_bits());
}
