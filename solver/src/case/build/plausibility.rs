//! Plausible ranges of the physical fields (issue 13 item 4): a value its field accepts
//! but far outside what the field means is warned at its field ([`CaseWarning`]); a value
//! no physical model can have (a Young's modulus of 1e300 Pa) is refused at its field
//! ([`check_material_limits`]) before it reaches the elements, where it would read as a
//! degenerate element.
//!
//! Every range below has its reason in its doc comment. The warning ranges are wide (a
//! factor of ten or more beyond the materials and loads a rock/concrete model meets) so
//! that a correct case is not warned, while a units slip — a factor 10³, 10⁶ or 10⁹ — is.

use std::collections::BTreeMap;

use crate::case::schema::{CaseFile, MaterialSection};
use crate::case::warnings::CaseWarning;
use crate::error::{DcfmError, Result};
use crate::readable::engineering;

/// A usual range of a field: values outside `[lo, hi]` are warned, with `why`.
struct Usual {
    lo: f64,
    hi: f64,
    unit: &'static str,
    why: &'static str,
}

/// Young's modulus: soft soils have E ≈ 1–10 MPa (1e5 Pa leaves a factor of ten); diamond,
/// the stiffest solid, has E ≈ 1.2e12 Pa. GPa typed as Pa (young = 20) or MPa (2e4) lands
/// far below.
const YOUNG: Usual = Usual {
    lo: 1e5,
    hi: 1.2e12,
    unit: "Pa",
    why: "from soft soils (≈ 1 MPa, less a factor of ten) to diamond (≈ 1.2e12 Pa), the \
          stiffest solid; GPa or MPa typed as Pa?",
};

/// Density: porous fills, foams and pumice are ≥ 100 kg/m³; osmium, the densest element,
/// is 22 590 kg/m³. t/m³ or g/cm³ typed as kg/m³ gives 2.7 for rock.
const DENSITY: Usual = Usual {
    lo: 100.0,
    hi: 23_000.0,
    unit: "kg/m³",
    why: "from porous fills and foams (≈ 100 kg/m³) to osmium (22 590 kg/m³), the densest \
          element; t/m³ or g/cm³ typed as kg/m³?",
};

/// Poisson's ratio: saturated, undrained soils reach 0.49–0.495; nearer to 0.5 the P-wave
/// speed √((λ + 2μ)/ρ) grows without bound (the stable step shrinks as √(1 − 2ν)) and
/// fully integrated hex8 lock volumetrically. Negative values (auxetic foams) are rare in
/// rock and concrete; −0.5 leaves room for the few reported.
const POISSON: Usual = Usual {
    lo: -0.5,
    hi: 0.495,
    unit: "-",
    why: "saturated undrained soils reach 0.49–0.495; nearer to 0.5 the P-wave speed grows \
          without bound, the stable step shrinks as √(1 − 2ν) and hex8 lock",
};

/// Tensile strength f_t0: weak cemented soils ≈ 10 kPa; the strongest rocks and fibre
/// concretes ≈ 10–30 MPa (100 MPa leaves a factor of three). MPa typed as Pa gives 1.3 Pa,
/// whose damage then softens every element at the first step (a 0.2 s run took minutes).
const TENSILE: Usual = Usual {
    lo: 1e4,
    hi: 1e8,
    unit: "Pa",
    why: "from weak cemented soils (≈ 10 kPa) to the strongest rocks and fibre concretes \
          (≈ 30 MPa); MPa typed as Pa?",
};

/// Compressive strength f_c, f_c0: weak rock and soil-cement ≈ 1 MPa (0.1 MPa leaves a
/// factor of ten); ultra-high-performance concrete and the strongest rocks ≈ 200–400 MPa.
const COMPRESSIVE: Usual = Usual {
    lo: 1e5,
    hi: 1e9,
    unit: "Pa",
    why: "from weak rock and soil-cement (≈ 1 MPa) to ultra-high-performance concrete and \
          the strongest rocks (≈ 400 MPa); MPa typed as Pa?",
};

/// Mohr–Coulomb cohesion of a material: soils ≈ 10 kPa, intact strong rock ≈ 50–100 MPa.
const COHESION: Usual = Usual {
    lo: 1e3,
    hi: 1e9,
    unit: "Pa",
    why: "from soils (≈ 10 kPa) to intact strong rock (≈ 100 MPa); MPa typed as Pa?",
};

