//! Excavation and activation: the model keeps its full mesh and an active flag per element;
//! the element groups are rebuilt from the active elements of each region (the templates
//! built by `Model::new`), carrying the integration-point data of the surviving elements
//! over by element id. Masses are recomputed from the active elements; a node of no active
//! element is dormant: zero mass, all three DOFs fixed at its displacement, out of contact
//! (its pairs inactive) and out of the static equations.
//!
//! An element activated where its nodes have already moved gets that displacement as its
//! reference (`ElementGroup::reference`): it is stress-free in the deformed configuration.

use crate::boundary::Constraints;
use crate::element::groups::ElementGroup;
use crate::model::Model;

/// The active set of a model during (and after) the static stage.
#[derive(Clone, Debug)]
pub struct Activation {
    /// The groups of the full regions as the case built them (virgin states).
    templates: Vec<ElementGroup>,
    /// Active flag of every element.
    pub active: Vec<bool>,
    /// Dormant flag of every node (no active element).
    pub dormant: Vec<bool>,
}

impl Activation {
    /// Every element active; the model's groups (which must still be the full regions)
    /// become the templates.
    pub fn new(model: &Model) -> Self {
        Self {
            templates: model.groups.clone(),
            active: vec![true; model.n_elements()],
            dormant: vec![false; model.mesh.n_nodes()],
        }
    }

    /// Number of active elements.
    pub fn n_active(&self) -> usize {
        self.active.iter().filter(|&&a| a).count()
    }

    /// Make the model follow `self.active`: groups rebuilt (surviving elements keep their
    /// states, initial strains and references), elements in `placed` made stress-free at
    /// the displacements `u`, masses recomputed, dormant nodes fixed on top of `base`
    /// constraints, inverse masses refreshed, contact pairs of dormant nodes switched off
    /// and pairs that come alive bonded at rest (their offset at `u` kept).
    pub fn apply(&mut self, model: &mut Model, base: &Constraints, u: &[[f64; 3]], placed: &[u32]) {
        let mut is_placed = vec![false; model.n_elements()];
        for &e in placed {
            is_placed[e as usize] = true;
        }
        for gi in 0..model.groups.len() {
            let active = &self.active;
            let mut g = self.templates[gi].retain_elements(|e| active[e as usize]);
            g.carry_point_data_from(&model.groups[gi]);
            for le in 0..g.len() {
                let e = g.elements[le] as usize;
                if is_placed[e] {
                    let conn = g.conn[le];
                    let ue: [[f64; 3]; 8] = std::array::from_fn(|a| u[conn[a] as usize]);
                    if ue.iter().flatten().any(|&x| x != 0.0) || g.reference.is_some() {
                        g.set_reference(le, ue);
                    }
                    if let Some(e0) = g.initial_strain.as_mut() {
                        let np = g.integration.points();
                        e0[le * np..(le + 1) * np].fill([0.0; 6]);
                    }
                }
            }
            model.groups[gi] = g;
        }
        for loc in model.element_location.iter_mut() {
            *loc = (u32::MAX, u32::MAX);
        }
        for (gi, g) in model.groups.iter().enumerate() {
            for (le, &e) in g.elements.iter().enumerate() {
                model.element_location[e as usize] = (gi as u32, le as u32);
            }
        }
        let mass = model.lumped_masses();
        for (d, &m) in self.dormant.iter_mut().zip(&mass) {
            *d = m <= 0.0;
        }
        model.mass = mass;
        self.constrain(model, base);
        if let Some(c) = model.contact.as_mut() {
            c.set_activity(&self.dormant, u);
        }
    }

    /// Constraints = `base` plus every dormant node fixed in x, y and z; inverse masses
    /// refreshed.
    pub fn constrain(&self, model: &mut Model, base: &Constraints) {
        let mut c = base.clone();
        let dormant: Vec<u32> = (0..self.dormant.len() as u32)
            .filter(|&i| self.dormant[i as usize])
            .collect();
        c.fix(&dormant, 0b111);
        model.constraints = c;
        model.refresh_inverse_mass();
    }

    /// Active flag of every element.
    pub fn active_elements(&self) -> &[bool] {
        &self.active
    }
}
