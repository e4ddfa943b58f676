//! Non-associated hyperbolic Drucker–Prager flow potential, eq. (26).
//!
//! In the Abaqus form Φ = √((ε f_t0 tan ψ)² + 3J̄₂) + (tan ψ/3) Ī₁. It is √(3/2) times the
//! paper's Φ = √((ξ α_p f_t0)² + 2J̄₂) + α_p Ī₁ with α_p = tan ψ/(3√(3/2)) and ξ = 3ε, so the
//! flow directions are identical (the factor goes into the plastic multiplier).
//!
//! The gradient m = ∂Φ/∂σ̄ = (3/2) s/R + (tan ψ/3) 1, R = √(h² + q²), h = ε f_t0 tan ψ, is
//! coaxial with σ̄. The backward-Euler return σ̄ = σ̄ᵗʳ − Δλ E₀ : m therefore keeps the
//! principal directions; the deviator shrinks radially, s = sᵗʳ q/qᵗʳ with
//! q (1 + 3μΔλ/R(q)) = qᵗʳ, and the mean stress moves by −K Δλ tan ψ.

/// Constants of the potential.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Potential {
    /// tan ψ.
    pub tan_psi: f64,
    /// h = ε f_t0 tan ψ (Pa).
    pub hyper: f64,
}

impl Potential {
    /// Flow direction m = ∂Φ/∂σ̄ in principal space (the return computes it inline).
    #[cfg(test)]
    pub fn gradient(&self, s: &[f64; 3]) -> [f64; 3] {
        let mean = (s[0] + s[1] + s[2]) / 3.0;
        let q = super::yield_surface::von_mises(s);
        let r = (self.hyper * self.hyper + q * q).sqrt();
        let t = self.tan_psi / 3.0;
        [
            1.5 * (s[0] - mean) / r + t,
            1.5 * (s[1] - mean) / r + t,
            1.5 * (s[2] - mean) / r + t,
        ]
    }

    /// Principal effective stress after a return of size Δλ from the trial `trial`
    /// (bulk modulus `k`, shear modulus `mu`), with the flow direction there (the return
    /// splits the trial once and calls [`Self::returned_from`]).
    #[cfg(test)]
    pub fn returned(&self, trial: &[f64; 3], dlam: f64, k: f64, mu: f64) -> ([f64; 3], [f64; 3]) {
        let (s, m, _) = self.returned_from(&TrialSplit::of(trial), dlam, k, mu);
        (s, m)
    }

    /// [`Self::returned`] from the trial's mean and deviator, split once per return; third,
    /// the returned √(3J̄₂) = q.
    #[inline]
    pub fn returned_from(
        &self,
        trial: &TrialSplit,
        dlam: f64,
        k: f64,
        mu: f64,
    ) -> ([f64; 3], [f64; 3], f64) {
        let q = self.shrink(trial.q, 3.0 * mu * dlam);
        let r = (self.hyper * self.hyper + q * q).sqrt();
        let (s, m) = self.at(trial, q, r, dlam, k);
        (s, m, q)
    }

    /// The return that leaves √(3J̄₂) = q, 0 < q ≤ qᵗʳ: its principal effective stress,
    /// its flow direction and its Δλ. The deviator's equation q (1 + 3μΔλ/R(q)) = qᵗʳ is
    /// explicit in Δλ,
    ///
    ///   Δλ = (qᵗʳ − q) R(q) / (3μ q),  R = √(h² + q²),
    ///
    /// where Δλ ↦ q needs a root ([`Self::shrink`]); Δλ decreases strictly from ∞ (q → 0,
    /// h > 0) to 0 (q = qᵗʳ), so q parametrises every return of a trial with qᵗʳ > 0.
    #[inline]
    pub fn returned_at_q(
        &self,
        trial: &TrialSplit,
        q: f64,
        k: f64,
        mu: f64,
    ) -> ([f64; 3], [f64; 3], f64) {
        let r = (self.hyper * self.hyper + q * q).sqrt();
        let dlam = (trial.q - q) * r / (3.0 * mu * q);
        let (s, m) = self.at(trial, q, r, dlam, k);
        (s, m, dlam)
    }

