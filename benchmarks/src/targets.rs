//! The throughput targets of issues #2, #3, #4, #7 and #11 (the 100³ one-point cube, dcfm
//! against the scipy CSR leapfrog), checked against a set of records, and the boundaries'
//! overhead per step (issue #7).

use crate::record::ThroughputRecord;
use crate::speedup::speedups;

/// One-point 40³ on 2 threads: element updates per second.
pub const ONE_POINT_40_RATE: f64 = 1.0e7;
/// One-point elastic 100³ (out of cache) on 2 threads: element updates per second
/// (issue #11).
pub const ONE_POINT_100_RATE: f64 = 3.0e7;
/// Fully integrated 40³ on 2 threads: element updates per second.
pub const FULL_40_RATE: f64 = 4.0e6;
/// Fully integrated plastic-damage 40³ in the elastic regime on 2 threads (issue #4).
pub const PLASTIC_DAMAGE_40_RATE: f64 = 1.5e6;
/// Fully integrated plastic-damage 40³ on 2 threads, issue #11's rates: elastic regime and
/// damaging regime.
pub const PLASTIC_DAMAGE_40_ELASTIC_RATE_11: f64 = 6.0e6;
/// See [`PLASTIC_DAMAGE_40_ELASTIC_RATE_11`].
pub const PLASTIC_DAMAGE_40_DAMAGING_RATE_11: f64 = 2.0e6;
/// 2 threads over 1 thread in the damaging regime (issue #11 item 4): the cubes damaged
/// throughout (`_pd_damaging`) and in a weak core only (`_pd_localised`).
pub const DAMAGING_SPEEDUP: f64 = 1.8;
/// Largest share of a step spent in the contact phase with ≥ 10⁴ interface pairs (issue #3).
pub const MAX_CONTACT_SHARE: f64 = 0.15;
/// 2 threads over 1 thread, every case.
pub const TWO_THREAD_SPEEDUP: f64 = 1.7;
/// The speed-up target applies to cases of at least this many elements (20³): below, the
/// per-step fork/join overhead of rayon dominates and no one expects it to scale.
pub const SPEEDUP_MIN_ELEMENTS: usize = 8000;
/// Bytes per element, every elastic case (issue #2: "for elastic elements").
pub const MAX_BYTES_PER_ELEMENT: f64 = 2048.0;
/// The static sparse Cholesky of a 40³ cube (≈ 2e5 DOFs), whole static stage (issue #7).
pub const STATIC_CHOLESKY_40_SECONDS: f64 = 30.0;

/// Fully integrated elastic 40³ on 2 threads over the scipy CSR leapfrog of the same cube
/// on one thread, measured in the same run (issue 11).
pub const SCIPY_CSR_RATIO: f64 = 2.0;

/// Largest extra time per step of the 40³ cube on seismic boundaries (absorbing base with
/// input, free-field sides) over the fixed-base cube (issue #7).
pub const MAX_BOUNDARY_OVERHEAD: f64 = 0.10;

/// The boundaries' cost of one size and thread count: `cube{n}_full_boundaries` against
/// `cube{n}_full` timed just before it.
#[derive(Clone, Debug, PartialEq)]
pub struct BoundaryOverhead {
    /// The boundary case, e.g. `cube40_full_boundaries`.
    pub case: String,
    pub threads: usize,
    /// Extra wall time per step over the fixed-base cube, as a fraction of its step.
    pub overhead: f64,
    /// Whether either timing was starved by other processes.
    pub machine_busy: bool,
}

/// Every boundary case paired with its fixed-base cube on the same thread count.
pub fn boundary_overheads(records: &[ThroughputRecord]) -> Vec<BoundaryOverhead> {
    let mut out = Vec::new();
    for r in records.iter().filter(|r| r.case.ends_with("_boundaries")) {
        let base_case = r.case.trim_end_matches("_boundaries");
        if let Some(b) = records
            .iter()
            .rev()
            .find(|b| b.case == base_case && b.threads == r.threads)
        {
            out.push(BoundaryOverhead {
                case: r.case.clone(),
                threads: r.threads,
                overhead: b.steps_per_s / r.steps_per_s.max(1e-300) - 1.0,
                machine_busy: starved(r) || starved(b),
            });
        }
    }
    out
}

/// dcfm against the scipy CSR leapfrog on one cube and dcfm thread count.
#[derive(Clone, Debug, PartialEq)]
pub struct ScipyRatio {
    /// The dcfm case, e.g. `cube40_full`.
    pub case: String,
    /// dcfm's threads (scipy ran on one).
    pub threads: usize,
    /// dcfm's element-updates/s over scipy's.
    pub ratio: f64,
    /// Whether either timing was starved by other processes.
    pub machine_busy: bool,
}

/// Every `cube{n}_scipy_csr` row against the `cube{n}_full` rows timed before it in the
/// same records (the last of each thread count), in thread order.
pub fn scipy_ratios(records: &[ThroughputRecord]) -> Vec<ScipyRatio> {
    let mut out = Vec::new();
    for (i, s) in records.iter().enumerate() {
        let Some(case) = crate::scipy_csr::dcfm_case(&s.case) else {
            continue;
        };
        let mut dcfm: Vec<&ThroughputRecord> = Vec::new();
        for r in records[..i].iter().filter(|r| r.case == case) {
            dcfm.retain(|x| x.threads != r.threads);
            dcfm.push(r);
        }
        dcfm.sort_by_key(|r| r.threads);
        for r in dcfm {
            out.push(ScipyRatio {
                case: case.clone(),
                threads: r.threads,
                ratio: r.element_updates_per_s / s.element_updates_per_s.max(1e-300),
                machine_busy: starved(r) || starved(s),
            });
        }
    }
    out
}