/// Fracture energies: G_t of concrete and rock ≈ 10–200 N/m, G_c ≈ 10⁴–5·10⁴ N/m (fib
/// Model Code 2010; Nakamura & Higai 2001). N/mm or kN/m typed as N/m is a factor 1000 off.
const FRACTURE_ENERGY: Usual = Usual {
    lo: 1.0,
    hi: 1e6,
    unit: "N/m",
    why: "fracture energies of concrete and rock are ≈ 10–200 N/m in tension and ≈ 1e4–5e4 \
          N/m in compression; kN/m or N/mm typed as N/m?",
};

/// Friction coefficient of an interface: rock and concrete joints 0.3–1.0 (Byerlee's
/// 0.6–0.85); above 2 no frictional surface (an angle in degrees or a percentage typed as
/// a coefficient?).
const FRICTION: Usual = Usual {
    lo: 0.0,
    hi: 2.0,
    unit: "-",
    why: "friction coefficients of rock and concrete joints are 0.3–1.0 (Byerlee: \
          0.6–0.85); an angle in degrees or a percentage typed as a coefficient?",
};

/// Cohesion or tensile strength of a bonded interface (when not 0): joints and bonded
/// construction joints ≈ 10 kPa–10 MPa; below 100 Pa a bond holds nothing but its own
/// weight (MPa or kPa typed as Pa?).
const BOND: Usual = Usual {
    lo: 1e2,
    hi: 1e9,
    unit: "Pa",
    why: "bonded joints carry ≈ 10 kPa–10 MPa; MPa or kPa typed as Pa? (0 for no bond)",
};

/// Gravity: 9.81 m/s² on Earth; from 0.1 m/s² (small bodies) to 1000 m/s² (≈ 100 g of a
/// geotechnical centrifuge). mm/s² typed as m/s² gives 9810.
const GRAVITY: Usual = Usual {
    lo: 0.1,
    hi: 1000.0,
    unit: "m/s²",
    why: "9.81 m/s² on Earth, up to ≈ 100 g in a centrifuge model; mm/s² or g typed as m/s²?",
};

/// Grading of a structured block (last to first element length): meshes graded towards a
/// boundary use ratios up to ≈ 20; beyond 100 the smallest elements set a step a hundred
/// times below the largest ones'.
const GRADING: Usual = Usual {
    lo: 0.01,
    hi: 100.0,
    unit: "-",
    why: "graded meshes use last/first length ratios up to ≈ 20; beyond 100 the smallest \
          elements set a stable step a hundred times below the others'",
};

/// A time step below this fraction of the stable step is warned: the run takes a thousand
/// times the steps stability needs, and the central difference's O(Δt²) error is already
/// negligible at the stable step.
pub(super) const SMALL_DT_FRACTION: f64 = 1e-3;

/// No solid is stiffer than diamond (1.2e12 Pa); above a thousand times that a Young's
/// modulus is refused (its squares overflow in the element eigenvalues near 1e154).
const YOUNG_IMPOSSIBLE: f64 = 1e15;
/// Below 1 Pa (a hundredth of the softest gels, ≈ 100 Pa) nothing is a solid.
const YOUNG_TOO_SOFT: f64 = 1.0;
/// Above 100 000 kg/m³ (four times osmium) no matter at ordinary pressure.
const DENSITY_IMPOSSIBLE: f64 = 1e5;
/// A weightless material is a legitimate static device (concrete placed on settled rock
/// without its own weight, density ≈ 1e-9 kg/m³: warned, not refused); below 1e-12 kg/m³
/// the masses are no longer a model of anything — the inverse masses overflow towards 1e300
/// and the stable step falls a million-fold below any solid's.
const DENSITY_TOO_LIGHT: f64 = 1e-12;

/// Refuse a Young's modulus or density that no material has, at its field.
pub(super) fn check_material_limits(name: &str, m: &MaterialSection, label: &str) -> Result<()> {
    let young = m.young;
    if young.is_finite() && young > 0.0 && !(YOUNG_TOO_SOFT..=YOUNG_IMPOSSIBLE).contains(&young) {
        return Err(DcfmError::invalid(
            label,
            format!("materials.{name}.young"),
            engineering(young),
            format!(
                "no solid has it: from {} Pa (softer than any gel) to {} Pa (a thousand \
                 times diamond, the stiffest solid, 1.2e12 Pa); a units slip?",
                engineering(YOUNG_TOO_SOFT),
                engineering(YOUNG_IMPOSSIBLE)
            ),
        ));
    }
    let rho = m.density;
    if rho.is_finite() && rho > 0.0 && !(DENSITY_TOO_LIGHT..=DENSITY_IMPOSSIBLE).contains(&rho) {
        return Err(DcfmError::invalid(
            label,
            format!("materials.{name}.density"),
            engineering(rho),
            format!(
                "no model has it: from {} kg/m³ (a weightless material) to {} kg/m³ \
                 (four times osmium, the densest element); a units slip?",
                engineering(DENSITY_TOO_LIGHT),
                engineering(DENSITY_IMPOSSIBLE)
            ),
        ));
    }
    Ok(())
}

