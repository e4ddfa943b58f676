//! Processing of a record into a [`GroundMotion`], in this fixed order (each step is
//! optional and recorded in the motion's provenance):
//!
//! 1. **window** `[t0, t1]` (s): keep that part of the record, re-timed to start at 0;
//! 2. **baseline**: `"mean"` (default) subtracts the mean, `"polynomial"` the least-squares
//!    polynomial of `baseline_order`, `"none"` nothing ([`baseline`]);
//! 3. **taper** (s, default 0): half-cosine ramps of that length at both ends ([`window`]);
//! 4. **band-pass**: Butterworth `highpass` and/or `lowpass` corners (Hz), `filter_order`
//!    (default 4), zero-phase forward–backward by default (`zero_phase`), on a record
//!    padded with zeros (`pad` s each side, default 1.5·order/highpass) that are removed
//!    afterwards ([`butterworth`]);
//! 5. **resample** to `resample_dt` (s), band-limited ([`resample`]);
//! 6. **zero_end** (default false): remove the linear acceleration α + βt that brings the
//!    final velocity and displacement to exactly zero ([`integrate::zero_end_motion`]);
//! 7. **target_pga**: a number (m/s²) scales all components by one factor so that the
//!    largest component peak equals it; `{ x = …, y = …, z = … }` scales each component
//!    to its own peak;
//! 8. integration to velocity and displacement (exact for piecewise-linear acceleration).

pub mod baseline;
pub mod butterworth;
pub mod integrate;
pub mod resample;
pub mod window;

use std::sync::Arc;

use serde::Deserialize;

use crate::error::{DcfmError, Result};

use super::ground_motion::{GroundMotion, MotionComponent};
use super::record::Record;
use butterworth::{Butterworth, Pass};

/// How the baseline is corrected.
#[derive(Clone, Copy, Debug, Default, Deserialize, PartialEq, Eq)]
#[serde(rename_all = "snake_case")]
pub enum Baseline {
    None,
    #[default]
    Mean,
    Polynomial,
}

/// The peak acceleration(s) to scale to (m/s²).
#[derive(Clone, Copy, Debug, Deserialize, PartialEq)]
#[serde(untagged)]
pub enum TargetPga {
    /// One factor for every component: the largest component peak becomes this.
    All(f64),
    /// Each component to its own peak.
    PerAxis {
        #[serde(default)]
        x: Option<f64>,
        #[serde(default)]
        y: Option<f64>,
        #[serde(default)]
        z: Option<f64>,
    },
}

/// Processing options (`[motions.NAME.processing]` in a case, flags of `dcfm motion`).
#[derive(Clone, Debug, Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct ProcessingOptions {
    #[serde(default)]
    pub window: Option<[f64; 2]>,
    /// Default: `mean` for records read from files, `none` for synthetic motions (which
    /// are generated with zero final velocity and displacement).
    #[serde(default)]
    pub baseline: Option<Baseline>,
    #[serde(default = "default_baseline_order")]
    pub baseline_order: usize,
    #[serde(default)]
    pub taper: f64,
    #[serde(default)]
    pub highpass: Option<f64>,
    #[serde(default)]
    pub lowpass: Option<f64>,
    #[serde(default = "default_filter_order")]
    pub filter_order: usize,
    #[serde(default = "default_true")]
    pub zero_phase: bool,
    #[serde(default)]
    pub pad: Option<f64>,
    #[serde(default)]
    pub resample_dt: Option<f64>,
    #[serde(default)]
    pub zero_end: bool,
    #[serde(default)]
    pub target_pga: Option<TargetPga>,
}

fn default_baseline_order() -> usize {
    1
}
fn default_filter_order() -> usize {
    4
}
fn default_true() -> bool {
    true
}

impl Default for ProcessingOptions {
    fn default() -> Self {
        Self {
            window: None,
            baseline: None,
            baseline_order: default_baseline_order(),
            taper: 0.0,
            highpass: None,
            lowpass: None,
            filter_order: default_filter_order(),
            zero_phase: true,
            pad: None,
            resample_dt: None,
            zero_end: false,
            target_pga: None,
        }
    }
}

