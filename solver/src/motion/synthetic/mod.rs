//! Seeded synthetic three-component ground motion: filtered white noise (Clough–Penzien
//! spectral shape: Kanai–Tajimi ground filter followed by a second-order high-pass, Clough
//! & Penzien, *Dynamics of Structures*, 2nd ed., §24-4 / Penzien & Watabe 1975) modulated
//! by a time envelope of one or more strong phases ([`envelope`]), then aligned, corrected
//! and scaled:
//!
//! 1. wᵢ: standard normal numbers from ChaCha20, one stream per axis ([`noise`]);
//! 2. Kanai–Tajimi: ẍ + 2ζ_gω_gẋ + ω_g²x = −w, output a₁ = −(2ζ_gω_gẋ + ω_g²x)
//!    (|H|² = (ω_g⁴ + 4ζ_g²ω_g²ω²)/((ω_g² − ω²)² + 4ζ_g²ω_g²ω²));
//! 3. high-pass: ÿ + 2ζ_fω_fẏ + ω_f²y = −a₁, output a₂ = ÿ (|H|² = ω⁴/((ω_f² − ω²)² +
//!    4ζ_f²ω_f²ω²)), which removes the long periods that would make the displacement drift;
//!    both filters are stepped with the exact Nigam–Jennings recursion
//!    ([`crate::motion::measures::spectrum::SdofCoefficients`], IEEE operations only);
//! 4. a₃ = e(t)·a₂, the envelope;
//! 5. where a `peak_time` is set, the peak is placed there: a Gaussian bump
//!    1 + β exp(−((t − t_p)/0.3 s)²) on the envelope, β raised (0.25, ×1.5, …) until the
//!    largest |a| within ±0.5 s of t_p exceeds every other by 10 %, then the component is
//!    shifted by whole samples (|shift| ≤ 0.5 s) so that its largest sample falls on t_p;
//! 6. the linear acceleration α + βt that zeroes the final velocity and displacement is
//!    removed ([`crate::motion::processing::integrate::zero_end_motion`]);
//! 7. the component is scaled to its `pga` exactly.
//!
//! Same seed, same motion, bit for bit, on every machine: the generator uses ChaCha20 and
//! libm (pure Rust) for every transcendental function, sums in a fixed order, runs on one
//! thread, and Rust does not contract a·b + c into fused multiply-adds.

pub mod envelope;
pub mod noise;
pub mod wolong;

use std::collections::BTreeMap;

use serde::Deserialize;

use crate::error::{DcfmError, Result};

use super::measures::spectrum::SdofCoefficients;
use super::processing::integrate::zero_end_motion;
use super::readers::Format;
use super::record::{Axis, Record, RecordComponent};
use super::units::AccelUnits;
pub use envelope::Phase;
use noise::GaussianStream;

/// Spectral shape and peak of one synthetic component.
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ComponentShape {
    /// Name written in outputs (default: the axis, or the preset's EW/NS/UD).
    #[serde(default)]
    pub name: Option<String>,
    /// Peak ground acceleration (m/s²).
    pub pga: f64,
    /// Kanai–Tajimi ground frequency f_g (Hz).
    pub ground_frequency: f64,
    /// Kanai–Tajimi damping ζ_g.
    pub ground_damping: f64,
    /// High-pass (Clough–Penzien) frequency f_f (Hz).
    pub highpass_frequency: f64,
    /// High-pass damping ζ_f.
    pub highpass_damping: f64,
    /// Time (s) where the peak is placed, if any.
    #[serde(default)]
    pub peak_time: Option<f64>,
}

/// `synthetic = { … }` of a case motion: a preset and/or generator parameters (those
/// given replace the preset's).
#[derive(Clone, Debug, Default, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct SyntheticSpec {
    /// `"wolong"`: the Wolong-like default input ([`wolong`]).
    #[serde(default)]
    pub preset: Option<String>,
    /// Seed (default 1).
    #[serde(default)]
    pub seed: Option<u64>,
    /// Length (s).
    #[serde(default)]
    pub duration: Option<f64>,
    /// Step (s).
    #[serde(default)]
    pub dt: Option<f64>,
    /// Strong phases of the envelope.
    #[serde(default)]
    pub phases: Option<Vec<Phase>>,
    /// Half-cosine fade to zero over the last `fade` seconds.
    #[serde(default)]
    pub fade: Option<f64>,
    /// Components by axis: `x`, `y`, `z`.
    #[serde(default)]
    pub components: Option<BTreeMap<String, ComponentShape>>,
}

/// A complete, checked parameter set.
#[derive(Clone, Debug, PartialEq)]
pub struct GeneratorParameters {
    pub seed: u64,
    pub duration: f64,
    pub dt: f64,
    pub phases: Vec<Phase>,
    pub fade: f64,
    pub components: Vec<(Axis, ComponentShape)>,
    /// Description for the provenance.
    pub label: String,
}

