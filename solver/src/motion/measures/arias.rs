//! Arias intensity I_a = π/(2g) ∫₀ᵀ a² dt (Arias 1970, "A measure of earthquake intensity",
//! in Seismic Design for Nuclear Power Plants, MIT Press), its normalised cumulative
//! (Husid 1969) plot H(t) = ∫₀ᵗ a² / ∫₀ᵀ a², and the significant duration D5–95 =
//! t(H = 0.95) − t(H = 0.05) (Trifunac & Brady 1975, BSSA 65(3)).
//!
//! The integral of a² uses the trapezoidal rule on the samples (for a sine sampled over
//! whole periods it is exact: π A² nT/(4g), VERIFICATION.md W15).

use crate::motion::units::STANDARD_GRAVITY;

/// Cumulative ∫₀^{tᵢ} a² dt at every sample (trapezoidal).
fn cumulative_square(a: &[f64], dt: f64) -> Vec<f64> {
    let mut c = vec![0.0; a.len()];
    for i in 1..a.len() {
        c[i] = c[i - 1] + 0.5 * dt * (a[i - 1] * a[i - 1] + a[i] * a[i]);
    }
    c
}

/// Arias intensity (m/s) of an acceleration in m/s².
pub fn arias_intensity(a: &[f64], dt: f64) -> f64 {
    std::f64::consts::PI / (2.0 * STANDARD_GRAVITY)
        * cumulative_square(a, dt).last().copied().unwrap_or(0.0)
}

/// The Husid curve H(tᵢ) ∈ [0, 1] (all zero for a motion without energy).
pub fn husid(a: &[f64], dt: f64) -> Vec<f64> {
    let mut c = cumulative_square(a, dt);
    let total = c.last().copied().unwrap_or(0.0);
    if total > 0.0 {
        c.iter_mut().for_each(|x| *x /= total);
    }
    c
}

/// Times (s) where the Husid curve reaches `lo` and `hi` (linear interpolation between
/// samples) and their difference: D5–95 for (0.05, 0.95). `None` without energy.
pub fn significant_duration(a: &[f64], dt: f64, lo: f64, hi: f64) -> Option<(f64, f64, f64)> {
    let h = husid(a, dt);
    if h.last().copied().unwrap_or(0.0) <= 0.0 {
        return None;
    }
    let crossing = |level: f64| -> f64 {
        let i = h.partition_point(|&x| x < level);
        if i == 0 {
            return 0.0;
        }
        let (h0, h1) = (h[i - 1], h[i.min(h.len() - 1)]);
        let w = if h1 > h0 {
            (level - h0) / (h1 - h0)
        } else {
            0.0
        };
        ((i - 1) as f64 + w) * dt
    };
    let (t0, t1) = (crossing(lo), crossing(hi));
    Some((t0, t1, t1 - t0))
}
