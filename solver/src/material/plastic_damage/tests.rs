//! Single-point verification of the plastic-damage model against closed forms
//! (VERIFICATION.md W10; Lee & Fenves 1998, J. Eng. Mech. 124(8)).

use super::*;

const E0: f64 = 31027e6;
const NU: f64 = 0.18;
const FT0: f64 = 2.9e6;
const FC0: f64 = 13e6;
const FC: f64 = 24.1e6;
const GT: f64 = 200.0;
const GC: f64 = 1.0e4;

fn w10() -> PlasticDamage {
    let el = Elastic::new("w10", E0, NU, 2400.0).unwrap();
    PlasticDamage::new(
        "w10",
        el,
        &PlasticDamageParams::from_strengths(FT0, FC0, FC, GT, GC),
    )
    .unwrap()
}

/// Mixed strain/stress driver of one point: prescribed strain components, zero stress in
/// the others, solved by Newton with a finite-difference Jacobian.
struct Driver<'a> {
    m: &'a PlasticDamage,
    state: Vec<f64>,
    strain: Voigt,
    last_inc: Voigt,
    ctx: PointContext,
}

impl<'a> Driver<'a> {
    fn new(m: &'a PlasticDamage, l: f64) -> Self {
        let mut state = vec![0.0; m.state_len()];
        m.init_state(&mut state);
        Self {
            m,
            state,
            strain: [0.0; 6],
            last_inc: [0.0; 6],
            ctx: PointContext {
                char_length: l,
                dt: 1e-4,
            },
        }
    }

    /// Set the components in `fixed` and find the common value x of the `free` ones
    /// (equal by symmetry in every test) that makes their stress zero, by bracketing and
    /// regula falsi (the response has a kink at σ̂_max = 0, eq. 25); commit.
    fn step(&mut self, fixed: &[(usize, f64)], free: &[usize]) -> Voigt {
        let mut eps = self.strain;
        let mut dfix = 0.0;
        let mut dfix_last = 0.0;
        for &(i, v) in fixed {
            dfix += (v - eps[i]) * (v - eps[i]);
            dfix_last += self.last_inc[i] * self.last_inc[i];
            eps[i] = v;
        }
        let mut x0 = eps[free[0]];
        if dfix_last > 0.0 {
            x0 += (dfix / dfix_last).sqrt() * self.last_inc[free[0]];
        }
        let mut new = vec![0.0; self.state.len()];
        let m = self.m;
        let (state, ctx) = (&self.state, &self.ctx);
        let eval = |x: f64, out: &mut [f64]| {
            let mut e = eps;
            for &k in free {
                e[k] = x;
            }
            let s = m.update(&e, state, out, ctx);
            (s[free[0]], s, e)
        };
        let (f0, _, _) = eval(x0, &mut new);
        // Bracket: the lateral stress increases with the lateral strain.
        let mut dx = 1e-7 * (1.0 + x0.abs() / 1e-4);
        let (mut a, mut fa, mut b, mut fb) = (x0, f0, x0, f0);
        for _ in 0..200 {
            if fa <= 0.0 && fb >= 0.0 {
                break;
            }
            if fa > 0.0 {
                a -= dx;
                fa = eval(a, &mut new).0;
            }
            if fb < 0.0 {
                b += dx;
                fb = eval(b, &mut new).0;
            }
            dx *= 2.0;
        }
        assert!(fa <= 0.0 && fb >= 0.0, "no bracket");
        let mut side = 0;
        let mut out = (0.0, [0.0; 6], eps);
        for _ in 0..300 {
            let mut c = (a * fb - b * fa) / (fb - fa);
            if !(c > a && c < b) {
                c = 0.5 * (a + b);
            }
            out = eval(c, &mut new);
            let tol = 1e-7 * FT0.max(out.1.iter().fold(0.0f64, |p, v| p.max(v.abs())));
            if out.0.abs() < tol || b - a < 1e-18 {
                break;
            }
            if out.0 < 0.0 {
                a = c;
                fa = out.0;
                if side == 1 {
                    fb *= 0.5;
                }
                side = 1;
            } else {
                b = c;
                fb = out.0;
                if side == -1 {
                    fa *= 0.5;
                }
                side = -1;
            }
        }
        let tol = 1e-6 * FT0.max(out.1.iter().fold(0.0f64, |p, v| p.max(v.abs())));
        assert!(
            out.0.abs() < tol,
            "driver did not converge: {:?} {:?}",
            out.2,
            out.1
        );
        for i in 0..6 {
            self.last_inc[i] = out.2[i] - self.strain[i];
        }
        self.state.copy_from_slice(&new);
        self.strain = out.2;
        out.1
    }