impl SyntheticSpec {
    /// Merge with the preset and check; `file`/`field` name it in errors.
    pub fn parameters(&self, file: &str, field: &str) -> Result<GeneratorParameters> {
        let mut p = match self.preset.as_deref() {
            Some(name) if name.eq_ignore_ascii_case("wolong") => wolong::parameters(),
            Some(other) => {
                return Err(DcfmError::invalid(
                    file,
                    format!("{field}.preset"),
                    format!("\"{other}\""),
                    "a known preset: wolong",
                ))
            }
            None => GeneratorParameters {
                seed: 1,
                duration: 0.0,
                dt: 0.0,
                phases: Vec::new(),
                fade: 0.0,
                components: Vec::new(),
                label: "synthetic".into(),
            },
        };
        if let Some(s) = self.seed {
            p.seed = s;
        }
        if let Some(d) = self.duration {
            p.duration = d;
        }
        if let Some(d) = self.dt {
            p.dt = d;
        }
        if let Some(ph) = &self.phases {
            p.phases = ph.clone();
        }
        if let Some(f) = self.fade {
            p.fade = f;
        }
        if let Some(cs) = &self.components {
            p.components.clear();
            for (k, c) in cs {
                let axis = Axis::parse(k).ok_or_else(|| {
                    DcfmError::invalid(
                        file,
                        format!("{field}.components.{k}"),
                        k,
                        "an axis: x, y or z",
                    )
                })?;
                p.components.push((axis, c.clone()));
            }
        }
        p.label = format!("{} (seed {})", p.label, p.seed);
        p.validate(file, field)?;
        Ok(p)
    }
}

impl GeneratorParameters {
    /// Check every parameter.
    pub fn validate(&self, file: &str, field: &str) -> Result<()> {
        let err = |name: &str, v: &dyn std::fmt::Display, what: &str| {
            Err(DcfmError::invalid(file, format!("{field}.{name}"), v, what))
        };
        if !(self.dt.is_finite() && self.dt > 0.0) {
            return err("dt", &self.dt, "a step > 0 s (or a preset)");
        }
        if !(self.duration.is_finite()
            && self.duration > 10.0 * self.dt
            && self.duration / self.dt < 5e7)
        {
            return err(
                "duration",
                &self.duration,
                "a length of more than 10 steps and at most 5·10⁷ steps",
            );
        }
        if self.phases.is_empty() {
            return err("phases", &"[]", "at least one strong phase");
        }
        for (k, ph) in self.phases.iter().enumerate() {
            let ok = [ph.rise, ph.start, ph.end, ph.decay, ph.level]
                .iter()
                .all(|v| v.is_finite())
                && ph.rise >= 0.0
                && ph.start > ph.rise
                && ph.end >= ph.start
                && ph.decay > 0.0
                && ph.level > 0.0;
            if !ok {
                return err(
                    &format!("phases[{k}]"),
                    &format!(
                        "{{ rise = {}, start = {}, end = {}, decay = {}, level = {} }}",
                        ph.rise, ph.start, ph.end, ph.decay, ph.level
                    ),
                    "0 ≤ rise < start ≤ end, decay > 0, level > 0",
                );
            }
        }
        if !(self.fade.is_finite() && self.fade >= 0.0 && self.fade < self.duration) {
            return err(
                "fade",
                &self.fade,
                "a length ≥ 0 s, shorter than the motion",
            );
        }
        if self.components.is_empty() {
            return err("components", &"{}", "at least one of x, y, z");
        }
        let nyquist = 0.5 / self.dt;
        for (axis, c) in &self.components {
            let f = |n: &str| format!("components.{}.{n}", axis.name());
            if !(c.pga.is_finite() && c.pga > 0.0) {
                return err(&f("pga"), &c.pga, "a peak acceleration > 0 m/s²");
            }
            for (n, v) in [
                ("ground_frequency", c.ground_frequency),
                ("highpass_frequency", c.highpass_frequency),
            ] {
                if !(v.is_finite() && v > 0.0 && v < nyquist) {
                    return err(
                        &f(n),
                        &v,
                        &format!("a frequency in (0, {nyquist}) Hz (below Nyquist)"),
                    );
                }
            }
            for (n, v) in [
                ("ground_damping", c.ground_damping),
                ("highpass_damping", c.highpass_damping),
            ] {
                if !(v.is_finite() && v > 0.0 && v <= 5.0) {
                    return err(&f(n), &v, "a damping ratio in (0, 5]");
                }
            }
            if let Some(tp) = c.peak_time {
                if !(tp.is_finite() && tp >= 1.0 && tp <= self.duration - self.fade - 1.0) {
                    return err(
                        &f("peak_time"),
                        &tp,
                        "a time at least 1 s inside the motion (before the fade)",
                    );
                }
            }
        }
        Ok(())
    }

