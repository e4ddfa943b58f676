//! Whole runs of a case file on several thread counts, recorded as throughput rows
//! (`run_<name>`) in `benchmarks/history.jsonl` (issue #11 item 5, issue #10's wall time
//! and memory of the Yingxiuwan case). docs/benchmarks.md, "Whole runs of a case".
//!
//! ```text
//! cargo run --release -p dcfm-benchmarks --bin case_run -- CASE.toml [--threads 1,2]
//!     [--resume-from RUN_DIR] [--name NAME] [--no-record]
//! ```
//!
//! With `--resume-from`, every thread count starts from a copy of RUN_DIR (a `dcfm run`
//! output folder of the same case, its checkpoint included) and runs to the case's
//! `time.end`: a stretch of a long run, e.g. the Yingxiuwan case's damaging seconds, timed
//! from the same state on each thread count. Stdout: one JSON record per run; stderr: the
//! runs and the speed-ups.

use std::io::Write;
use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;
use dcfm_benchmarks::case_run::{run_case_timed, CaseRunConfig};
use dcfm_benchmarks::speedup;

#[derive(Debug, Parser)]
#[command(about = "Time whole runs of a case file and record them as throughput rows")]
struct Cli {
    /// The case file.
    case: PathBuf,
    /// Thread counts (default 1,2).
    #[arg(long, value_delimiter = ',')]
    threads: Option<Vec<usize>>,
    /// A `dcfm run` output folder of the same case to resume from (its checkpoint).
    #[arg(long)]
    resume_from: Option<PathBuf>,
    /// Row name: records are named `run_<NAME>` (default: the case file's stem).
    #[arg(long)]
    name: Option<String>,
    /// Do not append the records to the history file.
    #[arg(long)]
    no_record: bool,
    /// History file to append to (default <workspace>/benchmarks/history.jsonl).
    #[arg(long)]
    history: Option<PathBuf>,
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let mut config = CaseRunConfig::new(cli.case);
    config.name = cli.name;
    config.resume_from = cli.resume_from;
    if let Some(t) = cli.threads {
        config.threads = t;
    }
    if cli.no_record {
        config.history = None;
    } else if let Some(h) = cli.history {
        config.history = Some(h);
    }
    let result = run_case_timed(&config, |r, s| {
        println!("{}", r.to_json_line());
        let _ = std::io::stdout().flush();
        eprintln!(
            "{} {} thread(s): {} steps to t = {:.4} s in {:.2} s, {:.1} steps/s, {:.3e} element-updates/s, peak {} MiB",
            r.case,
            r.threads,
            r.steps,
            s.end_time,
            r.wall_s,
            r.steps_per_s,
            r.element_updates_per_s,
            r.peak_rss_bytes.map_or("?".to_string(), |b| (b >> 20).to_string())
        );
    });
    match result {
        Ok(records) => {
            for s in speedup::speedups(&records) {
                eprintln!(
                    "  {} {}/{} threads: {:.2}x (efficiency {:.0}%)",
                    s.case,
                    s.threads,
                    s.base_threads,
                    s.factor(),
                    100.0 * s.efficiency()
                );
            }
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(2)
        }
    }
}
