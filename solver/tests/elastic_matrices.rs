//! Linear elastic, fully integrated elements through their stiffness matrices
//! (`element::elastic_matrices`) inside the step: on a box of repeated cells away from the
//! origin (so that the cells' coordinate differences agree only to round-off), with and
//! without Rayleigh stiffness damping and element references, the displacements and
//! internal forces after a run of steps are the scalar Gauss kernel's to 1e-11 of their
//! largest value (4.4e-13 measured: the matrix is that of the box's first cell, the other
//! cells differ from it by their coordinates' round-off), and the same bits on 1 and 2
//! threads. With an initial stress the group keeps the Gauss kernel.

mod common;

use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::RegionSetup;
use dcfm::stage::Simulation;

/// 7 × 5 × 4 cells of 0.37 × 0.61 × 0.29 m with their corner at (103.7, −52.3, 18.9),
/// base fixed, a random-looking initial velocity field.
fn simulation(lanes: bool, damping: bool, reference: bool) -> Simulation {
    let origin = [103.7, -52.3, 18.9];
    let n = [7, 5, 4];
    let size = [0.37, 0.61, 0.29];
    let extent = std::array::from_fn(|d| n[d] as f64 * size[d]);
    let mesh = BoxMeshSpec::single("rock", origin, extent, n)
        .build("matrices test")
        .unwrap();
    let setup = RegionSetup {
        region: "rock".to_string(),
        material: Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap()),
        integration: Integration::Full,
        hourglass: 0.05,
    };
    let (mut model, base) = common::rock_on_fixed_base(mesh, setup, "matrices test", damping);
    let mut lcg = common::Lcg(0x0bad_cafe_1234_5678u64);
    let mut rand = move || lcg.centred();
    for g in &mut model.groups {
        g.lanes = lanes;
        if reference {
            g.reference = Some(common::random_references(g.len(), &mut rand));
        }
    }
    common::kicked_simulation(model, &base, &mut rand)
}

/// Displacements and internal forces after 25 steps.
fn run(lanes: bool, damping: bool, reference: bool, threads: usize) -> (Vec<f64>, Vec<f64>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut sim = simulation(lanes, damping, reference);
        sim.run_steps(25).unwrap();
        sim.internal_forces();
        (
            sim.u.as_flattened().to_vec(),
            sim.internal_force().as_flattened().to_vec(),
        )
    })
}

fn largest(a: &[f64]) -> f64 {
    a.iter().fold(0.0f64, |m, v| m.max(v.abs()))
}

#[test]
fn every_cell_of_the_box_shares_one_matrix() {
    let sim = simulation(true, false, false);
    let g = &sim.model.groups[0];
    let m = g
        .elastic_matrices()
        .expect("a box of repeated cells has matrices");
    assert_eq!(m.distinct(), 1);
    assert_eq!(m.elements_with_matrix(), g.len());
}

#[test]
fn matrix_forces_step_like_the_gauss_kernel() {
    for (damping, reference) in [(false, false), (true, false), (false, true), (true, true)] {
        let case = format!("damping {damping}, reference {reference}");
        let (u_ref, f_ref) = run(false, damping, reference, 1);
        let (u1, f1) = run(true, damping, reference, 1);
        let (u2, f2) = run(true, damping, reference, 2);
        let (us, fs) = (largest(&u_ref), largest(&f_ref));
        assert!(us > 0.0 && fs > 0.0, "{case}: the run moves");
        for (a, b) in u_ref.iter().zip(&u1) {
            assert!((a - b).abs() <= 1e-11 * us, "{case}: u {a} against {b}");
        }
        for (a, b) in f_ref.iter().zip(&f1) {
            assert!((a - b).abs() <= 1e-11 * fs, "{case}: f {a} against {b}");
        }
        // Not the Gauss kernel's bits (the matrix path ran), but 1 = 2 threads bit for bit.
        assert!(u_ref
            .iter()
            .zip(&u1)
            .any(|(a, b)| a.to_bits() != b.to_bits()));
        assert!(
            u1.iter().zip(&u2).all(|(a, b)| a.to_bits() == b.to_bits()),
            "{case}"
        );
        assert!(
            f1.iter().zip(&f2).all(|(a, b)| a.to_bits() == b.to_bits()),
            "{case}"
        );
    }
}

#[test]
fn an_initial_stress_keeps_the_gauss_kernel() {
    // The matrices carry no initial strain: with one the group steps like the Gauss
    // kernel in lanes, which is the scalar kernel bit for bit.
    let run_with_stress = |lanes: bool| {
        let mut sim = simulation(lanes, true, false);
        let mesh = sim.model.mesh.clone();
        for g in &mut sim.model.groups {
            g.set_initial_stress(&mesh, |x| [-1e5 * x[2], -1e5, -2e5, 0.0, 0.0, 0.0]);
        }
        sim.run_steps(10).unwrap();
        sim.u.as_flattened().to_vec()
    };
    let (a, b) = (run_with_stress(false), run_with_stress(true));
    assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
}
