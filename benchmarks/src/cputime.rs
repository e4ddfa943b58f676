//! CPU time of this process, to tell a slow run from a starved one: on an idle machine the
//! timed steps get about `threads` CPU-seconds per wall second; when other processes
//! compete for the cores they get less, and the throughput drops for that reason alone.

/// User + system CPU time of the whole process (s), from `/proc/self/stat` (Linux; clock
/// ticks of 1/100 s). `None` where that file does not exist or cannot be parsed.
pub fn process_cpu_seconds() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // The command name (field 2) is in parentheses and may contain spaces: split after it.
    let rest = &stat[stat.rfind(')')? + 1..];
    let fields: Vec<&str> = rest.split_whitespace().collect();
    // After the name: state is field 3, so utime (14) and stime (15) are at 11 and 12.
    let utime: f64 = fields.get(11)?.parse().ok()?;
    let stime: f64 = fields.get(12)?.parse().ok()?;
    Some((utime + stime) / TICKS_PER_SECOND)
}

/// `sysconf(_SC_CLK_TCK)`, 100 on every Linux configuration in use.
const TICKS_PER_SECOND: f64 = 100.0;
