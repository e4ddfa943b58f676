//! W10 — Lee–Fenves plastic-damage model, single element (Lee & Fenves 1998, J. Eng.
//! Mech. 124(8); 3D after Omidi & Lotfi 2010; paper eqs. 23–26).
//!
//! Goal: the model, driven through the real hex8 element and explicit driver, follows the
//! closed-form uniaxial laws, regularises the fracture energy with the element size,
//! recovers stiffness on crack closure and has the biaxial strength of Kupfer's tests.
//!
//! ```text
//!   one fully integrated cube of side l, rollers on x=0, y=0, z=0;
//!   the x = l face (and y = l for biaxial) moves at constant velocity, slowly
//!   (≥ 10⁴ steps over the test: inertia negligible); β = 1e-6 s stiffness damping
//! ```
//!
//! Parameters (W10): E0 = 31027 MPa, ν 0.18, f_t0 2.9 MPa, G_t 200 N/m, a_t 0 (→ b_t = d_t
//! = 14500 at l = 1 m), f_c0 13 MPa, f_c 24.1 MPa, G_c 10⁴ N/m, s0 = 0.
//! References (docs/verification_references.md §W10): at εᵖ = 1/b: σ = f_t0/e = 1.0669 MPa, D = 1 − 1/e =
//! 0.632; g = ∫σ dεᵖ = G_t/l (200 J/m³ at 1 m); a_c = 5.2240; unloading slope (1−D)E0;
//! full stiffness recovery after crack closure (E/E0 = 1 − D_c = 1 here); f_b0/f_c0 = 1.16.
//! Tolerances (W10): curve 1 %, dissipated energy per crack area 2 %, slope 1 %; Kupfer
//! ratio 1 %.
//!
//! Note: g = ∫σ dεᵖ is the plastic dissipation of the Lee–Fenves regularisation
//! (`regularisation = "plastic"`, which these references state). The total work to failure
//! also releases the elastic energy at the peak, f_t0²/(2E0) per unit volume (135.5 J/m³
//! here), so the total per crack area is G_t + f_t0² l/(2E0). The model's default,
//! `regularisation = "total"` (crack band, Bažant & Oh 1983), makes that total G_t: checked
//! here for l = 0.1, 0.5, 1 and 7 m (at 7 m the tensile strength is reduced to
//! √((1 − θ) 2E0 G_t/l) = 1.2978 MPa, θ = 0.05). See docs/plastic_damage.md §1.

use dcfm::load::TimeFunction;
use dcfm::material::plastic_damage::{
    PlasticDamageParams, Recovery, Regularisation, MIN_SOFTENING_SHARE,
};
use dcfm::material::{Elastic, Material, PlasticDamage};
use dcfm::Result;

use dcfm::element::Integration;

use crate::models::single_element::{build, build_with, point_state};
use crate::record::{CaseOutput, Check};

/// The case title (the `case` of its rows).
pub const TITLE: &str = "W10 plastic-damage, single element";

pub(crate) const SOURCE: &str = "docs/verification_references.md §W10 (Lee & Fenves 1998)";
pub(crate) const E0: f64 = 31027e6;
pub(crate) const FT0: f64 = 2.9e6;
pub(crate) const GT: f64 = 200.0;
pub(crate) const FC0: f64 = 13e6;
pub(crate) const FC: f64 = 24.1e6;
pub(crate) const GC: f64 = 1.0e4;
const STEPS: usize = 20_000;

/// The W10 material (the Lee–Fenves regularisation and eq. (24) recovery its references
/// state).
pub fn w10_material() -> Result<PlasticDamage> {
    w10_material_with(Regularisation::Plastic, Recovery::LeeFenves)
}

/// The W10 material with the given crack-band regularisation and recovery rule.
pub fn w10_material_with(
    regularisation: Regularisation,
    recovery: Recovery,
) -> Result<PlasticDamage> {
    let el = Elastic::new("w10", E0, 0.18, 2400.0)?;
    PlasticDamage::new(
        "w10",
        el,
        &PlasticDamageParams {
            regularisation,
            recovery,
            ..PlasticDamageParams::from_strengths(FT0, FC0, FC, GT, GC)
        },
    )
}

/// Uniaxial tension of one element of size `l` to separation under the total
/// regularisation: (peak σ, work to separation per crack area l(∫σ dε − ψ_end) in N/m).
pub fn total_work(l: f64) -> Result<(f64, f64)> {
    total_work_with(l, Integration::Full)
}

/// [`total_work`] with the given integration rule.
pub fn total_work_with(l: f64, integration: Integration) -> Result<(f64, f64)> {
    let pd = w10_material_with(Regularisation::Total, Recovery::LeeFenves)?;
    let (t, _) = pd.element_laws(l);
    let eps_end = t.law.f0 / E0 + 12.0 / t.b;
    let probe = build_with(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(0.0), None],
        0.0,
        integration,
    )?;
    let v = eps_end * l / (STEPS as f64 * probe.dt);
    let mut sim = build_with(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(v), None],
        1e-6,
        integration,
    )?;
    let (mut e_prev, mut s_prev, mut w, mut peak) = (0.0, 0.0, 0.0, 0.0f64);
    let mut last = [0.0; 6];
    for _ in 0..STEPS {
        sim.step()?;
        let (e, s) = sim.model.element_strain_stress(0, &sim.u);
        w += 0.5 * (s[0] + s_prev) * (e[0] - e_prev);
        peak = peak.max(s[0]);
        e_prev = e[0];
        s_prev = s[0];
        last = e;
    }
    let psi = pd.recoverable_energy_density(&last, point_state(&sim));
    Ok((peak, l * (w - psi)))
}

