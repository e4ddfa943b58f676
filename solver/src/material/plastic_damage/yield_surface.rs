//! Yield function of the effective stress, eq. (25) (Lee & Fenves 1998; Omidi & Lotfi 2010):
//!
//! F = [α Ī₁ + √(3 J̄₂) + β ⟨σ̂_max⟩ − γ ⟨−σ̂_max⟩]/(1 − α) − c̄_c(κ_c),
//! β = (1 − α) c̄_c(κ_c)/c̄_t(κ_t) − (1 + α),
//!
//! written on the principal effective stresses σ̂₁ ≥ σ̂₂ ≥ σ̂₃.

use crate::element::lanes::Lane;

/// Smallest effective tensile cohesion used in β (Pa), guards the division when the
/// effective tensile strength has softened to nothing.
const MIN_COHESION: f64 = 1e-6;

/// Constants of eq. (25).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct YieldSurface {
    /// α = (f_b0/f_c0 − 1)/(2 f_b0/f_c0 − 1).
    pub alpha: f64,
    /// γ = 3(1 − K_c)/(2K_c − 1).
    pub gamma: f64,
}

impl YieldSurface {
    /// β of eq. (25) from the effective cohesions c̄_t, c̄_c (Pa).
    #[inline]
    pub fn beta(&self, ct: f64, cc: f64) -> f64 {
        (1.0 - self.alpha) * cc / ct.max(MIN_COHESION) - (1.0 + self.alpha)
    }

    /// F of eq. (25) for sorted principal effective stresses `s` (σ̂₁ ≥ σ̂₂ ≥ σ̂₃), Pa.
    #[inline]
    pub fn value(&self, s: &[f64; 3], ct: f64, cc: f64) -> f64 {
        self.value_from(s[0] + s[1] + s[2], von_mises(s), s[0], ct, cc)
    }

    /// F of eq. (25) from Ī₁, √(3J̄₂) and σ̂_max.
    #[inline]
    pub fn value_from(&self, i1: f64, q: f64, smax: f64, ct: f64, cc: f64) -> f64 {
        let bracket =
            self.alpha * i1 + q + self.beta(ct, cc) * smax.max(0.0) - self.gamma * (-smax).max(0.0);
        bracket / (1.0 - self.alpha) - cc
    }

    /// Whether F ≤ 0 is certain from the invariants alone (no eigenvalues): when β ≥ 0, F
    /// does not decrease with σ̂_max, and σ̂_max ≤ Ī₁/3 + (2/3)√(3J̄₂).
    #[inline]
    pub fn surely_inside(&self, i1: f64, q: f64, ct: f64, cc: f64) -> bool {
        self.beta(ct, cc) >= 0.0 && self.value_from(i1, q, i1 / 3.0 + 2.0 * q / 3.0, ct, cc) <= 0.0
    }

    /// [`Self::surely_inside`] for a stress known to have no positive principal value
    /// (`principal::definiteness`): then ⟨σ̂_max⟩ = 0, whatever β, and F does not decrease
    /// with σ̂_max (γ ≥ 0), so σ̂_max ≤ min(Ī₁/3 + (2/3)√(3J̄₂), 0) bounds F.
    #[inline]
    pub fn surely_inside_compressed(&self, i1: f64, q: f64, ct: f64, cc: f64) -> bool {
        self.value_from(i1, q, largest_value_bound(i1, q).min(0.0), ct, cc) <= 0.0
    }
}

/// Ī₁ and √(3J̄₂) of a stress-like Voigt vector (tensor shear components).
#[inline]
pub fn invariants<T: Lane>(s: &[T; 6]) -> (T, T) {
    let i1 = s[0] + s[1] + s[2];
    let m = i1 / T::splat(3.0);
    let (a, b, c) = (s[0] - m, s[1] - m, s[2] - m);
    let ss = a * a + b * b + c * c + T::splat(2.0) * (s[3] * s[3] + s[4] * s[4] + s[5] * s[5]);
    (i1, (T::splat(1.5) * ss).sqrt())
}

/// The upper bound Ī₁/3 + (2/3)√(3J̄₂) of the largest principal value from the invariants
/// `i1`, `q` of [`invariants`] (one point, or one per lane): every principal value is ≤ 0
/// when it is.
#[inline]
pub fn largest_value_bound<T: Lane>(i1: T, q: T) -> T {
    i1 / T::splat(3.0) + T::splat(2.0) * q / T::splat(3.0)
}

/// √(3 J₂) of principal stresses.
#[inline]
pub fn von_mises(s: &[f64; 3]) -> f64 {
    let m = (s[0] + s[1] + s[2]) / 3.0;
    von_mises_of_deviator(&[s[0] - m, s[1] - m, s[2] - m])
}

