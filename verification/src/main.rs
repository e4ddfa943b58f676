//! Verification runner: runs every registered case, writes `results.json` (one row per
//! checked quantity) and `reports/verification.md`. Exit status 1 if any check fails.

use std::path::PathBuf;
use std::process::ExitCode;

use clap::Parser;

use dcfm_verification::cases;
use dcfm_verification::record::{failures, CheckRow};
use dcfm_verification::report;

#[derive(Parser)]
#[command(
    about = "Run the dcfm verification cases and write results.json + reports/verification.md"
)]
struct Args {
    /// Where results.json goes.
    #[arg(long, default_value = "results/verification")]
    out: PathBuf,
    /// Where the Markdown report goes.
    #[arg(long, default_value = "reports/verification.md")]
    report: PathBuf,
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
    let mut errors = Vec::new();
    for case in cases::all() {
        if let Some(f) = &args.only {
            if !case.id.contains(f.as_str()) {
                continue;
            }
        }
        let t0 = std::time::Instant::now();
        match (case.run)() {
            Ok(r) => {
                let ok = r.iter().filter(|x| x.pass).count();
                eprintln!(
                    "{:<6} {}/{} pass  ({:.1} s)",
                    case.id,
                    ok,
                    r.len(),
                    t0.elapsed().as_secs_f64()
                );
                rows.extend(r);
            }
            Err(e) => {
                eprintln!("{:<6} ERROR: {e}", case.id);
                errors.push(format!("{}: {e}", case.id));
            }
        }
    }
    let json = serde_json::to_string_pretty(&rows).expect("rows serialise");
    let results = args.out.join("results.json");
    if let Err(e) = write_atomic(&results, &json) {
        eprintln!("{}: {e}", results.display());
        return ExitCode::FAILURE;
    }
    if let Err(e) = write_atomic(&args.report, &report::markdown(&rows, &commit())) {
        eprintln!("{}: {e}", args.report.display());
        return ExitCode::FAILURE;
    }
    let failed = failures(&rows);
    for f in &failed {
        eprintln!("FAIL {f}");
    }
    println!(
        "{} checks, {} failed, {} case errors; wrote {} and {}",
        rows.len(),
        failed.len(),
        errors.len(),
        results.display(),
        args.report.display()
    );
    if failed.is_empty() && errors.is_empty() {
        ExitCode::SUCCESS
    } else {
        ExitCode::FAILURE
    }
}
