//! The seismic input motion: vertically incident plane waves — P in z, SV/SH in x and y
//! (any horizontal polarisation is a combination of the two) — given as three time
//! functions of acceleration or velocity, and what they mean:
//!
//! - `incident`: the upgoing wave at the model's base, u_in(t); the ground below the base
//!   is a half-space of the base material (transmitting base).
//! - `outcrop`: the motion recorded on a rock outcrop of the base material. A free surface
//!   doubles an upgoing plane wave, so the incident wave is half of it:
//!   u_in = ½ u_outcrop (Kramer 1996, §7.2; SHAKE's "outcrop" convention).
//! - `within`: the total motion (up + down) at the base's depth, as recorded in a borehole
//!   there; the free field is then driven by a rigid base following it.
//!
//! docs/boundaries.md §4 gives the conversions and how the equivalent nodal forces
//! F = A (K u_ff + C v_ff + σ_ff·n) follow from the free-field solution.

use serde::Deserialize;

use crate::boundary::MotionKind;
use crate::error::{DcfmError, Result};
use crate::load::TimeFunction;

/// What the given motion is.
#[derive(Clone, Copy, Debug, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum MotionDefinition {
    /// Upgoing (incident) wave at the base.
    Incident,
    /// Rock-outcrop motion: twice the incident wave.
    Outcrop,
    /// Total motion at the base's depth (borehole record).
    Within,
}

/// The input motion: up to three components and their meaning.
#[derive(Clone, Debug)]
pub struct SeismicMotion {
    /// Components x, y (SV/SH) and z (P); `None` is zero.
    pub components: [Option<TimeFunction>; 3],
    /// Acceleration (m/s²) or velocity (m/s).
    pub quantity: MotionKind,
    pub definition: MotionDefinition,
}

impl SeismicMotion {
    /// Check the motion; `field` is its path in the case file.
    pub fn validate(&self, file: &str, field: &str) -> Result<()> {
        if self.quantity == MotionKind::Displacement {
            return Err(DcfmError::invalid(
                file,
                format!("{field}.quantity"),
                "\"displacement\"",
                "\"acceleration\" or \"velocity\"",
            ));
        }
        if self.components.iter().all(Option::is_none) {
            return Err(DcfmError::invalid(
                file,
                field,
                "no component",
                "at least one of x, y, z (a time function)",
            ));
        }
        for (d, c) in self.components.iter().enumerate() {
            if let Some(h) = c {
                h.validate(file, &format!("{field}.{}", ["x", "y", "z"][d]))?;
            }
        }
        Ok(())
    }

    /// Scale from the given motion to what drives the free field: ½ for an outcrop motion
    /// (→ incident), 1 otherwise.
    fn scale(&self) -> f64 {
        match self.definition {
            MotionDefinition::Outcrop => 0.5,
            MotionDefinition::Incident | MotionDefinition::Within => 1.0,
        }
    }

    /// Particle velocity of the driving motion at time t (incident wave for
    /// incident/outcrop, total motion for within).
    pub fn velocity(&self, t: f64) -> [f64; 3] {
        let s = self.scale();
        std::array::from_fn(|d| match &self.components[d] {
            None => 0.0,
            Some(h) => {
                s * match self.quantity {
                    MotionKind::Velocity => h.value(t),
                    // v(t) = ∫₀ᵗ a dτ (the record starts at rest).
                    _ => h.integral(t),
                }
            }
        })
    }

    /// Half-step velocity V^{n+½} of the driving motion over [t, t + Δt]: the exact
    /// displacement increment over Δt for a velocity history, the velocity at the half
    /// step for an acceleration history (the prescribed-motion rules of boundary::Prescribed).
    pub fn half_step_velocity(&self, t: f64, dt: f64) -> [f64; 3] {
        let s = self.scale();
        std::array::from_fn(|d| match &self.components[d] {
            None => 0.0,
            Some(h) => {
                s * match self.quantity {
                    MotionKind::Velocity => (h.integral(t + dt) - h.integral(t)) / dt,
                    _ => h.integral(t + 0.5 * dt),
                }
            }
        })
    }
}

/// `[seismic]`: the input motion and the free field's profile above the model.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SeismicSection {
    /// Component along x (SV/SH).
    #[serde(default)]
    pub x: Option<TimeFunction>,
    /// Component along y (SV/SH).
    #[serde(default)]
    pub y: Option<TimeFunction>,
    /// Vertical component (P).
    #[serde(default)]
    pub z: Option<TimeFunction>,
    /// "acceleration" (default, m/s²) or "velocity" (m/s).
    #[serde(default = "default_quantity")]
    pub quantity: MotionKind,
    /// "incident", "outcrop" or "within" (required: the case says which).
    pub definition: MotionDefinition,
    /// Plan position [x, y] of the vertical line whose layering the reference free-field
    /// column takes (default: the corner of the base nearest the bounding box's minimum).
    #[serde(default)]
    pub profile_at: Option<[f64; 2]>,
    /// Layers between the model's top and the ground surface, bottom to top (deep models).
    #[serde(default)]
    pub overburden: Vec<OverburdenLayer>,
}

fn default_quantity() -> MotionKind {
    MotionKind::Acceleration
}

impl SeismicSection {
    /// The motion of the section.
    pub fn motion(&self) -> SeismicMotion {
        SeismicMotion {
            components: [self.x.clone(), self.y.clone(), self.z.clone()],
            quantity: self.quantity,
            definition: self.definition,
        }
    }
}

/// `[[seismic.overburden]]`: one layer above the model's top.
#[derive(Clone, Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct OverburdenLayer {
    /// Thickness (m).
    pub thickness: f64,
    /// A `[materials]` name (its elastic constants and density are used).
    pub material: String,
    /// Elements across the layer (default: elements of about the model's top element height).
    #[serde(default)]
    pub divisions: Option<usize>,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn outcrop_is_twice_the_incident_wave() {
        let h = TimeFunction::Sine {
            amplitude: 2.0,
            frequency: 1.0,
            phase: 0.0,
        };
        let m = SeismicMotion {
            components: [Some(h.clone()), None, None],
            quantity: MotionKind::Velocity,
            definition: MotionDefinition::Outcrop,
        };
        assert!((m.velocity(0.25)[0] - 1.0).abs() < 1e-15);
        let a = SeismicMotion {
            components: [None, None, Some(h)],
            quantity: MotionKind::Acceleration,
            definition: MotionDefinition::Incident,
        };
        // v = ∫ 2 sin 2πt = (1 − cos 2πt)/π.
        assert!((a.velocity(0.5)[2] - 2.0 / std::f64::consts::PI).abs() < 1e-14);
    }
}
