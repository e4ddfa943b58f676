//! Lee–Fenves (1998) uniaxial hardening/softening laws, written in the scaled equivalent
//! plastic strain y = b ε̃ᵖ so that everything except the scale b is independent of the
//! element size.
//!
//! Lee & Fenves (1998, J. Eng. Mech. 124(8), eqs. 11–14 of their paper; VERIFICATION.md W10):
//!
//! * nominal strength   f(ε̃ᵖ) = f₀ [(1+a) e^(−b ε̃ᵖ) − a e^(−2b ε̃ᵖ)]
//! * degradation        D(ε̃ᵖ) = 1 − e^(−d ε̃ᵖ)                         (paper eq. 24)
//! * effective strength f̄ = f/(1 − D) = f₀ [(1+a) e^(−(1−r)y) − a e^(−(2−r)y)],  r = d/b
//! * dissipated energy  g = ∫₀^∞ f dε̃ᵖ = (f₀/b)(1 + a/2) = G_f / l_ch  (crack band)
//! * normalised dissipated energy κ = (1/g) ∫₀^ε̃ᵖ f dε̃ᵖ ∈ [0, 1] (Lee–Fenves' damage variable).

/// One uniaxial law (tension or compression).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SofteningLaw {
    /// Initial yield strength f₀ (Pa, positive).
    pub f0: f64,
    /// Shape parameter a (0 ≤ a < 1 in tension, a ≥ 1 in compression).
    pub a: f64,
    /// Degradation ratio r = d/b, 0 < r ≤ 1.
    pub r: f64,
    /// Fracture (crushing) energy G (J/m²).
    pub g_f: f64,
}

impl SofteningLaw {
    /// Scale b (1/strain) for a characteristic length `l` from g = (f₀/b)(1 + a/2) = G/l.
    #[inline]
    pub fn b(&self, l: f64) -> f64 {
        self.f0 * (1.0 + 0.5 * self.a) * l / self.g_f
    }

    /// Dissipated energy density g = G/l (J/m³).
    #[inline]
    pub fn g(&self, l: f64) -> f64 {
        self.g_f / l
    }

    /// Nominal (damaged) strength f at scaled plastic strain y = b ε̃ᵖ (Pa).
    #[inline]
    pub fn stress(&self, y: f64) -> f64 {
        let e = (-y).exp();
        self.f0 * ((1.0 + self.a) * e - self.a * e * e)
    }

    /// Effective strength f̄ = f/(1 − D) at y (Pa): the cohesion c̄ of the yield function.
    /// With r = 1 (d = b, the default of both laws) one exponential: e^(−(1−r)y) = e^(−0)
    /// = 1 exactly, so (1+a)·1 = 1+a, and e^(−(2−r)y) = e^(−y), the same argument rounded
    /// the same way — the two-exponential form bit for bit (a non-finite y, where 0·y is
    /// NaN, takes that form).
    #[inline]
    pub fn effective(&self, y: f64) -> f64 {
        if y == 0.0 {
            return self.f0;
        }
        if self.takes_one_exponential(y) {
            return self.effective_of_exp((-y).exp());
        }
        self.effective_two_exponentials(y)
    }

    /// Whether the laws at y follow from e^(−y) alone, bit for bit: r = 1 and y finite.
    #[inline(always)]
    fn takes_one_exponential(&self, y: f64) -> bool {
        self.r == 1.0 && y.is_finite()
    }

    /// f̄ for r = 1 from e = e^(−y): f₀ [(1+a) − a e].
    #[inline(always)]
    fn effective_of_exp(&self, e: f64) -> f64 {
        self.f0 * ((1.0 + self.a) - self.a * e)
    }

    /// f̄(y) = f₀ [(1+a) e^(−(1−r)y) − a e^(−(2−r)y)] as written, for any r (y ≠ 0).
    #[inline]
    fn effective_two_exponentials(&self, y: f64) -> f64 {
        let r = self.r;
        self.f0 * ((1.0 + self.a) * (-(1.0 - r) * y).exp() - self.a * (-(2.0 - r) * y).exp())
    }