/// Collects warnings for one case file.
struct Warnings<'a> {
    label: &'a str,
    out: Vec<CaseWarning>,
}

impl Warnings<'_> {
    fn check(&mut self, field: impl Into<String>, v: f64, usual: &Usual) {
        if v.is_finite() && !(usual.lo..=usual.hi).contains(&v) {
            self.push(
                field,
                v,
                format!(
                    "outside the usual {} to {} {}: {}",
                    engineering(usual.lo),
                    engineering(usual.hi),
                    usual.unit,
                    usual.why
                ),
            );
        }
    }

    fn push(&mut self, field: impl Into<String>, v: f64, expected: String) {
        self.out.push(CaseWarning {
            file: self.label.to_string(),
            field: field.into(),
            value: engineering(v),
            expected,
        });
    }
}

/// The warnings of a case whose fields are valid: every physical value outside its usual
/// range, and a given `time.dt` below [`SMALL_DT_FRACTION`] of the stable step
/// `critical` (damping included).
pub(super) fn warnings(file: &CaseFile, label: &str, dt: f64, critical: f64) -> Vec<CaseWarning> {
    let mut w = Warnings {
        label,
        out: Vec::new(),
    };
    materials(&mut w, &file.materials);
    for (k, i) in file.interfaces.iter().enumerate() {
        let f = format!("interfaces[{k}]");
        w.check(format!("{f}.mu_s"), i.mu_s, &FRICTION);
        w.check(format!("{f}.mu_d"), i.mu_d, &FRICTION);
        if i.cohesion > 0.0 {
            w.check(format!("{f}.cohesion"), i.cohesion, &BOND);
        }
        if let Some(t) = i.tensile_strength.filter(|&t| t > 0.0) {
            w.check(format!("{f}.tensile_strength"), t, &BOND);
        }
    }
    if let Some(g) = &file.loads.gravity {
        // hypot: a length of 1e300 does not overflow into ∞ (and escape the warning).
        let [x, y, z] = g.acceleration;
        let norm = x.hypot(y).hypot(z);
        if norm > 0.0 {
            w.check("loads.gravity.acceleration", norm, &GRAVITY);
        }
    }
    for (k, b) in file.mesh.blocks.iter().enumerate() {
        for d in 0..3 {
            if b.divisions[d] > 1 {
                w.check(
                    format!("mesh.blocks[{k}].grading[{d}]"),
                    b.grading[d],
                    &GRADING,
                );
            }
        }
    }
    if file.time.dt.is_none() && file.time.safety < SMALL_DT_FRACTION {
        w.push(
            "time.safety",
            file.time.safety,
            format!(
                "below {}: Δt = safety × the stable step takes more than a thousand times \
                 the steps stability needs (0.9 is usual; 0.5 for a margin)",
                engineering(SMALL_DT_FRACTION)
            ),
        );
    }
    if file.time.dt.is_some() && critical.is_finite() && dt < SMALL_DT_FRACTION * critical {
        w.push(
            "time.dt",
            dt,
            format!(
                "{} of the stable step {} s: a run of {} times the steps stability needs \
                 (leave time.dt out for {} × the stable step); a units slip?",
                engineering(dt / critical),
                engineering(critical),
                engineering((critical / dt).round()),
                file.time.safety
            ),
        );
    }
    w.out
}

fn materials(w: &mut Warnings, section: &BTreeMap<String, MaterialSection>) {
    for (name, m) in section {
        let f = format!("materials.{name}");
        w.check(format!("{f}.young"), m.young, &YOUNG);
        w.check(format!("{f}.density"), m.density, &DENSITY);
        w.check(format!("{f}.poisson"), m.poisson, &POISSON);
        let Some(p) = &m.plastic_damage else {
            continue;
        };
        let f = format!("{f}.plastic_damage");
        w.check(format!("{f}.ft0"), p.ft0, &TENSILE);
        for (key, v, usual) in [
            ("fc", p.fc, &COMPRESSIVE),
            ("fc0", p.fc0, &COMPRESSIVE),
            ("cohesion", p.cohesion, &COHESION),
            ("gt", p.gt, &FRACTURE_ENERGY),
            ("gc", p.gc, &FRACTURE_ENERGY),
        ] {
            if let Some(v) = v {
                w.check(format!("{f}.{key}"), v, usual);
            }
        }
    }
}
