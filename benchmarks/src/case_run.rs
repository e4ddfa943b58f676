//! Whole runs of a case file as throughput records (issue #11 item 5: rows for whole runs,
//! such as the Yingxiuwan case's damaging stretch; issue #10: the case's wall time and
//! memory in `history.jsonl`).
//!
//! Each thread count runs the case through the run driver (`dcfm_app::run::run_case`, what
//! `dcfm run` does) into a scratch folder of its own, from the start or — with
//! [`CaseRunConfig::resume_from`] — from a copy of a run folder's checkpoint, so that a
//! stretch late in a long run (where the damage is) is timed on every thread count from the
//! same state. The record's rates are those of the run summary: the steps this run took
//! over its wall time, start-up (building the model, reading the checkpoint) included.

use std::path::{Path, PathBuf};

use dcfm::case::load_case;
use dcfm_app::run::{run_case, RunOptions, RunSummary};

use crate::error::BenchError;
use crate::record::ThroughputRecord;
use crate::{cputime, git, history, machine, memory, timestamp};

/// What to run and where to record it.
#[derive(Clone, Debug)]
pub struct CaseRunConfig {
    /// The case file.
    pub case: PathBuf,
    /// Row name (`run_<name>` in the records); default: the case file's stem.
    pub name: Option<String>,
    /// A run folder of the same case (`dcfm run --out`) to resume from: its files are
    /// copied into each run's scratch folder and the run continues from its checkpoint
    /// with the case as it is now (a later `time.end`).
    pub resume_from: Option<PathBuf>,
    /// Thread counts, each timed on the same steps from the same state.
    pub threads: Vec<usize>,
    /// History file to append the records to (`None`: print only).
    pub history: Option<PathBuf>,
    /// Scratch folder root; each run gets `<scratch>/dcfm-case-run-<pid>-<threads>`,
    /// removed afterwards.
    pub scratch: PathBuf,
}

impl CaseRunConfig {
    /// The case on 1 and 2 threads, recorded in the default history, scratch in the
    /// system's temporary folder.
    pub fn new(case: PathBuf) -> Self {
        Self {
            case,
            name: None,
            resume_from: None,
            threads: vec![1, 2],
            history: Some(history::default_history_path()),
            scratch: std::env::temp_dir(),
        }
    }

    /// The record's case name: `run_<name>`.
    pub fn row_name(&self) -> String {
        let stem = self
            .case
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "case".to_string());
        format!("run_{}", self.name.clone().unwrap_or(stem))
    }
}

/// Copy the files of `from` (not its subfolders) into `to`.
fn copy_run_folder(from: &Path, to: &Path) -> Result<(), BenchError> {
    let io = |path: &Path| {
        let path = path.to_path_buf();
        move |source| BenchError::Io { path, source }
    };
    if !from.join("checkpoint.bin").is_file() {
        return Err(BenchError::Config(format!(
            "{}: no checkpoint.bin to resume from (a folder written by `dcfm run --out`)",
            from.display()
        )));
    }
    std::fs::create_dir_all(to).map_err(io(to))?;
    for entry in std::fs::read_dir(from).map_err(io(from))? {
        let entry = entry.map_err(io(from))?;
        if entry.file_type().map_err(io(from))?.is_file() {
            let target = to.join(entry.file_name());
            std::fs::copy(entry.path(), &target).map_err(io(&target))?;
        }
    }
    Ok(())
}

/// Run the case on every thread count and return (and record) one record each, with the
/// run summaries. A run that fails (the case refused, the run unstable) is an error.
pub fn run_case_timed(
    config: &CaseRunConfig,
    mut on_record: impl FnMut(&ThroughputRecord, &RunSummary),
) -> Result<Vec<ThroughputRecord>, BenchError> {
    if config.threads.is_empty() || config.threads.contains(&0) {
        return Err(BenchError::Config(
            "thread counts must be >= 1 (and at least one)".into(),
        ));
    }
    let commit = git::commit_label(&history::workspace_root());
    let host = machine::Host::here();
    let mut records = Vec::new();
    for &threads in &config.threads {
        let out = config
            .scratch
            .join(format!("dcfm-case-run-{}-{threads}", std::process::id()));
        let _ = std::fs::remove_dir_all(&out);
        if let Some(from) = &config.resume_from {
            copy_run_folder(from, &out)?;
        }
        let case = load_case(&config.case)?;
        let options = RunOptions {
            out: out.clone(),
            resume: config.resume_from.is_some(),
            resume_with_changed_case: config.resume_from.is_some(),
            allow_long: false,
            progress: false,
        };
        let reset = memory::reset_peak_rss();
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()?;
        let cpu0 = cputime::process_cpu_seconds();
        let summary = pool.install(|| run_case(case, &options));
        let cpu_s = cputime::process_cpu_seconds().zip(cpu0).map(|(b, a)| b - a);
        let _ = std::fs::remove_dir_all(&out);
        let summary = summary?;
        let steps = summary.steps - summary.resumed_from_step.unwrap_or(0);
        let wall_s = summary.wall_s.max(1e-9);
        let record = ThroughputRecord {
            case: config.row_name(),
            elements: summary.active_elements,
            nodes: summary.nodes,
            integration: "case".to_string(),
            threads,
            steps,
            wall_s,
            steps_per_s: summary.steps_per_s,
            element_updates_per_s: summary.element_updates_per_s,
            bytes_per_element: summary.bytes_per_element,
            dt_s: summary.dt,
            commit: commit.clone(),
            timestamp: timestamp::utc_now(),
            cpus: host.cpus,
            machine_cpus: host.machine_cpus,
            cpu_model: host.cpu_model.clone(),
            // The CPU time covers the whole call (checkpoint read and case build included);
            // the wall time of the summary starts with the run driver.
            cpu_share: cpu_s.map(|c| c / (wall_s * threads as f64)),
            contact_share: None,
            mode: if config.resume_from.is_some() {
                "case_resumed".to_string()
            } else {
                "case".to_string()
            },
            profile: host.profile.to_string(),
            peak_rss_bytes: memory::peak_rss_bytes(),
            peak_rss_reset: Some(reset),
            static_solve: None,
            scipy_csr: None,
        };
        if let Some(path) = &config.history {
            history::append(path, &record)?;
        }
        on_record(&record, &summary);
        records.push(record);
    }
    Ok(records)
}
