//! A seismic model — viscous-spring base with the input, free-field walls large enough to
//! be split across threads (24 × 24 faces each), edge columns — steps to bit-identical
//! displacements, velocities and energies on 1, 2 and 3 threads: the walls' element forces
//! are computed in parallel and added to each node in element order, the boundary sources
//! and the boundary nodes' updates are computed node by node in parallel, and the energy
//! sums run over fixed chunks.

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::Simulation;

const CASE: &str = r#"
title = "seismic threads"
[time]
end = 1.0
[mesh]
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, 0.0]
size = [48.0, 48.0, 48.0]
divisions = [24, 24, 24]
[materials.rock]
model = "elastic"
young = 10e9
poisson = 0.25
density = 2700.0
[[regions]]
name = "rock"
material = "rock"
integration = "one_point"
damping = { alpha = 0.5, beta = 1e-4 }
[[boundary.absorbing]]
set = "outer.zmin"
kind = "viscous_spring"
input = true
[boundary.free_field]
sides = ["outer.xmin", "outer.xmax", "outer.ymin", "outer.ymax"]
[seismic]
quantity = "acceleration"
definition = "outcrop"
x = { type = "ricker", amplitude = 2.0, frequency = 20.0 }
y = { type = "sine", amplitude = 1.0, frequency = 15.0 }
z = { type = "ricker", amplitude = 1.0, frequency = 25.0 }
"#;

/// Displacements, velocities and the energies' bits after 60 steps on `threads`.
fn run(threads: usize) -> (Vec<[f64; 3]>, Vec<[f64; 3]>, Vec<u64>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let case = parse_case(CASE, "seismic threads", Path::new(".")).unwrap();
        let mut sim = Simulation::new(case.model, case.dt, case.safety).unwrap();
        sim.run_steps(60).unwrap();
        let e = &sim.energies;
        let energies = [
            e.kinetic, e.internal, e.damping, e.external, e.input, e.boundary,
        ];
        (
            sim.u.clone(),
            sim.v.clone(),
            energies.map(f64::to_bits).to_vec(),
        )
    })
}

#[test]
fn seismic_model_with_free_field_walls_steps_alike_on_one_two_and_three_threads() {
    let one = run(1);
    let moved = one.0.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
    assert!(moved > 0.0, "the input must move the model");
    for threads in [2, 3] {
        let other = run(threads);
        assert!(
            one.0 == other.0,
            "displacements differ between 1 and {threads} threads"
        );
        assert!(
            one.1 == other.1,
            "velocities differ between 1 and {threads} threads"
        );
        assert_eq!(
            one.2, other.2,
            "energies differ between 1 and {threads} threads"
        );
    }
}
