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

/// A free bar along x, cross-section 2 m × 2 m (one element), with element lengths
/// `lengths` (m) in x order; elastic with E `young`, ν = 0 (a 1D P wave in a 3D mesh) and
/// ρ `density`, fully integrated.
pub fn elastic_bar(lengths: &[f64], young: f64, density: f64, name: &str) -> dcfm::model::Model {
    let n = lengths.len();
    let mut mesh =
        dcfm::mesh::BoxMeshSpec::single("rock", [0.0; 3], [n as f64, 2.0, 2.0], [n, 1, 1])
            .build(name)
            .unwrap();
    let mut edge = vec![0.0; n + 1];
    for k in 0..n {
        edge[k + 1] = edge[k] + lengths[k];
    }
    for x in mesh.coords.iter_mut() {
        x[0] = edge[x[0].round() as usize];
    }
    let setup = dcfm::model::RegionSetup {
        region: "rock".to_string(),
        material: Material::Elastic(Elastic::new("rock", young, 0.0, density).unwrap()),
        integration: dcfm::element::Integration::Full,
        hourglass: 0.05,
    };
    dcfm::model::Model::new(mesh, &[setup], name).unwrap()
}

/// sin² pulse of width `w` centred at `x0`: the velocity profile g(x) (m/s per unit v0)
/// and its integral G(x) = ∫_{−∞}^x g.
pub fn sin2_pulse(x: f64, x0: f64, w: f64) -> (f64, f64) {
    let s = x - (x0 - 0.5 * w);
    if s <= 0.0 {
        (0.0, 0.0)
    } else if s >= w {
        (0.0, 0.5 * w)
    } else {
        let a = std::f64::consts::PI * s / w;
        (
            a.sin().powi(2),
            0.5 * s - w / (4.0 * std::f64::consts::PI) * (2.0 * a).sin(),
        )
    }
}

/// Start `sim` (a bar along x with wave speed `c`) on a right-going P pulse
/// u = f(x − ct), v = −c f′ (amplitude `v0` in velocity, width `w`, centred at `x0`), the
/// leapfrog's V^{−½} taken at t = −Δt/2, and restart its energy account.
pub fn launch_right_going_pulse(
    sim: &mut dcfm::stage::Simulation,
    c: f64,
    x0: f64,
    w: f64,
    v0: f64,
) {
    let dt = sim.dt;
    for i in 0..sim.u.len() {
        let x = sim.model.mesh.coords[i][0];
        let (_, big) = sin2_pulse(x, x0, w);
        sim.u[i] = [-(v0 / c) * big, 0.0, 0.0];
        let (g, _) = sin2_pulse(x + 0.5 * c * dt, x0, w);
        sim.v[i] = [v0 * g, 0.0, 0.0];
    }
    sim.restart_energy_account();
}