    /// Degradation D = 1 − e^(−d ε̃ᵖ) = 1 − e^(−r y) (paper eq. 24).
    #[inline]
    pub fn damage(&self, y: f64) -> f64 {
        if y == 0.0 {
            return 0.0;
        }
        1.0 - (-self.r * y).exp()
    }

    /// [`Self::effective`] and [`Self::damage`] at one y, bit for bit theirs. With r = 1
    /// (d = b, the default of both laws) one exponential serves both: e^(−(1−r)y) = e^(−0)
    /// = 1 exactly and e^(−(2−r)y) = e^(−ry) = e^(−y), the same argument rounded the same
    /// way; any other r (or a non-finite y, where 0·y is NaN) takes the two functions.
    #[inline]
    pub fn effective_and_damage(&self, y: f64) -> (f64, f64) {
        if y != 0.0 && self.takes_one_exponential(y) {
            let e = (-y).exp();
            (self.effective_of_exp(e), 1.0 - e)
        } else {
            (self.effective(y), self.damage(y))
        }
    }

    /// [`Self::damage`] and [`Self::kappa`] at one y, bit for bit theirs. With r = 1 the
    /// damage's e^(−r y) is e^(−y) (r·y = y exactly), κ's exponential; any other r (or a
    /// non-finite y) takes the two functions.
    #[inline]
    pub fn damage_and_kappa(&self, y: f64) -> (f64, f64) {
        if self.takes_one_exponential(y) {
            let e = (-y).exp();
            (if y == 0.0 { 0.0 } else { 1.0 - e }, self.kappa_of_exp(e))
        } else {
            (self.damage(y), self.kappa(y))
        }
    }

    /// Normalised dissipated energy κ(y) = [(1+a)(1−e^(−y)) − (a/2)(1−e^(−2y))]/(1 + a/2).
    #[inline]
    pub fn kappa(&self, y: f64) -> f64 {
        self.kappa_of_exp((-y).exp())
    }

    /// κ from e = e^(−y).
    #[inline(always)]
    fn kappa_of_exp(&self, e: f64) -> f64 {
        ((1.0 + self.a) * (1.0 - e) - 0.5 * self.a * (1.0 - e * e)) / (1.0 + 0.5 * self.a)
    }

    /// Scaled plastic strain y at the peak of f (0 when the law softens from the start).
    pub fn y_peak(&self) -> f64 {
        if self.a > 1.0 {
            (2.0 * self.a / (1.0 + self.a)).ln()
        } else {
            0.0
        }
    }

    /// Peak nominal strength max f = f₀ (1+a)²/(4a) for a ≥ 1, f₀ otherwise (Pa).
    pub fn peak(&self) -> f64 {
        self.stress(self.y_peak())
    }

    /// Scaled plastic strain y at which the softening branch reaches f = f₀/2.
    pub fn y_half(&self) -> f64 {
        // a u² − (1+a) u + 1/2 = 0 with u = e^(−y), smaller root (after the peak).
        let a = self.a;
        let u = if a == 0.0 {
            0.5
        } else {
            ((1.0 + a) - ((1.0 + a) * (1.0 + a) - 2.0 * a).sqrt()) / (2.0 * a)
        };
        -u.ln()
    }

    /// Largest characteristic length (m) for which the uniaxial stress–strain response of
    /// one element has no snap-back, with initial modulus `e0`.
    ///
    /// Uniaxially ε = ε̃ᵖ + f̄(ε̃ᵖ)/E₀, so dε/dε̃ᵖ = 1 + f̄′/E₀ must stay ≥ 0. With
    /// f̄′ = −f₀ b m(y), m(y) = (1+a)(1−r)e^(−(1−r)y) − a(2−r)e^(−(2−r)y), and
    /// b = f₀(1+a/2) l/G the bound is l ≤ E₀ G / (f₀² (1+a/2) max m). When the effective
    /// strength never decreases (max m ≤ 0, e.g. r = 1 with a = 0) there is no bound
    /// (`f64::INFINITY`).
    pub fn max_char_length(&self, e0: f64) -> f64 {
        let mmax = self.max_softening_rate();
        if mmax <= 0.0 {
            f64::INFINITY
        } else {
            e0 * self.g_f / (self.f0 * self.f0 * (1.0 + 0.5 * self.a) * mmax)
        }
    }
}

