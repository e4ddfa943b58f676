//! The damaging one-point plastic-damage cube of the throughput runner (issue #11) steps to
//! the same bits on 1 and 2 threads: the material update at the centroid and the hourglass
//! stiffness κ (1 − D) are per element, and the colouring fixes the order of the nodal sums
//! (12³ elements: 7 colouring blocks of 256, so both threads work).

use dcfm::element::Integration;
use dcfm_benchmarks::cube::{CubeMaterial, CubeSpec};

fn run(threads: usize) -> (Vec<[f64; 3]>, f64) {
    let spec =
        CubeSpec::new(12, Integration::OnePoint).with_material(CubeMaterial::PlasticDamageDamaging);
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut sim = spec.simulation().unwrap();
        sim.run_steps(40).unwrap();
        let damage = sim.model.groups[0]
            .element_damage_fields()
            .unwrap()
            .iter()
            .fold(0.0f64, |m, d| m.max(d[0]));
        (sim.u.clone(), damage)
    })
}

#[test]
fn damaging_one_point_cube_is_bit_identical_on_one_and_two_threads() {
    let (u1, d1) = run(1);
    let (u2, d2) = run(2);
    assert!(d1 > 0.1, "the cube must damage (largest D {d1})");
    assert_eq!(d1.to_bits(), d2.to_bits());
    assert_eq!(u1.len(), u2.len());
    for (a, b) in u1.iter().zip(&u2) {
        for i in 0..3 {
            assert_eq!(a[i].to_bits(), b[i].to_bits(), "{a:?} vs {b:?}");
        }
    }
}
