//! Builders and measurements shared by the contact cases (W5–W9, bonded, drop): box
//! blocks, elastic regions, interface force sums and centre-of-mass motion.

use dcfm::contact::ContactSystem;
use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::{BlockSpec, Mesh};
use dcfm::model::RegionSetup;
use dcfm::stage::Simulation;
use dcfm::Result;

/// A uniform box block named `name` (its own region).
pub fn block(name: &str, origin: [f64; 3], size: [f64; 3], divisions: [usize; 3]) -> BlockSpec {
    BlockSpec {
        name: name.into(),
        region: None,
        origin,
        size,
        divisions,
        grading: [1.0; 3],
    }
}

/// A fully integrated elastic region.
pub fn elastic(region: &str, young: f64, poisson: f64, density: f64) -> Result<RegionSetup> {
    Ok(RegionSetup {
        region: region.into(),
        material: Material::Elastic(Elastic::new(region, young, poisson, density)?),
        integration: Integration::Full,
        hourglass: 0.05,
    })
}

/// Every node of the elements of region `region`, sorted.
pub fn region_nodes(mesh: &Mesh, region: &str) -> Vec<u32> {
    let r = mesh
        .region_names
        .iter()
        .position(|n| n == region)
        .expect("region exists");
    let mut nodes: Vec<u32> = mesh
        .elements
        .iter()
        .zip(&mesh.element_region)
        .filter(|(_, &er)| er as usize == r)
        .flat_map(|(e, _)| e.iter().copied())
        .collect();
    nodes.sort_unstable();
    nodes.dedup();
    nodes
}

/// Mass, mass-weighted mean displacement and mean (half-step) velocity of `nodes`.
pub fn centre_of_mass(sim: &Simulation, nodes: &[u32]) -> (f64, [f64; 3], [f64; 3]) {
    let mut m = 0.0;
    let mut u = [0.0; 3];
    let mut v = [0.0; 3];
    for &k in nodes {
        let k = k as usize;
        let mk = sim.model.mass[k];
        m += mk;
        for d in 0..3 {
            u[d] += mk * sim.u[k][d];
            v[d] += mk * sim.v[k][d];
        }
    }
    (m, u.map(|x| x / m), v.map(|x| x / m))
}

/// Forces of interface `k` summed over its surface-a nodes: (Σ normal force λ, compression
/// positive; Σ tangential force vector on surface a; [bonded, stick, sliding, separated]
/// counts, pairs and point-to-surface nodes together).
pub fn interface_forces(sim: &Simulation, k: usize) -> (f64, [f64; 3], [usize; 4]) {
    let contact: &ContactSystem = sim.model.contact.as_ref().expect("model has contact");
    let n = sim.model.mesh.n_nodes();
    let fields = contact.node_fields(n);
    let nf = &fields[4].2;
    let tf = &fields[5].2;
    let mut sum_n = 0.0;
    let mut sum_t = [0.0; 3];
    for (a, _, _, _) in contact.pairs(k) {
        let a = a as usize;
        sum_n += nf[a];
        for d in 0..3 {
            sum_t[d] += tf[3 * a + d];
        }
    }
    let (p, s) = contact.state_counts(k);
    let counts = [p[0] + s[0], p[1] + s[1], p[2] + s[2], p[3] + s[3]];
    (sum_n, sum_t, counts)
}

/// Largest penetration (−gap, m) over the surface-a nodes of interface `k` (0 if none).
pub fn max_penetration(sim: &Simulation, k: usize) -> f64 {
    let contact = sim.model.contact.as_ref().expect("model has contact");
    let fields = contact.node_fields(sim.model.mesh.n_nodes());
    let gap = &fields[1].2;
    contact
        .pairs(k)
        .iter()
        .map(|p| -gap[p.0 as usize])
        .fold(0.0, f64::max)
}