/// Smallest share θ of the work to separation G/l that the softening branch dissipates
/// under [`Regularisation::Total`] (the rest is the elastic energy released by the
/// degradation). θ > 0 keeps b finite for the elements whose strength is reduced; with
/// θ = 0 their response would be a vertical drop (the snap-back limit, Bažant & Oh 1983).
pub const MIN_SOFTENING_SHARE: f64 = 0.05;

/// How the softening law follows from the element's characteristic length l (crack band,
/// Bažant & Oh 1983). See `docs/plastic_damage.md` §1 "Regularisation".
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Regularisation {
    /// The total work to separation per crack area is G: g = ∫f dε̃ᵖ = G/l − w_e, where
    /// w_e is the elastic energy the degradation releases ([`SofteningLaw::released_elastic_energy`]).
    /// An element too large for that (G/l < (w_e + g_min)/(1 − θ)) gets its strengths scaled
    /// down by k, k² = (1 − θ) G / (l (w_e + g_min)), so that it stays free of snap-back and
    /// still dissipates exactly G per area (Bažant & Oh 1983; Jirásek & Bauer 2012).
    Total,
    /// Lee & Fenves (1998): the plastic dissipation g = ∫f dε̃ᵖ = G/l; the total work to
    /// separation is G + l w_e per crack area. Elements larger than
    /// [`SofteningLaw::max_char_length`] snap back and are rejected. The default until the
    /// cases and snapshots have been compared under `Total` (docs/plastic_damage.md §4).
    #[default]
    Plastic,
}

/// A law for one element size: strengths scaled by `k`, scale `b`, dissipation density `g`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ElementLaw {
    /// The law with f₀ scaled by `k` (shape a, ratio r and G unchanged).
    pub law: SofteningLaw,
    /// Strength factor k ∈ (0, 1] (1 unless the element is too large, see [`Regularisation`]).
    pub k: f64,
    /// Scale b = k f₀ (1 + a/2)/g (1/strain).
    pub b: f64,
    /// Softening (plastic) dissipation density g = ∫f dε̃ᵖ (J/m³).
    pub g: f64,
}

impl SofteningLaw {
    /// Elastic energy density released by the degradation when a uniaxial test is taken to
    /// separation (J/m³), w_e = (1/2E₀) ∫₀^∞ c̄(y)² dD(y): uniaxially ε = ε̃ᵖ + c̄/E₀ and
    /// σ = (1 − D) c̄, so ∫σ dε = g + (1/E₀)∫(1 − D) c̄ dc̄ = g + w_e (by parts, D: 0 → 1).
    /// With c̄ = f₀[(1+a)e^(−(1−r)y) − a e^(−(2−r)y)] and dD = r e^(−ry) dy:
    /// w_e = (f₀² r/2E₀) [(1+a)²/(2−r) − 2a(1+a)/(3−r) + a²/(4−r)] (f₀²/2E₀ for a = 0, r = 1).
    pub fn released_elastic_energy(&self, e0: f64) -> f64 {
        let (a, r) = (self.a, self.r);
        let bracket =
            (1.0 + a) * (1.0 + a) / (2.0 - r) - 2.0 * a * (1.0 + a) / (3.0 - r) + a * a / (4.0 - r);
        self.f0 * self.f0 * r / (2.0 * e0) * bracket
    }

    /// Smallest g without snap-back (J/m³): dε/dy = 1/b + c̄′(y)/E₀ ≥ 0 with
    /// c̄′ = −f₀ m(y) and b = f₀(1 + a/2)/g gives g ≥ f₀²(1 + a/2) max m/E₀ (0 when the
    /// effective strength never softens), see [`Self::max_char_length`].
    pub fn min_softening_energy(&self, e0: f64) -> f64 {
        let m = self.max_softening_rate();
        if m <= 0.0 {
            0.0
        } else {
            self.f0 * self.f0 * (1.0 + 0.5 * self.a) * m / e0
        }
    }