    /// Principal stress and flow direction after a return of size Δλ whose deviator
    /// shrank to √(3J̄₂) = q, with R = √(h² + q²): s = sᵗʳ q/qᵗʳ, mean − K Δλ tan ψ;
    /// m = (3/2) s/R + (tan ψ/3) 1.
    #[inline(always)]
    fn at(&self, trial: &TrialSplit, q: f64, r: f64, dlam: f64, k: f64) -> ([f64; 3], [f64; 3]) {
        let (dev, q_tr) = (&trial.dev, trial.q);
        let scale = if q_tr > 0.0 { q / q_tr } else { 0.0 };
        let mean = trial.mean - k * dlam * self.tan_psi;
        let s = [
            mean + scale * dev[0],
            mean + scale * dev[1],
            mean + scale * dev[2],
        ];
        let t = self.tan_psi / 3.0;
        let k_dev = 1.5 * scale / r;
        let m = [k_dev * dev[0] + t, k_dev * dev[1] + t, k_dev * dev[2] + t];
        (s, m)
    }

    /// The largest q that the root of [`Self::shrink`] for c = 3μΔλ cannot be below:
    /// max(qᵗʳ − c, qᵗʳ h/(h + c)) (φ ≤ 0 at both, as R ≥ q and R ≥ h), so a return to it
    /// has a Δλ at least c/(3μ).
    #[inline]
    pub fn q_below(&self, q_tr: f64, c: f64) -> f64 {
        (q_tr - c).max(q_tr * self.hyper / (self.hyper + c))
    }

    /// Root q ∈ [0, qᵗʳ] of φ(q) = q + c q/√(h² + q²) − qᵗʳ, c = 3μΔλ ≥ 0.
    ///
    /// φ is increasing and concave, so Newton started left of the root (at the h = 0
    /// solution max(qᵗʳ − c, 0), where φ ≤ 0) climbs monotonically to it. With
    /// R = √(h² + q²) the step φ/φ' = R² (R (q − qᵗʳ) + c q)/(R³ + c h²) takes one
    /// division (the return's latency chain is divisions and square roots).
    fn shrink(&self, q_tr: f64, c: f64) -> f64 {
        if q_tr <= 0.0 {
            return 0.0;
        }
        if c <= 0.0 {
            return q_tr;
        }
        let h2 = self.hyper * self.hyper;
        let mut q = (q_tr - c).max(0.0);
        for _ in 0..100 {
            let r2 = h2 + q * q;
            let r = r2.sqrt();
            let step = r2 * (r * (q - q_tr) + c * q) / (r2 * r + c * h2);
            q = (q - step).clamp(0.0, q_tr);
            if step.abs() <= 1e-15 * q_tr {
                break;
            }
        }
        q
    }
}

/// The mean stress, the deviator and qᵗʳ = √(3J̄₂) of a principal trial stress, the
/// constant part of every evaluation of a return.
#[derive(Clone, Copy, Debug)]
pub struct TrialSplit {
    /// Ī₁/3 of the trial (Pa).
    pub mean: f64,
    /// Principal deviator of the trial (Pa).
    pub dev: [f64; 3],
    /// √(3J̄₂) of the trial (Pa).
    pub q: f64,
}

