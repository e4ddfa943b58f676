//! `dcfm motion FILE… [options]`: read (or generate), process and measure a ground motion;
//! print a summary and write the processed motion, its response spectrum, its Husid curve
//! and its Fourier amplitude spectrum as CSV (each with the provenance in its header), and
//! an SVG plot if asked. See docs/motion.md.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use clap::Args;

use dcfm::error::{DcfmError, Result};
use dcfm::motion::measures::spectrum::log_periods;
use dcfm::motion::measures::{fourier_amplitude, husid, response_spectrum};
use dcfm::motion::processing::{Baseline, TargetPga};
use dcfm::motion::summary::summarize;
use dcfm::motion::units::STANDARD_GRAVITY;
use dcfm::motion::{GroundMotion, MotionSpec, ProcessingOptions, SyntheticSpec};

use crate::output::write_atomic;

/// Options of `dcfm motion`.
#[derive(Args, Debug)]
pub struct MotionArgs {
    /// Record file(s); several files make one motion (their components together).
    pub files: Vec<PathBuf>,
    /// Format: auto, text, csv, at2, knet, cosmos, smc.
    #[arg(long)]
    pub format: Option<String>,
    /// Units where the file does not state them: g, gal (cm/s2), m/s2.
    #[arg(long)]
    pub units: Option<String>,
    /// Sampling step (s) where the file does not state it.
    #[arg(long)]
    pub dt: Option<f64>,
    /// Axis of each component in reading order, e.g. x,y,z.
    #[arg(long, value_delimiter = ',')]
    pub components: Option<Vec<String>>,
    /// Generate a synthetic motion instead of reading one: "wolong".
    #[arg(long)]
    pub synthetic: Option<String>,
    /// Seed of the synthetic motion.
    #[arg(long)]
    pub seed: Option<u64>,
    /// Time window T0,T1 (s).
    #[arg(long, value_delimiter = ',', num_args = 2)]
    pub window: Option<Vec<f64>>,
    /// Baseline correction: none, mean (default for records), polynomial.
    #[arg(long)]
    pub baseline: Option<String>,
    /// Order of the polynomial baseline.
    #[arg(long, default_value_t = 1)]
    pub baseline_order: usize,
    /// Cosine taper length at each end (s).
    #[arg(long, default_value_t = 0.0)]
    pub taper: f64,
    /// High-pass corner (Hz).
    #[arg(long)]
    pub highpass: Option<f64>,
    /// Low-pass corner (Hz).
    #[arg(long)]
    pub lowpass: Option<f64>,
    /// Butterworth order.
    #[arg(long, default_value_t = 4)]
    pub filter_order: usize,
    /// One causal pass instead of the zero-phase forward-backward filter.
    #[arg(long)]
    pub causal: bool,
    /// Zero pad at each side before filtering (s); default 1.5·order/highpass.
    #[arg(long)]
    pub pad: Option<f64>,
    /// Resample to this step (s), band-limited.
    #[arg(long)]
    pub resample_dt: Option<f64>,
    /// Remove the linear trend that makes the final velocity and displacement zero.
    #[arg(long)]
    pub zero_end: bool,
    /// Scale so that the largest component peak is this (m/s²).
    #[arg(long)]
    pub target_pga: Option<f64>,
    /// Damping ratio of the response spectrum.
    #[arg(long, default_value_t = 0.05)]
    pub damping: f64,
    /// Number of spectrum periods, log-spaced from 0.01 to 10 s.
    #[arg(long, default_value_t = 200)]
    pub periods: usize,
    /// Output directory (default: results/motion/<name>).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// Also write a plot: svg.
    #[arg(long)]
    pub plot: Option<String>,
}