    fn uniaxial(&mut self, axis: usize, value: f64) -> Voigt {
        let free: Vec<usize> = (0..3).filter(|&i| i != axis).collect();
        self.step(&[(axis, value), (3, 0.0), (4, 0.0), (5, 0.0)], &free)
    }
}

/// Uniaxial tension to y_t = y_end in `n` steps: (εᵖ_xx, σ_xx, D) after every step.
fn tension_curve(m: &PlasticDamage, l: f64, y_end: f64, n: usize) -> Vec<(f64, f64, f64)> {
    let b = m.constants().tension.b(l);
    let mut d = Driver::new(m, l);
    let e_end = FT0 / E0 + y_end / b;
    (1..=n)
        .map(|k| {
            let s = d.uniaxial(0, e_end * k as f64 / n as f64);
            (m.plastic_strain(&d.state)[0], s[0], m.damage(&d.state))
        })
        .collect()
}

fn trapezoid(curve: &[(f64, f64, f64)]) -> f64 {
    let mut w = 0.0;
    let mut prev = (0.0, curve[0].1);
    for &(ep, s, _) in curve {
        w += 0.5 * (s + prev.1) * (ep - prev.0);
        prev = (ep, s);
    }
    w
}

#[test]
fn w10_uniaxial_tension_follows_the_closed_form() {
    // Requirement: σ(εᵖ) = f_t0 e^(−b εᵖ), D = 1 − e^(−d εᵖ) with b = d = 14500 (W10), 1 %.
    let m = w10();
    let b = m.constants().tension.b(1.0);
    assert!((b - 14500.0).abs() < 1e-9);
    let curve = tension_curve(&m, 1.0, 3.0, 600);
    let mut worst = 0.0f64;
    for &(ep, s, d) in curve.iter().filter(|c| c.0 > 0.0) {
        let exact = FT0 * (-b * ep).exp();
        worst = worst.max((s - exact).abs() / exact);
        assert!(
            (d - (1.0 - (-b * ep).exp())).abs() < 0.01 * d.max(1e-3),
            "D {d} at {ep}"
        );
    }
    assert!(worst < 0.01, "worst relative error {worst}");
    // At εᵖ = 1/b: σ = 1.0669 MPa, D = 0.632 (interpolated along the driven curve).
    let k = curve.iter().position(|c| c.0 >= 1.0 / b).unwrap();
    let (p0, p1) = (curve[k - 1], curve[k]);
    let t = (1.0 / b - p0.0) / (p1.0 - p0.0);
    let s = p0.1 + t * (p1.1 - p0.1);
    let d = p0.2 + t * (p1.2 - p0.2);
    assert!((s - 1.0669e6).abs() < 0.01 * 1.0669e6, "σ(1/b) = {s}");
    assert!((d - 0.632).abs() < 0.01 * 0.632, "D(1/b) = {d}");
}

#[test]
fn w10_tensile_dissipation_is_g_t_over_l() {
    // ∫σ dεᵖ = G_t/l_ch = 200.00 J/m³ (W10), 2 %.
    let m = w10();
    let curve = tension_curve(&m, 1.0, 12.0, 1200);
    let w = trapezoid(&curve);
    assert!((w - 200.0).abs() < 0.02 * 200.0, "∫σ dεᵖ = {w}");
    // Total dissipation to separation adds the elastic energy at peak released by the
    // degradation (d_t = b_t keeps σ̄ = f_t0): g + f_t0²/(2E0) = 200 + 135.53 J/m³.
    let m = w10();
    let mut d = Driver::new(&m, 1.0);
    let b = m.constants().tension.b(1.0);
    let e_end = FT0 / E0 + 12.0 / b;
    for k in 1..=1200 {
        d.uniaxial(0, e_end * k as f64 / 1200.0);
    }
    let total = m.dissipated_energy_density(&d.state);
    let expect = 200.0 + FT0 * FT0 / (2.0 * E0);
    assert!(
        (total - expect).abs() < 0.02 * expect,
        "total {total} vs {expect}"
    );
    assert!((m.fracture_energy_density(&d.state) - 200.0).abs() < 0.02 * 200.0);
}

