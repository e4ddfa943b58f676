//! Numbers and durations as a person reads them in messages and `dcfm check`: an end time
//! of 1e30 s is `1e30`, not 31 digits, and its step count `10e33`, not 35.

/// `x` with at most six significant digits: plain from 10⁻³ to 10⁶, else in engineering
/// notation (mantissa from 1 to 999.9, four significant digits, exponent a multiple of 3).
pub fn engineering(x: f64) -> String {
    if !x.is_finite() {
        return format!("{x}");
    }
    if x == 0.0 {
        return "0".into();
    }
    let a = x.abs();
    if (1e-3..1e6).contains(&a) {
        let decimals = (5 - a.log10().floor() as i32).max(0) as usize;
        return trim(format!("{x:.decimals$}"));
    }
    let mut exp = (a.log10() / 3.0).floor() as i32 * 3;
    let mut m = x / 10f64.powi(exp);
    // Four significant digits; a mantissa that rounds up to 1000 moves to the next power.
    let digits = |m: f64| (3 - m.abs().log10().floor() as i32).max(0) as usize;
    let mut s = format!("{m:.*}", digits(m));
    if s.trim_start_matches('-').parse::<f64>().unwrap_or(0.0) >= 1000.0 {
        exp += 3;
        m /= 1000.0;
        s = format!("{m:.*}", digits(m));
    }
    format!("{}e{exp}", trim(s))
}

fn trim(s: String) -> String {
    if s.contains('.') {
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        s
    }
}

/// A wall-clock duration: seconds, minutes, hours, days or years as fits.
pub fn duration(seconds: f64) -> String {
    const MIN: f64 = 60.0;
    const HOUR: f64 = 3600.0;
    const DAY: f64 = 86_400.0;
    const YEAR: f64 = 365.25 * DAY;
    if !seconds.is_finite() {
        return "forever".into();
    }
    let one = |x: f64, unit: &str| format!("{} {unit}", engineering((x * 10.0).round() / 10.0));
    match seconds {
        s if s < 1.0 => "under a second".into(),
        s if s < MIN => format!("{} s", s.round()),
        s if s < HOUR => one(s / MIN, "min"),
        s if s < DAY => one(s / HOUR, "h"),
        s if s < YEAR => one(s / DAY, "days"),
        s if s < 1e4 * YEAR => one(s / YEAR, "years"),
        s => format!("{} years", engineering(s / YEAR)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn engineering_notation() {
        for (x, s) in [
            (0.0, "0"),
            (2e-3, "0.002"),
            (0.30000000000000004, "0.3"),
            (600_000.0, "600000"),
            (123_456.0, "123456"),
            (1e6, "1e6"),
            (1.5e7, "15e6"),
            (1e34, "10e33"),
            (1.23456e34, "12.35e33"),
            (999_960_000.0, "1e9"),
            (-2.5e-7, "-250e-9"),
            (f64::INFINITY, "inf"),
        ] {
            assert_eq!(engineering(x), s, "{x}");
        }
        // Never hundreds of digits.
        assert!(engineering(1e300).len() < 12);
        assert!(engineering(f64::MAX).len() < 12);
    }

    #[test]
    fn durations() {
        assert_eq!(duration(0.2), "under a second");
        assert_eq!(duration(42.4), "42 s");
        assert_eq!(duration(90.0), "1.5 min");
        assert_eq!(duration(7200.0), "2 h");
        assert_eq!(duration(3.0 * 86_400.0), "3 days");
        assert_eq!(duration(1e30), "31.69e21 years");
    }
}
