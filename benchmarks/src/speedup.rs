//! Parallel speed-up of each case: throughput on n threads over throughput on the fewest
//! threads measured for that case (normally 1).

use crate::record::ThroughputRecord;

/// Speed-up of one case at one thread count.
#[derive(Clone, Debug, PartialEq)]
pub struct Speedup {
    /// Case name.
    pub case: String,
    /// Threads of the faster run.
    pub threads: usize,
    /// Threads of the reference run.
    pub base_threads: usize,
    /// Element updates per second of the reference run.
    pub base_rate: f64,
    /// Element updates per second at `threads`.
    pub rate: f64,
}

impl Speedup {
    /// rate / base_rate.
    pub fn factor(&self) -> f64 {
        self.rate / self.base_rate
    }

    /// factor / (threads / base_threads): 1 is perfect scaling.
    pub fn efficiency(&self) -> f64 {
        self.factor() * self.base_threads as f64 / self.threads as f64
    }
}

/// Speed-ups of every case measured on more than one thread count, in the order the cases
/// first appear. When a case/thread pair was measured more than once, the last one counts.
pub fn speedups(records: &[ThroughputRecord]) -> Vec<Speedup> {
    let mut cases: Vec<&str> = Vec::new();
    for r in records {
        if !cases.contains(&r.case.as_str()) {
            cases.push(&r.case);
        }
    }
    let mut out = Vec::new();
    for case in cases {
        let mut runs: Vec<&ThroughputRecord> = Vec::new();
        for r in records.iter().filter(|r| r.case == case) {
            runs.retain(|x| x.threads != r.threads);
            runs.push(r);
        }
        runs.sort_by_key(|r| r.threads);
        let Some((base, rest)) = runs.split_first() else {
            continue;
        };
        for r in rest {
            out.push(Speedup {
                case: case.to_string(),
                threads: r.threads,
                base_threads: base.threads,
                base_rate: base.element_updates_per_s,
                rate: r.element_updates_per_s,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rec(case: &str, threads: usize, rate: f64) -> ThroughputRecord {
        ThroughputRecord {
            case: case.into(),
            elements: 8,
            nodes: 27,
            integration: "one_point".into(),
            threads,
            steps: 1,
            wall_s: 1.0,
            steps_per_s: 1.0,
            element_updates_per_s: rate,
            bytes_per_element: 1.0,
            dt_s: 1e-4,
            commit: "unknown".into(),
            timestamp: String::new(),
            cpus: 2,
            machine_cpus: None,
            cpu_model: None,
            cpu_share: None,
            contact_share: None,
            mode: "quick".into(),
            profile: "release".into(),
            peak_rss_bytes: None,
            peak_rss_reset: None,
            static_solve: None,
            scipy_csr: None,
        }
    }

    #[test]
    fn factor_against_fewest_threads() {
        let s = speedups(&[rec("a", 2, 3.0), rec("a", 1, 2.0), rec("b", 1, 1.0)]);
        assert_eq!(s.len(), 1);
        assert_eq!((s[0].threads, s[0].base_threads), (2, 1));
        assert!((s[0].factor() - 1.5).abs() < 1e-12);
        assert!((s[0].efficiency() - 0.75).abs() < 1e-12);
    }
}
