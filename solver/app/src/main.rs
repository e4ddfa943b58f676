//! `dcfm` — run or check a case file.
//!
//! ```text
//! dcfm check CASE                       validate, print the model, the stable step, the wall time
//! dcfm run CASE [--out DIR] [--threads N] [--resume] [--resume-with-changed-case]
//!               [--allow-long] [--quiet]
//! dcfm mesh yingxiuwan [--variant full|ci] [--measure LIST] [--end T] [--stable-step B] [--out DIR]
//! dcfm post yingxiuwan RUN_DIR [--case CASE]
//! dcfm motion FILE… [--format F] [--units U] [--dt DT] [processing flags] [--out DIR] [--plot svg]
//! ```

use std::path::PathBuf;
use std::process::ExitCode;

use std::io::Write;

use clap::{Parser, Subcommand};

use dcfm::case::load_case;
use dcfm::readable::{duration, engineering};
use dcfm_app::run::{run_case, RunOptions};

#[derive(Parser)]
#[command(
    name = "dcfm",
    version,
    about = "Explicit dynamics with the dynamic contact force method"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Validate a case file and print the model summary, the stable time step and the
    /// expected wall time (from a few timed steps).
    Check {
        /// The case file (TOML).
        case: PathBuf,
    },
    /// Run a case: VTU + PVD, histories.csv and summary.json under --out.
    Run {
        /// The case file (TOML).
        case: PathBuf,
        /// Output directory (default: results/<case file stem>).
        #[arg(long)]
        out: Option<PathBuf>,
        /// Worker threads (default: all cores). Results do not depend on it.
        #[arg(long)]
        threads: Option<usize>,
        /// Continue from the checkpoint in the output directory (refused when the case
        /// or its mesh changed since it was written, or when it is corrupted).
        #[arg(long)]
        resume: bool,
        /// Like --resume, and continue even when the case or its mesh changed since the
        /// checkpoint was written (the changes are reported).
        #[arg(long)]
        resume_with_changed_case: bool,
        /// Run even when the case has more steps than its budget `[time] max_steps`.
        #[arg(long)]
        allow_long: bool,
        /// No progress bar.
        #[arg(long)]
        quiet: bool,
    },
    /// Generate a model's mesh (Gmsh MSH 4.1) and its case file.
    Mesh {
        /// The model: "yingxiuwan".
        model: String,
        /// Mesh variant: "full" (≈ the paper's 171k hex8) or "ci" (≈ 10⁴ elements).
        #[arg(long, default_value = "full")]
        variant: String,
        /// Anti-seismic measures (paper §6): "none", "all", or a comma-separated list of
        /// reinforced_rock, upper_anchorage, isolation_layer.
        #[arg(long, default_value = "none")]
        measure: String,
        /// End time of the seismic stage (s); default 60.
        #[arg(long)]
        end: Option<f64>,
        /// How the case bounds its critical step (`time.stable_step`): "element" (each
        /// element with its own lumped masses) or "shared_mass" (the nodal masses shared
        /// among the elements: a larger step that is still a bound, docs/case_format.md).
        /// Default: "shared_mass" for the full variant, "element" for the CI variant.
        #[arg(long)]
        stable_step: Option<String>,
        /// Output directory.
        #[arg(long, default_value = "yingxiuwan")]
        out: PathBuf,
    },
    /// Read, process and measure a ground motion (docs/motion.md): prints PGA/PGV/PGD,
    /// Arias intensity and D5–95, writes motion, spectrum, Husid and Fourier CSV files.
    Motion(Box<dcfm_app::motion_cmd::MotionArgs>),
}

/// Print a line to stdout, ignoring a closed pipe (`dcfm check x | head` must not panic).
macro_rules! say {
    ($($arg:tt)*) => {{
        let _ = writeln!(std::io::stdout(), $($arg)*);
    }};
}

