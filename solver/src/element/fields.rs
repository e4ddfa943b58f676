//! Element fields of a state in global element order: the volume-averaged strain and
//! stress, the damage variables and the region of every element — what outputs and the
//! Python module show of a state.

use crate::model::Model;

/// Per-element fields, row-major, global element order.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ElementFields {
    /// Volume-averaged strain, 6 per element (Voigt, engineering shear).
    pub strain: Vec<f64>,
    /// Volume-averaged stress, 6 per element (Pa).
    pub stress: Vec<f64>,
    /// [D, D_t, D_c, κ_t, κ_c, εᵖ (6)] per element, volume-averaged (zero for materials
    /// without damage), the layout of `ElementGroup::element_damage_fields`.
    pub damage: Vec<f64>,
    /// Region index of every element, in mesh-block order (`mesh.region_names`; the VTU
    /// files number regions in `[[regions]]` order instead, `Model::region_number`).
    pub region: Vec<f64>,
}

/// Values per element in [`ElementFields::damage`].
pub const DAMAGE_VALUES: usize = 11;

impl ElementFields {
    /// The fields of `model` for displacements `u` and the committed material states.
    pub fn of(model: &Model, u: &[[f64; 3]]) -> Self {
        let ne = model.n_elements();
        let mut f = Self {
            strain: vec![0.0; 6 * ne],
            stress: vec![0.0; 6 * ne],
            damage: vec![0.0; DAMAGE_VALUES * ne],
            region: vec![0.0; ne],
        };
        for g in &model.groups {
            let ss = g.element_strain_stress(u);
            let dmg = g.element_damage_fields();
            for (le, &e) in g.elements.iter().enumerate() {
                let e = e as usize;
                f.strain[6 * e..6 * e + 6].copy_from_slice(&ss[le].0);
                f.stress[6 * e..6 * e + 6].copy_from_slice(&ss[le].1);
                if let Some(d) = &dmg {
                    f.damage[DAMAGE_VALUES * e..DAMAGE_VALUES * (e + 1)].copy_from_slice(&d[le]);
                }
                f.region[e] = g.region as f64;
            }
        }
        f
    }

    /// `n` consecutive damage values starting at `k` of every element (k = 0: D, 1: D_t,
    /// 2: D_c, 3: κ_t, 4: κ_c, 5..11: εᵖ).
    pub fn damage_values(&self, k: usize, n: usize) -> Vec<f64> {
        self.damage
            .chunks_exact(DAMAGE_VALUES)
            .flat_map(|d| d[k..k + n].iter().copied())
            .collect()
    }
}
