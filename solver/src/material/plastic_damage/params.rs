//! User parameters of the plastic-damage model (the case-file sub-table) and their
//! validation into the constants the return mapping uses.
//!
//! Two ways to give the strengths (see `docs/plastic_damage.md`):
//!
//! * **strengths**: `ft0`, `fc` (and optionally `fc0`), in the vocabulary of Abaqus'
//!   "concrete damaged plasticity";
//! * **Mohr–Coulomb** (the paper's Table 1): `ft0`, `cohesion`, `friction_angle_deg`; the
//!   uniaxial compressive strength is then f_c = 2c cos φ/(1 − sin φ) (Mohr–Coulomb
//!   uniaxial compression, e.g. Jaeger, Cook & Zimmerman 2007, §4.6).
//!
//! Missing `fc0` is 0.5 f_c. Missing fracture energies take the fib Model Code 2010
//! (eq. 5.1-9) tensile value G_t = 73 f_c^0.18 N/m (f_c in MPa) and the compressive
//! value G_c = 8.8 √f_c N/mm of Nakamura & Higai (2001).

use super::hardening::{compressive_shape, ratio_from_damage, Regularisation, SofteningLaw};
use super::recovery::Recovery;
use crate::error::{DcfmError, Result};

/// What the user writes in the case file's `plastic_damage` sub-table (SI units).
#[derive(Clone, Debug, serde::Deserialize, PartialEq)]
#[serde(deny_unknown_fields)]
pub struct PlasticDamageParams {
    /// Uniaxial tensile strength f_t0 (Pa); Table 1's "tensile strength".
    pub ft0: f64,
    /// Uniaxial compressive peak strength f_c (Pa). Give either this or
    /// `cohesion` + `friction_angle_deg`.
    #[serde(default)]
    pub fc: Option<f64>,
    /// Initial compressive yield stress f_c0 (Pa), f_t0 < f_c0 ≤ f_c; default 0.5 f_c.
    #[serde(default)]
    pub fc0: Option<f64>,
    /// Mohr–Coulomb cohesion c (Pa), Table 1.
    #[serde(default)]
    pub cohesion: Option<f64>,
    /// Mohr–Coulomb friction angle φ (degrees), Table 1.
    #[serde(default)]
    pub friction_angle_deg: Option<f64>,
    /// Tensile fracture energy G_t (N/m); default 73 f_c^0.18 (Model Code 2010).
    #[serde(default)]
    pub gt: Option<f64>,
    /// Compressive crushing energy G_c (N/m); default 8.8 √f_c N/mm (Nakamura & Higai 2001).
    #[serde(default)]
    pub gc: Option<f64>,
    /// Tension shape parameter a_t, 0 ≤ a_t < 1 (0: exponential softening; default).
    #[serde(default)]
    pub at: f64,
    /// Dilation angle ψ (degrees) of the hyperbolic Drucker–Prager potential, 0 < ψ < 56.
    #[serde(default = "default_dilation")]
    pub dilation_angle_deg: f64,
    /// Eccentricity ε of the potential (Abaqus meaning; ξ = 3ε in the paper's eq. 26), > 0.
    #[serde(default = "default_eccentricity")]
    pub eccentricity: f64,
    /// Equibiaxial to uniaxial initial compressive yield ratio f_b0/f_c0 > 1 (Kupfer: 1.16).
    #[serde(default = "default_fb0_fc0")]
    pub fb0_fc0: f64,
    /// Ratio K_c of the tensile to the compressive meridian, 0.5 < K_c ≤ 1.
    #[serde(default = "default_kc")]
    pub kc: f64,
    /// Duvaut–Lions viscosity (s); 0 = rate independent (default).
    #[serde(default)]
    pub viscosity: f64,
    /// Stiffness-recovery floor s0 of eq. (24), 0 ≤ s0 ≤ 1; equals 1 − w_c of Abaqus
    /// (w_c = 1: full recovery of tensile damage on crack closure; default s0 = 0).
    #[serde(default)]
    pub s0: f64,
    /// Tensile degradation D_t where the softening stress has fallen to f_t0/2; default:
    /// the value for d_t = b_t (0.5 when a_t = 0, as in W10).
    #[serde(default)]
    pub dt_half: Option<f64>,
    /// Compressive degradation D_c at the peak strength f_c; default: the value for
    /// d_c = b_c, i.e. 1 − (1 + a_c)/(2 a_c) (0.404 for W10's a_c = 5.224).
    #[serde(default)]
    pub dc_peak: Option<f64>,
    /// Crack-band regularisation: `"plastic"` (default; Lee & Fenves 1998: ∫f dε̃ᵖ = G/l)
    /// or `"total"` (the total work to separation per crack area is G, strengths reduced in
    /// elements too large for that; recommended for large elements). See
    /// `docs/plastic_damage.md` §1 and §4.
    #[serde(default)]
    pub regularisation: Regularisation,
    /// Stiffness recovery on crack closure: `"lee_fenves"` (default; eq. 24 with s(σ̄), the
    /// paper's model, which can return energy on closing-crack cycles) or `"consistent"`
    /// (from a Gibbs energy, no energy created on any cycle). See `docs/plastic_damage.md`
    /// §1 and §7.
    #[serde(default)]
    pub recovery: Recovery,
}

