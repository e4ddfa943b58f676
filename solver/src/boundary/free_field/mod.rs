//! The free field: the motion the ground would have without the model's cavern and
//! structures, computed alongside the main grid in the same explicit step and felt by
//! the main grid through its boundaries (FLAC3D's free-field boundary; Nielsen 2006).
//!
//! - [`column`]: 1D layered columns (vertically incident P, SV, SH), transmitting or
//!   rigid base, free surface on top: the reference column that drives the seismic input
//!   at the base and the coupling of a buried top, and one column at each vertical edge
//!   of the free-field sides;
//! - [`wall`]: plane free-field walls beside the vertical sides, one element per side
//!   face, coupled to the edge columns at their ends;
//! - [`sides`]: building the walls and edge columns from the sides' face sets.
//!
//! Stepping order within a step: every column (driven by the same base motion), then
//! every wall (reading the columns at tⁿ); the main grid then reads columns and walls at
//! tⁿ. The free field is not loaded by the main grid (one-way coupling).

pub mod column;
pub mod sides;
pub mod wall;

use serde::Deserialize;

use crate::boundary::absorbing::SetNames;
use crate::boundary::seismic_input::SeismicMotion;
use column::{BaseDrive, Column, ColumnBase, ColumnElement};
use wall::Wall;

/// `[boundary.free_field]`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct FreeFieldSection {
    /// The model's vertical sides that get free-field walls: each entry one plane
    /// vertical side (a face set, or a list of face sets forming it, e.g. one per layer).
    #[serde(default)]
    pub sides: Vec<SetNames>,
    /// The model's top face set when it lies below the ground surface: coupled to the
    /// free-field column at its depth (dashpots on the relative velocity plus the
    /// overburden's free-field traction). Needs `[[seismic.overburden]]`.
    #[serde(default)]
    pub top: Option<SetNames>,
}

/// The layering of one column, before Δt is known.
#[derive(Clone, Debug)]
pub struct ColumnSpec {
    /// Plan position (m), for messages.
    pub at: [f64; 2],
    pub levels: Vec<f64>,
    pub elements: Vec<ColumnElement>,
}

/// All free-field grids of a model and the motion driving them.
#[derive(Clone, Debug)]
pub struct FreeField {
    /// Columns; index 0 is the reference column.
    pub specs: Vec<ColumnSpec>,
    /// Built by [`FreeField::prepare`].
    pub columns: Vec<Column>,
    pub walls: Vec<Wall>,
    pub motion: SeismicMotion,
    pub base: ColumnBase,
    /// Level of the model's top in the reference column.
    pub model_top_level: usize,
}

impl FreeField {
    /// Build the columns for Δt; prepare the walls.
    pub fn prepare(&mut self, dt: f64) {
        self.columns = self
            .specs
            .iter()
            .map(|s| Column::new(s.levels.clone(), s.elements.clone(), self.base, dt))
            .collect();
        for w in self.walls.iter_mut() {
            w.prepare(dt);
        }
    }

    /// Step every column, then every wall, from tⁿ to tⁿ⁺¹.
    pub fn step(&mut self, t: f64, dt: f64) {
        let drive = match self.base {
            ColumnBase::Transmitting => BaseDrive::Incident(self.motion.velocity(t)),
            ColumnBase::Rigid => BaseDrive::HalfStepVelocity(self.motion.half_step_velocity(t, dt)),
        };
        for c in self.columns.iter_mut() {
            c.step(drive, dt);
        }
        for w in self.walls.iter_mut() {
            w.step(&self.columns, dt);
        }
    }

    /// Critical step of the free-field grids: columns min h/c_p, walls 2/ω_max.
    pub fn critical_step(&self) -> f64 {
        let columns = self
            .specs
            .iter()
            .flat_map(|s| s.elements.iter())
            .map(|e| e.height / e.material.p_wave_speed())
            .fold(f64::INFINITY, f64::min);
        let walls = self
            .walls
            .iter()
            .map(|w| 2.0 / w.max_omega_squared().sqrt())
            .fold(f64::INFINITY, f64::min);
        columns.min(walls)
    }

    /// The reference column (after [`FreeField::prepare`]).
    pub fn reference(&self) -> Option<&Column> {
        self.columns.first()
    }

    /// State for checkpoints.
    pub fn state_values(&self, out: &mut Vec<f64>) {
        for c in &self.columns {
            c.state_values(out);
        }
        for w in &self.walls {
            w.state_values(out);
        }
    }

    /// Restore what [`FreeField::state_values`] wrote; returns the values consumed.
    pub fn restore_state(&mut self, values: &[f64]) -> Result<usize, String> {
        let mut used = 0;
        for c in self.columns.iter_mut() {
            used += c.restore_state(&values[used..])?;
        }
        for w in self.walls.iter_mut() {
            used += w.restore_state(&values[used..])?;
        }
        Ok(used)
    }
}