    /// The law of an element of characteristic length `l` (m) with initial modulus `e0`.
    pub fn for_length(&self, l: f64, e0: f64, reg: Regularisation) -> ElementLaw {
        let we = self.released_elastic_energy(e0);
        self.for_length_with(l, reg, we, we + self.min_softening_energy(e0))
    }

    /// [`Self::for_length`] with w_e = `we` and w_e + g_min = `need` computed beforehand
    /// (they depend on the material only; the update calls this once per point).
    #[inline]
    pub fn for_length_with(&self, l: f64, reg: Regularisation, we: f64, need: f64) -> ElementLaw {
        let gl = self.g_f / l;
        let (k, g) = match reg {
            Regularisation::Plastic => (1.0, gl),
            Regularisation::Total => {
                let k2 = ((1.0 - MIN_SOFTENING_SHARE) * gl / need).min(1.0);
                if k2 == 1.0 {
                    (1.0, gl - we)
                } else {
                    (k2.sqrt(), gl - k2 * we)
                }
            }
        };
        let law = SofteningLaw {
            f0: k * self.f0,
            ..*self
        };
        ElementLaw {
            law,
            k,
            b: law.f0 * (1.0 + 0.5 * self.a) / g,
            g,
        }
    }

    /// Largest characteristic length (m) at which [`Regularisation::Total`] keeps the full
    /// strength: (1 − θ) G/(w_e + g_min).
    pub fn full_strength_length(&self, e0: f64) -> f64 {
        (1.0 - MIN_SOFTENING_SHARE) * self.g_f
            / (self.released_elastic_energy(e0) + self.min_softening_energy(e0))
    }

    /// max over y ≥ 0 of m(y) = (1+a)(1−r)e^(−(1−r)y) − a(2−r)e^(−(2−r)y) (≤ 0: no softening
    /// of the effective strength).
    fn max_softening_rate(&self) -> f64 {
        let (a, r) = (self.a, self.r);
        let m = |y: f64| {
            (1.0 + a) * (1.0 - r) * (-(1.0 - r) * y).exp() - a * (2.0 - r) * (-(2.0 - r) * y).exp()
        };
        let mut mmax = m(0.0).max(0.0);
        if a > 0.0 && r < 1.0 {
            let arg = a * (2.0 - r) * (2.0 - r) / ((1.0 + a) * (1.0 - r) * (1.0 - r));
            if arg > 1.0 {
                mmax = mmax.max(m(arg.ln()));
            }
        }
        mmax
    }
}

/// Compression shape parameter from the initial yield and the peak strength,
/// a_c = 2 f_c/f_c0 − 1 + 2 √((f_c/f_c0)² − f_c/f_c0) (Lee & Fenves 1998; W10).
pub fn compressive_shape(fc0: f64, fc: f64) -> f64 {
    let q = fc / fc0;
    2.0 * q - 1.0 + 2.0 * (q * q - q).max(0.0).sqrt()
}

