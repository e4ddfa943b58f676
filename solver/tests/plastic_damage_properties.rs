//! Properties of the Lee–Fenves plastic-damage model along random strain paths
//! (DESIGN.md §5): 0 ≤ D ≤ 1; the damage variables D_t, D_c, κ_t, κ_c never decrease;
//! F ≤ tol after the return mapping; the Lee–Fenves dissipation g κ ≥ 0 and never decreasing; an elastic path
//! is exactly elastic; the total mechanical dissipation (work in minus recoverable energy)
//! is never negative — without stiffness recovery (s0 = 1), and with it (s0 < 1) under the
//! default consistent recovery rule, while eq. (24)'s rule is shown to create energy on a
//! path; splitting a strain increment into more sub-steps converges.
//!
//! D of eq. (24) itself may fall when a crack closes (stiffness recovery, s < 1), so the
//! monotonicity is asserted on D_t, D_c and on the fully-open value 1 − (1 − D_c)(1 − D_t).

use dcfm::material::plastic_damage::{PlasticDamageParams, Recovery};
use dcfm::material::{Elastic, PlasticDamage, PointContext, Voigt};
use proptest::prelude::*;
use std::alloc::{GlobalAlloc, Layout, System};
use std::cell::Cell;

/// Counts heap allocations per thread, to check that `update` allocates nothing.
struct Counting;

thread_local! {
    static ALLOCATIONS: Cell<usize> = const { Cell::new(0) };
}

unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        let _ = ALLOCATIONS.try_with(|c| c.set(c.get() + 1));
        System.alloc(layout)
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        System.dealloc(ptr, layout)
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

fn allocations() -> usize {
    ALLOCATIONS.with(|c| c.get())
}

const FC0: f64 = 13e6;

fn model() -> PlasticDamage {
    let el = Elastic::new("pd", 31027e6, 0.18, 2400.0).unwrap();
    PlasticDamage::new(
        "pd",
        el,
        &PlasticDamageParams::from_strengths(2.9e6, FC0, 24.1e6, 200.0, 1.0e4),
    )
    .unwrap()
}

/// The same material with s0 = 1: tensile damage is never recovered in compression.
fn model_without_recovery() -> PlasticDamage {
    let el = Elastic::new("pd", 31027e6, 0.18, 2400.0).unwrap();
    let mut p = PlasticDamageParams::from_strengths(2.9e6, FC0, 24.1e6, 200.0, 1.0e4);
    p.s0 = 1.0;
    PlasticDamage::new("pd", el, &p).unwrap()
}

/// The material with recovery floor `s0` and the given recovery rule.
fn model_with(s0: f64, recovery: Recovery) -> PlasticDamage {
    let el = Elastic::new("pd", 31027e6, 0.18, 2400.0).unwrap();
    let mut p = PlasticDamageParams::from_strengths(2.9e6, FC0, 24.1e6, 200.0, 1.0e4);
    p.s0 = s0;
    p.recovery = recovery;
    PlasticDamage::new("pd", el, &p).unwrap()
}

/// Mechanical dissipation W − ψ after each increment of `path`, W = ∫σ : dε by the
/// trapezoid over `sub` equal sub-steps per increment (each one a model update), and the
/// gross work Σ|ΔW|; also the largest gap between the model's tracked dissipation and W − ψ.
fn dissipation(m: &PlasticDamage, path: &[Voigt], l: f64, sub: usize) -> (Vec<f64>, f64, f64) {
    let mut st = vec![0.0; m.state_len()];
    m.init_state(&mut st);
    let mut new = st.clone();
    let (mut eps, mut sig) = ([0.0; 6], [0.0; 6]);
    let (mut work, mut gross, mut gap) = (0.0, 0.0, 0.0f64);
    let mut out = Vec::with_capacity(path.len());
    for inc in path {
        for _ in 0..sub {
            let e2: Voigt = std::array::from_fn(|i| eps[i] + inc[i] / sub as f64);
            let s = m.update(&e2, &st, &mut new, &ctx(l));
            let dw: f64 = (0..6)
                .map(|i| 0.5 * (s[i] + sig[i]) * (e2[i] - eps[i]))
                .sum();
            work += dw;
            gross += dw.abs();
            eps = e2;
            sig = s;
            st.copy_from_slice(&new);
        }
        let d = work - m.recoverable_energy_density(&eps, &st);
        gap = gap.max((m.dissipated_energy_density(&st) - d).abs());
        out.push(d);
    }
    (out, gross, gap)
}