/// Run the command; returns the lines to print.
pub fn run(args: &MotionArgs) -> Result<Vec<String>> {
    let (spec, name) = spec_of(args)?;
    if let Some(p) = &args.plot {
        if !p.eq_ignore_ascii_case("svg") {
            return Err(DcfmError::invalid(
                "command line",
                "--plot",
                p,
                "svg (the plot is written as SVG)",
            ));
        }
    }
    if !(args.damping.is_finite() && (0.0..1.0).contains(&args.damping)) {
        return Err(DcfmError::invalid(
            "command line",
            "--damping",
            args.damping,
            "a damping ratio in [0, 1)",
        ));
    }
    if !(1..=10_000).contains(&args.periods) {
        return Err(DcfmError::invalid(
            "command line",
            "--periods",
            args.periods,
            "1 to 10000 periods",
        ));
    }
    let motion = spec.load(&name, "command line", Path::new(""))?;
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| PathBuf::from("results").join("motion").join(&name));
    std::fs::create_dir_all(&out).map_err(|e| DcfmError::io(out.display().to_string(), e))?;
    let periods = log_periods(0.01, 10.0, args.periods);
    let spectra: Vec<_> = motion
        .components
        .iter()
        .map(|c| response_spectrum(&c.acceleration, c.dt, &periods, args.damping))
        .collect();
    write_atomic(&out.join("motion.csv"), motion_csv(&motion).as_bytes())?;
    write_atomic(
        &out.join("spectrum.csv"),
        spectrum_csv(&motion, &periods, &spectra, args.damping).as_bytes(),
    )?;
    write_atomic(&out.join("husid.csv"), husid_csv(&motion).as_bytes())?;
    write_atomic(&out.join("fourier.csv"), fourier_csv(&motion).as_bytes())?;
    if args.plot.is_some() {
        write_atomic(
            &out.join("motion.svg"),
            svg_plot(&motion, &periods, &spectra, args.damping).as_bytes(),
        )?;
    }
    let mut lines = summary_lines(&motion);
    lines.push(format!(
        "outputs    {}/{{motion,spectrum,husid,fourier}}.csv{}",
        out.display(),
        if args.plot.is_some() {
            " and motion.svg"
        } else {
            ""
        }
    ));
    Ok(lines)
}

/// The motion spec the flags describe, and the motion's name.
fn spec_of(args: &MotionArgs) -> Result<(MotionSpec, String)> {
    let baseline = match args.baseline.as_deref() {
        None => None,
        Some("none") => Some(Baseline::None),
        Some("mean") => Some(Baseline::Mean),
        Some("polynomial") => Some(Baseline::Polynomial),
        Some(other) => {
            return Err(DcfmError::invalid(
                "command line",
                "--baseline",
                other,
                "none, mean or polynomial",
            ))
        }
    };
    let processing = ProcessingOptions {
        window: args.window.as_ref().map(|w| [w[0], w[1]]),
        baseline,
        baseline_order: args.baseline_order,
        taper: args.taper,
        highpass: args.highpass,
        lowpass: args.lowpass,
        filter_order: args.filter_order,
        zero_phase: !args.causal,
        pad: args.pad,
        resample_dt: args.resample_dt,
        zero_end: args.zero_end,
        target_pga: args.target_pga.map(TargetPga::All),
    };
    let mut spec = MotionSpec {
        processing: Some(processing),
        ..MotionSpec::default()
    };
    let name;
    if let Some(preset) = &args.synthetic {
        if !args.files.is_empty() {
            return Err(DcfmError::invalid(
                "command line",
                "FILE",
                args.files[0].display(),
                "no file with --synthetic",
            ));
        }
        spec.synthetic = Some(SyntheticSpec {
            preset: Some(preset.clone()),
            seed: args.seed,
            ..SyntheticSpec::default()
        });
        name = format!("{preset}-seed{}", args.seed.unwrap_or(1));
    } else {
        if args.files.is_empty() {
            return Err(DcfmError::invalid(
                "command line",
                "FILE",
                "none",
                "a record file (or --synthetic wolong)",
            ));
        }
        spec.files = Some(args.files.iter().map(|p| p.display().to_string()).collect());
        spec.format = args.format.clone();
        spec.units = args.units.clone();
        spec.dt = args.dt;
        spec.components = args.components.clone();
        name = args.files[0]
            .file_stem()
            .map(|s| s.to_string_lossy().to_string())
            .unwrap_or_else(|| "motion".into());
    }
    Ok((spec, name))
}

