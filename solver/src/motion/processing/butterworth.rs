//! Butterworth high-pass and low-pass filters as cascades of second-order sections,
//! designed by the bilinear transform with pre-warped corners, applied forward and
//! backward for zero phase.
//!
//! Design (Oppenheim & Schafer, *Discrete-Time Signal Processing*, 3rd ed., §7.1.2 and
//! §7.3; Butterworth poles §7.1.1): the analog prototype of order n has |H(jΩ)|² =
//! 1/(1 + (Ω/Ω_c)^{2n}); its poles pair into sections s² + 2ζ_k s + 1 with
//! ζ_k = sin((2k − 1)π/(2n)), k = 1…⌊n/2⌋, plus s + 1 when n is odd. The bilinear transform
//! s = (2/Δt)(1 − z⁻¹)/(1 + z⁻¹) with the pre-warped corner K = tan(π f_c Δt) gives, per
//! section (denominator d₀ + d₁z⁻¹ + d₂z⁻² with d₀ = 1 + 2ζK + K², d₁ = 2(K² − 1),
//! d₂ = 1 − 2ζK + K²):
//!
//! - low-pass:  K²(1 + z⁻¹)²/d,   first order K(1 + z⁻¹)/((1 + K) + (K − 1)z⁻¹);
//! - high-pass: (1 − z⁻¹)²/d,     first order (1 − z⁻¹)/((1 + K) + (K − 1)z⁻¹).
//!
//! Pre-warping makes the digital gain at f_c exactly the analog one, 1/√2 (−3 dB), for one
//! pass; the forward-backward pass squares the magnitude (−6 dB at the corner) and cancels
//! the phase, so a symmetric pulse stays symmetric (VERIFICATION.md W15).

/// One second-order section y = (b₀ + b₁z⁻¹ + b₂z⁻²)/(1 + a₁z⁻¹ + a₂z⁻²) x.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Biquad {
    pub b: [f64; 3],
    pub a: [f64; 2],
}

impl Biquad {
    /// Filter `x` in place (direct form II transposed), from rest.
    pub fn run(&self, x: &mut [f64]) {
        let (mut s1, mut s2) = (0.0, 0.0);
        let [b0, b1, b2] = self.b;
        let [a1, a2] = self.a;
        for v in x.iter_mut() {
            let input = *v;
            let y = b0 * input + s1;
            s1 = b1 * input - a1 * y + s2;
            s2 = b2 * input - a2 * y;
            *v = y;
        }
    }

    /// Complex response at normalised frequency f·Δt: |H|.
    pub fn gain(&self, f_dt: f64) -> f64 {
        let w = 2.0 * std::f64::consts::PI * f_dt;
        let (c1, s1, c2, s2) = (w.cos(), w.sin(), (2.0 * w).cos(), (2.0 * w).sin());
        let num = (
            self.b[0] + self.b[1] * c1 + self.b[2] * c2,
            -(self.b[1] * s1 + self.b[2] * s2),
        );
        let den = (
            1.0 + self.a[0] * c1 + self.a[1] * c2,
            -(self.a[0] * s1 + self.a[1] * s2),
        );
        (num.0.hypot(num.1)) / (den.0.hypot(den.1))
    }
}

/// Which side a filter passes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Pass {
    Low,
    High,
}

/// A Butterworth filter of order n as ⌈n/2⌉ sections.
#[derive(Clone, Debug, PartialEq)]
pub struct Butterworth {
    pub sections: Vec<Biquad>,
}

impl Butterworth {
    /// Design a low- or high-pass filter of `order` ≥ 1 with corner `corner` (Hz) for step
    /// `dt` (s). The corner must be in (0, 1/(2Δt)) — the caller checks and names it.
    pub fn new(pass: Pass, order: usize, corner: f64, dt: f64) -> Self {
        let k = (std::f64::consts::PI * corner * dt).tan();
        let mut sections = Vec::with_capacity(order.div_ceil(2));
        for j in 1..=order / 2 {
            let zeta = ((2 * j - 1) as f64 * std::f64::consts::PI / (2 * order) as f64).sin();
            let d0 = 1.0 + 2.0 * zeta * k + k * k;
            let d1 = 2.0 * (k * k - 1.0);
            let d2 = 1.0 - 2.0 * zeta * k + k * k;
            let b = match pass {
                Pass::Low => [k * k, 2.0 * k * k, k * k],
                Pass::High => [1.0, -2.0, 1.0],
            };
            sections.push(Biquad {
                b: b.map(|x| x / d0),
                a: [d1 / d0, d2 / d0],
            });
        }
        if order % 2 == 1 {
            let d0 = 1.0 + k;
            let b = match pass {
                Pass::Low => [k / d0, k / d0, 0.0],
                Pass::High => [1.0 / d0, -1.0 / d0, 0.0],
            };
            sections.push(Biquad {
                b,
                a: [(k - 1.0) / d0, 0.0],
            });
        }
        Self { sections }
    }

    /// One causal pass, in place.
    pub fn forward(&self, x: &mut [f64]) {
        for s in &self.sections {
            s.run(x);
        }
    }

    /// Zero-phase forward-backward pass, in place (gain squared, phase cancelled).
    pub fn forward_backward(&self, x: &mut [f64]) {
        self.forward(x);
        x.reverse();
        self.forward(x);
        x.reverse();
    }

    /// |H| of one pass at frequency `f` (Hz) for step `dt`.
    pub fn gain(&self, f: f64, dt: f64) -> f64 {
        self.sections.iter().map(|s| s.gain(f * dt)).product()
    }
}

/// Default zero-pad length (s) on each side for a high-pass corner f_c and order n:
/// 1.5 n / f_c (Converse & Brady 1992, as recommended by Boore 2005, "On pads and filters
/// for processing strong-motion data", BSSA 95(2)), so the filter transients fit in the pads.
pub fn default_pad(order: usize, highpass: f64) -> f64 {
    1.5 * order as f64 / highpass
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corner_gain_is_minus_3_db() {
        for order in 1..=8 {
            for pass in [Pass::Low, Pass::High] {
                let f = Butterworth::new(pass, order, 2.0, 0.01);
                let g = f.gain(2.0, 0.01);
                assert!(
                    (g - std::f64::consts::FRAC_1_SQRT_2).abs() < 1e-12,
                    "{order} {pass:?} {g}"
                );
            }
        }
    }
}
