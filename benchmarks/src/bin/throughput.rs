//! Whole-run throughput of the explicit solver on structured elastic cubes.
//!
//! ```text
//! cargo run --release -p dcfm-benchmarks --bin throughput [-- --quick --no-record --filter cube40]
//! cargo run --release -p dcfm-benchmarks --bin throughput -- --filter static --static-sizes 40
//! ```
//!
//! Stdout: one JSON record per timed configuration (JSON Lines, pipe it to `jq`).
//! Stderr: progress, the thread speed-ups of every case, dcfm over the scipy CSR leapfrog
//! and the targets. Every record is also appended to `benchmarks/history.jsonl` unless
//! `--no-record`. After every elastic `cube{n}_full` case the scipy CSR leapfrog runs on the
//! same cube through Python (`--python`, else `$DCFM_BENCH_PYTHON`, else `.venv/bin/python`;
//! `--no-scipy`: not at all).

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use dcfm_benchmarks::{run, speedup, targets, RunConfig, ScipyBaseline};

#[derive(Debug, Parser)]
#[command(about = "Time explicit steps on elastic hex8 cubes and record element-updates/s")]
struct Cli {
    /// CI smoke run: 4³ and 8³ cubes, a few steps each.
    #[arg(long)]
    quick: bool,
    /// Do not append the records to the history file.
    #[arg(long)]
    no_record: bool,
    /// Run only the cases whose name (e.g. `cube40_full`) contains this substring.
    #[arg(long)]
    filter: Option<String>,
    /// Thread counts to time each case on (default 1,2).
    #[arg(long, value_delimiter = ',')]
    threads: Option<Vec<usize>>,
    /// Cube divisions n, n³ elements (default 20,40; 4,8 with --quick).
    #[arg(long, value_delimiter = ',')]
    sizes: Option<Vec<usize>>,
    /// One-point elastic cubes run last, out of cache (default 100; 12 with --quick;
    /// empty: none).
    #[arg(long, value_parser = size_list)]
    large_sizes: Option<SizeList>,
    /// Static direct solves of n³ cubes (default 40; 8 with --quick; empty: none).
    #[arg(long, value_parser = size_list)]
    static_sizes: Option<SizeList>,
    /// Minimum timed wall time per configuration, seconds (default 2; 0.1 with --quick).
    #[arg(long)]
    min_wall: Option<f64>,
    /// Time exactly this many steps per configuration instead of stepping until
    /// --min-wall has passed (A/B comparisons of two builds: in the damaging regime the
    /// cost of a step grows with the damage, so rates compare only over the same steps).
    #[arg(long, conflicts_with = "min_wall", value_parser = clap::value_parser!(u64).range(1..))]
    steps: Option<u64>,
    /// History file to append to (default <workspace>/benchmarks/history.jsonl).
    #[arg(long)]
    history: Option<PathBuf>,
    /// Python with numpy, scipy and scikit-fem for the scipy CSR rows (default
    /// $DCFM_BENCH_PYTHON, else <workspace>/.venv/bin/python).
    #[arg(long, conflicts_with = "no_scipy")]
    python: Option<PathBuf>,
    /// Do not run the scipy CSR leapfrog rows.
    #[arg(long)]
    no_scipy: bool,
}

/// A comma-separated list of cube divisions that may be empty (`--large-sizes ""`: none).
#[derive(Clone, Debug)]
struct SizeList(Vec<usize>);

