//! The two-phase element force pass (`element::groups::add_internal_forces`, issue 11
//! item 4): plastic-damage groups compute every element's forces in parallel into
//! per-element buffers, then add them to the nodes run by run in the colouring's order.
//! On a distorted, graded block of damaging concrete (several colouring runs per colour,
//! one-point and fully integrated, with and without Rayleigh damping, single and
//! subcycled steps) the displacements, internal forces and damage states after a run are
//! those of the one-phase pass bit for bit, on 1 and 2 threads. The same block checks the
//! explicit core's in-place material states (`PointStates::set_in_place`) against
//! buffered ones (old and new buffers, swapped at the end of the step).
//!
//! The variants with three groups interleaved element by element (both integrations, two
//! strengths, each colouring block holding elements of all three) check that every node
//! receives the groups' forces in the one-phase pass's order: colour, then group.

mod common;

use dcfm::element::Integration;
use dcfm::material::Elastic;
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, Rayleigh, RegionSetup};
use dcfm::stage::Simulation;

/// What one variant runs.
#[derive(Clone, Copy, Debug)]
struct Variant {
    integration: Integration,
    damping: bool,
    subcycled: bool,
    /// Material states updated in place (the explicit core's way), else buffered.
    in_place: bool,
    /// Three groups interleaved: `integration` and the other rule in two concretes.
    mixed: bool,
}

/// 16 × 8 × 6 elements (768: three colouring blocks of 256), the first 8 columns 0.5 m
/// long in x and the others 2 m (1 m across: they step at 2 Δt), interior nodes moved by up
/// to 10 % of the spacing; base fixed; a random velocity field of ±2 m/s, strong enough
/// to crack the concrete (f_t/E0 ≈ 1.2e-4 against v/c_p ≈ 6e-4).
fn simulation(v: Variant, two_phase: bool) -> Simulation {
    let (nx, ny, nz) = (16usize, 8usize, 6usize);
    let mut mesh = BoxMeshSpec::single(
        "concrete",
        [0.0; 3],
        [nx as f64, ny as f64, nz as f64],
        [nx, ny, nz],
    )
    .build("two-phase test")
    .unwrap();
    let mut lcg = common::Lcg(0x0ddc_0ffe_e15b_ad5eu64);
    let mut rand = move || lcg.centred();
    let grade = |i: f64| {
        if i <= 8.0 {
            0.5 * i
        } else {
            4.0 + 2.0 * (i - 8.0)
        }
    };
    for x in mesh.coords.iter_mut() {
        let inside =
            (0..3).all(|d| x[d] > 1e-9 && x[d] < [nx as f64, ny as f64, nz as f64][d] - 1e-9);
        let jitter: [f64; 3] = std::array::from_fn(|_| 0.2 * rand());
        let i = x[0];
        let h = if i < 8.0 { 0.5 } else { 2.0 };
        x[0] = grade(i);
        if inside {
            x[0] += h * jitter[0];
            x[1] += jitter[1];
            x[2] += jitter[2];
        }
    }
    let elastic = Elastic::new("concrete", 25e9, 0.17, 2450.0).unwrap();
    let material = common::damaging_concrete(elastic);
    let mut setups = vec![RegionSetup {
        region: "concrete".to_string(),
        material,
        integration: v.integration,
        hourglass: 0.05,
    }];
    if v.mixed {
        // Regions by a pattern that mixes them inside every colouring block.
        for (e, r) in mesh.element_region.iter_mut().enumerate() {
            *r = ((e * 7 / 5) % 3) as u16;
        }
        mesh.region_names = vec!["concrete".into(), "other_rule".into(), "weaker".into()];
        let other = match v.integration {
            Integration::Full => Integration::OnePoint,
            Integration::OnePoint => Integration::Full,
        };
        let weaker = Elastic::new("weaker", 20e9, 0.2, 2400.0).unwrap();
        setups.push(RegionSetup {
            region: "other_rule".to_string(),
            material: common::damaging_concrete(elastic),
            integration: other,
            hourglass: 0.05,
        });
        setups.push(RegionSetup {
            region: "weaker".to_string(),
            material: common::damaging_concrete(weaker),
            integration: v.integration,
            hourglass: 0.08,
        });
    }
    let mut model = Model::new(mesh, &setups, "two-phase test").unwrap();
    assert_eq!(model.groups.len(), setups.len());
    let base = model.mesh.node_sets["concrete.zmin"].clone();
    model.constraints.fix(&base, 0b111);
    if v.damping {
        model.damping = Rayleigh {
            alpha: 0.1,
            beta: 1e-5,
        };
    }
    for g in &mut model.groups {
        assert!(
            g.element_forces.is_some(),
            "plastic-damage groups default to two phases"
        );
        if !two_phase {
            g.element_forces = None;
        }
    }
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = Simulation::new(model, dt, 0.9).unwrap();
    for g in &mut sim.model.groups {
        assert!(
            g.states().is_in_place(),
            "the explicit core updates in place"
        );
        g.set_states_in_place(v.in_place);
    }
    for vel in sim.v.iter_mut() {
        *vel = [4.0 * rand(), 4.0 * rand(), 4.0 * rand()];
    }
    for &n in &base {
        sim.v[n as usize] = [0.0; 3];
    }
    sim.restart_energy_account();
    if v.subcycled {
        sim.enable_subcycling(3, 0.9).unwrap();
        assert!(
            sim.subcycling().unwrap().elements_per_level[1] > 0,
            "the coarse elements step at 2 Δt"
        );
    }
    sim
}