/// Uniaxial tension of one element of size `l`: (σ at εᵖ = 1/b, D there, ∫σ dεᵖ).
pub fn tension(l: f64) -> Result<(f64, f64, f64)> {
    tension_with(l, Integration::Full)
}

/// [`tension`] with the given integration rule.
pub fn tension_with(l: f64, integration: Integration) -> Result<(f64, f64, f64)> {
    let pd = w10_material()?;
    let b = FT0 * l / GT;
    let eps_end = FT0 / E0 + 12.0 / b;
    let probe = build_with(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(0.0), None],
        0.0,
        integration,
    )?;
    let dt = probe.dt;
    let v = eps_end * l / (STEPS as f64 * dt);
    let mut sim = build_with(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(v), None],
        1e-6,
        integration,
    )?;
    let (mut ep_prev, mut s_prev) = (0.0, 0.0);
    let mut g = 0.0;
    let mut at_1_over_b = None;
    let mut d_prev = 0.0;
    for _ in 0..STEPS {
        sim.step()?;
        let (_, s) = sim.model.element_strain_stress(0, &sim.u);
        let st = point_state(&sim);
        let ep = pd.plastic_strain(st)[0];
        let d = pd.damage(st);
        g += 0.5 * (s[0] + s_prev) * (ep - ep_prev);
        if at_1_over_b.is_none() && ep >= 1.0 / b && ep > ep_prev {
            let w = (1.0 / b - ep_prev) / (ep - ep_prev);
            at_1_over_b = Some((s_prev + w * (s[0] - s_prev), d_prev + w * (d - d_prev)));
        }
        ep_prev = ep;
        s_prev = s[0];
        d_prev = d;
    }
    let (s, d) = at_1_over_b.unwrap_or((f64::NAN, f64::NAN));
    Ok((s, d, g))
}

/// Tension to about D_t = 0.6, unloading and reloading into compression:
/// (D_t at the turn, unloading slope / E0, compressive slope after closure / E0).
pub fn cycle() -> Result<(f64, f64, f64)> {
    cycle_of(w10_material()?)
}

/// [`cycle`] for a given W10 material.
pub fn cycle_of(pd: PlasticDamage) -> Result<(f64, f64, f64)> {
    cycle_with(pd, Integration::Full)
}

/// [`cycle_of`] with the given integration rule.
pub fn cycle_with(pd: PlasticDamage, integration: Integration) -> Result<(f64, f64, f64)> {
    let l = 1.0;
    let b = FT0 * l / GT;
    // D_t = 1 − e^{−d εᵖ} = 0.6 at εᵖ = ln(2.5)/b; turn a little after the peak strain.
    let eps_turn = FT0 / E0 + (2.5f64).ln() / b;
    let probe = build_with(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(0.0), None],
        0.0,
        integration,
    )?;
    let dt = probe.dt;
    let t_turn = STEPS as f64 * dt;
    let v = eps_turn * l / t_turn;
    let history = TimeFunction::Table {
        times: vec![0.0, t_turn, t_turn + dt],
        values: vec![v, v, -v],
    };
    let mut sim = build_with(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(v), None],
        0.0,
        integration,
    )?;
    sim.model.constraints.prescribed[0].history = history;
    let mut rows: Vec<(f64, f64)> = Vec::new();
    let mut dt_turn = 0.0;
    for n in 0..(3 * STEPS) {
        sim.step()?;
        let (e, s) = sim.model.element_strain_stress(0, &sim.u);
        if n + 1 == STEPS {
            dt_turn = pd.tensile_damage(point_state(&sim));
        }
        if n >= STEPS + 10 {
            rows.push((e[0], s[0]));
        }
    }
    // Unloading slope: tensile part of the unloading branch (σ between 0.8 and 0.2 of the
    // turning stress); compressive slope: σ between −2 f_t0 and −0.5 f_t0 (closed crack).
    let s_turn = rows.first().map_or(0.0, |r| r.1);
    let slope = |lo: f64, hi: f64| -> f64 {
        let pts: Vec<&(f64, f64)> = rows.iter().filter(|r| r.1 > lo && r.1 < hi).collect();
        if pts.len() < 2 {
            return f64::NAN;
        }
        let (a, z) = (pts[0], pts[pts.len() - 1]);
        (z.1 - a.1) / (z.0 - a.0)
    };
    let unload = slope(0.2 * s_turn, 0.8 * s_turn) / E0;
    let closed = slope(-2.0 * FT0, -0.5 * FT0) / E0;
    Ok((dt_turn, unload, closed))
}