/// Print a line to stderr, ignoring a closed pipe.
macro_rules! esay {
    ($($arg:tt)*) => {{
        let _ = writeln!(std::io::stderr(), $($arg)*);
    }};
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    match cli.command {
        Command::Mesh {
            model,
            variant,
            measure,
            end,
            stable_step,
            out,
        } => dcfm_app::mesh_cmd::run_mesh_command(
            &model,
            &dcfm_app::mesh_cmd::MeshRequest {
                variant: &variant,
                measure: &measure,
                end,
                stable_step: stable_step.as_deref(),
                out: &out,
            },
        ),
        Command::Motion(args) => match dcfm_app::motion_cmd::run(&args) {
            Ok(lines) => {
                for l in lines {
                    say!("{l}");
                }
                ExitCode::SUCCESS
            }
            Err(e) => {
                esay!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Check { case } => match load_case(&case) {
            Ok(c) => {
                for w in &c.warnings {
                    esay!("warning: {w}");
                }
                let m = &c.model;
                say!("case      {} ({})", case.display(), c.title);
                say!(
                    "mesh      {} nodes, {} hex8 elements, {} colours",
                    m.mesh.n_nodes(),
                    m.n_elements(),
                    m.n_colours
                );
                for g in &m.groups {
                    say!(
                        "region    {:<16} {:>8} elements  {:<9} {}  E = {:.3e} Pa  ν = {}  ρ = {} kg/m³",
                        g.name,
                        g.len(),
                        g.integration.name(),
                        match g.material {
                            dcfm::material::Material::Elastic(_) => "elastic",
                            dcfm::material::Material::PlasticDamage(_) => "plastic-damage",
                        },
                        g.material.elastic().young,
                        g.material.elastic().poisson,
                        g.material.density()
                    );
                }
                if let Some(scaling) = &m.mass_scaling {
                    for line in scaling.describe() {
                        say!("{line}");
                    }
                }
                say!(
                    "stable    critical Δt = {:.4e} s (element {} in region '{}', L = {:.4e} m, c_p = {:.1} m/s); with damping {:.4e} s",
                    m.stable.critical,
                    m.stable.element,
                    m.groups[m.element_location[m.stable.element].0 as usize].name,
                    m.stable.length,
                    m.stable.speed,
                    m.critical_step_with_damping()
                );
                let limits =
                    dcfm::step_limits::step_limits(m, &[1.1, 1.25, 1.5], &[10, 100, 1000, 10000]);
                if m.step_bound == dcfm::model::StepBound::SharedMass {
                    say!(
                        "          bound with the nodal masses shared among the elements (time.stable_step = \"shared_mass\"): {:.3}× the elements' own bound {:.4e} s, which the lines below refer to",
                        m.stable.critical / limits.critical,
                        limits.critical
                    );
                }
                for band in &limits.bands {
                    let regions: Vec<String> = band
                        .by_region
                        .iter()
                        .map(|(r, n)| format!("{r} {n}"))
                        .collect();
                    let (lo, hi) = band.bounds;
                    say!(
                        "          below {:.2}× that step: {} elements ({}), centroids in x {:.2}–{:.2}, y {:.2}–{:.2}, z {:.2}–{:.2} m",
                        band.factor,
                        band.count,
                        regions.join(", "),
                        lo[0],
                        hi[0],
                        lo[1],
                        hi[1],
                        lo[2],
                        hi[2]
                    );
                }
                say!(
                    "          critical Δt without the worst {} of the {} moving elements: {} s",
                    limits
                        .without_worst
                        .iter()
                        .map(|(n, _)| n.to_string())
                        .collect::<Vec<_>>()
                        .join(" / "),
                    limits.moving,
                    limits
                        .without_worst
                        .iter()
                        .map(|(_, dt)| format!("{dt:.4e}"))
                        .collect::<Vec<_>>()
                        .join(" / ")
                );
                let prescribed = (0..m.n_elements())
                    .filter(|&e| m.element_fully_prescribed(e))
                    .count();
                if prescribed > 0 {
                    say!(
                        "          {prescribed} elements with every node prescribed (fixed or driven in x, y and z) do not limit the step"
                    );
                }
                let schedule = dcfm::stage::StepSchedule::new(c.end, c.dt);
                say!(
                    "time      Δt = {:.4e} s (safety {}), end {} s → {} steps{}",
                    c.dt,
                    c.safety,
                    engineering(c.end),
                    engineering(c.step_count()),
                    if !schedule.shortened(c.dt) {
                        String::new()
                    } else if m.boundaries.is_some() {
                        format!(
                            " (full steps with absorbing boundaries: ends at {:.6e} s)",
                            schedule.steps as f64 * c.dt
                        )
                    } else {
                        format!(
                            ", the last one {:.4e} s to land on the end",
                            schedule.last_step
                        )
                    }
                );
                say!("memory    {:.0} bytes per element", m.bytes_per_element());
                if let Some(a) = &m.anchors {
                    for (group, bars, length, mass) in a.group_totals() {
                        say!(
                            "anchors   {group}: {bars} bars, {length:.1} m of steel, {:.1} t",
                            mass / 1000.0
                        );
                    }
                }
                if let Some(b) = &m.boundaries {
                    for r in &b.reports {
                        say!("boundary  {}: {}", r.field, r.description);
                    }
                    if let Some(ff) = b.free_field_critical_step() {
                        say!(
                            "          {} boundary nodes; free-field grids' own critical step {:.4e} s",
                            b.nodes.len(),
                            ff
                        );
                    }
                }
                if let Some(plan) = &c.static_plan {
                    for line in plan.describe() {
                        say!("{line}");
                    }
                }
                for line in c.probes.describe() {
                    say!("{line}");
                }
                if let Err(e) = c.checked_step_count(false) {
                    say!("warning   dcfm run will refuse it: {e}");
                }
                match dcfm_app::estimate::estimate_wall_time(c) {
                    Ok(w) => {
                        if let Some(s) = &w.subcycling {
                            say!(
                                "subcycle  max_level {}: elements evaluated every 1, 2, 4, … steps: {:?}; nodes stepping at Δt, 2Δt, …: {:?}; {:.3} of the element evaluations per step ({} saved per step)",
                                s.max_level,
                                s.elements_per_level,
                                s.nodes_per_level,
                                s.element_update_fraction,
                                s.element_updates_saved_per_step.round()
                            );
                        }
                        say!(
                            "estimate  {} wall time for {} steps ({} element-updates/s{} timed over {} steps on {} threads here; static stage and outputs not included)",
                            duration(w.wall_s),
                            engineering(w.steps),
                            engineering(w.element_updates_per_s.round()),
                            if w.subcycling.is_some() { " single-step equivalent" } else { "" },
                            w.steps_timed,
                            w.threads
                        )
                    }
                    Err(e) => say!("estimate  no wall time: the timed steps failed ({e})"),
                }
                ExitCode::SUCCESS
            }
            Err(e) => {
                esay!("error: {e}");
                ExitCode::from(2)
            }
        },
        Command::Run {
            case,
            out,
            threads,
            resume,
            resume_with_changed_case,
            allow_long,
            quiet,
        } => {
            let resume = resume || resume_with_changed_case;
            if let Some(mut n) = threads {
                if n == 0 {
                    esay!("error: --threads 0: expected at least 1");
                    return ExitCode::from(2);
                }
                let cores = std::thread::available_parallelism().map_or(n, |c| c.get());
                if n > cores {
                    esay!("note: --threads {n} is more than the {cores} cores here; using {cores}");
                    n = cores;
                }
                if let Err(e) = rayon::ThreadPoolBuilder::new()
                    .num_threads(n)
                    .build_global()
                {
                    esay!("error: --threads {n}: {e}");
                    return ExitCode::from(2);
                }
            }
            let out = out.unwrap_or_else(|| {
                PathBuf::from("results").join(
                    case.file_stem()
                        .map(|s| s.to_string_lossy().to_string())
                        .unwrap_or_else(|| "case".into()),
                )
            });
            let loaded = match load_case(&case) {
                Ok(c) => c,
                Err(e) => {
                    esay!("error: {e}");
                    return ExitCode::from(2);
                }
            };
            for w in &loaded.warnings {
                esay!("warning: {w}");
            }
            if resume && !out.join("checkpoint.bin").exists() {
                esay!(
                    "note: --resume: no checkpoint in {}; starting from scratch (step 0)",
                    out.display()
                );
            }
            let opts = RunOptions {
                out: out.clone(),
                resume,
                resume_with_changed_case,
                allow_long,
                progress: !quiet,
            };
            match run_case(loaded, &opts) {
                Ok(s) => {
                    say!(
                        "{}: {} steps of {:.4e} s to t = {:.4e} s in {:.2} s ({:.3e} element-updates/s); energy residual {:.2e} of the largest energy; outputs in {}",
                        case.display(),
                        s.steps,
                        s.dt,
                        s.end_time,
                        s.wall_s,
                        s.element_updates_per_s,
                        s.energy_residual_relative,
                        out.display()
                    );
                    ExitCode::SUCCESS
                }
                Err(e) => {
                    esay!("error: {e}");
                    ExitCode::from(1)
                }
            }
        }
    }
}