/// Displacements, element damage fields and internal forces after 60 steps (the forces of
/// one more pass at the last displacements).
fn run(v: Variant, two_phase: bool, threads: usize) -> (Vec<u64>, Vec<u64>, Vec<u64>) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .unwrap();
    pool.install(|| {
        let mut sim = simulation(v, two_phase);
        sim.run_steps(60).unwrap();
        // The committed states after step 60 (before a pass that, in place, commits).
        let damage: Vec<u64> = sim
            .model
            .groups
            .iter()
            .flat_map(|g| g.element_damage_fields().unwrap())
            .flatten()
            .map(|x| x.to_bits())
            .collect();

        sim.internal_forces();
        let bits = |a: &[[f64; 3]]| a.iter().flatten().map(|x| x.to_bits()).collect();
        (bits(&sim.u), damage, bits(sim.internal_force()))
    })
}

/// Full and one-point integration, each plain, with Rayleigh damping and subcycled
/// (subcycling refuses stiffness-proportional damping), states in place.
fn variants() -> impl Iterator<Item = Variant> {
    [Integration::Full, Integration::OnePoint]
        .into_iter()
        .flat_map(|integration| {
            [
                (false, false, false),
                (true, false, false),
                (false, true, false),
                (false, false, true),
                (true, false, true),
            ]
            .map(|(damping, subcycled, mixed)| Variant {
                integration,
                damping,
                subcycled,
                in_place: true,
                mixed,
            })
        })
}

/// The reference run of `v`, checked to crack the concrete (some element's D_t > 0.05).
fn cracking_run(v: Variant, two_phase: bool, threads: usize) -> (Vec<u64>, Vec<u64>, Vec<u64>) {
    let r = run(v, two_phase, threads);
    let damaged = sim_damage_max(&r.1);
    assert!(damaged > 0.05, "{v:?}: largest d_t {damaged}");
    r
}

#[test]
fn two_phase_pass_is_the_one_phase_pass_bit_for_bit() {
    for v in variants() {
        let one_phase = cracking_run(v, false, 1);
        for threads in [1, 2] {
            let two_phase = run(v, true, threads);
            assert!(
                one_phase.0 == two_phase.0,
                "{v:?}: displacements, {threads} thread(s)"
            );
            assert!(
                one_phase.1 == two_phase.1,
                "{v:?}: damage, {threads} thread(s)"
            );
            assert!(
                one_phase.2 == two_phase.2,
                "{v:?}: forces, {threads} thread(s)"
            );
        }
    }
}

#[test]
fn in_place_states_step_like_buffered_ones_bit_for_bit() {
    for v in variants() {
        let buffered = cracking_run(
            Variant {
                in_place: false,
                ..v
            },
            true,
            2,
        );
        let in_place = run(v, true, 2);
        assert!(buffered.0 == in_place.0, "{v:?}: displacements");
        assert!(buffered.1 == in_place.1, "{v:?}: damage");
        assert!(buffered.2 == in_place.2, "{v:?}: forces");
    }
}

/// Largest tensile damage D_t over the elements (the second of each element's 11
/// fields, `ElementGroup::element_damage_fields`).
fn sim_damage_max(fields: &[u64]) -> f64 {
    fields
        .chunks(11)
        .map(|f| f64::from_bits(f[1]))
        .fold(0.0, f64::max)
}