fn increment(scale: f64) -> impl Strategy<Value = Voigt> {
    prop::array::uniform6(-scale..scale)
}

fn ctx(l: f64) -> PointContext {
    PointContext {
        char_length: l,
        dt: 1e-4,
        reads_damage: false,
    }
}

/// Run `path` (strain increments) from the virgin state; the final strain and state.
fn run(m: &PlasticDamage, path: &[Voigt], l: f64) -> (Voigt, Vec<f64>) {
    let mut st = vec![0.0; m.state_len()];
    m.init_state(&mut st);
    let mut new = st.clone();
    let mut eps = [0.0; 6];
    for inc in path {
        for i in 0..6 {
            eps[i] += inc[i];
        }
        m.update(&eps, &st, &mut new, &ctx(l));
        st.copy_from_slice(&new);
    }
    (eps, st)
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1024, ..ProptestConfig::default() })]

    #[test]
    fn damage_bounded_monotone_and_admissible(
        path in prop::collection::vec(increment(4e-4), 1..25),
        l in 0.05f64..2.0,
    ) {
        let m = model();
        let mut st = vec![0.0; m.state_len()];
        m.init_state(&mut st);
        let mut new = st.clone();
        let mut eps = [0.0; 6];
        for inc in &path {
            for i in 0..6 {
                eps[i] += inc[i];
            }
            let s = m.update(&eps, &st, &mut new, &ctx(l));
            prop_assert!(s.iter().all(|v| v.is_finite()), "stress {:?}", s);
            let d = m.damage(&new);
            prop_assert!((0.0..=1.0).contains(&d), "D = {}", d);
            let open = |x: &[f64]| 1.0 - (1.0 - m.compressive_damage(x)) * (1.0 - m.tensile_damage(x));
            prop_assert!(open(&new) >= open(&st));
            prop_assert!(m.tensile_damage(&new) >= m.tensile_damage(&st));
            prop_assert!(m.compressive_damage(&new) >= m.compressive_damage(&st));
            prop_assert!(m.kappa_t(&new) >= m.kappa_t(&st) && m.kappa_c(&new) >= m.kappa_c(&st));
            let w = m.fracture_energy_density(&new);
            prop_assert!(w >= 0.0 && w >= m.fracture_energy_density(&st));
            let f = m.yield_function(&eps, &new, l);
            prop_assert!(f <= 1e-7 * FC0, "F = {} after return", f);
            prop_assert_eq!(m.stress_from_state(&eps, &new), s);
            st.copy_from_slice(&new);
        }
    }

    #[test]
    fn elastic_path_is_exactly_elastic(
        dirs in prop::collection::vec(increment(1.0), 1..10),
        frac in prop::collection::vec(0.0f64..0.95, 10),
    ) {
        // Every strain of the path lies inside the initial yield surface (F is positively
        // homogeneous in σ̄, so scaling a direction to a fraction of its yield strain works).
        let m = model();
        let el = *m.elastic();
        let virgin = vec![0.0; m.state_len()];
        let mut st = virgin.clone();
        let mut new = virgin.clone();
        // The initial compressive yield stress of a 0.5 m element (reduced by the total
        // regularisation, docs/plastic_damage.md §1).
        let fc0 = m.element_laws(0.5).1.law.f0;
        for (k, dir) in dirs.iter().enumerate() {
            let phi = m.yield_function(dir, &virgin, 0.5) + fc0;
            prop_assume!(phi > 0.0);
            let t = frac[k] * fc0 / phi;
            let eps = dir.map(|v| t * v);
            let s = m.update(&eps, &st, &mut new, &ctx(0.5));
            prop_assert_eq!(s, el.stress(&eps));
            prop_assert_eq!(m.plastic_strain(&new), [0.0; 6]);
            prop_assert_eq!(m.damage(&new), 0.0);
            prop_assert_eq!(m.dissipated_energy_density(&new), 0.0);
            prop_assert_eq!(m.fracture_energy_density(&new), 0.0);
            st.copy_from_slice(&new);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

    #[test]
    fn sub_stepping_an_increment_converges(
        pre in prop::collection::vec(increment(2e-4), 0..5),
        inc in increment(6e-4),
        l in 0.1f64..1.0,
    ) {
        let m = model();
        let (eps0, st0) = run(&m, &pre, l);
        let split = |n: usize| {
            let mut st = st0.clone();
            let mut new = st0.clone();
            for k in 1..=n {
                let t = k as f64 / n as f64;
                let eps: Voigt = std::array::from_fn(|i| eps0[i] + t * inc[i]);
                m.update(&eps, &st, &mut new, &ctx(l));
                st.copy_from_slice(&new);
            }
            let p = m.plastic_strain(&st);
            let mut v: Vec<f64> = p.iter().map(|x| x / 1e-4).collect();
            v.push(m.kappa_t(&st));
            v.push(m.kappa_c(&st));
            v
        };
        let dist = |a: &[f64], b: &[f64]| a.iter().zip(b).fold(0.0f64, |d, (x, y)| d.max((x - y).abs()));
        // Cauchy criterion on S_n (n equal sub-steps): S_256 and S_512 agree to 1 % of the
        // change the increment makes (backward Euler is first order, so the gap is about
        // 1/512 of the one-step error; elastic sub-steps before the yield onset change
        // nothing, which rules out comparing coarse splittings with each other).
        let start = split(0);
        let (s256, s512) = (split(256), split(512));
        let change = dist(&s512, &start);
        let gap = dist(&s256, &s512);
        prop_assert!(gap <= 0.01 * change + 1e-12, "gap {} change {}", gap, change);
        // (How close the one-step answer is to the converged one is not a property of the
        // model: on a softening branch a single backward-Euler step of 6e-4 strain can be
        // off by more than half the change — found by this test — so it is not asserted.)
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn total_mechanical_dissipation_is_never_negative_without_stiffness_recovery(
        path in prop::collection::vec(increment(4e-4), 1..15),
        l in 0.1f64..1.0,
    ) {
        // W = ∫σ : dε (trapezoid over 40 sub-steps per increment) minus the recoverable
        // energy ½ σ : (ε − εᵖ) must stay ≥ 0 (second law, isothermal), up to the
        // quadrature error, bounded here by 1e-6 of Σ|ΔW|.
        //
        // With s0 = 1 (no stiffness recovery). With recovery (s0 < 1) the stiffness of
        // eq. (24) depends on the stress state through s(σ̄) and is not derived from a free
        // energy, so a strain cycle through crack closure can return slightly more work
        // than it took: this test found a path with −0.77 J/m³ against 5119 J/m³ of gross
        // work (converged in the quadrature: −0.772 with 400 and 4000 sub-steps), which
        // is ≥ +408 J/m³ on the same path with s0 = 1. See docs/plastic_damage.md.
        let m = model_without_recovery();
        let mut st = vec![0.0; m.state_len()];
        m.init_state(&mut st);
        let mut new = st.clone();
        let (mut eps, mut sig) = ([0.0; 6], [0.0; 6]);
        let (mut work, mut gross) = (0.0, 0.0);
        for inc in &path {
            for _ in 0..40 {
                let e2: Voigt = std::array::from_fn(|i| eps[i] + inc[i] / 40.0);
                let s = m.update(&e2, &st, &mut new, &ctx(l));
                let dw: f64 = (0..6).map(|i| 0.5 * (s[i] + sig[i]) * (e2[i] - eps[i])).sum();
                work += dw;
                gross += dw.abs();
                eps = e2;
                sig = s;
                st.copy_from_slice(&new);
            }
            let dissipated = work - m.recoverable_energy_density(&eps, &st);
            prop_assert!(dissipated >= -1e-6 * gross - 1e-9, "dissipated {} of {}", dissipated, gross);
            // The state tracks the same quantity.
            let tracked = m.dissipated_energy_density(&st);
            prop_assert!((tracked - dissipated).abs() <= 1e-9 * gross + 1e-9, "{} vs {}", tracked, dissipated);
        }
    }
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

    #[test]
    fn consistent_recovery_never_creates_energy(
        path in prop::collection::vec(increment(4e-4), 1..15),
        l in 0.1f64..1.0,
        s0 in prop::sample::select(vec![0.0, 0.3, 0.7]),
    ) {
        // With stiffness recovery (s0 < 1) under the consistent rule (recovery.rs) the
        // mechanical dissipation W − ψ is never negative: ≥ −1e-9 of the gross work, beyond
        // the discretisation error of the work integral, estimated from the same path with
        // 4× the sub-steps (|D₄₀ − D₁₆₀|; the trapezoid is second order, the return first).
        let m = model_with(s0, Recovery::Consistent);
        let (coarse, gross, gap) = dissipation(&m, &path, l, 40);
        let (fine, _, _) = dissipation(&m, &path, l, 160);
        for (c, f) in coarse.iter().zip(&fine) {
            let err = (c - f).abs();
            prop_assert!(*f >= -1e-9 * gross - 2.0 * err - 1e-9,
                "dissipated {} (40 sub-steps: {}) of {}", f, c, gross);
        }
        prop_assert!(gap <= 1e-9 * gross + 1e-9, "tracked differs by {}", gap);
    }
}

#[test]
fn lee_fenves_recovery_creates_energy_on_the_documented_path() {
    // The negative case the property above must be able to see: docs/plastic_damage.md §7
    // records a path on which eq. (24) with s0 = 0 returns more work than it took. Search
    // deterministic pseudo-random paths (the distribution of the property tests) for one
    // whose dissipation is negative beyond 2 × its discretisation error; then the same path
    // under the consistent rule must not be.
    let lf = model_with(0.0, Recovery::LeeFenves);
    let cons = model_with(0.0, Recovery::Consistent);
    let mut seed: u64 = 0x9E37_79B9_7F4A_7C15;
    let mut uniform = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (seed >> 11) as f64 / (1u64 << 53) as f64
    };
    let worst = |m: &PlasticDamage, path: &[Voigt], l: f64| {
        let (c, gross, _) = dissipation(m, path, l, 40);
        let (f, _, _) = dissipation(m, path, l, 160);
        c.iter()
            .zip(&f)
            .map(|(c, f)| (f + 2.0 * (c - f).abs()) / gross)
            .fold(f64::INFINITY, f64::min)
    };
    for trial in 0..3000 {
        let n = 1 + (uniform() * 14.0) as usize;
        let path: Vec<Voigt> = (0..n)
            .map(|_| std::array::from_fn(|_| (2.0 * uniform() - 1.0) * 4e-4))
            .collect();
        let l = 0.1 + 0.9 * uniform();
        let w = worst(&lf, &path, l);
        if w < -1e-6 {
            let wc = worst(&cons, &path, l);
            eprintln!("trial {trial}: eq. (24) {w:.3e} of the gross work, consistent {wc:.3e}");
            assert!(wc >= -1e-9, "consistent rule on the same path: {wc:e}");
            return;
        }
    }
    panic!("no energy-creating path found for eq. (24) in 3000 trials");
}

#[test]
fn update_does_not_allocate() {
    let m = model();
    let mut st = vec![0.0; m.state_len()];
    let mut new = st.clone();
    let path: [Voigt; 5] = [
        [1e-5, 0.0, 0.0, 0.0, 0.0, 0.0],
        [4e-4, -5e-5, 2e-5, 1e-4, -3e-5, 4e-5],
        [-2e-3, 2e-4, 1e-4, 1e-4, 0.0, -5e-5],
        [5e-2, 5e-2, 5e-2, 0.0, 0.0, 0.0],
        [-5e-2, 1e-2, 0.0, 3e-2, 0.0, 0.0],
    ];
    let before = allocations();
    for eps in &path {
        m.update(eps, &st, &mut new, &ctx(0.5));
        st.copy_from_slice(&new);
    }
    assert_eq!(allocations() - before, 0);
    assert!(m.damage(&st) > 0.0);
}
