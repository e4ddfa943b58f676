//! A column of hex8 elements one element wide, driven at its base — the 1D wave set-up of
//! docs/verification_references.md §W1.
//!
//! ```text
//!   top (free or fixed)   z = H
//!   ┌─┐
//!   │ │  one element wide, lateral DOFs constrained so that only the chosen wave travels
//!   │ │
//!   └─┘  base: prescribed velocity v0 sin(πt/T)    z = 0
//! ```

use dcfm::boundary::{MotionKind, Prescribed};
use dcfm::element::Integration;
use dcfm::load::TimeFunction;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup};
use dcfm::stage::Simulation;
use dcfm::Result;

use crate::analytic::PulseShape;

/// Which wave the column carries.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Wave {
    /// Uniaxial strain: lateral DOFs fixed, base moves vertically.
    P,
    /// Horizontal motion only: y and z fixed, base moves along x.
    S,
}

/// Boundary at the top of the column.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum TopEnd {
    Free,
    Fixed,
}

/// Column parameters.
#[derive(Clone, Copy, Debug)]
pub struct ColumnSetup {
    pub height: f64,
    pub element_size: f64,
    pub wave: Wave,
    pub top: TopEnd,
    pub integration: Integration,
    /// Δt as a fraction of h / c_p.
    pub courant_p: f64,
    pub v0: f64,
    pub period: f64,
    pub shape: PulseShape,
    pub young: f64,
    pub poisson: f64,
    pub density: f64,
}

impl ColumnSetup {
    /// docs/verification_references.md §W1 defaults: 200 m, default rock, v0 0.1 m/s, T 0.02 s, h = 1 m.
    pub fn w1(wave: Wave, top: TopEnd) -> Self {
        Self {
            height: 200.0,
            element_size: 1.0,
            wave,
            top,
            integration: Integration::Full,
            courant_p: 0.9,
            v0: 0.1,
            period: 0.02,
            shape: PulseShape::HalfSine,
            young: 20e9,
            poisson: 0.25,
            density: 2700.0,
        }
    }

    /// The wave speed of the chosen wave.
    pub fn speed(&self) -> f64 {
        let e = Elastic::new("rock", self.young, self.poisson, self.density).expect("valid rock");
        match self.wave {
            Wave::P => e.p_wave_speed(),
            Wave::S => e.s_wave_speed(),
        }
    }

    /// Build the simulation. Node sets: `col.zmin` (base), `col.zmax` (top).
    pub fn build(&self) -> Result<Simulation> {
        let n = (self.height / self.element_size).round() as usize;
        let h = self.element_size;
        let mesh =
            BoxMeshSpec::single("col", [0.0; 3], [h, h, self.height], [1, 1, n]).build("column")?;
        let elastic = Elastic::new("rock", self.young, self.poisson, self.density)?;
        let setup = RegionSetup {
            region: "col".into(),
            material: Material::Elastic(elastic),
            integration: self.integration,
            hourglass: 0.05,
        };
        let mut model = Model::new(mesh, &[setup], "column")?;
        let all: Vec<u32> = (0..model.mesh.n_nodes() as u32).collect();
        let base = model.mesh.node_sets["col.zmin"].clone();
        let top = model.mesh.node_sets["col.zmax"].clone();
        let (lateral, dof) = match self.wave {
            Wave::P => (0b011, 2),
            Wave::S => (0b110, 0),
        };
        model.constraints.fix(&all, lateral);
        if self.top == TopEnd::Fixed {
            model.constraints.fix(&top, 1 << dof);
        }
        model
            .constraints
            .prescribe(Prescribed {
                nodes: base,
                dof,
                kind: MotionKind::Velocity,
                history: match self.shape {
                    PulseShape::HalfSine => TimeFunction::HalfSine {
                        amplitude: self.v0,
                        period: self.period,
                        start: 0.0,
                    },
                    PulseShape::SineSquared => TimeFunction::SineSquared {
                        amplitude: self.v0,
                        period: self.period,
                        start: 0.0,
                    },
                },
            })
            .map_err(|n| dcfm::DcfmError::Mesh(format!("node {n} constrained twice")))?;
        // The column moves in one direction only, so its stable limit is the 1D one,
        // Δt = h/c_p (lumped 1D central difference is exact there), not the 3D single-element
        // bound 0.775 h/c_p that the model's critical step (rightly) uses for free elements.
        let c_p = elastic.p_wave_speed();
        let dt = self.courant_p * h / c_p;
        if self.courant_p > 1.0 {
            return Err(dcfm::DcfmError::invalid(
                "column",
                "courant_p",
                self.courant_p,
                "≤ 1 (1D stability)",
            ));
        }
        Ok(Simulation::new_unchecked(model, dt))
    }
}

/// Index of the element whose centre is nearest height z in a column built by
/// [`ColumnSetup::build`] (elements are stacked in z order, one per layer).
pub fn element_at(setup: &ColumnSetup, z: f64) -> usize {
    let n = (setup.height / setup.element_size).round() as usize;
    ((z / setup.element_size).floor() as usize).min(n - 1)
}

/// Node of the column on the axis corner (x = 0, y = 0) nearest height z.
pub fn node_at(setup: &ColumnSetup, z: f64) -> usize {
    let k = (z / setup.element_size).round() as usize;
    4 * k
}