#[test]
fn w10_mesh_objectivity_of_the_dissipated_energy() {
    // Energy per crack area l_ch ∫σ dεᵖ = G_t within 2 % for l_ch = 0.1, 0.5, 1 m.
    let m = w10();
    assert_eq!(m.max_element_size(), f64::INFINITY);
    for l in [0.1, 0.5, 1.0] {
        let mut d = Driver::new(&m, l);
        let b = m.constants().tension.b(l);
        let n = 1200;
        let e_end = FT0 / E0 + 12.0 / b;
        let mut curve = Vec::with_capacity(n);
        for k in 1..=n {
            let s = d.uniaxial(0, e_end * k as f64 / n as f64);
            curve.push((m.plastic_strain(&d.state)[0], s[0], 0.0));
        }
        let g = l * trapezoid(&curve);
        assert!((g - GT).abs() < 0.02 * GT, "l = {l}: {g} J/m²");
        let tracked = l * m.fracture_energy_density(&d.state);
        assert!(
            (tracked - GT).abs() < 0.02 * GT,
            "l = {l}: tracked {tracked}"
        );
    }
}

#[test]
fn w10_uniaxial_compression_follows_the_closed_form() {
    // f_c0 = 13, f_c = 24.1 MPa → a_c = 5.2240; σ = f_c0[(1+a)e^(−bε̃) − a e^(−2bε̃)], 1 %.
    let m = w10();
    let law = m.constants().compression;
    assert!((law.a - 5.2240).abs() < 5e-5);
    let l = 0.1;
    let b = law.b(l);
    let mut d = Driver::new(&m, l);
    let n = 800;
    let e_end = -(FC0 / E0 + 3.0 / b);
    let mut peak = 0.0f64;
    let mut worst = 0.0f64;
    for k in 1..=n {
        let s = d.uniaxial(2, e_end * k as f64 / n as f64);
        let ep = -m.plastic_strain(&d.state)[2];
        peak = peak.max(-s[2]);
        if ep > 0.0 {
            let y = b * ep;
            let exact = FC0 * ((1.0 + law.a) * (-y).exp() - law.a * (-2.0 * y).exp());
            worst = worst.max((-s[2] - exact).abs() / exact);
        }
    }
    assert!(worst < 0.01, "worst relative error {worst}");
    assert!((peak - FC).abs() < 0.01 * FC, "peak {peak}");
}

#[test]
fn w10_stiffness_recovery_on_crack_closure() {
    // D_t = 0.6, D_c = 0.1, s0 = 0: E/E0 = 0.36 in tension, 0.90 after crack closure.
    let m = w10();
    let mut st = vec![0.0; m.state_len()];
    st[slot::Y_T] = -(0.4f64).ln() / m.constants().tension.r;
    st[slot::Y_C] = -(0.9f64).ln() / m.constants().compression.r;
    assert!((m.tensile_damage(&st) - 0.6).abs() < 1e-12);
    assert!((m.compressive_damage(&st) - 0.1).abs() < 1e-12);
    let ctx = PointContext {
        char_length: 1.0,
        dt: 1e-4,
    };
    let el = *m.elastic();
    for (sign, expect) in [(1.0, 0.36), (-1.0, 0.90)] {
        let eps = [sign * 1e-6, 0.0, 0.0, 0.0, 0.0, 0.0];
        let mut new = vec![0.0; m.state_len()];
        let s = m.update(&eps, &st, &mut new, &ctx);
        let ratio = s[0] / el.stress(&eps)[0];
        assert!((ratio - expect).abs() < 1e-12, "{sign}: {ratio}");
        assert!((m.damage(&new) - (1.0 - expect)).abs() < 1e-12);
        assert_eq!(m.stress_from_state(&eps, &new), s);
    }
}