/// Peak uniaxial compressive stress and the first-yield stresses in uniaxial and in
/// equibiaxial compression: (peak, σ_y uniaxial, σ_y biaxial).
pub fn compression() -> Result<(f64, f64, f64)> {
    let l = 1.0;
    let pd = w10_material()?;
    let probe = build(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(0.0), None],
        0.0,
    )?;
    let dt = probe.dt;
    let eps_end = 3.0 * FC / E0;
    let v = -eps_end * l / (STEPS as f64 * dt);
    let first_yield = |sim: &mut dcfm::stage::Simulation| -> Result<(f64, f64)> {
        let mut peak = 0.0f64;
        let mut yield_stress = f64::NAN;
        let mut s_prev = 0.0;
        for _ in 0..STEPS {
            sim.step()?;
            let (_, s) = sim.model.element_strain_stress(0, &sim.u);
            let ep = pd.plastic_strain(point_state(sim));
            if yield_stress.is_nan() && ep.iter().any(|x| x.abs() > 1e-12) {
                yield_stress = -0.5 * (s[0] + s_prev);
            }
            s_prev = s[0];
            peak = peak.max(-s[0]);
        }
        Ok((peak, yield_stress))
    };
    let mut uni = build(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(v), None],
        1e-6,
    )?;
    let (peak, yu) = first_yield(&mut uni)?;
    let mut bi = build(
        Material::PlasticDamage(Box::new(pd.clone())),
        l,
        [Some(v), Some(v)],
        1e-6,
    )?;
    let (_, yb) = first_yield(&mut bi)?;
    Ok((peak, yu, yb))
}

/// Run W10.
pub fn run() -> Result<CaseOutput> {
    let mut check = Check::new(TITLE);
    let (s, d, g) = tension(1.0)?;
    check
        .relative(
            "tension: σ at εᵖ = 1/b (Pa)",
            FT0 / std::f64::consts::E,
            s,
            0.01,
            SOURCE,
        )
        .relative(
            "tension: D at εᵖ = 1/b",
            1.0 - (-1.0f64).exp(),
            d,
            0.01,
            SOURCE,
        )
        .relative("tension: ∫σ dεᵖ at l = 1 m (J/m³)", 200.0, g, 0.02, SOURCE);
    for l in [0.1, 0.5] {
        let (_, _, g) = tension(l)?;
        check.relative(
            &format!("tension: l·∫σ dεᵖ at l = {l} m (N/m)"),
            GT,
            l * g,
            0.02,
            SOURCE,
        );
    }
    // The default crack-band regularisation: total work to separation per area = G_t.
    for l in [0.1, 0.5, 1.0, 7.0] {
        let (peak, w) = total_work(l)?;
        check.relative(
            &format!("total regularisation: work to separation per area at l = {l} m (N/m)"),
            GT,
            w,
            0.02,
            "Bažant & Oh 1983 crack band; docs/plastic_damage.md §1",
        );
        if l > 1.5 {
            check.relative(
                &format!("total regularisation: reduced strength at l = {l} m (Pa)"),
                ((1.0 - MIN_SOFTENING_SHARE) * 2.0 * E0 * GT / l).sqrt(),
                peak,
                0.01,
                "Bažant & Oh 1983; Jirásek & Bauer 2012; docs/plastic_damage.md §1",
            );
        }
    }
    let a_c = w10_material()?.constants().compression.a;
    check.relative("compression: a_c from f_c/f_c0", 5.2240, a_c, 1e-4, SOURCE);
    let (peak, yu, yb) = compression()?;
    check
        .relative("compression: peak stress f_c (Pa)", FC, peak, 0.01, SOURCE)
        .relative("compression: first yield f_c0 (Pa)", FC0, yu, 0.01, SOURCE)
        .relative(
            "equibiaxial / uniaxial first yield (Kupfer)",
            1.16,
            yb / yu,
            0.01,
            "Kupfer et al. 1969; docs/verification_references.md §W10",
        );
    let (dt_turn, unload, closed) = cycle()?;
    check
        .relative(
            "cycle: unloading slope / E0 = 1 − D_t",
            1.0 - dt_turn,
            unload,
            0.01,
            SOURCE,
        )
        .relative(
            "cycle: slope after crack closure / E0 (s0 = 0, D_c = 0)",
            1.0,
            closed,
            0.01,
            SOURCE,
        );
    // The default, thermodynamically consistent recovery rule keeps both slopes.
    let (dt_turn, unload, closed) = cycle_of(w10_material_with(
        Regularisation::Plastic,
        Recovery::Consistent,
    )?)?;
    let src = "eq. (24) uniaxial slopes; docs/plastic_damage.md §1 (consistent recovery)";
    check
        .relative(
            "cycle, consistent recovery: unloading slope / E0 = 1 − D_t",
            1.0 - dt_turn,
            unload,
            0.01,
            src,
        )
        .relative(
            "cycle, consistent recovery: slope after crack closure / E0",
            1.0,
            closed,
            0.01,
            src,
        );
    Ok(check.finish().into())
}
