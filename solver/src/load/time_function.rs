//! Scalar functions of time that scale loads and prescribed motions.

use std::sync::Arc;

use serde::Deserialize;

use crate::error::{DcfmError, Result};
use crate::motion::{motion_by_name, MotionComponent, Motions};

/// Which history of a ground-motion component a [`TimeFunction::Motion`] gives.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum MotionQuantity {
    #[default]
    Acceleration,
    Velocity,
    Displacement,
}

/// A scalar history h(t). In case files: `{ type = "half_sine", amplitude = 0.1, period = 0.02 }`.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(tag = "type", rename_all = "snake_case", deny_unknown_fields)]
pub enum TimeFunction {
    /// h = value.
    Constant { value: f64 },
    /// h = rate · (t − start) after `start`, 0 before.
    Ramp {
        rate: f64,
        #[serde(default)]
        start: f64,
    },
    /// h = amplitude sin(π (t − start)/period) for start ≤ t ≤ start + period, else 0.
    HalfSine {
        amplitude: f64,
        period: f64,
        #[serde(default)]
        start: f64,
    },
    /// h = amplitude sin²(π (t − start)/period) for start ≤ t ≤ start + period, else 0
    /// (a Hann pulse: smooth start and end).
    SineSquared {
        amplitude: f64,
        period: f64,
        #[serde(default)]
        start: f64,
    },
    /// h = amplitude sin(2π f t + phase).
    Sine {
        amplitude: f64,
        frequency: f64,
        #[serde(default)]
        phase: f64,
    },
    /// h = amplitude for start ≤ t < start + duration, else 0.
    Pulse {
        amplitude: f64,
        duration: f64,
        #[serde(default)]
        start: f64,
    },
    /// Piecewise-linear table; constant beyond its ends.
    Table { times: Vec<f64>, values: Vec<f64> },
    /// Ricker wavelet h = amplitude (1 − 2π²f²τ²) exp(−π²f²τ²), τ = t − delay
    /// (f the peak frequency; delay 1.5/f by default, where h is 1e-8 of its peak).
    Ricker {
        amplitude: f64,
        frequency: f64,
        #[serde(default)]
        delay: Option<f64>,
    },
    /// h = scale · q(t − start), q the acceleration (m/s²), velocity or displacement of
    /// component `component` ("x", "y", "z" or the record's own name) of the case's
    /// `[motions.NAME]`: `{ type = "motion", motion = "wolong", component = "x" }`.
    /// Resolved when the case is built ([`TimeFunction::resolve_motions`]); the ground is
    /// at rest before the motion starts. O(1) and allocation-free (see
    /// [`MotionComponent::at`]).
    Motion {
        motion: String,
        component: String,
        #[serde(default)]
        quantity: MotionQuantity,
        #[serde(default = "unit_scale")]
        scale: f64,
        #[serde(default)]
        start: f64,
        /// The component, once resolved.
        #[serde(skip)]
        series: Option<Arc<MotionComponent>>,
    },
}

fn unit_scale() -> f64 {
    1.0
}

impl TimeFunction {
    /// Attach the ground-motion component a [`TimeFunction::Motion`] names (other variants
    /// are left as they are). `field` is the function's path in the case file.
    pub fn resolve_motions(&mut self, motions: &Motions, file: &str, field: &str) -> Result<()> {
        if let TimeFunction::Motion {
            motion,
            component,
            series,
            ..
        } = self
        {
            let m = motion_by_name(motions, motion, file, &format!("{field}.motion"))?;
            let c = m.component_named(component).ok_or_else(|| {
                let names: Vec<String> = m
                    .components
                    .iter()
                    .map(|c| match c.axis {
                        Some(a) => format!("{} ({})", a.name(), c.name),
                        None => c.name.clone(),
                    })
                    .collect();
                DcfmError::invalid(
                    file,
                    format!("{field}.component"),
                    format!("\"{component}\""),
                    format!("a component of motion \"{motion}\": {}", names.join(", ")),
                )
            })?;
            *series = Some(c.clone());
        }
        Ok(())
    }

