//! The measures of every component of a motion, as `dcfm motion` prints them.

use super::ground_motion::GroundMotion;
use super::measures::{arias_intensity, peak, significant_duration, Peak};

/// Measures of one component.
#[derive(Clone, Debug, PartialEq)]
pub struct ComponentSummary {
    pub name: String,
    /// "x", "y", "z" or "-".
    pub axis: String,
    pub pga: Peak,
    pub pgv: Peak,
    pub pgd: Peak,
    /// Arias intensity (m/s).
    pub arias: f64,
    /// Times of 5 % and 95 % of the Arias intensity and D5–95 (s).
    pub d5_95: Option<(f64, f64, f64)>,
    /// Final velocity and displacement.
    pub v_end: f64,
    pub u_end: f64,
}

/// Measures of every component.
pub fn summarize(motion: &GroundMotion) -> Vec<ComponentSummary> {
    motion
        .components
        .iter()
        .map(|c| ComponentSummary {
            name: c.name.clone(),
            axis: c
                .axis
                .map(|a| a.name().to_string())
                .unwrap_or_else(|| "-".into()),
            pga: peak(&c.acceleration, c.dt),
            pgv: peak(&c.velocity, c.dt),
            pgd: peak(&c.displacement, c.dt),
            arias: arias_intensity(&c.acceleration, c.dt),
            d5_95: significant_duration(&c.acceleration, c.dt, 0.05, 0.95),
            v_end: c.velocity.last().copied().unwrap_or(0.0),
            u_end: c.displacement.last().copied().unwrap_or(0.0),
        })
        .collect()
}