/// The printed summary.
pub fn summary_lines(m: &GroundMotion) -> Vec<String> {
    let mut l = vec![
        format!("motion     {}  ({})", m.name, m.source),
        format!(
            "format     {}  station \"{}\"  stored in {} (shown in SI and g)",
            m.format, m.station, m.original_units
        ),
        format!(
            "samples    {} × dt {} s = {:.3} s",
            m.npts(),
            m.dt,
            m.duration()
        ),
        format!(
            "{:<10} {:>4} {:>10} {:>7} {:>8} {:>10} {:>8} {:>10} {:>8} {:>11} {:>8}",
            "component",
            "axis",
            "PGA m/s²",
            "g",
            "at s",
            "PGV m/s",
            "at s",
            "PGD m",
            "at s",
            "Arias m/s",
            "D5-95 s"
        ),
    ];
    for s in summarize(m) {
        l.push(format!(
            "{:<10} {:>4} {:>10.4} {:>7.4} {:>8.3} {:>10.4} {:>8.3} {:>10.4} {:>8.3} {:>11.4} {:>8}",
            s.name,
            s.axis,
            s.pga.value,
            s.pga.value / STANDARD_GRAVITY,
            s.pga.time,
            s.pgv.value,
            s.pgv.time,
            s.pgd.value,
            s.pgd.time,
            s.arias,
            s.d5_95.map(|d| format!("{:.3}", d.2)).unwrap_or_else(|| "-".into())
        ));
    }
    for p in &m.provenance {
        l.push(format!("processing {p}"));
    }
    l
}

/// `# ` lines: the motion and every processing step.
fn header(m: &GroundMotion, what: &str) -> String {
    let mut h = format!("# dcfm motion: {what} of \"{}\" ({})\n", m.name, m.source);
    for p in &m.provenance {
        let _ = writeln!(h, "# {p}");
    }
    h
}

fn column_name(c: &dcfm::motion::MotionComponent) -> String {
    match c.axis {
        Some(a) => a.name().to_string(),
        None => c.name.replace([',', ' '], "_"),
    }
}

fn motion_csv(m: &GroundMotion) -> String {
    let mut s = header(m, "processed motion (SI: m/s², m/s, m)");
    s.push('t');
    for c in &m.components {
        let n = column_name(c);
        let _ = write!(s, ",a_{n},v_{n},u_{n}");
    }
    s.push('\n');
    for i in 0..m.npts() {
        let _ = write!(s, "{:.6}", i as f64 * m.dt);
        for c in &m.components {
            let _ = write!(
                s,
                ",{:.9e},{:.9e},{:.9e}",
                c.acceleration[i], c.velocity[i], c.displacement[i]
            );
        }
        s.push('\n');
    }
    s
}

fn spectrum_csv(
    m: &GroundMotion,
    periods: &[f64],
    spectra: &[Vec<dcfm::motion::measures::SpectrumPoint>],
    damping: f64,
) -> String {
    let mut s = header(
        m,
        &format!("elastic response spectrum, damping {damping} (Nigam–Jennings)"),
    );
    s.push_str("period");
    for c in &m.components {
        let n = column_name(c);
        let _ = write!(s, ",sa_{n},psa_{n},sv_{n},psv_{n},sd_{n}");
    }
    s.push('\n');
    for (k, t) in periods.iter().enumerate() {
        let _ = write!(s, "{t:.6e}");
        for sp in spectra {
            let p = sp[k];
            let _ = write!(
                s,
                ",{:.6e},{:.6e},{:.6e},{:.6e},{:.6e}",
                p.sa, p.psa, p.sv, p.psv, p.sd
            );
        }
        s.push('\n');
    }
    s
}

fn husid_csv(m: &GroundMotion) -> String {
    let mut s = header(m, "Husid curve (normalised Arias intensity)");
    s.push('t');
    let curves: Vec<Vec<f64>> = m
        .components
        .iter()
        .map(|c| husid(&c.acceleration, c.dt))
        .collect();
    for c in &m.components {
        let _ = write!(s, ",h_{}", column_name(c));
    }
    s.push('\n');
    for i in 0..m.npts() {
        let _ = write!(s, "{:.6}", i as f64 * m.dt);
        for h in &curves {
            let _ = write!(s, ",{:.6e}", h[i]);
        }
        s.push('\n');
    }
    s
}

fn fourier_csv(m: &GroundMotion) -> String {
    let mut s = header(m, "Fourier amplitude spectrum (m/s)");
    let spectra: Vec<(Vec<f64>, Vec<f64>)> = m
        .components
        .iter()
        .map(|c| fourier_amplitude(&c.acceleration, c.dt))
        .collect();
    s.push('f');
    for c in &m.components {
        let _ = write!(s, ",fas_{}", column_name(c));
    }
    s.push('\n');
    let n = spectra.iter().map(|x| x.0.len()).min().unwrap_or(0);
    for k in 0..n {
        let _ = write!(s, "{:.6e}", spectra[0].0[k]);
        for sp in &spectra {
            let _ = write!(s, ",{:.6e}", sp.1[k]);
        }
        s.push('\n');
    }
    s
}

