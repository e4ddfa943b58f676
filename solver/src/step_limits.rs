//! Which elements limit the stable step, and what the step would be without them.
//!
//! The explicit step is the smallest of the elements' own steps
//! (`Model::element_steps`, min(L_e/c_p, 2/ω_max,e), element/stable_step.rs). A mesh is
//! often held back by a handful of distorted or thin elements; `dcfm check` reports, for
//! the elements that move (those with a free DOF, as [`Model::refresh_stable_step`]
//! counts them), how many lie within a few factors of the smallest step, in which regions
//! and where, and the step the model would have if its worst elements were as good as the
//! next ones — the figures a user needs to decide whether remeshing a corner pays.
//! Anchor bars' stiffness is folded in as for the critical step itself
//! ([`Model::fold_extra_stiffness`]).

use crate::model::Model;

/// Elements whose own step is below `factor` × the smallest.
#[derive(Clone, Debug, PartialEq)]
pub struct StepBand {
    pub factor: f64,
    /// Number of elements in the band.
    pub count: usize,
    /// (region, count) in the order of the model's groups, regions with none left out.
    pub by_region: Vec<(String, usize)>,
    /// Bounding box of the band's element centroids: (lower, upper) corner.
    pub bounds: ([f64; 3], [f64; 3]),
}

/// The step limits of a model.
#[derive(Clone, Debug, PartialEq)]
pub struct StepLimits {
    /// Critical step of the elements that move, anchors folded in (s).
    pub critical: f64,
    /// Number of elements that move.
    pub moving: usize,
    /// One band per requested factor.
    pub bands: Vec<StepBand>,
    /// (number of elements left out, the critical step without them): the critical step
    /// if the worst `count` elements were no worse than the next one.
    pub without_worst: Vec<(usize, f64)>,
}

/// The step limits of `model` for the given `factors` (each ≥ 1) and numbers of worst
/// elements left out (`counts`; none left at or beyond the number of moving elements:
/// an infinite step).
pub fn step_limits(model: &Model, factors: &[f64], counts: &[usize]) -> StepLimits {
    let mut moving: Vec<(f64, usize, usize)> = model
        .moving_elements()
        .into_iter()
        .map(|(gi, e)| (model.element_steps[e], e, gi))
        .collect();
    moving.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.cmp(&b.1)));
    let with_extra = |dt: f64| model.fold_extra_stiffness(dt);
    let smallest = moving.first().map_or(f64::INFINITY, |m| m.0);
    let bands = factors
        .iter()
        .map(|&factor| {
            let limit = factor * smallest;
            let members = moving.iter().take_while(|m| m.0 < limit);
            let mut by_group = vec![0usize; model.groups.len()];
            let mut lower = [f64::INFINITY; 3];
            let mut upper = [f64::NEG_INFINITY; 3];
            let mut count = 0;
            for &(_, e, gi) in members {
                count += 1;
                by_group[gi] += 1;
                let x = model.mesh.element_coords(e);
                for d in 0..3 {
                    let c = x.iter().map(|p| p[d]).sum::<f64>() / 8.0;
                    lower[d] = lower[d].min(c);
                    upper[d] = upper[d].max(c);
                }
            }
            let mut by_region: Vec<(String, usize)> = Vec::new();
            for (gi, &n) in by_group.iter().enumerate() {
                if n == 0 {
                    continue;
                }
                let name = &model.groups[gi].name;
                match by_region.iter_mut().find(|(r, _)| r == name) {
                    Some(entry) => entry.1 += n,
                    None => by_region.push((name.clone(), n)),
                }
            }
            StepBand {
                factor,
                count,
                by_region,
                bounds: (lower, upper),
            }
        })
        .collect();
    let without_worst = counts
        .iter()
        .map(|&skip| {
            let dt = moving.get(skip).map_or(f64::INFINITY, |m| m.0);
            (skip, with_extra(dt))
        })
        .collect();
    StepLimits {
        critical: with_extra(smallest),
        moving: moving.len(),
        bands,
        without_worst,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::element::Integration;
    use crate::material::{Elastic, Material};
    use crate::mesh::BoxMeshSpec;
    use crate::model::RegionSetup;

    fn bar_of_cubes(n: usize, first_width: f64) -> Model {
        let mut mesh = BoxMeshSpec::single("bar", [0.0; 3], [n as f64, 1.0, 1.0], [n, 1, 1])
            .build("t")
            .unwrap();
        // Move the nodes of the plane x = 1 to x = first_width: the first element thins,
        // the second widens.
        for p in mesh.coords.iter_mut() {
            if (p[0] - 1.0).abs() < 1e-12 {
                p[0] = first_width;
            }
        }
        let setup = RegionSetup {
            region: "bar".into(),
            material: Material::Elastic(Elastic::new("c", 25e9, 0.2, 2450.0).unwrap()),
            integration: Integration::Full,
            hourglass: 0.0,
        };
        Model::new(mesh, &[setup], "t").unwrap()
    }

    #[test]
    fn the_thin_element_is_found_and_the_step_without_it_is_a_unit_cubes() {
        let model = bar_of_cubes(3, 0.4);
        let cube = bar_of_cubes(1, 1.0).stable.critical;
        let limits = step_limits(&model, &[1.01, 1.5], &[0, 1, 3]);
        assert_eq!(limits.moving, 3);
        assert_eq!(limits.critical, model.stable.critical);
        // Only the 0.5 m element is within 1 % of the smallest step; its centroid.
        let thin = &limits.bands[0];
        assert_eq!(thin.count, 1);
        assert_eq!(thin.by_region, vec![("bar".to_string(), 1)]);
        assert!((thin.bounds.0[0] - 0.2).abs() < 1e-12 && thin.bounds.1[0] == thin.bounds.0[0]);
        // A 0.4 m wide element steps at L/c_p = 0.4/c_p, a cube at 0.775/c_p (W13): the cube at x 2–3
        // is not within 1.5× of it.
        assert!(
            model.stable.critical < 0.6 * cube,
            "{} vs {cube}",
            model.stable.critical
        );
        assert_eq!(limits.bands[1].count, 1);
        // Leaving out the thin element leaves the unit cube's step (the 1.6 m wide element
        // steps at more than that); leaving out all three, no limit.
        assert_eq!(limits.without_worst[0].1, model.stable.critical);
        assert!((limits.without_worst[1].1 - cube).abs() < 1e-12 * cube);
        assert_eq!(limits.without_worst[2].1, f64::INFINITY);
    }

    #[test]
    fn anchors_stiffness_is_folded_in_as_for_the_critical_step() {
        let mut model = bar_of_cubes(2, 1.0);
        let w = 2.0 / model.stable.critical;
        model.include_extra_stiffness(0.5 * w * w);
        let limits = step_limits(&model, &[1.1], &[1]);
        assert!((limits.critical - model.stable.critical).abs() < 1e-15);
        assert!(
            (limits.critical - model.element_steps[0] / 1.5f64.sqrt()).abs()
                < 1e-12 * limits.critical
        );
        // Both unit cubes have the same step: the band holds both.
        assert_eq!(limits.bands[0].count, 2);
        assert_eq!(limits.without_worst[0].1, limits.critical);
    }
}