    /// Generate the record (m/s²) and the provenance lines of its making.
    pub fn generate(&self) -> (Record, Vec<String>) {
        let n = (self.duration / self.dt).round() as usize + 1;
        let mut components = Vec::with_capacity(self.components.len());
        let mut provenance = vec![format!(
            "synthetic {}: Clough–Penzien filtered ChaCha20 white noise, {} s at dt {} s, envelope of {} strong phase(s), fade {} s",
            self.label,
            self.duration,
            self.dt,
            self.phases.len(),
            self.fade
        )];
        for (axis, shape) in &self.components {
            let a = self.component(*axis, shape, n);
            provenance.push(format!(
                "  {}: f_g {} Hz ζ_g {}, high-pass f_f {} Hz ζ_f {}, PGA {} m/s²{}; final velocity and displacement zeroed",
                axis.name(),
                shape.ground_frequency,
                shape.ground_damping,
                shape.highpass_frequency,
                shape.highpass_damping,
                shape.pga,
                shape.peak_time.map(|t| format!(", peak placed at {t} s")).unwrap_or_default()
            ));
            components.push(RecordComponent {
                name: shape
                    .name
                    .clone()
                    .unwrap_or_else(|| axis.name().to_string()),
                axis: Some(*axis),
                acceleration: a,
                header_peak: Some(shape.pga),
            });
        }
        (
            Record {
                source: self.label.clone(),
                format: Format::Synthetic,
                station: String::new(),
                description: self.label.clone(),
                units: AccelUnits::MetrePerSecond2,
                dt: self.dt,
                components,
            },
            provenance,
        )
    }

    /// Steps 1–7 of the module doc for one component.
    fn component(&self, axis: Axis, shape: &ComponentShape, n: usize) -> Vec<f64> {
        let dt = self.dt;
        let two_pi = 2.0 * std::f64::consts::PI;
        let mut noise = GaussianStream::new(self.seed, axis.index() as u64);
        let w: Vec<f64> = (0..n).map(|_| noise.next_normal()).collect();
        let kt = filter(
            &w,
            dt,
            two_pi * shape.ground_frequency,
            shape.ground_damping,
            false,
        );
        let cp = filter(
            &kt,
            dt,
            two_pi * shape.highpass_frequency,
            shape.highpass_damping,
            true,
        );
        let mut a: Vec<f64> = cp
            .iter()
            .enumerate()
            .map(|(i, &x)| {
                x * envelope::envelope(&self.phases, i as f64 * dt, self.duration, self.fade)
            })
            .collect();
        zero_end_motion(&mut a, dt);
        if let Some(tp) = shape.peak_time {
            place_peak(&mut a, dt, tp);
        }
        let peak = a.iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if peak > 0.0 {
            let f = shape.pga / peak;
            a.iter_mut().for_each(|v| *v *= f);
        }
        a
    }
}

/// Second-order filter of `input` by the exact recursion: the oscillator ü + 2ζωu̇ + ω²u
/// = −input; output −(2ζωu̇ + ω²u) (the absolute acceleration: Kanai–Tajimi) or, with
/// `relative`, ü = −input − 2ζωu̇ − ω²u (the high-pass).
fn filter(input: &[f64], dt: f64, omega: f64, zeta: f64, relative: bool) -> Vec<f64> {
    let k = SdofCoefficients::new(omega, zeta, dt);
    let (cv, cu) = (2.0 * zeta * omega, omega * omega);
    let mut out = Vec::with_capacity(input.len());
    let (mut u, mut v) = (0.0, 0.0);
    for i in 0..input.len() {
        if i > 0 {
            (u, v) = k.step(u, v, -input[i - 1], -input[i]);
        }
        let restoring = cv * v + cu * u;
        out.push(if relative {
            -input[i] - restoring
        } else {
            -restoring
        });
    }
    out
}

/// Step 5 (and 6 again): bump the envelope at `tp` until the peak is there by a 10 %
/// margin, shift by whole samples so the largest sample is at `tp`, re-zero the ends.
fn place_peak(a: &mut [f64], dt: f64, tp: f64) {
    let n = a.len();
    let ip = (tp / dt).round() as usize;
    let near = (0.5 / dt).round() as usize;
    let base = a.to_vec();
    let mut beta = 0.0;
    for _ in 0..60 {
        for (i, (x, b)) in a.iter_mut().zip(&base).enumerate() {
            let s = (i as f64 * dt - tp) / 0.3;
            *x = b * (1.0 + beta * libm::exp(-s * s));
        }
        let (mut inside, mut outside) = (0.0f64, 0.0f64);
        for (i, x) in a.iter().enumerate() {
            if i.abs_diff(ip) <= near {
                inside = inside.max(x.abs());
            } else {
                outside = outside.max(x.abs());
            }
        }
        if inside >= 1.1 * outside {
            break;
        }
        beta = if beta == 0.0 { 0.25 } else { beta * 1.5 };
    }
    zero_end_motion(a, dt);
    for _ in 0..4 {
        let imax = argmax_abs(a);
        if imax == ip {
            break;
        }
        let shift = ip as i64 - imax as i64;
        let old = a.to_vec();
        for (i, x) in a.iter_mut().enumerate() {
            let j = i as i64 - shift;
            *x = if (0..n as i64).contains(&j) {
                old[j as usize]
            } else {
                0.0
            };
        }
        zero_end_motion(a, dt);
    }
}

fn argmax_abs(a: &[f64]) -> usize {
    let mut best = (0, 0.0f64);
    for (i, x) in a.iter().enumerate() {
        if x.abs() > best.1 {
            best = (i, x.abs());
        }
    }
    best.0
}
