//! Peak memory of this process: the resident-set high-water mark `VmHWM` of
//! `/proc/self/status` (Linux), reset before each case through `/proc/self/clear_refs`
//! (writing `5` resets the peak to the current RSS, Linux ≥ 4.0; proc(5)), so that a
//! row's peak is that of building and timing its own case (issue #11: peak memory per run).

/// `VmHWM` in bytes, `None` where `/proc/self/status` does not exist or has no such line.
pub fn peak_rss_bytes() -> Option<u64> {
    let status = std::fs::read_to_string("/proc/self/status").ok()?;
    kib_field(&status, "VmHWM:").map(|k| k * 1024)
}

/// Reset the high-water mark to the current RSS; false where the kernel does not allow it
/// (the peak then covers the process so far).
pub fn reset_peak_rss() -> bool {
    std::fs::write("/proc/self/clear_refs", "5").is_ok()
}

/// The value in kB of a `Name:   123 kB` line.
fn kib_field(status: &str, name: &str) -> Option<u64> {
    status
        .lines()
        .find_map(|l| l.strip_prefix(name))
        .and_then(|rest| rest.split_whitespace().next())
        .and_then(|v| v.parse().ok())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_the_status_line() {
        let s = "VmPeak:\t  200 kB\nVmHWM:\t    1234 kB\nVmRSS:\t 1000 kB\n";
        assert_eq!(kib_field(s, "VmHWM:"), Some(1234));
        assert_eq!(kib_field(s, "VmSwap:"), None);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_large_allocation_raises_the_peak() {
        let before = peak_rss_bytes().expect("VmHWM on Linux");
        let v = vec![1u8; 64 << 20];
        let after = peak_rss_bytes().expect("VmHWM on Linux");
        assert!(v.iter().step_by(4096).all(|&b| b == 1));
        assert!(after >= before + (60 << 20), "{before} -> {after}");
    }
}
