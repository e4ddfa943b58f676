//! The processed motion the solver consumes: per component the acceleration, velocity and
//! displacement on one uniform grid, consistent with each other (v and u are the exact
//! integrals of the piecewise-linear acceleration, see [`super::processing::integrate`]).
//!
//! Evaluation at any time is O(1) and allocation-free: index arithmetic on the uniform
//! grid, then the exact kinematics of a linear acceleration inside the step. Before t = 0
//! the ground is at rest; after the last sample the acceleration is zero, the velocity
//! keeps its final value and the displacement grows with it (both end near zero after the
//! usual processing).

use std::sync::Arc;

use super::readers::Format;
use super::record::Axis;
use super::units::AccelUnits;

/// Acceleration (m/s²), velocity (m/s) and displacement (m) at one time.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Kinematics {
    pub a: f64,
    pub v: f64,
    pub u: f64,
}

/// One component of a ground motion.
#[derive(Clone, Debug, PartialEq)]
pub struct MotionComponent {
    /// The record's name for it ("EW", "090", "x", …).
    pub name: String,
    /// The model axis it drives, when known.
    pub axis: Option<Axis>,
    /// Step (s); sample i is at t = i·dt.
    pub dt: f64,
    pub acceleration: Vec<f64>,
    pub velocity: Vec<f64>,
    pub displacement: Vec<f64>,
    /// ∫₀^{t_i} u dt, for the integral of a displacement history.
    displacement_integral: Vec<f64>,
}

impl MotionComponent {
    /// A component from its acceleration samples (m/s², step `dt` s), integrated from rest.
    pub fn new(
        name: impl Into<String>,
        axis: Option<Axis>,
        dt: f64,
        acceleration: Vec<f64>,
    ) -> Self {
        let (velocity, displacement) = super::processing::integrate::integrate(&acceleration, dt);
        let n = acceleration.len();
        let mut w = vec![0.0; n];
        for i in 1..n {
            // ∫ u over a step of linear acceleration: Δt u_i + Δt² v_i/2 + Δt³ (3a_i + a_{i+1})/24.
            w[i] = w[i - 1]
                + dt * displacement[i - 1]
                + dt * dt * velocity[i - 1] / 2.0
                + dt * dt * dt * (3.0 * acceleration[i - 1] + acceleration[i]) / 24.0;
        }
        Self {
            name: name.into(),
            axis,
            dt,
            acceleration,
            velocity,
            displacement,
            displacement_integral: w,
        }
    }

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.acceleration.len()
    }

    /// True when there is no sample.
    pub fn is_empty(&self) -> bool {
        self.acceleration.is_empty()
    }

    /// Time of the last sample (s).
    pub fn duration(&self) -> f64 {
        self.len().saturating_sub(1) as f64 * self.dt
    }

    /// Index of the step holding t and the time into it, or where t lies outside.
    #[inline]
    fn locate(&self, t: f64) -> Place {
        let n = self.acceleration.len();
        if n == 0 || t.is_nan() || t <= 0.0 {
            return Place::Before;
        }
        let x = t / self.dt;
        if x > (n - 1) as f64 {
            return Place::After(t - self.duration());
        }
        let i = x as usize;
        Place::Inside(i.min(n - 2), t - i.min(n - 2) as f64 * self.dt)
    }

    /// (a, v, u) at time t — exact kinematics of the piecewise-linear acceleration.
    #[inline]
    pub fn at(&self, t: f64) -> Kinematics {
        match self.locate(t) {
            Place::Before => Kinematics::default(),
            Place::After(s) => {
                let n = self.len();
                Kinematics {
                    a: 0.0,
                    v: self.velocity[n - 1],
                    u: self.displacement[n - 1] + self.velocity[n - 1] * s,
                }
            }
            Place::Inside(i, s) => {
                let (a0, a1) = (self.acceleration[i], self.acceleration[i + 1]);
                let slope = (a1 - a0) / self.dt;
                Kinematics {
                    a: a0 + slope * s,
                    v: self.velocity[i] + a0 * s + 0.5 * slope * s * s,
                    u: self.displacement[i]
                        + self.velocity[i] * s
                        + 0.5 * a0 * s * s
                        + slope * s * s * s / 6.0,
                }
            }
        }
    }

    /// ∫₀ᵗ u dτ (the integral of the displacement history), O(1).
    #[inline]
    pub fn displacement_integral_at(&self, t: f64) -> f64 {
        match self.locate(t) {
            Place::Before => 0.0,
            Place::After(s) => {
                let n = self.len();
                self.displacement_integral[n - 1]
                    + self.displacement[n - 1] * s
                    + 0.5 * self.velocity[n - 1] * s * s
            }
            Place::Inside(i, s) => {
                let (a0, a1) = (self.acceleration[i], self.acceleration[i + 1]);
                let slope = (a1 - a0) / self.dt;
                self.displacement_integral[i]
                    + self.displacement[i] * s
                    + 0.5 * self.velocity[i] * s * s
                    + a0 * s * s * s / 6.0
                    + slope * s * s * s * s / 24.0
            }
        }
    }
}

