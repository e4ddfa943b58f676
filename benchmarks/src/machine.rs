//! Which machine a record was measured on: the CPU model from `/proc/cpuinfo` and the
//! logical CPUs of the whole machine (not only those the process may run on), so that a run
//! confined to two cores of a larger machine (`taskset -c 0,1`) is not read as a run on
//! the 2-core development machine.

/// The machine fields of a record, read once per run.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Host {
    /// CPUs this process may run on.
    pub cpus: usize,
    /// The machine's logical CPUs, when more than `cpus`.
    pub machine_cpus: Option<usize>,
    /// See [`cpu_model`].
    pub cpu_model: Option<String>,
    /// `"release"` or `"debug"`: how this binary was built.
    pub profile: &'static str,
}

impl Host {
    /// This machine and binary.
    pub fn here() -> Self {
        let cpus = std::thread::available_parallelism().map_or(1, |n| n.get());
        Self {
            cpus,
            machine_cpus: machine_cpus().filter(|&n| n > cpus),
            cpu_model: cpu_model(),
            profile: if cfg!(debug_assertions) {
                "debug"
            } else {
                "release"
            },
        }
    }
}

/// The first `model name` of `/proc/cpuinfo` (x86 Linux), `None` elsewhere.
pub fn cpu_model() -> Option<String> {
    let info = std::fs::read_to_string("/proc/cpuinfo").ok()?;
    model_name(&info)
}

/// Logical CPUs of the machine: the `processor` entries of `/proc/cpuinfo`, `None` where it
/// cannot be read.
pub fn machine_cpus() -> Option<usize> {
    let info = std::fs::read_to_string("/proc/cpuinfo").ok()?;
    let n = processors(&info);
    (n > 0).then_some(n)
}

fn model_name(info: &str) -> Option<String> {
    info.lines()
        .filter_map(|l| l.split_once(':'))
        .find(|(k, _)| k.trim() == "model name")
        .map(|(_, v)| v.trim().to_string())
        .filter(|v| !v.is_empty())
}

fn processors(info: &str) -> usize {
    info.lines()
        .filter_map(|l| l.split_once(':'))
        .filter(|(k, _)| k.trim() == "processor")
        .count()
}

#[cfg(test)]
mod tests {
    use super::*;

    const INFO: &str = "processor\t: 0\nvendor_id\t: AuthenticAMD\nmodel name\t: AMD EPYC 9554 64-Core Processor\n\n\
                        processor\t: 1\nvendor_id\t: AuthenticAMD\nmodel name\t: AMD EPYC 9554 64-Core Processor\n";

    #[test]
    fn the_model_and_the_processor_count_are_read_from_cpuinfo() {
        assert_eq!(
            model_name(INFO).as_deref(),
            Some("AMD EPYC 9554 64-Core Processor")
        );
        assert_eq!(processors(INFO), 2);
        assert_eq!(model_name("processor\t: 0\n"), None);
        assert_eq!(processors(""), 0);
    }
}