#[test]
fn cyclic_tension_then_compression_recovers_the_stiffness() {
    // Crack in tension, unload, close: the compressive tangent is (1 − D_c) E0 = E0.
    let m = w10();
    let b = m.constants().tension.b(1.0);
    let mut d = Driver::new(&m, 1.0);
    let e_peak = FT0 / E0 + 1.0 / b;
    for k in 1..=100 {
        d.uniaxial(0, e_peak * k as f64 / 100.0);
    }
    let dt = m.tensile_damage(&d.state);
    let ep = m.plastic_strain(&d.state)[0];
    // Reverse well past crack closure (ε < εᵖ) while staying elastic in compression.
    let targets = [ep + 2e-6, ep + 1e-6, ep - 1e-5, ep - 1.1e-5];
    let s: Vec<f64> = targets.iter().map(|&e| d.uniaxial(0, e)[0]).collect();
    let open = (s[1] - s[0]) / (targets[1] - targets[0]);
    let closed = (s[3] - s[2]) / (targets[3] - targets[2]);
    assert!(
        (open / E0 - (1.0 - dt)).abs() < 0.01 * (1.0 - dt),
        "open {}",
        open / E0
    );
    assert!((closed / E0 - 1.0).abs() < 0.01, "closed {}", closed / E0);
    assert!(m.compressive_damage(&d.state) < 1e-6);
}

#[test]
fn unloading_slope_is_the_degraded_modulus() {
    // Requirement: unloading slope (1 − D) E0 within 1 % (W10).
    let m = w10();
    let b = m.constants().tension.b(1.0);
    let mut d = Driver::new(&m, 1.0);
    let e_max = FT0 / E0 + 1.5 / b;
    for k in 1..=150 {
        d.uniaxial(0, e_max * k as f64 / 150.0);
    }
    let dmg = m.damage(&d.state);
    let s0 = d.uniaxial(0, e_max - 1e-6)[0];
    let s1 = d.uniaxial(0, e_max - 2e-6)[0];
    let slope = (s0 - s1) / 1e-6;
    let expect = (1.0 - dmg) * E0;
    assert!(dmg > 0.7);
    assert!(
        (slope - expect).abs() < 0.01 * expect,
        "{slope} vs {expect}"
    );
}

#[test]
fn equibiaxial_compression_yields_at_fb0_over_fc0() {
    // Kupfer: initial equibiaxial yield f_b0 = 1.16 f_c0 (eq. 25 with α from f_b0/f_c0).
    let m = w10();
    let first_yield = |biaxial: bool| {
        let mut d = Driver::new(&m, 0.1);
        let n = 3000;
        let e_end = -1.5 * FC0 / E0;
        let mut last = 0.0;
        for k in 1..=n {
            let e = e_end * k as f64 / n as f64;
            let s = if biaxial {
                d.step(&[(0, e), (1, e), (3, 0.0), (4, 0.0), (5, 0.0)], &[2])
            } else {
                d.uniaxial(0, e)
            };
            if m.kappa_c(&d.state) > 0.0 {
                return -last;
            }
            last = s[0];
        }
        panic!("no yield");
    };
    let ratio = first_yield(true) / first_yield(false);
    assert!((ratio - 1.16).abs() < 0.01 * 1.16, "f_b0/f_c0 = {ratio}");
}

#[test]
fn purely_elastic_path_is_exactly_elastic() {
    let m = w10();
    let mut d = Driver::new(&m, 1.0);
    let el = *m.elastic();
    let path = [
        [2e-5, -1e-5, 0.5e-5, 1e-5, 0.0, -2e-5],
        [-1e-4, -0.5e-4, 0.0, 0.0, 3e-5, 0.0],
        [1e-5, 1e-5, 1e-5, 0.0, 0.0, 0.0],
    ];
    for eps in path {
        let mut new = vec![0.0; m.state_len()];
        let s = m.update(&eps, &d.state, &mut new, &d.ctx);
        assert_eq!(s, el.stress(&eps));
        assert_eq!(m.damage(&new), 0.0);
        assert_eq!(m.plastic_strain(&new), [0.0; 6]);
        assert_eq!(m.dissipated_energy_density(&new), 0.0);
        d.state = new;
    }
}

