//! One throughput measurement: the JSON object printed per configuration and appended to
//! `benchmarks/history.jsonl`.

use serde::{Deserialize, Serialize};

/// Keys every record carries (the contract of `history.jsonl`; later versions may add keys,
/// never remove these).
pub const REQUIRED_KEYS: [&str; 11] = [
    "case",
    "elements",
    "integration",
    "threads",
    "steps",
    "wall_s",
    "element_updates_per_s",
    "bytes_per_element",
    "commit",
    "timestamp",
    "steps_per_s",
];

/// The timing of `steps` steps of one case on `threads` threads.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
pub struct ThroughputRecord {
    /// Case name, e.g. `cube40_one_point` (same for every thread count).
    pub case: String,
    /// Number of elements.
    pub elements: usize,
    /// Number of nodes.
    #[serde(default)]
    pub nodes: usize,
    /// Integration rule: `one_point` or `full`.
    pub integration: String,
    /// Threads of the rayon pool the steps ran in.
    pub threads: usize,
    /// Timed steps (after the warm-up).
    pub steps: u64,
    /// Wall time of the timed steps (s).
    pub wall_s: f64,
    /// steps / wall_s.
    pub steps_per_s: f64,
    /// elements × steps / wall_s: element internal-force evaluations per second (an element
    /// update of a fully integrated element covers its 8 points).
    pub element_updates_per_s: f64,
    /// Bytes per element held by the element groups (geometry, connectivity, state).
    pub bytes_per_element: f64,
    /// Time step (s).
    #[serde(default)]
    pub dt_s: f64,
    /// `git rev-parse --short HEAD`, `-dirty` appended for uncommitted changes, or `unknown`.
    pub commit: String,
    /// UTC time the measurement ended, RFC 3339 (`2026-11-22T04:13:35Z`).
    pub timestamp: String,
    /// Logical CPUs the machine offered (for comparing records across machines).
    #[serde(default)]
    pub cpus: usize,
    /// Logical CPUs of the whole machine, when more than `cpus` were there but the process
    /// was confined to fewer (`taskset`). Absent where they are the same or unknown.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub machine_cpus: Option<usize>,
    /// The CPU model (`/proc/cpuinfo`), to tell machines apart. Absent where unknown.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_model: Option<String>,
    /// CPU seconds the process used during the timed steps over (wall_s × threads): about 1
    /// on an otherwise idle machine, lower when other processes took the cores (the
    /// throughput is then understated). Absent where the CPU time cannot be read.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub cpu_share: Option<f64>,
    /// Share of the timed wall time spent in the contact phase (interface cases only).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub contact_share: Option<f64>,
    /// `quick` (CI smoke sizes) or `standard`.
    #[serde(default)]
    pub mode: String,
    /// `release`, or `debug` when built with debug assertions (numbers not comparable).
    #[serde(default)]
    pub profile: String,
    /// Peak resident memory while the case was built and timed (bytes): `VmHWM`, reset
    /// before the case where the kernel allows (`peak_rss_reset`). Absent off Linux.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_rss_bytes: Option<u64>,
    /// Whether the peak was reset before the case (false: it is the process's peak so far,
    /// an upper bound for the case).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub peak_rss_reset: Option<bool>,
    /// Static direct-solve cases (`static_cholesky_cube*`): the phases, sizes and memory of
    /// the solve; `steps` is 1 and `wall_s` the whole static stage.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub static_solve: Option<crate::static_solve::StaticSolveTiming>,
    /// The scipy CSR leapfrog rows (`cube{n}_scipy_csr`, issue 11): the stepped system's
    /// size, the versions, and dcfm's `cube{n}_full` rate in the same run over this row's
    /// per thread count. `threads` is 1, `profile` that of the runner.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub scipy_csr: Option<crate::scipy_csr::ScipyCsrInfo>,
}

impl ThroughputRecord {
    /// The record as one line of JSON (no trailing newline).
    pub fn to_json_line(&self) -> String {
        serde_json::to_string(self)
            .expect("a record of plain numbers and strings always serialises")
    }
}
