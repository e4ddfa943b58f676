//! The contact solve beside the node pass (`stage::contact_overlap`) takes the step of the
//! order it replaces bit for bit: a rock block with a lining and an inner block on it,
//! three interfaces meeting at a junction edge (bonded, frictional, weak), gravity and a
//! strong base motion through a viscous-spring base, y fixed everywhere — stepped with the
//! contact solve beside the node pass and after it, on one, two and three threads, gives
//! the same displacements, velocities, energies, contact forces and contact states; and
//! the contact is busy (pairs held, slid and separated along the way).

use std::path::Path;

use dcfm::case::parse_case;
use dcfm::stage::Simulation;

const CASE: &str = r#"
title = "contact beside the node pass"
[time]
end = 1.0
[mesh]
split = [["rock", "lining"], ["rock", "inner"], ["lining", "inner"]]
[[mesh.blocks]]
name = "rock"
origin = [0.0, 0.0, 0.0]
size = [8.0, 4.0, 4.0]
divisions = [8, 4, 4]
[[mesh.blocks]]
name = "lining"
origin = [0.0, 0.0, 4.0]
size = [4.0, 4.0, 2.0]
divisions = [4, 4, 2]
[[mesh.blocks]]
name = "inner"
origin = [4.0, 0.0, 4.0]
size = [4.0, 4.0, 2.0]
divisions = [4, 4, 2]
[node_sets.all]
box = [[-1.0, -1.0, -1.0], [9.0, 5.0, 7.0]]
[materials.rock]
model = "elastic"
young = 20e9
poisson = 0.25
density = 2700.0
[materials.concrete]
model = "elastic"
young = 30e9
poisson = 0.2
density = 2400.0
[[regions]]
name = "rock"
material = "rock"
integration = "full"
[[regions]]
name = "lining"
material = "concrete"
integration = "full"
[[regions]]
name = "inner"
material = "concrete"
integration = "one_point"
[[interfaces]]
name = "lining_rock"
surface_a = "lining-rock"
surface_b = "rock-lining"
mu_s = 0.8
mu_d = 0.6
cohesion = 2.0e5
[[interfaces]]
name = "inner_rock"
surface_a = "inner-rock"
surface_b = "rock-inner"
mu_s = 0.3
mu_d = 0.2
cohesion = 0.0
[[interfaces]]
name = "lining_inner"
surface_a = "lining-inner"
surface_b = "inner-lining"
mu_s = 0.5
mu_d = 0.4
cohesion = 1.0e3
[loads.gravity]
acceleration = [0.0, 0.0, -9.81]
[[boundary.fixed]]
set = "all"
dofs = "y"
[[boundary.absorbing]]
set = "outer.zmin"
kind = "viscous_spring"
input = true
[seismic]
quantity = "acceleration"
definition = "outcrop"
x = { type = "ricker", amplitude = 40.0, frequency = 25.0 }
z = { type = "ricker", amplitude = 30.0, frequency = 30.0 }
"#;

/// Everything a step leaves, as bits: U, V, the energies, the contact forces' work and the
/// contact fields of every node.
#[derive(PartialEq, Debug)]
struct Outcome {
    u: Vec<u64>,
    v: Vec<u64>,
    energies: Vec<u64>,
    contact: Vec<u64>,
}

/// `steps` steps on `threads` threads, the contact solve beside the node pass or after it;
/// the outcome and the contact states seen at the end of each of the steps.
fn run(threads: usize, beside: bool, steps: usize) -> (Outcome, Vec<f64>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let case = parse_case(CASE, "contact beside", Path::new(".")).unwrap();
        let mut sim = Simulation::new(case.model, case.dt, case.safety).unwrap();
        sim.set_contact_beside_node_pass(beside);
        let n = sim.model.mesh.n_nodes();
        let mut states = Vec::new();
        for _ in 0..steps {
            sim.step().unwrap();
            let c = sim.model.contact.as_ref().unwrap();
            let fields = c.node_fields(n);
            let state = &fields.iter().find(|f| f.0 == "contact_state").unwrap().2;
            states.extend(state.iter().copied());
        }
        let c = sim.model.contact.as_ref().unwrap();
        let bits = |x: &[[f64; 3]]| x.iter().flatten().map(|v| v.to_bits()).collect();
        let e = &sim.energies;
        let mut contact: Vec<u64> = c
            .node_fields(n)
            .iter()
            .flat_map(|f| f.2.iter().map(|v| v.to_bits()))
            .collect();
        contact.push(c.friction_work().to_bits());
        (
            Outcome {
                u: bits(&sim.u),
                v: bits(&sim.v),
                energies: [
                    e.kinetic, e.internal, e.damping, e.external, e.input, e.boundary,
                ]
                .map(f64::to_bits)
                .to_vec(),
                contact,
            },
            states,
        )
    })
}

#[test]
fn contact_beside_the_node_pass_gives_the_same_step_bit_for_bit() {
    let steps = 400;
    let (after, states) = run(2, false, steps);
    for threads in [1, 2, 3] {
        let (beside, _) = run(threads, true, steps);
        assert!(
            beside == after,
            "{threads} thread(s): the step differs with the contact solve beside the node pass"
        );
    }
    // The contact is busy: pairs held (bonded 0 or sticking 1), sliding (2) and separated
    // (3) along the way.
    for (state, what) in [(0.0, "bonded"), (2.0, "sliding"), (3.0, "separated")] {
        assert!(
            states.contains(&state),
            "no {what} pair in {steps} steps: the test would not exercise the contact"
        );
    }
}