/// √(3 J₂) = √(3/2 |s|²) of principal deviatoric stresses `dev`.
#[inline]
pub fn von_mises_of_deviator(dev: &[f64; 3]) -> f64 {
    (1.5 * (dev[0] * dev[0] + dev[1] * dev[1] + dev[2] * dev[2])).sqrt()
}

/// Lee–Fenves (1998) weight of the tensile principal effective stresses,
/// r = Σ⟨σ̂ᵢ⟩/Σ|σ̂ᵢ| (0 for a zero stress): 1 in pure tension, 0 in pure compression.
#[inline]
pub fn tension_weight(s: &[f64; 3]) -> f64 {
    let den = s[0].abs() + s[1].abs() + s[2].abs();
    if den > 0.0 {
        (s[0].max(0.0) + s[1].max(0.0) + s[2].max(0.0)) / den
    } else {
        0.0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn surface(fb: f64, kc: f64) -> YieldSurface {
        YieldSurface {
            alpha: (fb - 1.0) / (2.0 * fb - 1.0),
            gamma: 3.0 * (1.0 - kc) / (2.0 * kc - 1.0),
        }
    }

    #[test]
    fn reproduces_uniaxial_and_equibiaxial_strengths() {
        let y = surface(1.16, 2.0 / 3.0);
        let (ft, fc) = (2.9e6, 13e6);
        assert!(y.value(&[ft, 0.0, 0.0], ft, fc).abs() < 1e-6);
        assert!(y.value(&[0.0, 0.0, -fc], ft, fc).abs() < 1e-6);
        // Kupfer: equibiaxial initial yield 1.16 f_c0.
        let fb = 1.16 * fc;
        assert!(y.value(&[0.0, -fb, -fb], ft, fc).abs() < 1e-6);
    }

    #[test]
    fn kc_is_the_ratio_of_the_meridians() {
        // On the tensile and the compressive meridian
        // at the same negative pressure and σ̂max < 0, q_TM/q_CM = K_c.
        let kc = 0.7;
        let y = surface(1.16, kc);
        let (ft, fc) = (2.9e6, 13e6);
        let p = -30e6;
        // Solve F = 0 along each meridian by bisection on q.
        let solve = |tm: bool| {
            let (mut lo, mut hi) = (0.0, 1e9);
            for _ in 0..200 {
                let q = 0.5 * (lo + hi);
                // Tensile meridian σ̂1 > σ̂2 = σ̂3, compressive meridian σ̂1 = σ̂2 > σ̂3.
                let s = if tm {
                    [p + 2.0 * q / 3.0, p - q / 3.0, p - q / 3.0]
                } else {
                    [p + q / 3.0, p + q / 3.0, p - 2.0 * q / 3.0]
                };
                if y.value(&s, ft, fc) > 0.0 {
                    hi = q
                } else {
                    lo = q
                }
            }
            0.5 * (lo + hi)
        };
        let ratio = solve(true) / solve(false);
        assert!((ratio - kc).abs() < 1e-9, "{ratio}");
    }

    #[test]
    fn invariant_bound_never_misses_a_yielding_stress() {
        let y = surface(1.16, 2.0 / 3.0);
        let (ft, fc) = (2.9e6, 13e6);
        let mut lcg = crate::test_random::Lcg(12345);
        let mut rnd = || (lcg.next() - 0.5) * 3.0e7;
        let mut inside = 0;
        for _ in 0..20000 {
            let v = [rnd(), rnd(), rnd(), rnd() * 0.3, rnd() * 0.3, rnd() * 0.3];
            let (i1, q) = invariants(&v);
            let m = nalgebra::Matrix3::new(v[0], v[3], v[5], v[3], v[1], v[4], v[5], v[4], v[2]);
            let mut e: Vec<f64> = m.symmetric_eigenvalues().iter().copied().collect();
            e.sort_by(|a, b| b.total_cmp(a));
            let f = y.value(&[e[0], e[1], e[2]], ft, fc);
            assert!((von_mises(&[e[0], e[1], e[2]]) - q).abs() < 1e-6);
            if y.surely_inside(i1, q, ft, fc) {
                inside += 1;
                assert!(f <= 0.0, "{v:?}");
            }
        }
        assert!(inside > 100);
    }

    #[test]
    fn weight_factor_limits() {
        assert_eq!(tension_weight(&[1.0, 0.5, 0.0]), 1.0);
        assert_eq!(tension_weight(&[0.0, -0.5, -1.0]), 0.0);
        assert_eq!(tension_weight(&[1.0, 0.0, -1.0]), 0.5);
        assert_eq!(tension_weight(&[0.0, 0.0, 0.0]), 0.0);
    }
}