fn size_list(text: &str) -> Result<SizeList, String> {
    text.split(',')
        .map(str::trim)
        .filter(|t| !t.is_empty())
        .map(|t| {
            t.parse::<usize>()
                .map_err(|_| format!("`{t}` is not a cube division (a whole number ≥ 1)"))
        })
        .collect::<Result<Vec<_>, _>>()
        .map(SizeList)
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let mut config = if cli.quick {
        RunConfig::quick()
    } else {
        RunConfig::standard()
    };
    config.filter = cli.filter;
    if let Some(t) = cli.threads {
        config.threads = t;
    }
    if let Some(s) = cli.sizes {
        config.sizes = s;
    }
    if let Some(SizeList(s)) = cli.large_sizes {
        config.large_one_point_sizes = s;
    }
    if let Some(SizeList(s)) = cli.static_sizes {
        config.static_sizes = s;
    }
    if let Some(w) = cli.min_wall {
        config.min_wall_s = w;
    }
    if let Some(n) = cli.steps {
        config.min_wall_s = 0.0;
        config.min_steps = n;
        config.max_steps = n;
        config.mode = format!("{}_steps{n}", config.mode);
    }
    if let Some(h) = cli.history {
        config.history = Some(h);
    }
    if cli.no_record {
        config.history = None;
    }
    if let Some(p) = cli.python {
        config.scipy = ScipyBaseline::Python(p);
    }
    if cli.no_scipy {
        config.scipy = ScipyBaseline::Off;
    }
    if let Some(path) = &config.history {
        eprintln!("recording to {}", path.display());
    }
    let records = match run(&config, |r| {
        println!("{}", r.to_json_line());
        let _ = std::io::stdout().flush();
        if let Some(s) = &r.static_solve {
            let peak = s
                .peak_rss_bytes
                .map_or("n/a".to_string(), |b| format!("{:.2} GB", b as f64 / 1e9));
            if let Some(iterations) = s.cg_iterations {
                eprintln!(
                    "{:<22} {} equations: assembly {:.2} s, conjugate gradients {} iterations in {:.2} s; static stage {:.2} s; peak memory {}",
                    r.case, s.equations, s.assembly_s, iterations, s.factorization_s, r.wall_s, peak
                );
                return;
            }
            eprintln!(
                "{:<22} {} equations: assembly {:.2} s, factorisation {:.2} s ({}, L {:.3e} nonzeros, {:.2} GB), solve {:.3} s; static stage {:.2} s; peak memory {}",
                r.case,
                s.equations,
                s.assembly_s,
                s.factorization_s,
                if s.supernodal { "supernodal" } else { "simplicial" },
                s.factor_nonzeros as f64,
                s.factor_bytes as f64 / 1e9,
                s.solve_s,
                r.wall_s,
                peak
            );
            return;
        }
        if let Some(s) = &r.scipy_csr {
            eprintln!(
                "{:<18} scipy {} CSR leapfrog, 1 thread: {:>6} steps in {:6.2} s, {:9.3e} element-updates/s ({} DOFs, {:.3e} nonzeros; scikit-fem {} assembly {:.1} s){}",
                r.case,
                s.scipy,
                r.steps,
                r.wall_s,
                r.element_updates_per_s,
                s.dofs,
                s.nnz as f64,
                s.skfem,
                s.assembly_s,
                if targets::starved(r) { " (machine busy)" } else { "" }
            );
            return;
        }
        eprintln!(
            "{:<18} {} thread(s): {:>6} steps in {:6.2} s, {:9.3e} element-updates/s{}",
            r.case,
            r.threads,
            r.steps,
            r.wall_s,
            r.element_updates_per_s,
            match r.cpu_share {
                Some(s) if targets::starved(r) => format!(
                    " (got {:.0}% of {} core(s): machine busy)",
                    100.0 * s,
                    r.threads
                ),
                _ => String::new(),
            }
        );
    }) {
        Ok(r) => r,
        Err(e) => {
            eprintln!("throughput: {e}");
            return ExitCode::FAILURE;
        }
    };
    let speedups = speedup::speedups(&records);
    if !speedups.is_empty() {
        eprintln!("\nspeed-up (element-updates/s on n threads / on the fewest threads):");
        for s in &speedups {
            eprintln!(
                "  {:<18} {}/{} threads: {:.2}x (efficiency {:.0}%)",
                s.case,
                s.threads,
                s.base_threads,
                s.factor(),
                100.0 * s.efficiency()
            );
        }
    }
    let ratios = targets::scipy_ratios(&records);
    if !ratios.is_empty() {
        eprintln!("\ndcfm over the scipy CSR leapfrog (1 thread) on the same cube, same run:");
        for q in &ratios {
            eprintln!(
                "  {:<18} {} thread(s): {:.2}x{}",
                q.case,
                q.threads,
                q.ratio,
                if q.machine_busy {
                    " (machine busy)"
                } else {
                    ""
                }
            );
        }
    }
    let overheads = targets::boundary_overheads(&records);
    if !overheads.is_empty() {
        eprintln!("\nboundaries (absorbing base with input + free-field sides) per step:");
        for o in &overheads {
            eprintln!(
                "  {:<24} {} thread(s): {:+.1}% over the fixed base{}",
                o.case,
                o.threads,
                100.0 * o.overhead,
                if o.machine_busy {
                    " (machine busy)"
                } else {
                    ""
                }
            );
        }
    }
    let checks = targets::check(&records);
    if !checks.is_empty() {
        eprintln!("\ntargets (issues #2, #3, #4, #7, #11):");
        for c in &checks {
            eprintln!(
                "  [{}] {} (measured {:.3e}){}",
                if c.met { "met " } else { "MISS" },
                c.target,
                c.value,
                if c.machine_busy && !c.met {
                    " -- inconclusive: the machine was busy"
                } else {
                    ""
                }
            );
        }
    }
    ExitCode::SUCCESS
}