impl ProcessingOptions {
    /// Check the options against a record of step `dt` and duration `duration`; `field`
    /// is their path in errors (`motions.NAME.processing`, or `--…` on the command line).
    pub fn validate(&self, file: &str, field: &str, dt: f64, duration: f64) -> Result<()> {
        let bad = |name: &str, v: &dyn std::fmt::Display, what: &str| {
            Err(DcfmError::invalid(file, format!("{field}.{name}"), v, what))
        };
        if let Some([t0, t1]) = self.window {
            if !(t0.is_finite()
                && t1.is_finite()
                && t0 >= 0.0
                && t1 > t0
                && t1 <= duration + 0.5 * dt)
            {
                return bad(
                    "window",
                    &format!("[{t0}, {t1}]"),
                    &format!("0 ≤ t0 < t1 ≤ {duration} s (the record's length)"),
                );
            }
        }
        if self.baseline == Some(Baseline::Polynomial) && !(1..=10).contains(&self.baseline_order) {
            return bad(
                "baseline_order",
                &self.baseline_order,
                "an order from 1 to 10",
            );
        }
        if !(self.taper.is_finite() && self.taper >= 0.0) {
            return bad("taper", &self.taper, "a length ≥ 0 s");
        }
        let nyquist = 0.5 / dt;
        for (name, f) in [("highpass", self.highpass), ("lowpass", self.lowpass)] {
            if let Some(f) = f {
                if !(f.is_finite() && f > 0.0) {
                    return bad(name, &f, "a corner frequency > 0 Hz");
                }
                if f >= nyquist {
                    return bad(
                        name,
                        &f,
                        &format!("a corner below the Nyquist frequency {nyquist} Hz (dt = {dt} s): band-pass above Nyquist"),
                    );
                }
            }
        }
        if let (Some(h), Some(l)) = (self.highpass, self.lowpass) {
            if h >= l {
                return bad("highpass", &h, &format!("a corner below lowpass = {l} Hz"));
            }
        }
        if !(1..=16).contains(&self.filter_order) {
            return bad("filter_order", &self.filter_order, "an order from 1 to 16");
        }
        if let Some(p) = self.pad {
            if !(p.is_finite() && p >= 0.0) {
                return bad("pad", &p, "a length ≥ 0 s");
            }
        }
        if let Some(r) = self.resample_dt {
            if !(r.is_finite() && r > 0.0 && r < duration) {
                return bad(
                    "resample_dt",
                    &r,
                    "a step > 0 s and shorter than the record",
                );
            }
            if duration / r > 5e7 {
                return bad("resample_dt", &r, "a step giving at most 5·10⁷ samples");
            }
        }
        let positive = |name: &str, v: f64| {
            if v.is_finite() && v > 0.0 {
                Ok(())
            } else {
                bad(name, &v, "a peak acceleration > 0 m/s²")
            }
        };
        match self.target_pga {
            Some(TargetPga::All(v)) => positive("target_pga", v)?,
            Some(TargetPga::PerAxis { x, y, z }) => {
                for (n, v) in [
                    ("target_pga.x", x),
                    ("target_pga.y", y),
                    ("target_pga.z", z),
                ] {
                    if let Some(v) = v {
                        positive(n, v)?;
                    }
                }
            }
            None => {}
        }
        Ok(())
    }
}