fn default_dilation() -> f64 {
    30.0
}
fn default_eccentricity() -> f64 {
    0.1
}
fn default_fb0_fc0() -> f64 {
    1.16
}
fn default_kc() -> f64 {
    2.0 / 3.0
}

impl PlasticDamageParams {
    /// Strength form with every optional parameter at its default.
    pub fn from_strengths(ft0: f64, fc0: f64, fc: f64, gt: f64, gc: f64) -> Self {
        Self {
            ft0,
            fc: Some(fc),
            fc0: Some(fc0),
            cohesion: None,
            friction_angle_deg: None,
            gt: Some(gt),
            gc: Some(gc),
            at: 0.0,
            dilation_angle_deg: default_dilation(),
            eccentricity: default_eccentricity(),
            fb0_fc0: default_fb0_fc0(),
            kc: default_kc(),
            viscosity: 0.0,
            s0: 0.0,
            dt_half: None,
            dc_peak: None,
            regularisation: Regularisation::default(),
            recovery: Recovery::default(),
        }
    }

    /// Mohr–Coulomb form (the paper's Table 1: c, φ, f_t), defaults elsewhere.
    pub fn from_mohr_coulomb(cohesion: f64, friction_angle_deg: f64, ft0: f64) -> Self {
        Self {
            fc: None,
            fc0: None,
            cohesion: Some(cohesion),
            friction_angle_deg: Some(friction_angle_deg),
            gt: None,
            gc: None,
            ..Self::from_strengths(ft0, 0.0, 0.0, 0.0, 0.0)
        }
    }
}

/// Uniaxial compressive strength of a Mohr–Coulomb material, f_c = 2c cos φ/(1 − sin φ).
pub fn mohr_coulomb_fc(cohesion: f64, friction_angle_deg: f64) -> f64 {
    let phi = friction_angle_deg.to_radians();
    2.0 * cohesion * phi.cos() / (1.0 - phi.sin())
}

/// Validated constants of the model.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Constants {
    /// Tension law (f_t0, a_t, d_t/b_t, G_t).
    pub tension: SofteningLaw,
    /// Compression law (f_c0, a_c, d_c/b_c, G_c).
    pub compression: SofteningLaw,
    /// α = (f_b0/f_c0 − 1)/(2 f_b0/f_c0 − 1) of eq. (25).
    pub alpha: f64,
    /// γ = 3(1 − K_c)/(2K_c − 1) of eq. (25).
    pub gamma: f64,
    /// tan ψ.
    pub tan_psi: f64,
    /// Hyperbola parameter ε f_t0 tan ψ of the potential (Pa).
    pub hyper: f64,
    /// Stiffness-recovery floor s0.
    pub s0: f64,
    /// Viscosity (s).
    pub viscosity: f64,
    /// Crack-band regularisation.
    pub regularisation: Regularisation,
    /// Stiffness-recovery rule.
    pub recovery: Recovery,
}

