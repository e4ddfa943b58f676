//! Fourier amplitude spectrum |A(f)| = Δt |Σₙ aₙ e^{−2πi k n/N}| at f_k = k/(NΔt),
//! k = 0 … ⌊N/2⌋ (the discrete approximation of |∫ a(t) e^{−2πift} dt|, units m/s for an
//! acceleration in m/s²), computed with rustfft.

use rustfft::{num_complex::Complex, FftPlanner};

/// (frequencies in Hz, amplitudes) of the one-sided Fourier amplitude spectrum.
pub fn fourier_amplitude(a: &[f64], dt: f64) -> (Vec<f64>, Vec<f64>) {
    let n = a.len();
    if n == 0 {
        return (Vec::new(), Vec::new());
    }
    let mut buf: Vec<Complex<f64>> = a.iter().map(|&x| Complex::new(x, 0.0)).collect();
    FftPlanner::new().plan_fft_forward(n).process(&mut buf);
    let m = n / 2 + 1;
    let freqs = (0..m).map(|k| k as f64 / (n as f64 * dt)).collect();
    let amps = buf[..m].iter().map(|c| dt * c.norm()).collect();
    (freqs, amps)
}