/// A target and how the records fare against it.
#[derive(Clone, Debug, PartialEq)]
pub struct TargetCheck {
    /// What is required, e.g. `cube40_full, 2 threads: >= 4.0e6 element-updates/s`.
    pub target: String,
    /// The measured value.
    pub value: f64,
    /// Whether the value meets the target.
    pub met: bool,
    /// Whether a timing behind the value got less than [`BUSY_CPU_SHARE`] of its cores
    /// (other processes competed): a miss then says little about the code.
    pub machine_busy: bool,
}

/// Below this CPU share (see `ThroughputRecord::cpu_share`) a timing counts as starved.
pub const BUSY_CPU_SHARE: f64 = 0.9;

/// Whether `r` was timed while other processes took a noticeable part of its cores (only
/// judged for timings of 0.5 s or more: the CPU time has a resolution of 10 ms).
pub fn starved(r: &ThroughputRecord) -> bool {
    r.wall_s >= 0.5 && r.cpu_share.is_some_and(|s| s < BUSY_CPU_SHARE)
}

/// Check every target the records allow (a target whose case was not run is skipped).
pub fn check(records: &[ThroughputRecord]) -> Vec<TargetCheck> {
    let mut out = Vec::new();
    for (case, min) in [
        ("cube40_one_point", ONE_POINT_40_RATE),
        ("cube100_one_point", ONE_POINT_100_RATE),
        ("cube40_full", FULL_40_RATE),
        ("cube40_full_pd_elastic", PLASTIC_DAMAGE_40_RATE),
        ("cube40_full_pd_elastic", PLASTIC_DAMAGE_40_ELASTIC_RATE_11),
        (
            "cube40_full_pd_damaging",
            PLASTIC_DAMAGE_40_DAMAGING_RATE_11,
        ),
    ] {
        if let Some(r) = records
            .iter()
            .rev()
            .find(|r| r.case == case && r.threads == 2)
        {
            out.push(TargetCheck {
                target: format!("{case}, 2 threads: >= {min:.1e} element-updates/s"),
                value: r.element_updates_per_s,
                met: r.element_updates_per_s >= min,
                machine_busy: starved(r),
            });
        }
    }
    for s in speedups(records) {
        let big = records
            .iter()
            .any(|r| r.case == s.case && r.elements >= SPEEDUP_MIN_ELEMENTS);
        if big && s.base_threads == 1 && s.threads == 2 {
            let busy = records
                .iter()
                .any(|r| r.case == s.case && (r.threads == 1 || r.threads == 2) && starved(r));
            let damaging = s.case.ends_with("_pd_damaging") || s.case.ends_with("_pd_localised");
            let min = if damaging {
                DAMAGING_SPEEDUP
            } else {
                TWO_THREAD_SPEEDUP
            };
            out.push(TargetCheck {
                target: format!("{}, 2 threads: >= {min}x 1 thread", s.case),
                value: s.factor(),
                met: s.factor() >= min,
                machine_busy: busy,
            });
        }
    }
    for o in boundary_overheads(records)
        .into_iter()
        .filter(|o| o.case == "cube40_full_boundaries")
    {
        out.push(TargetCheck {
            target: format!(
                "{}, {} thread(s): boundaries add <= {:.0}% per step",
                o.case,
                o.threads,
                100.0 * MAX_BOUNDARY_OVERHEAD
            ),
            value: o.overhead,
            met: o.overhead <= MAX_BOUNDARY_OVERHEAD,
            machine_busy: o.machine_busy,
        });
    }
    if let Some(q) = scipy_ratios(records)
        .into_iter()
        .rev()
        .find(|q| q.case == "cube40_full" && q.threads == 2)
    {
        out.push(TargetCheck {
            target: format!(
                "cube40_full, 2 threads: >= {SCIPY_CSR_RATIO}x cube40_scipy_csr (scipy CSR leapfrog, 1 thread, same run)"
            ),
            value: q.ratio,
            met: q.ratio >= SCIPY_CSR_RATIO,
            machine_busy: q.machine_busy,
        });
    }
    for r in records.iter().filter(|r| r.contact_share.is_some()) {
        let share = r.contact_share.unwrap_or(0.0);
        out.push(TargetCheck {
            target: format!(
                "{}, {} thread(s): contact phase <= {MAX_CONTACT_SHARE} of the step",
                r.case, r.threads
            ),
            value: share,
            met: share <= MAX_CONTACT_SHARE,
            machine_busy: starved(r),
        });
    }
    if let Some(r) = records.iter().rev().find(|r| {
        r.case
            == crate::static_solve::case_name(
                40,
                dcfm::stage::static_stage::linear_solver::LinearSolverChoice::Cholesky,
            )
    }) {
        out.push(TargetCheck {
            target: format!(
                "{}: static stage (assembly + Cholesky + solve) <= {STATIC_CHOLESKY_40_SECONDS} s",
                r.case
            ),
            value: r.wall_s,
            met: r.wall_s <= STATIC_CHOLESKY_40_SECONDS,
            machine_busy: starved(r),
        });
    }
    let mut seen: Vec<&str> = Vec::new();
    // Bytes per element of the element groups; the static rows carry the bytes of K and L,
    // the scipy rows those of scipy's CSR matrix.
    for r in records
        .iter()
        .filter(|r| !r.case.contains("_pd_") && r.static_solve.is_none() && r.scipy_csr.is_none())
    {
        if seen.contains(&r.case.as_str()) {
            continue;
        }
        seen.push(&r.case);
        out.push(TargetCheck {
            target: format!("{}: bytes/element < {MAX_BYTES_PER_ELEMENT}", r.case),
            value: r.bytes_per_element,
            met: r.bytes_per_element < MAX_BYTES_PER_ELEMENT,
            machine_busy: false,
        });
    }
    out
}
