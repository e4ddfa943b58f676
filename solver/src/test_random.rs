//! A small deterministic generator for the unit tests' random inputs (64-bit LCG with
//! Knuth's MMIX constants, the top 53 bits as a uniform number in [0, 1)): the same
//! sequence on every machine, no dependency.

/// Uniform numbers in [0, 1) from `seed`.
pub struct Lcg(pub u64);

impl Lcg {
    /// The next number in [0, 1).
    pub fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// The next number in [−1, 1).
    pub fn sym(&mut self) -> f64 {
        2.0 * self.next() - 1.0
    }
}

/// The unit tests' distorted hexahedron (node order of `hex8_shape::NODE_XI`): the unit
/// cube with every node but the first moved by up to 0.2.
pub fn distorted_hex() -> [[f64; 3]; 8] {
    [
        [0.0, 0.0, 0.0],
        [1.1, 0.05, -0.02],
        [1.2, 0.9, 0.1],
        [-0.1, 1.05, 0.0],
        [0.05, -0.1, 1.0],
        [1.0, 0.1, 1.2],
        [1.1, 1.1, 0.95],
        [0.0, 0.9, 1.1],
    ]
}

/// The unit tests' cracking concrete: E₀ 30 GPa, ν 0.2, ρ 2400 kg/m³, f_t0 3 MPa,
/// f_c0 20 MPa, f_cu 30 MPa, G_t 100 J/m², G_c 10 kJ/m² (cracks at ε ≈ 1e-4), with its
/// elastic part.
pub fn cracking_concrete() -> (crate::material::Material, crate::material::Elastic) {
    use crate::material::plastic_damage::PlasticDamageParams;
    use crate::material::{Elastic, Material, PlasticDamage};
    let el = Elastic::new("concrete", 30e9, 0.2, 2400.0).expect("valid elastic constants");
    let pd = PlasticDamage::new(
        "concrete",
        el,
        &PlasticDamageParams::from_strengths(3e6, 20e6, 30e6, 100.0, 10e3),
    )
    .expect("valid plastic-damage constants");
    (Material::PlasticDamage(Box::new(pd)), el)
}