/// Process `record` into a ground motion called `name`. `file`/`field` name the options
/// in errors.
pub fn process(
    record: &Record,
    name: &str,
    options: &ProcessingOptions,
    file: &str,
    field: &str,
) -> Result<GroundMotion> {
    let mut dt = record.dt;
    let npts = record.npts();
    let duration = (npts.max(1) - 1) as f64 * dt;
    options.validate(file, field, dt, duration)?;
    let mut provenance = vec![format!(
        "{} {} ({} format, station \"{}\"): {} component(s) of {npts} samples, dt {dt} s, stored in {}, converted to m/s²",
        if record.format == super::readers::Format::Synthetic { "generated" } else { "read" },
        record.source,
        record.format,
        record.station,
        record.components.len(),
        record.units
    )];
    let mut series: Vec<Vec<f64>> = record
        .components
        .iter()
        .map(|c| c.acceleration[..npts].to_vec())
        .collect();

    if let Some([t0, t1]) = options.window {
        for s in series.iter_mut() {
            *s = window::window(s, dt, t0, t1).ok_or_else(|| {
                DcfmError::invalid(
                    file,
                    format!("{field}.window"),
                    format!("[{t0}, {t1}]"),
                    "a window inside the record",
                )
            })?;
        }
        provenance.push(format!(
            "window {t0}–{t1} s of the record, re-timed to start at 0"
        ));
    }

    let baseline_kind =
        options
            .baseline
            .unwrap_or(if record.format == super::readers::Format::Synthetic {
                Baseline::None
            } else {
                Baseline::Mean
            });
    match baseline_kind {
        Baseline::None => provenance.push("baseline: none".into()),
        Baseline::Mean => {
            let means: Vec<String> = series
                .iter_mut()
                .map(|s| format!("{:.6e}", baseline::remove_mean(s)))
                .collect();
            provenance.push(format!(
                "baseline: mean removed ({} m/s²)",
                means.join(", ")
            ));
        }
        Baseline::Polynomial => {
            for s in series.iter_mut() {
                baseline::remove_polynomial(s, options.baseline_order);
            }
            provenance.push(format!(
                "baseline: least-squares polynomial of order {} removed",
                options.baseline_order
            ));
        }
    }

    if options.taper > 0.0 {
        for s in series.iter_mut() {
            window::cosine_taper(s, dt, options.taper);
        }
        provenance.push(format!(
            "taper: half-cosine, {} s at each end",
            options.taper
        ));
    }

    if options.highpass.is_some() || options.lowpass.is_some() {
        let order = options.filter_order;
        let pad = options.pad.unwrap_or_else(|| {
            options
                .highpass
                .map(|f| butterworth::default_pad(order, f))
                .unwrap_or(0.0)
        });
        // At most ten record lengths of padding each side (a tiny high-pass corner would
        // otherwise ask for an absurd pad).
        let pad = pad.min(10.0 * duration.max(dt));
        let n_pad = (pad / dt).round() as usize;
        let mut filters = Vec::new();
        if let Some(f) = options.highpass {
            filters.push(Butterworth::new(Pass::High, order, f, dt));
        }
        if let Some(f) = options.lowpass {
            filters.push(Butterworth::new(Pass::Low, order, f, dt));
        }
        for s in series.iter_mut() {
            let mut padded = vec![0.0; s.len() + 2 * n_pad];
            padded[n_pad..n_pad + s.len()].copy_from_slice(s);
            for f in &filters {
                if options.zero_phase {
                    f.forward_backward(&mut padded);
                } else {
                    f.forward(&mut padded);
                }
            }
            let len = s.len();
            s.copy_from_slice(&padded[n_pad..n_pad + len]);
        }
        provenance.push(format!(
            "band-pass: Butterworth order {order}{}{}, {}, zero pads of {:.3} s each side (removed after filtering)",
            options.highpass.map(|f| format!(", high-pass {f} Hz")).unwrap_or_default(),
            options.lowpass.map(|f| format!(", low-pass {f} Hz")).unwrap_or_default(),
            if options.zero_phase { "zero-phase (forward-backward: −6 dB at the corners)" } else { "causal single pass (−3 dB at the corners)" },
            n_pad as f64 * dt
        ));
    }

    if let Some(new_dt) = options.resample_dt {
        if (new_dt - dt).abs() > 1e-12 * dt {
            for s in series.iter_mut() {
                *s = resample::resample(s, dt, new_dt);
            }
            provenance.push(format!(
                "resampled from dt {dt} s to {new_dt} s: windowed sinc (Kaiser β 10, 32 zero crossings), pass band to {:.4} Hz",
                0.9 * 0.5 / dt.max(new_dt)
            ));
            dt = new_dt;
        }
    }

    if options.zero_end {
        for s in series.iter_mut() {
            integrate::zero_end_motion(s, dt);
        }
        provenance.push("end correction: linear acceleration α + βt removed so that the final velocity and displacement are zero".into());
    }

    let peaks: Vec<f64> = series
        .iter()
        .map(|s| s.iter().fold(0.0f64, |m, v| m.max(v.abs())))
        .collect();
    match options.target_pga {
        None => {}
        Some(TargetPga::All(target)) => {
            let largest = peaks.iter().cloned().fold(0.0f64, f64::max);
            if largest > 0.0 {
                let factor = target / largest;
                for s in series.iter_mut() {
                    s.iter_mut().for_each(|v| *v *= factor);
                }
                provenance.push(format!(
                    "scaled ×{factor:.6} so that the largest component peak is {target} m/s²"
                ));
            }
        }
        Some(TargetPga::PerAxis { x, y, z }) => {
            for (k, c) in record.components.iter().enumerate() {
                let target = match c.axis.map(|a| a.index()) {
                    Some(0) => x,
                    Some(1) => y,
                    Some(2) => z,
                    _ => None,
                };
                if let (Some(target), true) = (target, peaks[k] > 0.0) {
                    let factor = target / peaks[k];
                    series[k].iter_mut().for_each(|v| *v *= factor);
                    provenance.push(format!(
                        "component {} scaled ×{factor:.6} to a peak of {target} m/s²",
                        c.name
                    ));
                }
            }
        }
    }

    provenance.push("integrated to velocity and displacement (exact for piecewise-linear acceleration, from rest)".into());
    let components = record
        .components
        .iter()
        .zip(series)
        .map(|(c, s)| Arc::new(MotionComponent::new(c.name.clone(), c.axis, dt, s)))
        .collect();
    Ok(GroundMotion {
        name: name.to_string(),
        source: record.source.clone(),
        format: record.format,
        station: record.station.clone(),
        description: record.description.clone(),
        original_units: record.units,
        dt,
        components,
        provenance,
    })
}
