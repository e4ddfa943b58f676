//! The shared-mass bound on the critical step (`time.stable_step = "shared_mass"`,
//! `element::shared_mass_step`): on graded, distorted meshes it must stay at or above the
//! largest eigenvalue of the assembled M⁻¹K (`dcfm::dense_spectrum`, a dense eigensolve:
//! an independent reference), at or below the elements' own bound, and the same on 1 and
//! 2 threads.

use dcfm::dense_spectrum::omega_max_squared;
use dcfm::element::Integration;
use dcfm::material::{Elastic, Material};
use dcfm::mesh::BoxMeshSpec;
use dcfm::model::{Model, RegionSetup, StepBound};

/// A box whose cells have the widths `widths` along each axis, its interior nodes moved by
/// up to `jitter` m, Poisson's ratio `nu`, and its base fixed when `fixed_base`.
fn box_model(
    widths: [&[f64]; 3],
    jitter: f64,
    nu: f64,
    integration: Integration,
    fixed_base: bool,
) -> Model {
    let cells = widths.map(|w| w.len());
    let extent = cells.map(|n| n as f64);
    let mut mesh = BoxMeshSpec::single("rock", [0.0; 3], extent, cells)
        .build("t")
        .unwrap();
    let planes = widths.map(|w| {
        std::iter::once(0.0)
            .chain(w.iter().scan(0.0, |x, &h| {
                *x += h;
                Some(*x)
            }))
            .collect::<Vec<f64>>()
    });
    for (k, p) in mesh.coords.iter_mut().enumerate() {
        let index: [usize; 3] = std::array::from_fn(|d| p[d].round() as usize);
        let interior = (0..3).all(|d| index[d] > 0 && index[d] < cells[d]);
        for (d, scale) in [1.3, 2.1, 0.7].into_iter().enumerate() {
            let moved = if interior {
                jitter * (k as f64 * scale).sin()
            } else {
                0.0
            };
            p[d] = planes[d][index[d]] + moved;
        }
    }
    let setup = RegionSetup {
        region: "rock".into(),
        material: Material::Elastic(Elastic::new("r", 20e9, nu, 2700.0).unwrap()),
        integration,
        hourglass: 0.05,
    };
    let mut model = Model::new(mesh, &[setup], "t").unwrap();
    if fixed_base {
        let base: Vec<u32> = (0..model.mesh.n_nodes() as u32)
            .filter(|&n| model.mesh.coords[n as usize][2] == 0.0)
            .collect();
        model.constraints.fix(&base, 0b111);
        model.refresh_stable_step();
    }
    model
}

/// A 4 × 3 × 3 box graded along every axis (elements from 0.25 m to 1.6 m), its interior
/// nodes jittered, and its base fixed when `fixed_base`.
fn graded_box(integration: Integration, fixed_base: bool) -> Model {
    box_model(
        [&[0.25, 1.6, 0.75, 1.4], &[1.0, 0.3, 1.7], &[0.4, 1.1, 1.5]],
        0.04,
        0.25,
        integration,
        fixed_base,
    )
}

fn critical_steps(mut model: Model) -> (f64, f64, f64) {
    model.step_bound = StepBound::Element;
    model.refresh_stable_step();
    let element = model.stable.critical;
    model.step_bound = StepBound::SharedMass;
    model.refresh_stable_step();
    let shared = model.stable.critical;
    let exact = 2.0 / omega_max_squared(&model).sqrt();
    (element, shared, exact)
}

#[test]
fn the_shared_mass_step_is_a_bound_and_no_smaller_than_the_elements_own() {
    for integration in [Integration::Full, Integration::OnePoint] {
        for fixed_base in [false, true] {
            let (element, shared, exact) = critical_steps(graded_box(integration, fixed_base));
            let label = format!("{integration:?}, fixed base {fixed_base}");
            eprintln!(
                "{label}: element {element:.4e} s, shared {shared:.4e} s, exact {exact:.4e} s"
            );
            // A bound: never above the assembled system's critical step.
            assert!(
                shared <= exact * (1.0 + 1e-12),
                "{label}: shared-mass step {shared:e} above the exact critical step {exact:e}"
            );
            // Never below the elements' own bound, which it refines.
            assert!(shared >= element, "{label}: {shared:e} < {element:e}");
            // On this graded mesh (a 0.25 m layer between 1.6 m cells) sharing gains
            // at least 10 % of the step.
            assert!(
                shared >= 1.1 * element,
                "{label}: shared {shared:e} against the element bound {element:e} \
                 (exact {exact:e})"
            );
        }
    }
}

#[test]
fn the_shared_mass_step_does_not_depend_on_the_thread_count() {
    let steps: Vec<f64> = [1, 2]
        .iter()
        .map(|&threads| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            pool.install(|| {
                let mut model = graded_box(Integration::Full, true);
                model.step_bound = StepBound::SharedMass;
                model.refresh_stable_step();
                model.stable.critical
            })
        })
        .collect();
    assert_eq!(steps[0].to_bits(), steps[1].to_bits());
}

proptest::proptest! {
    #![proptest_config(proptest::prelude::ProptestConfig::with_cases(100))]

    /// On random graded boxes (2–4 cells per axis of 0.2–2 m, interior nodes jittered,
    /// ν from 0.05 to 0.45, either integration, base fixed or free) the shared-mass step
    /// stays between the elements' own bound and the exact critical step.
    #[test]
    fn the_shared_mass_step_lies_between_the_elements_bound_and_the_exact_step(
        wx in proptest::collection::vec(0.2f64..2.0, 2..=4),
        wy in proptest::collection::vec(0.2f64..2.0, 2..=4),
        wz in proptest::collection::vec(0.2f64..2.0, 2..=4),
        jitter in 0.0f64..0.05,
        nu in 0.05f64..0.45,
        full in proptest::bool::ANY,
        fixed_base in proptest::bool::ANY,
    ) {
        let integration = if full { Integration::Full } else { Integration::OnePoint };
        let (element, shared, exact) =
            critical_steps(box_model([&wx, &wy, &wz], jitter, nu, integration, fixed_base));
        proptest::prop_assert!(
            shared <= exact * (1.0 + 1e-12),
            "shared-mass step {shared:e} above the exact critical step {exact:e}"
        );
        proptest::prop_assert!(shared >= element, "{shared:e} < the elements' {element:e}");
    }
}
