//! Time window and cosine taper.

/// Samples of `a` (step `dt`) in [t0, t1] (the nearest samples), or `None` when the window
/// does not lie inside the record or holds fewer than 2 samples.
pub fn window(a: &[f64], dt: f64, t0: f64, t1: f64) -> Option<Vec<f64>> {
    if !(t0.is_finite() && t1.is_finite() && t0 >= 0.0 && t1 > t0) {
        return None;
    }
    let i0 = (t0 / dt).round() as usize;
    let i1 = (t1 / dt).round() as usize;
    if i1 > a.len() || i1 <= i0 {
        return None;
    }
    let i1 = i1.min(a.len() - 1);
    (i1 > i0).then(|| a[i0..=i1].to_vec())
}

/// Multiply the first and last `length` seconds by the half-cosine (Hann) ramp
/// w(τ) = ½(1 − cos(πτ/length)), τ the time from the nearer end (a Tukey window).
pub fn cosine_taper(a: &mut [f64], dt: f64, length: f64) {
    let n = a.len();
    if n < 2 || length <= 0.0 {
        return;
    }
    let m = ((length / dt).round() as usize).min(n / 2);
    for k in 0..m {
        let w = 0.5 * (1.0 - (std::f64::consts::PI * k as f64 / m as f64).cos());
        a[k] *= w;
        a[n - 1 - k] *= w;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn window_and_taper() {
        let a: Vec<f64> = (0..101).map(|i| i as f64).collect();
        let w = window(&a, 0.1, 2.0, 8.0).unwrap();
        assert_eq!((w[0], w[w.len() - 1], w.len()), (20.0, 80.0, 61));
        assert!(window(&a, 0.1, 2.0, 20.0).is_none());
        let mut b = vec![1.0; 100];
        cosine_taper(&mut b, 0.1, 1.0);
        assert_eq!(b[0], 0.0);
        assert_eq!(b[99], 0.0);
        assert_eq!(b[50], 1.0);
        assert!((b[5] - 0.5).abs() < 1e-12);
    }
}
