//! The SIMD-lane kernels inside the step — fully integrated elements with their Gauss points
//! in lanes (`hex8_full_lanes`), one-point elements eight at a time (`hex8_uniform_lanes`):
//! on a distorted mesh, elastic and plastic-damage (cracking under a strong initial
//! velocity), with Rayleigh stiffness damping, element references and an in-situ initial
//! stress, the internal and damping forces, the displacements and the material states
//! after a run of steps are the scalar kernels' bit for bit, on 1 and 2 threads.

mod common;

use dcfm::element::Integration;
use dcfm::material::plastic_damage::PlasticDamageParams;
use dcfm::material::{Elastic, Material, PlasticDamage};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::RegionSetup;
use dcfm::stage::Simulation;

/// 7 × 5 × 3 elements of rock, every interior node moved by up to 20 % of the spacing,
/// base fixed, a random-looking initial velocity field.
fn simulation(
    integration: Integration,
    lanes: bool,
    damping: bool,
    reference: bool,
    plastic: bool,
) -> Simulation {
    let mut mesh = BoxMeshSpec::single("rock", [0.0; 3], [7.0, 5.0, 3.0], [7, 5, 3])
        .build("lanes test")
        .unwrap();
    let mut lcg = common::Lcg(0x1234_5678_9abc_def1u64);
    let mut rand = move || lcg.centred();
    for x in mesh.coords.iter_mut() {
        let inside = (0..3).all(|d| x[d] > 1e-9 && x[d] < [7.0, 5.0, 3.0][d] - 1e-9);
        if inside {
            for c in x.iter_mut() {
                *c += 0.4 * rand();
            }
        }
    }
    let setup = RegionSetup {
        region: "rock".to_string(),
        material: if plastic {
            // Tensile strength near the ≈ 3 MPa of the waves of the initial velocity.
            let el = Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap();
            let p = PlasticDamageParams::from_strengths(3.0e6, 24e6, 36e6, 100.0, 10e3);
            Material::PlasticDamage(Box::new(PlasticDamage::new("rock", el, &p).unwrap()))
        } else {
            Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap())
        },
        integration,
        hourglass: 0.05,
    };
    let (mut model, base) = common::rock_on_fixed_base(mesh, setup, "lanes test", damping);
    let mesh = model.mesh.clone();
    for g in &mut model.groups {
        g.lanes = lanes;
        if plastic {
            // An in-situ stress growing with depth (initial strains at every point).
            g.set_initial_stress(&mesh, |x| {
                let s = -0.2e6 * (3.0 - x[2]);
                [s, 0.8 * s, 1.2 * s, 0.05e6 * x[0], 0.0, -0.03e6 * x[1]]
            });
        }
        if reference {
            g.reference = Some(common::random_references(g.len(), &mut rand));
        }
    }
    common::kicked_simulation(model, &base, &mut rand)
}

/// Displacements, internal forces and the material states of every point after 25 steps.
type Outcome = (Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<f64>);

fn run(
    integration: Integration,
    lanes: bool,
    damping: bool,
    reference: bool,
    plastic: bool,
    threads: usize,
) -> Outcome {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut sim = simulation(integration, lanes, damping, reference, plastic);
        sim.run_steps(25).unwrap();
        sim.internal_forces();
        let states = sim
            .model
            .groups
            .iter()
            .flat_map(|g| g.states().current().to_vec())
            .collect();
        (sim.u.clone(), sim.internal_force().to_vec(), states)
    })
}

fn same(a: &[f64], b: &[f64]) -> bool {
    a.len() == b.len() && a.iter().zip(b).all(|(x, y)| x.to_bits() == y.to_bits())
}

#[test]
fn lanes_step_like_the_scalar_kernel_bit_for_bit() {
    for (integration, plastic) in [
        (Integration::Full, false),
        (Integration::Full, true),
        (Integration::OnePoint, false),
        (Integration::OnePoint, true),
    ] {
        for (damping, reference) in [(false, false), (true, false), (false, true), (true, true)] {
            let scalar = run(integration, false, damping, reference, plastic, 1);
            assert!(scalar.1.iter().flatten().any(|f| f.abs() > 0.0));
            for threads in [1, 2] {
                let lanes = run(integration, true, damping, reference, plastic, threads);
                let case = format!(
                    "{integration:?}, plastic {plastic}, damping {damping}, reference \
                     {reference}, {threads} thread(s)"
                );
                assert!(
                    same(scalar.0.as_flattened(), lanes.0.as_flattened()),
                    "displacements, {case}"
                );
                assert!(
                    same(scalar.1.as_flattened(), lanes.1.as_flattened()),
                    "forces, {case}"
                );
                assert!(same(&scalar.2, &lanes.2), "material states, {case}");
            }
        }
    }
}

#[test]
fn the_plastic_case_cracks() {
    // The comparison above covers the return mapping: some points of the plastic case
    // have damaged within the 25 steps, others have not, with either integration.
    for (integration, least) in [(Integration::Full, 20), (Integration::OnePoint, 5)] {
        cracks(integration, least);
    }
}

fn cracks(integration: Integration, least: usize) {
    let sim = {
        let mut sim = simulation(integration, true, false, false, true);
        sim.run_steps(25).unwrap();
        sim
    };
    let g = &sim.model.groups[0];
    let stride = g.material.state_len();
    let (mut damaged, mut intact) = (0, 0);
    for state in g.states().current().chunks_exact(stride) {
        match g.material.tensile_and_compressive_damage(state) {
            Some((dt, dc)) if dt > 0.0 || dc > 0.0 => damaged += 1,
            _ => intact += 1,
        }
    }
    assert!(
        damaged > least && intact > least,
        "{integration:?}: {damaged} damaged, {intact} intact"
    );
}