/// Check the parameters and derive the model constants. Errors name the material and the
/// violated limit.
pub fn validate(name: &str, p: &PlasticDamageParams) -> Result<Constants> {
    let bad = |msg: String| DcfmError::Material {
        material: name.to_string(),
        message: msg,
    };
    let positive = |field: &str, v: f64, unit: &str| -> Result<f64> {
        if v.is_finite() && v > 0.0 {
            Ok(v)
        } else {
            Err(bad(format!(
                "{field} = {v}: must be a finite value > 0 ({unit})"
            )))
        }
    };
    let ft0 = positive("ft0", p.ft0, "Pa")?;
    let fc = match (p.fc, p.cohesion, p.friction_angle_deg) {
        (Some(fc), None, None) => positive("fc", fc, "Pa")?,
        (None, Some(c), Some(phi)) => {
            let c = positive("cohesion", c, "Pa")?;
            if !(phi.is_finite() && phi > 0.0 && phi < 90.0) {
                return Err(bad(format!(
                    "friction_angle_deg = {phi}: must be in (0, 90) degrees"
                )));
            }
            mohr_coulomb_fc(c, phi)
        }
        (Some(_), _, _) => {
            return Err(bad(
                "give either fc or cohesion + friction_angle_deg, not both".to_string(),
            ))
        }
        _ => {
            return Err(bad(
                "the compressive strength is missing: give fc, or cohesion and \
                 friction_angle_deg (Mohr–Coulomb, Table 1)"
                    .to_string(),
            ))
        }
    };
    let fc0 = positive("fc0", p.fc0.unwrap_or(0.5 * fc), "Pa")?;
    if fc0 > fc {
        return Err(bad(format!("fc0 = {fc0} exceeds fc = {fc}: need fc0 ≤ fc")));
    }
    if ft0 >= fc0 {
        return Err(bad(format!("ft0 = {ft0} must be below fc0 = {fc0}")));
    }
    let fc_mpa = fc * 1e-6;
    let gt = positive("gt", p.gt.unwrap_or(73.0 * fc_mpa.powf(0.18)), "N/m")?;
    let gc = positive("gc", p.gc.unwrap_or(8.8e3 * fc_mpa.sqrt()), "N/m")?;
    if !(p.at.is_finite() && p.at >= 0.0 && p.at < 1.0) {
        return Err(bad(format!("at = {}: must be in [0, 1)", p.at)));
    }
    let psi = p.dilation_angle_deg;
    if !(psi.is_finite() && psi > 0.0 && psi < 56.0) {
        return Err(bad(format!(
            "dilation_angle_deg = {psi}: must be in (0, 56) degrees"
        )));
    }
    positive("eccentricity", p.eccentricity, "-")?;
    let fb = p.fb0_fc0;
    if !(fb.is_finite() && fb > 1.0) {
        return Err(bad(format!("fb0_fc0 = {fb}: must be > 1 (Kupfer: 1.16)")));
    }
    let kc = p.kc;
    if !(kc.is_finite() && kc > 0.5 && kc <= 1.0) {
        return Err(bad(format!("kc = {kc}: must be in (0.5, 1]")));
    }
    if !(p.viscosity.is_finite() && p.viscosity >= 0.0) {
        return Err(bad(format!("viscosity = {}: must be ≥ 0 (s)", p.viscosity)));
    }
    if !(p.s0.is_finite() && (0.0..=1.0).contains(&p.s0)) {
        return Err(bad(format!("s0 = {}: must be in [0, 1]", p.s0)));
    }

    let mut tension = SofteningLaw {
        f0: ft0,
        a: p.at,
        r: 1.0,
        g_f: gt,
    };
    if let Some(d) = p.dt_half {
        let yh = tension.y_half();
        let dmax = 1.0 - (-yh).exp();
        if !(d.is_finite() && d > 0.0 && d <= dmax) {
            return Err(bad(format!(
                "dt_half = {d}: must be in (0, {dmax:.4}] (d_t ≤ b_t keeps the effective \
                 tensile strength bounded)"
            )));
        }
        tension.r = ratio_from_damage(yh, d);
    }
    let a_c = compressive_shape(fc0, fc);
    let mut compression = SofteningLaw {
        f0: fc0,
        a: a_c,
        r: 1.0,
        g_f: gc,
    };
    if let Some(d) = p.dc_peak {
        let yp = compression.y_peak();
        let dmax = 1.0 - (-yp).exp();
        if !(d.is_finite() && d > 0.0 && d <= dmax) {
            return Err(bad(format!(
                "dc_peak = {d}: must be in (0, {dmax:.4}] for fc/fc0 = {:.4} \
                 (d_c ≤ b_c; needs fc > fc0)",
                fc / fc0
            )));
        }
        compression.r = ratio_from_damage(yp, d);
    }
    let tan_psi = psi.to_radians().tan();
    Ok(Constants {
        tension,
        compression,
        alpha: (fb - 1.0) / (2.0 * fb - 1.0),
        gamma: 3.0 * (1.0 - kc) / (2.0 * kc - 1.0),
        tan_psi,
        hyper: p.eccentricity * ft0 * tan_psi,
        s0: p.s0,
        viscosity: p.viscosity,
        regularisation: p.regularisation,
        recovery: p.recovery,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(p: &PlasticDamageParams) -> String {
        validate("lining", p).unwrap_err().to_string()
    }

    #[test]
    fn table1_mohr_coulomb_mapping() {
        // Rock: c 2.18 MPa, φ 41.6° → f_c = 2c cos φ/(1 − sin φ) = 9.70 MPa.
        assert!((mohr_coulomb_fc(2.18e6, 41.6) - 9.7015e6).abs() < 1e3);
        // Concrete: c 2.0 MPa, φ 46° → 9.900 MPa.
        assert!((mohr_coulomb_fc(2.0e6, 46.0) - 9.9003e6).abs() < 1e3);
        let rock = PlasticDamageParams::from_mohr_coulomb(2.18e6, 41.6, 1.97e6);
        let c = validate("rock", &rock).unwrap();
        assert!((c.compression.f0 - 0.5 * 9.7015e6).abs() < 1e3);
        // G_t = 73 f_c^0.18 N/m with f_c in MPa.
        assert!((c.tension.g_f - 73.0 * 9.7015f64.powf(0.18)).abs() < 1e-2);
    }

    #[test]
    fn alpha_gamma_from_abaqus_vocabulary() {
        let c = validate(
            "c",
            &PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 200.0, 1e4),
        )
        .unwrap();
        assert!((c.alpha - 0.16 / 1.32).abs() < 1e-15);
        assert!((c.gamma - 3.0).abs() < 1e-12);
    }

    #[test]
    fn rejects_out_of_range_parameters_naming_the_limit() {
        let base = PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 200.0, 1e4);
        let m = err(&PlasticDamageParams {
            fb0_fc0: 1.0,
            ..base.clone()
        });
        assert!(
            m.contains("lining") && m.contains("fb0_fc0 = 1") && m.contains("> 1"),
            "{m}"
        );
        let m = err(&PlasticDamageParams {
            kc: 0.5,
            ..base.clone()
        });
        assert!(m.contains("kc = 0.5") && m.contains("(0.5, 1]"), "{m}");
        let m = err(&PlasticDamageParams {
            kc: 1.2,
            ..base.clone()
        });
        assert!(m.contains("kc = 1.2"), "{m}");
        let m = err(&PlasticDamageParams {
            dilation_angle_deg: 60.0,
            ..base.clone()
        });
        assert!(
            m.contains("dilation_angle_deg = 60") && m.contains("(0, 56)"),
            "{m}"
        );
        let m = err(&PlasticDamageParams {
            dilation_angle_deg: 0.0,
            ..base.clone()
        });
        assert!(m.contains("dilation_angle_deg = 0"), "{m}");
        let m = err(&PlasticDamageParams {
            ft0: -1.0,
            ..base.clone()
        });
        assert!(m.contains("ft0 = -1") && m.contains("> 0"), "{m}");
        let m = err(&PlasticDamageParams {
            fc: Some(0.0),
            ..base.clone()
        });
        assert!(m.contains("fc = 0"), "{m}");
        let m = err(&PlasticDamageParams {
            gt: Some(0.0),
            ..base.clone()
        });
        assert!(m.contains("gt = 0"), "{m}");
        let m = err(&PlasticDamageParams {
            cohesion: Some(2e6),
            ..base.clone()
        });
        assert!(m.contains("either fc or cohesion"), "{m}");
        let m = err(&PlasticDamageParams {
            dc_peak: Some(0.6),
            ..base
        });
        assert!(m.contains("dc_peak = 0.6") && m.contains("0.4043"), "{m}");
    }

    #[test]
    fn parses_table1_rock_from_toml() {
        let p: PlasticDamageParams =
            toml::from_str("ft0 = 1.97e6\ncohesion = 2.18e6\nfriction_angle_deg = 41.6\n").unwrap();
        assert_eq!(
            p,
            PlasticDamageParams::from_mohr_coulomb(2.18e6, 41.6, 1.97e6)
        );
        assert!(toml::from_str::<PlasticDamageParams>("ft0 = 1e6\nfc = 1e7\nbogus = 1\n").is_err());
        assert_eq!(p.regularisation, Regularisation::Plastic);
        let cb: PlasticDamageParams =
            toml::from_str("ft0 = 1e6\nfc = 1e7\nregularisation = \"total\"\n").unwrap();
        assert_eq!(cb.regularisation, Regularisation::Total);
        assert_eq!(p.recovery, Recovery::LeeFenves);
        let cr: PlasticDamageParams =
            toml::from_str("ft0 = 1e6\nfc = 1e7\nrecovery = \"consistent\"\n").unwrap();
        assert_eq!(cr.recovery, Recovery::Consistent);
        let e =
            toml::from_str::<PlasticDamageParams>("ft0 = 1e6\nfc = 1e7\nregularisation = \"x\"\n")
                .unwrap_err()
                .to_string();
        assert!(e.contains("total") && e.contains("plastic"), "{e}");
    }

    #[test]
    fn parses_the_full_abaqus_vocabulary() {
        let p: PlasticDamageParams = toml::from_str(
            "ft0 = 2.9e6\nfc0 = 13e6\nfc = 24.1e6\ngt = 200.0\ngc = 1e4\nat = 0.2\n\
             dilation_angle_deg = 36.0\neccentricity = 0.1\nfb0_fc0 = 1.16\nkc = 0.667\n\
             viscosity = 1e-4\ns0 = 0.2\ndt_half = 0.4\ndc_peak = 0.3\n",
        )
        .unwrap();
        let c = validate("c", &p).unwrap();
        assert_eq!(c.viscosity, 1e-4);
        assert_eq!(c.s0, 0.2);
        assert!((c.tan_psi - 36f64.to_radians().tan()).abs() < 1e-15);
        // d/b from the degradation at the reference points.
        let yh = c.tension.y_half();
        assert!((c.tension.damage(yh) - 0.4).abs() < 1e-12);
        assert!((c.tension.stress(yh) - 0.5 * 2.9e6).abs() < 1e-6);
        let yp = c.compression.y_peak();
        assert!((c.compression.damage(yp) - 0.3).abs() < 1e-12);
        assert!((c.compression.stress(yp) - 24.1e6).abs() < 1e-3);
    }
}