enum Place {
    Before,
    Inside(usize, f64),
    After(f64),
}

/// A processed ground motion: components on one grid plus where it came from and every
/// processing step applied (the provenance, written in the header of every output).
#[derive(Clone, Debug, PartialEq)]
pub struct GroundMotion {
    /// Case name (`[motions.NAME]`) or file stem.
    pub name: String,
    /// File(s) or generator it came from.
    pub source: String,
    pub format: Format,
    pub station: String,
    pub description: String,
    /// Units the file stored (everything here is SI).
    pub original_units: AccelUnits,
    /// Step (s) of every component.
    pub dt: f64,
    pub components: Vec<Arc<MotionComponent>>,
    /// One line per step: reading, window, baseline, taper, filter, resampling, end
    /// correction, scaling, integration.
    pub provenance: Vec<String>,
}

impl GroundMotion {
    /// The component that drives `axis`.
    pub fn component(&self, axis: Axis) -> Option<&Arc<MotionComponent>> {
        self.components.iter().find(|c| c.axis == Some(axis))
    }

    /// The component called `name`: an axis ("x", "y", "z") or the record's own name
    /// ("EW", "090", …; case-insensitive).
    pub fn component_named(&self, name: &str) -> Option<&Arc<MotionComponent>> {
        if let Some(axis) = Axis::parse(name) {
            if let Some(c) = self.component(axis) {
                return Some(c);
            }
        }
        self.components
            .iter()
            .find(|c| c.name.eq_ignore_ascii_case(name.trim()))
    }

    /// (a, v, u) of the `axis` component at time t; zero for an axis the motion lacks.
    #[inline]
    pub fn at(&self, axis: Axis, t: f64) -> Kinematics {
        self.component(axis).map(|c| c.at(t)).unwrap_or_default()
    }

    /// Number of samples per component.
    pub fn npts(&self) -> usize {
        self.components.iter().map(|c| c.len()).min().unwrap_or(0)
    }

    /// Time of the last sample (s).
    pub fn duration(&self) -> f64 {
        self.npts().saturating_sub(1) as f64 * self.dt
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn kinematics_between_samples_are_exact_for_linear_acceleration() {
        // a = 2 + 3t: v = 2t + 1.5t², u = t² + t³/2, ∫u = t³/3 + t⁴/8.
        let dt = 0.25;
        let a: Vec<f64> = (0..9).map(|i| 2.0 + 3.0 * i as f64 * dt).collect();
        let c = MotionComponent::new("x", Some(Axis::X), dt, a);
        for &t in &[0.1, 0.6, 1.37, 2.0] {
            let k = c.at(t);
            assert!((k.a - (2.0 + 3.0 * t)).abs() < 1e-12);
            assert!((k.v - (2.0 * t + 1.5 * t * t)).abs() < 1e-12);
            assert!((k.u - (t * t + 0.5 * t * t * t)).abs() < 1e-12);
            let w = t * t * t / 3.0 + t * t * t * t / 8.0;
            assert!((c.displacement_integral_at(t) - w).abs() < 1e-12, "{t}");
        }
        let after = c.at(3.0);
        assert_eq!(after.a, 0.0);
        assert_eq!(c.at(-1.0), Kinematics::default());
    }
}
