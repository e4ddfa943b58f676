//! Helpers shared by the integration tests (each test file includes this module with
//! `mod common;` and uses what it needs).
#![allow(dead_code)]

use dcfm::material::plastic_damage::PlasticDamageParams;
use dcfm::material::{Elastic, Material, PlasticDamage};

/// A deterministic generator for random-looking inputs: a 64-bit LCG with Knuth's MMIX
/// constants, the top 53 bits as a number in [−½, ½) — the same sequence on every
/// machine, no dependency.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in [−½, ½).
    pub fn centred(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }
}

/// The plastic-damage concrete of the damaging test blocks (f_t 2.9 MPa, f_c0 13 MPa,
/// f_c 24.1 MPa, G_t 200 N/m, G_c 1e4 N/m; `PlasticDamageParams::from_strengths`) over
/// `elastic`.
pub fn damaging_concrete(elastic: Elastic) -> Material {
    Material::PlasticDamage(Box::new(
        PlasticDamage::new(
            "concrete",
            elastic,
            &PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 200.0, 1e4),
        )
        .unwrap(),
    ))
}

/// Element references of up to ±5e-5 m from `rand` for `n` elements: each element starts
/// stress-free at its own random nodal displacements.
pub fn random_references(n: usize, rand: &mut impl FnMut() -> f64) -> Vec<[[f64; 3]; 8]> {
    (0..n)
        .map(|_| std::array::from_fn(|_| [1e-4 * rand(), 1e-4 * rand(), 1e-4 * rand()]))
        .collect()
}

/// The simulation of `model` at the step `dt` with a random-looking initial velocity from
/// `rand` on every node but the `fixed` ones, its energy account started there.
pub fn kicked_simulation(
    model: dcfm::model::Model,
    fixed: &[u32],
    rand: &mut impl FnMut() -> f64,
) -> dcfm::stage::Simulation {
    let dt = model.time_step(None, 0.9).unwrap();
    let mut sim = dcfm::stage::Simulation::new(model, dt, 0.9).unwrap();
    for v in sim.v.iter_mut() {
        *v = [rand(), rand(), 0.5 * rand()];
    }
    for &n in fixed {
        sim.v[n as usize] = [0.0; 3];
    }
    sim.restart_energy_account();
    sim
}

/// The model of `setup` on `mesh` (one region "rock") with its base `rock.zmin` fixed and,
/// when `damping`, Rayleigh damping α 0.1, β 1e-5; with the base's nodes.
pub fn rock_on_fixed_base(
    mesh: dcfm::mesh::Mesh,
    setup: dcfm::model::RegionSetup,
    name: &str,
    damping: bool,
) -> (dcfm::model::Model, Vec<u32>) {
    let mut model = dcfm::model::Model::new(mesh, &[setup], name).unwrap();
    let base = model.mesh.node_sets["rock.zmin"].clone();
    model.constraints.fix(&base, 0b111);
    if damping {
        model.damping = dcfm::model::Rayleigh {
            alpha: 0.1,
            beta: 1e-5,
        };
    }
    (model, base)
}
