//! Material update per integration point: the Lee–Fenves plastic-damage model on its
//! elastic branch (trial inside the yield surface) and on its plastic branch (return
//! mapping in principal space), with linear elasticity as the baseline.

use criterion::{black_box, criterion_group, criterion_main, Criterion};
use dcfm::material::plastic_damage::{PlasticDamageParams, Recovery};
use dcfm::material::{Elastic, PlasticDamage, PointContext};

fn material_update(c: &mut Criterion) {
    let el = Elastic::new("concrete", 31027e6, 0.18, 2400.0).unwrap();
    let pd = PlasticDamage::new(
        "concrete",
        el,
        &PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 200.0, 1.0e4),
    )
    .unwrap();
    let ctx = PointContext {
        char_length: 0.5,
        dt: 1e-4,
        reads_damage: false,
    };
    let n = pd.state_len();
    let old = vec![0.0; n];
    let mut new = vec![0.0; n];
    let mut g = c.benchmark_group("material_update");

    let small = [2e-5, -1e-5, 0.5e-5, 1e-5, 0.0, -2e-5];
    g.bench_function("elastic_baseline", |b| {
        b.iter(|| el.stress(black_box(&small)))
    });
    g.bench_function("plastic_damage_elastic_branch", |b| {
        b.iter(|| pd.update(black_box(&small), black_box(&old), &mut new, &ctx))
    });
    // Tensile cracking under a general 3D strain (return with tension and shear).
    let crack = [3e-4, -5e-5, 2e-5, 1e-4, -3e-5, 4e-5];
    g.bench_function("plastic_damage_plastic_branch_tension", |b| {
        b.iter(|| pd.update(black_box(&crack), black_box(&old), &mut new, &ctx))
    });
    // Compressive crushing (return on the compressive side, hardening in κ_c).
    let crush = [-1.2e-3, 2e-4, 1e-4, 1e-4, 0.0, -5e-5];
    g.bench_function("plastic_damage_plastic_branch_compression", |b| {
        b.iter(|| pd.update(black_box(&crush), black_box(&old), &mut new, &ctx))
    });
    // A cracked point (y_t > 0 after the tensile return above) unloading elastically into
    // a mixed tension–compression state: the branch most yielded points of a damaged model
    // take in most steps (trial inside the current surface, r(σ̄) from principal values).
    let mut cracked = vec![0.0; n];
    pd.update(&crack, &old, &mut cracked, &ctx);
    let unloading = [1.5e-4, -1.5e-4, 2e-5, 5e-5, -3e-5, 4e-5];
    let mut next = vec![0.0; n];
    pd.update(&unloading, &cracked, &mut next, &ctx);
    assert_eq!(
        pd.plastic_strain(&next),
        pd.plastic_strain(&cracked),
        "the unloading strain must stay elastic"
    );
    g.bench_function("plastic_damage_cracked_elastic_mixed", |b| {
        b.iter(|| pd.update(black_box(&unloading), black_box(&cracked), &mut next, &ctx))
    });
    // The cracked point a hair inside its current surface (its elastic strain scaled by
    // 0.999): elastic, but beyond the reach of the invariant bound σ̂_max ≤ Ī₁/3 +
    // (2/3)√(3J̄₂) — the points of a damaged region that stay near their surface.
    let plastic = pd.plastic_strain(&cracked);
    let near: [f64; 6] = std::array::from_fn(|i| plastic[i] + 0.999 * (crack[i] - plastic[i]));
    pd.update(&near, &cracked, &mut next, &ctx);
    assert_eq!(
        pd.plastic_strain(&next),
        plastic,
        "the strain near the surface must stay elastic"
    );
    g.bench_function("plastic_damage_cracked_elastic_near_surface", |b| {
        b.iter(|| pd.update(black_box(&near), black_box(&cracked), &mut next, &ctx))
    });
    // The same two cracked points under the consistent recovery rule (the concrete of the
    // Yingxiuwan case, docs/plastic_damage.md §7): the return mapping works on σ̄, so the
    // points and their states are those above; the nominal stress comes from the Gibbs
    // energy, and D of eq. (24) is not formed in the update.
    let consistent = PlasticDamage::new(
        "concrete",
        el,
        &PlasticDamageParams {
            recovery: Recovery::Consistent,
            ..PlasticDamageParams::from_strengths(2.9e6, 13e6, 24.1e6, 200.0, 1.0e4)
        },
    )
    .unwrap();
    let mut cracked_c = vec![0.0; n];
    consistent.update(&crack, &old, &mut cracked_c, &ctx);
    g.bench_function("plastic_damage_cracked_elastic_mixed_consistent", |b| {
        b.iter(|| {
            consistent.update(
                black_box(&unloading),
                black_box(&cracked_c),
                &mut next,
                &ctx,
            )
        })
    });
    g.bench_function(
        "plastic_damage_cracked_elastic_near_surface_consistent",
        |b| b.iter(|| consistent.update(black_box(&near), black_box(&cracked_c), &mut next, &ctx)),
    );
    // The mixed point as a one-point element takes it: the update, then 1 − D for the
    // hourglass stiffness. D formed from the state after the update (the element not
    // saying it reads D) against D stored by the update from the σ̄ it classified.
    let reading = PointContext {
        reads_damage: true,
        ..ctx
    };
    for (name, ctx) in [
        (
            "plastic_damage_cracked_elastic_mixed_consistent_factor_formed",
            ctx,
        ),
        (
            "plastic_damage_cracked_elastic_mixed_consistent_factor_stored",
            reading,
        ),
    ] {
        g.bench_function(name, |b| {
            b.iter(|| {
                let sig = consistent.update(
                    black_box(&unloading),
                    black_box(&cracked_c),
                    &mut next,
                    &ctx,
                );
                (sig, consistent.stiffness_factor(&next))
            })
        });
    }
    g.finish();
}

criterion_group!(benches, material_update);
criterion_main!(benches);