impl TrialSplit {
    /// Split the sorted principal trial stress `trial`.
    #[inline]
    pub fn of(trial: &[f64; 3]) -> Self {
        let mean = (trial[0] + trial[1] + trial[2]) / 3.0;
        let dev = [trial[0] - mean, trial[1] - mean, trial[2] - mean];
        Self {
            mean,
            dev,
            q: super::yield_surface::von_mises_of_deviator(&dev),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn returned_stress_satisfies_backward_euler() {
        let pot = Potential {
            tan_psi: 30f64.to_radians().tan(),
            hyper: 0.1 * 2.9e6 * 30f64.to_radians().tan(),
        };
        let (k, mu) = (16e9, 13e9);
        let trial = [5e6, -1e6, -8e6];
        let dlam = 2e-4;
        let (s, m) = pot.returned(&trial, dlam, k, mu);
        // σ̄ = σ̄tr − Δλ E0 : m with E0 : m = 2μ m + λ tr(m) 1, λ = k − 2μ/3.
        let lam = k - 2.0 * mu / 3.0;
        let tr = m[0] + m[1] + m[2];
        for i in 0..3 {
            let expect = trial[i] - dlam * (2.0 * mu * m[i] + lam * tr);
            assert!((s[i] - expect).abs() < 1e-6, "{i}: {} vs {}", s[i], expect);
        }
        // And m is the gradient at the returned stress.
        let g = pot.gradient(&s);
        for i in 0..3 {
            assert!((g[i] - m[i]).abs() < 1e-12);
        }
    }

    /// ψ = 36°, eccentricity 0.1, f_t0 = 2.9 MPa (the W10 concrete's potential).
    fn psi36() -> Potential {
        let tan_psi = 36f64.to_radians().tan();
        Potential {
            tan_psi,
            hyper: 0.1 * 2.9e6 * tan_psi,
        }
    }

    #[test]
    fn a_return_to_q_is_the_return_of_its_explicit_dlam() {
        let pot = psi36();
        let (k, mu) = (16e9, 13e9);
        for trial in [[5e6, -1e6, -8e6], [4e6, 3.9e6, 3.8e6], [1e5, -2e4, -3e4]] {
            let split = TrialSplit::of(&trial);
            // No return at q = qᵗʳ, exactly.
            let (s, _, dlam) = pot.returned_at_q(&split, split.q, k, mu);
            assert_eq!(dlam, 0.0);
            assert_eq!(
                s,
                [
                    split.mean + split.dev[0],
                    split.mean + split.dev[1],
                    split.mean + split.dev[2]
                ]
            );
            for frac in [1e-6, 0.01, 0.3, 0.9, 0.999999] {
                let q = frac * split.q;
                let (s, m, dlam) = pot.returned_at_q(&split, q, k, mu);
                assert!(dlam > 0.0 && dlam.is_finite(), "{dlam}");
                // The same return driven by its Δλ: the deviator shrinks to q again.
                let (s2, m2, q2) = pot.returned_from(&split, dlam, k, mu);
                assert!((q2 - q).abs() <= 1e-12 * split.q, "{frac}: {q2} vs {q}");
                for i in 0..3 {
                    assert!((s2[i] - s[i]).abs() <= 1e-9 * split.q.max(split.mean.abs()));
                    assert!((m2[i] - m[i]).abs() <= 1e-9, "{frac} {i}: {m2:?} vs {m:?}");
                }
            }
        }
    }

    #[test]
    fn q_below_bounds_the_shrunk_deviator_from_below() {
        let pot = psi36();
        for q_tr in [1e-3, 1e4, 2e5, 3e6, 5e7] {
            let mut c = 1e-3;
            while c < 1e12 {
                let root = pot.shrink(q_tr, c);
                let below = pot.q_below(q_tr, c);
                assert!(
                    below > 0.0 && below <= root * (1.0 + 1e-14),
                    "{q_tr} {c}: {below} > {root}"
                );
                c *= 7.0;
            }
        }
    }

    #[test]
    fn abaqus_form_is_a_multiple_of_paper_eq_26() {
        // Φ_abaqus = √(3/2) Φ_paper with α_p = tanψ/(3√(3/2)), ξ = 3ε: compare gradients.
        let (psi, ecc, ft0): (f64, f64, f64) = (35f64.to_radians(), 0.1, 3e6);
        let pot = Potential {
            tan_psi: psi.tan(),
            hyper: ecc * ft0 * psi.tan(),
        };
        let ap = psi.tan() / (3.0 * 1.5f64.sqrt());
        let xi = 3.0 * ecc;
        let s = [4e6, 1e6, -6e6];
        let mean = (s[0] + s[1] + s[2]) / 3.0;
        let j2: f64 = s.iter().map(|v| (v - mean) * (v - mean)).sum::<f64>() / 2.0;
        let root = ((xi * ap * ft0).powi(2) + 2.0 * j2).sqrt();
        let g = pot.gradient(&s);
        for i in 0..3 {
            let paper = (s[i] - mean) / root + ap;
            assert!((g[i] - 1.5f64.sqrt() * paper).abs() < 1e-12, "{i}");
        }
    }
}
