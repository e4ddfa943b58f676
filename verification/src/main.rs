//! Verification runner: runs every registered case and writes `results.json` (the cases'
//! metadata, one row per checked quantity, the errors of cases that could not run) and
//! `series.json` (the curves the report plots). The report itself (reports/index.html and
//! reports/verification.md) is generated from these files by `reports/generate.py`.
//! Exit status 1 if any check fails.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;

use serde::Serialize;

use dcfm_verification::cases::{self, CaseInfo};
use dcfm_verification::record::{failures, CheckRow, Series};

/// `results.json`.
#[derive(Serialize)]
struct Results<'a> {
    /// Commit the results were computed at.
    commit: String,
    /// Every registered case that ran (id, title, group, requirement, reference,
    /// tolerance and why).
    cases: Vec<CaseInfo>,
    /// One row per checked quantity.
    rows: &'a [CheckRow],
    /// Cases that stopped with an error: (id, message).
    errors: Vec<(String, String)>,
}

#[derive(Parser)]
#[command(about = "Run the dcfm verification cases and write results.json + series.json")]
struct Args {
    /// Where results.json and series.json go.
    #[arg(long, default_value = "results/verification")]
    out: PathBuf,
    /// Run only cases whose id contains this text.
    #[arg(long)]
    only: Option<String>,
}

fn commit() -> String {
    std::process::Command::new("git")
        .args(["rev-parse", "--short", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
        .unwrap_or_else(|| "unknown".into())
}

fn write_atomic(path: &std::path::Path, text: &str) -> std::io::Result<()> {
    if let Some(dir) = path.parent() {
        if !dir.as_os_str().is_empty() {
            std::fs::create_dir_all(dir)?;
        }
    }
    let tmp = path.with_extension("tmp");
    std::fs::write(&tmp, text)?;
    std::fs::rename(&tmp, path)
}

fn main() -> ExitCode {
    let args = Args::parse();
    let mut rows: Vec<CheckRow> = Vec::new();
    let mut series: Vec<Series> = Vec::new();
    let mut infos = Vec::new();
    let mut errors = Vec::new();
    for case in cases::all() {
        if let Some(f) = &args.only {
            if !case.info.id.contains(f.as_str()) {
                continue;
            }
        }
        infos.push(case.info);
        let t0 = std::time::Instant::now();
        match (case.run)() {
            Ok(out) => {
                let ok = out.rows.iter().filter(|x| x.pass).count();
                eprintln!(
                    "{:<7} {}/{} pass  ({:.1} s)",
                    case.info.id,
                    ok,
                    out.rows.len(),
                    t0.elapsed().as_secs_f64()
                );
                rows.extend(out.rows);
                series.extend(out.series);
            }
            Err(e) => {
                eprintln!("{:<7} ERROR: {e}", case.info.id);
                errors.push((case.info.id.to_string(), e.to_string()));
            }
        }
    }
    let n_errors = errors.len();
    let doc = Results {
        commit: commit(),
        cases: infos,
        rows: &rows,
        errors,
    };
    let json = serde_json::to_string_pretty(&doc).expect("results serialise");
    let results = args.out.join("results.json");
    let series_path = args.out.join("series.json");
    let series_json = serde_json::to_string(&series).expect("series serialise");
    for (path, text) in [(&results, &json), (&series_path, &series_json)] {
        if let Err(e) = write_atomic(path, text) {
            eprintln!("{}: {e}", path.display());
            return ExitCode::FAILURE;
        }
    }
    let failed = failures(&rows);
    for f in &failed {
        eprintln!("FAIL {f}");
    }
    println!(
        "{} checks, {} failed, {} case errors; wrote {} and {}",
        rows.len(),
        failed.len(),
        n_errors,
        results.display(),
        series_path.display()
    );
    if failed.is_empty() && n_errors == 0 {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
