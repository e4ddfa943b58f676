//! The throughput runner's localised-damage cube (issue #11 item 4: the damaging work
//! concentrated in a few blocks, as the concrete of a cavern in a rock mass that stays
//! elastic): its fully integrated weak core damages throughout inside a linear elastic
//! host, and the run is bit-identical on one and two threads.

use dcfm::element::Integration;
use dcfm::stage::Simulation;
use dcfm_benchmarks::cube::{CubeMaterial, CubeSpec, REGION, WEAK_REGION};

/// Per element of the group named `region`: max(D_t, D_c) (element averages) and the
/// height of its centroid.
fn damage_and_height(sim: &Simulation, region: &str) -> Vec<(f64, f64)> {
    let group = sim
        .model
        .groups
        .iter()
        .find(|g| g.name == region)
        .unwrap_or_else(|| panic!("no element group {region}"));
    let fields = group.element_damage_fields().expect("plastic-damage group");
    fields
        .iter()
        .zip(&group.elements)
        .map(|(f, &e)| {
            let x = sim.model.mesh.element_coords(e as usize);
            (f[1].max(f[2]), x.iter().map(|p| p[2]).sum::<f64>() / 8.0)
        })
        .collect()
}

type Outcome = (Vec<u64>, Vec<(f64, f64)>);

fn run(spec: CubeSpec, threads: usize) -> Outcome {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("pool");
    pool.install(|| {
        let mut sim = spec.simulation().expect("localised cube");
        sim.run_steps(80).expect("80 steps");
        let bits = sim.u.iter().flatten().map(|x| x.to_bits()).collect();
        (bits, damage_and_height(&sim, WEAK_REGION))
    })
}

#[test]
fn the_weak_core_damages_in_an_elastic_host_and_threads_agree() {
    for integration in [Integration::Full, Integration::OnePoint] {
        let spec =
            CubeSpec::new(8, integration).with_material(CubeMaterial::PlasticDamageLocalised);
        assert_eq!(
            spec.name(),
            format!("cube8_{}_pd_localised", integration.name())
        );
        let sim = spec.simulation().expect("localised cube");
        let host = sim.model.groups.iter().find(|g| g.name == REGION).unwrap();
        let core = sim
            .model
            .groups
            .iter()
            .find(|g| g.name == WEAK_REGION)
            .unwrap();
        assert_eq!((host.len(), core.len()), (504, 8));
        assert!(host.element_damage_fields().is_none(), "host is elastic");
        assert_eq!(host.integration, integration);
        assert_eq!(core.integration, Integration::Full);
        let (u1, core) = run(spec, 1);
        // The core, the central 2³ of the 8³ elements, cracks everywhere: f_t0 0.145 MPa
        // against the ≈ 0.5 MPa shear wave the initial velocity sends through it.
        for (d, z) in &core {
            assert!(
                *d > 0.1,
                "{integration:?}: core element at z {z}: damage {d}"
            );
        }
        let (u2, _) = run(spec, 2);
        assert!(u1 == u2, "{integration:?}: 1 and 2 threads differ");
    }
}