    /// Check the parameters; `field` is the path of the function in the case file.
    pub fn validate(&self, file: &str, field: &str) -> Result<()> {
        let finite = |name: &str, v: f64| -> Result<()> {
            if v.is_finite() {
                Ok(())
            } else {
                Err(DcfmError::invalid(
                    file,
                    format!("{field}.{name}"),
                    v,
                    "must be finite",
                ))
            }
        };
        let positive = |name: &str, v: f64| -> Result<()> {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                Err(DcfmError::invalid(
                    file,
                    format!("{field}.{name}"),
                    v,
                    "must be finite and > 0",
                ))
            }
        };
        match self {
            TimeFunction::Constant { value } => finite("value", *value),
            TimeFunction::Ramp { rate, start } => {
                finite("rate", *rate)?;
                finite("start", *start)
            }
            TimeFunction::HalfSine {
                amplitude,
                period,
                start,
            } => {
                finite("amplitude", *amplitude)?;
                positive("period", *period)?;
                finite("start", *start)
            }
            TimeFunction::SineSquared {
                amplitude,
                period,
                start,
            } => {
                finite("amplitude", *amplitude)?;
                positive("period", *period)?;
                finite("start", *start)
            }
            TimeFunction::Sine {
                amplitude,
                frequency,
                phase,
            } => {
                finite("amplitude", *amplitude)?;
                positive("frequency", *frequency)?;
                finite("phase", *phase)
            }
            TimeFunction::Pulse {
                amplitude,
                duration,
                start,
            } => {
                finite("amplitude", *amplitude)?;
                positive("duration", *duration)?;
                finite("start", *start)
            }
            TimeFunction::Ricker {
                amplitude,
                frequency,
                delay,
            } => {
                finite("amplitude", *amplitude)?;
                positive("frequency", *frequency)?;
                if let Some(d) = delay {
                    finite("delay", *d)?;
                }
                Ok(())
            }
            TimeFunction::Motion {
                motion,
                scale,
                start,
                series,
                ..
            } => {
                finite("scale", *scale)?;
                finite("start", *start)?;
                if series.is_none() {
                    return Err(DcfmError::invalid(
                        file,
                        format!("{field}.motion"),
                        format!("\"{motion}\""),
                        "a motion resolved from [motions.NAME] (this function was not resolved)",
                    ));
                }
                Ok(())
            }
            TimeFunction::Table { times, values } => {
                if times.is_empty() || times.len() != values.len() {
                    return Err(DcfmError::invalid(
                        file,
                        format!("{field}.times"),
                        format!("{} times, {} values", times.len(), values.len()),
                        "non-empty and as many times as values",
                    ));
                }
                for (i, w) in times.windows(2).enumerate() {
                    if w[1].is_nan() || w[1] <= w[0] {
                        return Err(DcfmError::invalid(
                            file,
                            format!("{field}.times[{}]", i + 1),
                            w[1],
                            "times must increase strictly",
                        ));
                    }
                }
                for (i, v) in times.iter().chain(values).enumerate() {
                    if !v.is_finite() {
                        return Err(DcfmError::invalid(
                            file,
                            format!("{field}[{i}]"),
                            v,
                            "must be finite",
                        ));
                    }
                }
                Ok(())
            }
        }
    }

    /// h(t).
    pub fn value(&self, t: f64) -> f64 {
        match self {
            TimeFunction::Constant { value } => *value,
            TimeFunction::Ramp { rate, start } => {
                if t > *start {
                    rate * (t - start)
                } else {
                    0.0
                }
            }
            TimeFunction::HalfSine {
                amplitude,
                period,
                start,
            } => {
                let s = t - start;
                if (0.0..=*period).contains(&s) {
                    amplitude * (std::f64::consts::PI * s / period).sin()
                } else {
                    0.0
                }
            }
            TimeFunction::SineSquared {
                amplitude,
                period,
                start,
            } => {
                let s = t - start;
                if (0.0..=*period).contains(&s) {
                    amplitude * (std::f64::consts::PI * s / period).sin().powi(2)
                } else {
                    0.0
                }
            }
            TimeFunction::Sine {
                amplitude,
                frequency,
                phase,
            } => amplitude * (2.0 * std::f64::consts::PI * frequency * t + phase).sin(),
            TimeFunction::Pulse {
                amplitude,
                duration,
                start,
            } => {
                if t >= *start && t < start + duration {
                    *amplitude
                } else {
                    0.0
                }
            }
            TimeFunction::Ricker {
                amplitude,
                frequency,
                delay,
            } => {
                let tau = t - delay.unwrap_or(1.5 / frequency);
                let a = (std::f64::consts::PI * frequency * tau).powi(2);
                amplitude * (1.0 - 2.0 * a) * (-a).exp()
            }
            TimeFunction::Table { times, values } => {
                let n = times.len();
                if t <= times[0] {
                    return values[0];
                }
                if t >= times[n - 1] {
                    return values[n - 1];
                }
                let i = times.partition_point(|&x| x <= t) - 1;
                let w = (t - times[i]) / (times[i + 1] - times[i]);
                values[i] + w * (values[i + 1] - values[i])
            }
            TimeFunction::Motion {
                quantity,
                scale,
                start,
                series,
                ..
            } => match series {
                Some(c) => {
                    let k = c.at(t - start);
                    scale
                        * match quantity {
                            MotionQuantity::Acceleration => k.a,
                            MotionQuantity::Velocity => k.v,
                            MotionQuantity::Displacement => k.u,
                        }
                }
                // Unresolved (validate rejects it): loud rather than silently zero.
                None => f64::NAN,
            },
        }
    }

    /// ∫₀ᵗ h dτ (exact for the analytic forms, trapezoidal for tables) — used when a
    /// velocity history must give a displacement.
    pub fn integral(&self, t: f64) -> f64 {
        use std::f64::consts::PI;
        match self {
            TimeFunction::Constant { value } => value * t,
            TimeFunction::Ramp { rate, start } => {
                if t > *start {
                    0.5 * rate * (t - start).powi(2)
                } else {
                    0.0
                }
            }
            TimeFunction::HalfSine {
                amplitude,
                period,
                start,
            } => {
                let s = (t - start).clamp(0.0, *period);
                amplitude * period / PI * (1.0 - (PI * s / period).cos())
            }
            TimeFunction::SineSquared {
                amplitude,
                period,
                start,
            } => {
                let s = (t - start).clamp(0.0, *period);
                amplitude * (0.5 * s - period / (4.0 * PI) * (2.0 * PI * s / period).sin())
            }
            TimeFunction::Sine {
                amplitude,
                frequency,
                phase,
            } => {
                let w = 2.0 * PI * frequency;
                amplitude / w * (phase.cos() - (w * t + phase).cos())
            }
            TimeFunction::Pulse {
                amplitude,
                duration,
                start,
            } => amplitude * (t - start).clamp(0.0, *duration),
            TimeFunction::Ricker {
                amplitude,
                frequency,
                delay,
            } => {
                // d/dτ [τ exp(−π²f²τ²)] = (1 − 2π²f²τ²) exp(−π²f²τ²).
                let t0 = delay.unwrap_or(1.5 / frequency);
                let a = (PI * frequency).powi(2);
                let g = |tau: f64| tau * (-a * tau * tau).exp();
                amplitude * (g(t - t0) - g(-t0))
            }
            TimeFunction::Table { times, values } => {
                let mut acc = 0.0;
                let mut prev_t = 0.0f64.min(times[0]);
                let mut prev_v = self.value(prev_t);
                for (&ti, &vi) in times.iter().zip(values) {
                    if ti >= t {
                        break;
                    }
                    if ti > prev_t {
                        acc += 0.5 * (prev_v + vi) * (ti - prev_t);
                        prev_t = ti;
                        prev_v = vi;
                    }
                }
                if t > prev_t {
                    acc += 0.5 * (prev_v + self.value(t)) * (t - prev_t);
                }
                acc
            }
            TimeFunction::Motion {
                quantity,
                scale,
                start,
                series,
                ..
            } => match series {
                Some(c) => {
                    // ∫₀ᵗ q(τ − start) dτ = F(t − start) − F(−start), F(s) = ∫₀ˢ q.
                    let f = |s: f64| match quantity {
                        MotionQuantity::Acceleration => c.at(s).v,
                        MotionQuantity::Velocity => c.at(s).u,
                        MotionQuantity::Displacement => c.displacement_integral_at(s),
                    };
                    scale * (f(t - start) - f(-start))
                }
                None => f64::NAN,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_sine_integral_is_net_displacement() {
        // VERIFICATION.md W1: net displacement 2 v0 T / π = 1.2732 mm for v0 0.1, T 0.02.
        let h = TimeFunction::HalfSine {
            amplitude: 0.1,
            period: 0.02,
            start: 0.0,
        };
        assert!((h.integral(1.0) - 1.2732e-3).abs() < 1e-7);
        assert!((h.value(0.01) - 0.1).abs() < 1e-15);
    }

    #[test]
    fn ricker_integral_matches_quadrature() {
        let h = TimeFunction::Ricker {
            amplitude: 2.0,
            frequency: 5.0,
            delay: None,
        };
        assert!((h.value(0.3) - 2.0).abs() < 1e-15);
        let n = 20000;
        let t = 0.5;
        let dt = t / n as f64;
        let quad: f64 = (0..n)
            .map(|k| 0.5 * dt * (h.value(k as f64 * dt) + h.value((k + 1) as f64 * dt)))
            .sum();
        assert!(
            (h.integral(t) - quad).abs() < 1e-8,
            "{} vs {quad}",
            h.integral(t)
        );
        // The wavelet has zero mean: its integral returns to ~0.
        assert!(h.integral(1.0).abs() < 1e-8);
    }

    #[test]
    fn table_interpolates_and_integrates() {
        let h = TimeFunction::Table {
            times: vec![0.0, 1.0, 2.0],
            values: vec![0.0, 2.0, 2.0],
        };
        assert_eq!(h.value(0.5), 1.0);
        assert!((h.integral(2.0) - 3.0).abs() < 1e-14);
        assert!(TimeFunction::Table {
            times: vec![1.0, 1.0],
            values: vec![0.0, 1.0]
        }
        .validate("c.toml", "loads[0].history")
        .unwrap_err()
        .to_string()
        .contains("c.toml: loads[0].history.times[1] = 1"));
    }
}