#[test]
fn duvaut_lions_relaxes_halfway_when_dt_equals_viscosity() {
    let el = Elastic::new("v", E0, NU, 2400.0).unwrap();
    let p = PlasticDamageParams::from_strengths(FT0, FC0, FC, GT, GC);
    let inviscid = PlasticDamage::new("v", el, &p).unwrap();
    let viscous = PlasticDamage::new(
        "v",
        el,
        &PlasticDamageParams {
            viscosity: 1e-3,
            ..p
        },
    )
    .unwrap();
    let eps = [3.0 * FT0 / E0, 0.0, 0.0, 0.0, 0.0, 0.0];
    let ctx = PointContext {
        char_length: 1.0,
        dt: 1e-3,
    };
    let old = vec![0.0; 17];
    let (mut a, mut b) = (vec![0.0; 17], vec![0.0; 17]);
    inviscid.update(&eps, &old, &mut a, &ctx);
    let s = viscous.update(&eps, &old, &mut b, &ctx);
    let (pa, pb) = (inviscid.plastic_strain(&a), viscous.plastic_strain(&b));
    assert!(pa[0] > 0.0);
    for i in 0..6 {
        assert!((pb[i] - 0.5 * pa[i]).abs() <= 1e-12 * pa[0], "{i}");
    }
    // The viscous stress lies above the inviscid surface (overstress).
    assert!(viscous.yield_function(&eps, &b) > 0.0);
    assert!(s[0] > inviscid.stress_from_state(&eps, &a)[0]);
}

#[test]
fn table1_materials_reach_their_strengths() {
    // Rock (E 10 GPa, ν 0.25, c 2.18 MPa, φ 41.6°, f_t 1.97 MPa) and concrete (E 25 GPa,
    // ν 0.17, c 2.0 MPa, φ 46°, f_t 1.30 MPa): peaks f_t and f_c = 2c cosφ/(1 − sinφ).
    for (e, nu, c, phi, ft) in [
        (10e9, 0.25, 2.18e6, 41.6, 1.97e6),
        (25e9, 0.17, 2.0e6, 46.0, 1.30e6),
    ] {
        let el = Elastic::new("t1", e, nu, 2500.0).unwrap();
        let m = PlasticDamage::new(
            "t1",
            el,
            &PlasticDamageParams::from_mohr_coulomb(c, phi, ft),
        )
        .unwrap();
        let fc = mohr_coulomb_fc(c, phi);
        let l = 2.0;
        for (axis, f, strain) in [(0usize, ft, 3.0 * ft / e), (2, fc, -6.0 * fc / e)] {
            let mut d = Driver::new(&m, l);
            let mut peak = 0.0f64;
            for k in 1..=600 {
                let s = d.uniaxial(axis, strain * k as f64 / 600.0);
                peak = peak.max(s[axis].abs());
            }
            assert!(
                (peak - f).abs() < 0.01 * f,
                "axis {axis}: peak {peak} vs {f}"
            );
        }
    }
}

#[test]
fn snap_back_limit_is_reported_with_the_largest_element_size() {
    let el = Elastic::new("lining", E0, NU, 2400.0).unwrap();
    let p = PlasticDamageParams {
        dt_half: Some(0.2),
        ..PlasticDamageParams::from_strengths(FT0, FC0, FC, 50.0, GC)
    };
    let m = PlasticDamage::new("lining", el, &p).unwrap();
    let lmax = m.max_element_size();
    // r = ln(1/0.8)/ln 2, a = 0: l_max = E0 G/(f0² (1 − r)).
    let r = (1.0f64 / 0.8).ln() / 2f64.ln();
    let expect = E0 * 50.0 / (FT0 * FT0 * (1.0 - r));
    assert!((lmax - expect).abs() < 1e-9 * expect, "{lmax} vs {expect}");
    assert!(m.check_char_length(0.99 * lmax).is_ok());
    let msg = m.check_char_length(1.5 * lmax).unwrap_err().to_string();
    assert!(
        msg.contains("lining") && msg.contains(&format!("{lmax:.4e}")),
        "{msg}"
    );
}

#[test]
fn large_increments_stay_finite_and_admissible() {
    let m = w10();
    let ctx = PointContext {
        char_length: 0.5,
        dt: 1e-4,
    };
    let mut st = vec![0.0; 17];
    let path = [
        [5e-3, -2e-3, 1e-3, 4e-3, -1e-3, 2e-3],
        [-2e-2, -1e-2, -3e-2, 0.0, 1e-2, 0.0],
        [1e-1, 1e-1, 1e-1, 0.0, 0.0, 0.0],
        [-1e-1, 0.0, 0.0, 0.0, 0.0, 0.0],
    ];
    for eps in path {
        let mut new = vec![0.0; 17];
        let s = m.update(&eps, &st, &mut new, &ctx);
        assert!(s.iter().all(|v| v.is_finite()), "{s:?}");
        assert!(m.yield_function(&eps, &new) <= 1e-6 * FC0);
        let dm = m.damage(&new);
        assert!((0.0..=1.0).contains(&dm));
        st = new;
    }
}