/// Degradation ratio r = d/b that gives degradation `d_ref` at scaled plastic strain `y_ref`
/// (Lee & Fenves fix d from the stiffness degradation observed at one point of the curve).
pub fn ratio_from_damage(y_ref: f64, d_ref: f64) -> f64 {
    -(1.0 - d_ref).ln() / y_ref
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn w10_compression_shape_parameter() {
        // VERIFICATION.md W10: f_c0 = 13, f_c = 24.1 MPa → a_c = 5.2240.
        let a = compressive_shape(13.0e6, 24.1e6);
        assert!((a - 5.2240).abs() < 5e-5, "a_c = {a}");
        let law = SofteningLaw {
            f0: 13.0e6,
            a,
            r: 1.0,
            g_f: 1.0e4,
        };
        assert!(
            (law.peak() - 24.1e6).abs() < 1e-6 * 24.1e6,
            "peak {}",
            law.peak()
        );
    }

    #[test]
    fn w10_tension_scale_and_energy() {
        // E0 31027 MPa, f_t0 2.9 MPa, G_t 200 N/m, l 1 m, a_t 0 → b_t = 14500.
        let law = SofteningLaw {
            f0: 2.9e6,
            a: 0.0,
            r: 1.0,
            g_f: 200.0,
        };
        assert!((law.b(1.0) - 14500.0).abs() < 1e-9);
        assert!((law.stress(1.0) - 1.0669e6).abs() < 1e-4 * 1.0669e6);
        assert!((law.damage(1.0) - 0.632).abs() < 5e-4);
        assert!((law.kappa(1.0) - (1.0 - (-1.0f64).exp())).abs() < 1e-15);
        assert_eq!(law.max_char_length(31027e6), f64::INFINITY);
    }

    #[test]
    fn snap_back_bound_matches_pure_plastic_exponential_softening() {
        // r → 0 (no degradation), a = 0: classical bound l ≤ E0 G/f0² for exponential softening.
        let law = SofteningLaw {
            f0: 3.0e6,
            a: 0.0,
            r: 1e-12,
            g_f: 100.0,
        };
        let l = law.max_char_length(30e9);
        assert!((l - 30e9 * 100.0 / 9e12).abs() < 1e-6 * l, "{l}");
        // Check by sampling dε/dε̃ᵖ = 1 + f̄'/E0 at 1.01 l_max: negative at y = 0.
        let b = law.b(1.01 * l);
        let h = 1e-7;
        let slope = (law.effective(h) - law.effective(0.0)) / h * b;
        assert!(1.0 + slope / 30e9 < 0.0);
    }

    proptest::proptest! {
        /// The one-exponential forms of r = 1 are the written formulas bit for bit — f̄
        /// against its two-exponential form, (c̄, D) and (D, κ) against the separate
        /// functions — for r = 1 and any other r (the written formulas), over the scaled
        /// plastic strains a run reaches, down to saturation (e^(−y) below 2⁻⁵³).
        #[test]
        fn one_exponential_forms_are_the_written_formulas_bit_for_bit(
            f0 in 1.0e5f64..1.0e8,
            a in 0.0f64..8.0,
            r_is_one in proptest::bool::ANY,
            r_other in 0.05f64..0.999,
            y in proptest::prop_oneof![0.0f64..1.0, 0.0f64..60.0, 1e-300f64..1e-10, proptest::strategy::Just(0.0)],
        ) {
            let law = SofteningLaw { f0, a, r: if r_is_one { 1.0 } else { r_other }, g_f: 100.0 };
            let written = if y == 0.0 { law.f0 } else { law.effective_two_exponentials(y) };
            proptest::prop_assert_eq!(law.effective(y).to_bits(), written.to_bits(), "c̄ at y = {}", y);
            let (c, d) = law.effective_and_damage(y);
            proptest::prop_assert_eq!(c.to_bits(), written.to_bits(), "c̄ at y = {}", y);
            proptest::prop_assert_eq!(d.to_bits(), law.damage(y).to_bits(), "D at y = {}", y);
            let (d, kappa) = law.damage_and_kappa(y);
            proptest::prop_assert_eq!(d.to_bits(), law.damage(y).to_bits(), "D at y = {}", y);
            proptest::prop_assert_eq!(kappa.to_bits(), law.kappa(y).to_bits(), "κ at y = {}", y);
        }
    }

    #[test]
    fn one_exponential_forms_keep_the_written_formulas_at_non_finite_y() {
        let law = SofteningLaw {
            f0: 2.0e6,
            a: 0.5,
            r: 1.0,
            g_f: 100.0,
        };
        for y in [f64::INFINITY, f64::NAN] {
            let written = law.effective_two_exponentials(y);
            assert_eq!(law.effective(y).to_bits(), written.to_bits());
            let (c, d) = law.effective_and_damage(y);
            assert_eq!(c.to_bits(), written.to_bits());
            assert_eq!(d.to_bits(), law.damage(y).to_bits());
            let (d, kappa) = law.damage_and_kappa(y);
            assert_eq!(d.to_bits(), law.damage(y).to_bits());
            assert_eq!(kappa.to_bits(), law.kappa(y).to_bits());
        }
    }
}