/// A hand-written SVG: one panel of acceleration per component, and the 5 % spectra (PSA)
/// on a log period axis.
fn svg_plot(
    m: &GroundMotion,
    periods: &[f64],
    spectra: &[Vec<dcfm::motion::measures::SpectrumPoint>],
    damping: f64,
) -> String {
    const W: f64 = 900.0;
    const PANEL: f64 = 150.0;
    const LEFT: f64 = 70.0;
    let colours = ["#1f77b4", "#d62728", "#2ca02c", "#9467bd"];
    let nc = m.components.len();
    let height = 40.0 + (nc as f64 + 1.5) * (PANEL + 30.0);
    let mut s = format!(
        "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"{W}\" height=\"{height}\" font-family=\"sans-serif\" font-size=\"12\">\n<rect width=\"100%\" height=\"100%\" fill=\"white\"/>\n<text x=\"{LEFT}\" y=\"22\" font-size=\"15\">{} — {}</text>\n",
        xml(&m.name),
        xml(&m.source)
    );
    let duration = m.duration().max(m.dt);
    let plot_w = W - LEFT - 20.0;
    for (k, c) in m.components.iter().enumerate() {
        let top = 40.0 + k as f64 * (PANEL + 30.0);
        let peak = c
            .acceleration
            .iter()
            .fold(0.0f64, |a, v| a.max(v.abs()))
            .max(1e-30);
        let _ = writeln!(
            s,
            "<rect x=\"{LEFT}\" y=\"{top}\" width=\"{plot_w}\" height=\"{PANEL}\" fill=\"none\" stroke=\"#888\"/>\n<text x=\"{}\" y=\"{}\">{} ({}): PGA {:.3} m/s² — time 0 to {:.2} s</text>",
            LEFT + 5.0,
            top + 14.0,
            xml(&c.name),
            c.axis.map(|a| a.name()).unwrap_or("-"),
            peak,
            duration
        );
        // Min/max per pixel column keeps every peak visible.
        let cols = plot_w as usize;
        let mut pts = String::new();
        for col in 0..cols {
            let i0 = col * c.len() / cols;
            let i1 = ((col + 1) * c.len() / cols).max(i0 + 1).min(c.len());
            let (lo, hi) = c.acceleration[i0..i1]
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            let x = LEFT + col as f64;
            let y = |v: f64| top + PANEL / 2.0 - v / peak * (PANEL / 2.0 - 18.0);
            let _ = write!(pts, "{x:.1},{:.1} {x:.1},{:.1} ", y(lo), y(hi));
        }
        let _ = writeln!(
            s,
            "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"0.8\" points=\"{}\"/>",
            colours[k % 4],
            pts.trim_end()
        );
    }
    // Spectra panel.
    let top = 40.0 + nc as f64 * (PANEL + 30.0);
    let ph = PANEL * 1.5;
    let smax = spectra
        .iter()
        .flatten()
        .fold(0.0f64, |a, p| a.max(p.psa))
        .max(1e-30);
    let (lt0, lt1) = (
        periods[0].ln(),
        periods[periods.len() - 1].ln().max(periods[0].ln() + 1e-9),
    );
    let _ = writeln!(
        s,
        "<rect x=\"{LEFT}\" y=\"{top}\" width=\"{plot_w}\" height=\"{ph}\" fill=\"none\" stroke=\"#888\"/>\n<text x=\"{}\" y=\"{}\">pseudo-acceleration spectra, damping {damping} (max {:.3} m/s²); period {:.3} to {:.3} s, log scale</text>",
        LEFT + 5.0,
        top + 14.0,
        smax,
        periods[0],
        periods[periods.len() - 1]
    );
    for (k, sp) in spectra.iter().enumerate() {
        let pts: Vec<String> = sp
            .iter()
            .map(|p| {
                let x = LEFT + (p.period.ln() - lt0) / (lt1 - lt0) * plot_w;
                let y = top + ph - p.psa / smax * (ph - 20.0);
                format!("{x:.1},{y:.1}")
            })
            .collect();
        let _ = writeln!(
            s,
            "<polyline fill=\"none\" stroke=\"{}\" stroke-width=\"1.5\" points=\"{}\"/>",
            colours[k % 4],
            pts.join(" ")
        );
    }
    s.push_str("</svg>\n");
    s
}

fn xml(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}