#[test]
fn compression_unloading_slope_and_plastic_dilatancy() {
    // After crushing past the peak: unloading slope (1 − D_c) E0 (1 %), and the lateral to
    // axial plastic strain ratio of the potential (eq. 26) in uniaxial compression,
    // −m_lat/m_ax with m = (3/2)s/√(h² + q²) + tanψ/3, s = σ(1/3, 1/3, −2/3), q = σ.
    let m = w10();
    let l = 0.1;
    let law = m.constants().compression;
    let b = law.b(l);
    let mut d = Driver::new(&m, l);
    let e_max = -(FC0 / E0 + 1.5 / b);
    let n = 300;
    let mut prev = (0.0, 0.0);
    let mut ratio = 0.0;
    let mut sig = 0.0;
    for k in 1..=n {
        let s = d.uniaxial(2, e_max * k as f64 / n as f64);
        let p = m.plastic_strain(&d.state);
        if k == n {
            ratio = (p[0] - prev.0) / (p[2] - prev.1);
            sig = -s[2] / (1.0 - m.damage(&d.state));
        }
        prev = (p[0], p[2]);
    }
    let c = m.constants();
    let r = (c.hyper * c.hyper + sig * sig).sqrt();
    let (m_lat, m_ax) = (0.5 * sig / r + c.tan_psi / 3.0, -sig / r + c.tan_psi / 3.0);
    let expect = m_lat / m_ax;
    assert!(
        (ratio - expect).abs() < 0.01 * expect.abs(),
        "{ratio} vs {expect}"
    );
    let dmg = m.damage(&d.state);
    assert!((dmg - m.compressive_damage(&d.state)).abs() < 1e-9 && dmg > 0.5);
    let s0 = d.uniaxial(2, e_max + 1e-6)[2];
    let s1 = d.uniaxial(2, e_max + 2e-6)[2];
    let slope = (s1 - s0) / 1e-6;
    let expect = (1.0 - dmg) * E0;
    assert!(
        (slope - expect).abs() < 0.01 * expect,
        "{slope} vs {expect}"
    );
}

#[test]
fn sub_stepping_rescues_a_local_solve_that_does_not_converge() {
    // With the regula-falsi capped at 2 iterations a large increment fails in one step; the
    // fallback redoes it in 4, 16, 64 sub-steps. The result must be finite, admissible
    // (F ≤ 0 is kept by construction) and close to the fully converged answer.
    let m = w10();
    let l = 0.5;
    let start = Internal {
        plastic: [0.0; 6],
        y_t: 0.0,
        y_c: 0.0,
    };
    let eps = [-1.5e-3, 3e-4, 2e-4, 4e-4, -1e-4, 2e-4];
    let exact = m.integrate(&m.problem(l), &[0.0; 6], &eps, &start);
    let mut capped = m.problem(l);
    capped.max_iter = 2;
    let (one, ok) = m.return_map(&capped, &eps, &start);
    assert!(!ok, "the capped solve should fail in one step");
    let rescued = m.integrate(&capped, &[0.0; 6], &eps, &start);
    assert!(rescued.plastic.iter().all(|v| v.is_finite()));
    let mut st = vec![0.0; m.state_len()];
    st[slot::PLASTIC..slot::PLASTIC + 6].copy_from_slice(&rescued.plastic);
    st[slot::Y_T] = rescued.y_t;
    st[slot::Y_C] = rescued.y_c;
    assert!(m.yield_function(&eps, &st) <= 1e-7 * FC0);
    // Closer to the converged state than the failed single step, and within 5 %.
    let gap = |a: &Internal| (a.y_c - exact.y_c).abs() / exact.y_c;
    assert!(gap(&rescued) < 0.05, "rescued gap {}", gap(&rescued));
    assert!(gap(&rescued) <= gap(&one) + 1e-12);
}
