//! The SIMD-lane kernel of fully integrated elastic elements (`hex8_full_lanes`) inside the
//! step: on a distorted mesh whose group sizes leave partial lane blocks, with Rayleigh
//! stiffness damping and element references, the internal and damping forces and a run of
//! steps are the scalar kernel's bit for bit, on 1 and 2 threads.

use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, Rayleigh, RegionSetup};
use dcfm::stage::Simulation;

/// 7 × 5 × 3 elements of rock, every interior node moved by up to 20 % of the spacing,
/// base fixed, a random-looking initial velocity field.
fn simulation(lanes: bool, damping: bool, reference: bool) -> Simulation {
    let mut mesh = BoxMeshSpec::single("rock", [0.0; 3], [7.0, 5.0, 3.0], [7, 5, 3])
        .build("lanes test")
        .unwrap();
    let mut seed = 0x1234_5678_9abc_def1u64;
    let mut rand = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    };
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
        material: Material::Elastic(Elastic::new("rock", 20e9, 0.25, 2700.0).unwrap()),
        integration: Integration::Full,
        hourglass: 0.05,
    };
    let mut model = Model::new(mesh, &[setup], "lanes test").unwrap();
    let base = model.mesh.node_sets["rock.zmin"].clone();
    model.constraints.fix(&base, 0b111);
    if damping {
        model.damping = Rayleigh {
            alpha: 0.1,
            beta: 1e-5,
        };
    }
    for g in &mut model.groups {
        g.lanes = lanes;
        if reference {
            g.reference = Some(
                (0..g.len())
                    .map(|_| std::array::from_fn(|_| [1e-4 * rand(), 1e-4 * rand(), 1e-4 * rand()]))
                    .collect(),
            );
        }
    }
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = Simulation::new(model, dt, 0.9).unwrap();
    for v in sim.v.iter_mut() {
        *v = [rand(), rand(), 0.5 * rand()];
    }
    for &n in &base {
        sim.v[n as usize] = [0.0; 3];
    }
    sim.restart_energy_account();
    sim
}

fn run(
    lanes: bool,
    damping: bool,
    reference: bool,
    threads: usize,
) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut sim = simulation(lanes, damping, reference);
        sim.run_steps(25).unwrap();
        sim.internal_forces();
        (sim.u.clone(), sim.internal_force().to_vec())
    })
}

#[test]
fn lanes_step_like_the_scalar_kernel_bit_for_bit() {
    for (damping, reference) in [(false, false), (true, false), (false, true), (true, true)] {
        let scalar = run(false, damping, reference, 1);
        assert!(scalar.1.iter().flatten().any(|f| f.abs() > 0.0));
        for threads in [1, 2] {
            let lanes = run(true, damping, reference, threads);
            let same = |a: &[[f64; 3]], b: &[[f64; 3]]| {
                a.iter()
                    .flatten()
                    .zip(b.iter().flatten())
                    .all(|(x, y)| x.to_bits() == y.to_bits())
            };
            assert!(
                same(&scalar.0, &lanes.0),
                "displacements, damping {damping}, reference {reference}, {threads} thread(s)"
            );
            assert!(
                same(&scalar.1, &lanes.1),
                "forces, damping {damping}, reference {reference}, {threads} thread(s)"
            );
        }
    }
}
