//! Selective mass scaling, an explicit option of the case (`time.mass_scaling`).
//!
//! A mesh whose step is held back by a few small or distorted elements can run at a
//! larger step if those elements are made heavier: an element's own step
//! Δt_e = min(L_e/c_p, 2/ω_max,e) grows as √ρ (c_p = √(E'/ρ), ω² ∝ 1/ρ for a stiffness
//! that does not depend on ρ), so every element whose own step is below the requested
//! `min_element_step` Δt_min gets its density multiplied by
//!
//! f_e = (Δt_min / Δt_e)²   (f_e > 1; 1 for every other element),
//!
//! which makes its own step exactly Δt_min (elements within [`NEGLIGIBLE`] of Δt_min are
//! left alone): the "conventional" selective mass scaling of LS-DYNA's `DT2MS < 0`, mass
//! added only where an element is below the target. The run's step then follows from the
//! scaled model as always (safety × the critical step with anchors, springs and damping
//! folded in).
//!
//! The added mass is mass like any other: inertia, weight under gravity and the
//! mass-proportional damping αM all see it, as the lumped masses carry it. It changes the
//! dynamics of the scaled elements (a heavier element slows the waves through it and
//! reflects part of them), so it is never applied unless asked for, it is refused above
//! `max_added_fraction` of any region's mass, and `dcfm check` and `summary.json` report
//! the elements, the added mass and the largest factor by region.

use serde::Serialize;

use crate::element::lumped_mass::element_masses;
use crate::error::{DcfmError, Result};
use crate::model::Model;

/// What `time.mass_scaling` asks for.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct MassScalingSettings {
    /// Δt_min (s): every element whose own step is below it is made heavy enough to step
    /// at it.
    pub min_element_step: f64,
    /// Largest added mass accepted in any region, as a fraction of the region's mass.
    pub max_added_fraction: f64,
}

/// Elements whose own step is within this fraction of Δt_min are left alone: their
/// factor would add less than twice this fraction of their mass (equal elements' steps
/// differ by round-off).
pub const NEGLIGIBLE: f64 = 1e-9;

/// Default `time.mass_scaling.max_added_fraction`: 5 % of a region's mass.
pub const DEFAULT_MAX_ADDED_FRACTION: f64 = 0.05;

/// The mass added in one region.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct RegionAddedMass {
    pub region: String,
    /// Elements of the region made heavier.
    pub elements: usize,
    /// The region's mass without scaling (kg).
    pub mass: f64,
    /// Mass added (kg).
    pub added: f64,
    /// `added` / `mass`.
    pub added_fraction: f64,
    /// Largest density factor f_e of the region.
    pub largest_factor: f64,
}

/// What the mass scaling did, over the mesh's elements as the case built them (before any
/// excavation), for `dcfm check` and `summary.json`.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct MassScalingSummary {
    /// The requested Δt_min (s).
    pub min_element_step: f64,
    /// The smallest own element step before scaling (s).
    pub smallest_step_before: f64,
    /// Elements made heavier.
    pub elements: usize,
    /// Mass added (kg).
    pub added_mass: f64,
    /// The model's element mass without scaling (kg).
    pub total_mass: f64,
    /// `added_mass` / `total_mass`.
    pub added_fraction: f64,
    /// Largest density factor f_e.
    pub largest_factor: f64,
    /// Regions with added mass, in the order of the model's groups.
    pub by_region: Vec<RegionAddedMass>,
}

impl MassScalingSummary {
    /// One line per region for `dcfm check`, after a line for the whole model.
    pub fn describe(&self) -> Vec<String> {
        let mut lines = vec![format!(
            "mass      time.mass_scaling: {} elements below {:.4e} s (smallest {:.4e} s) made heavier, largest factor {:.4}: +{:.4e} kg, {:.3e} of the model's mass",
            self.elements,
            self.min_element_step,
            self.smallest_step_before,
            self.largest_factor,
            self.added_mass,
            self.added_fraction
        )];
        for r in &self.by_region {
            lines.push(format!(
                "          {}: {} elements, +{:.4e} kg, {:.3e} of its mass, largest factor {:.4}",
                r.region, r.elements, r.added, r.added_fraction, r.largest_factor
            ));
        }
        lines
    }
}

/// Scale the masses of `model`'s elements whose own step is below
/// `settings.min_element_step` (module docs): the density factors go to
/// `Model::mass_factor`, the elements' own steps become Δt_min, the lumped masses are
/// rebuilt and the stable step refreshed. Refused, naming `file`'s fields, for a step that
/// is not a positive number, a fraction outside (0, 1], a model already scaled, or a
/// region whose added mass would exceed the fraction.
pub fn apply_mass_scaling(
    model: &mut Model,
    settings: &MassScalingSettings,
    file: &str,
) -> Result<MassScalingSummary> {
    let target = settings.min_element_step;
    if !(target.is_finite() && target > 0.0) {
        return Err(DcfmError::invalid(
            file,
            "time.mass_scaling.min_element_step",
            target,
            "a finite step > 0 (s)",
        ));
    }
    let limit = settings.max_added_fraction;
    if !(limit.is_finite() && limit > 0.0) {
        return Err(DcfmError::invalid(
            file,
            "time.mass_scaling.max_added_fraction",
            limit,
            "a finite fraction > 0 of a region's mass (0.05: 5 %)",
        ));
    }
    if !model.mass_factor.is_empty() {
        return Err(DcfmError::invalid(
            file,
            "time.mass_scaling",
            "a second scaling",
            "one mass scaling per model",
        ));
    }
    let mut factor = vec![1.0; model.n_elements()];
    let mut by_region: Vec<RegionAddedMass> = Vec::new();
    let mut summary = MassScalingSummary {
        min_element_step: target,
        smallest_step_before: f64::INFINITY,
        elements: 0,
        added_mass: 0.0,
        total_mass: 0.0,
        added_fraction: 0.0,
        largest_factor: 1.0,
        by_region: Vec::new(),
    };
    for g in &model.groups {
        let rho = g.material.density();
        let mut region = RegionAddedMass {
            region: g.name.clone(),
            elements: 0,
            mass: 0.0,
            added: 0.0,
            added_fraction: 0.0,
            largest_factor: 1.0,
        };
        for &e in &g.elements {
            let e = e as usize;
            let m: f64 = element_masses(&model.mesh.element_coords(e), rho)
                .iter()
                .sum();
            region.mass += m;
            let own = model.element_steps[e];
            summary.smallest_step_before = summary.smallest_step_before.min(own);
            if own < target * (1.0 - NEGLIGIBLE) {
                let f = (target / own).powi(2);
                factor[e] = f;
                region.elements += 1;
                region.added += (f - 1.0) * m;
                region.largest_factor = region.largest_factor.max(f);
            }
        }
        region.added_fraction = if region.mass > 0.0 {
            region.added / region.mass
        } else {
            0.0
        };
        summary.total_mass += region.mass;
        summary.elements += region.elements;
        summary.added_mass += region.added;
        summary.largest_factor = summary.largest_factor.max(region.largest_factor);
        if region.added_fraction > limit {
            return Err(DcfmError::invalid(
                file,
                "time.mass_scaling.min_element_step",
                target,
                format!(
                    "a step that adds at most max_added_fraction = {limit} of a region's mass: \
                     region {} would gain {:.4e} kg, {:.3e} of its {:.4e} kg ({} elements below \
                     the step, largest factor {:.4}); lower the step, raise \
                     time.mass_scaling.max_added_fraction, or remesh those elements \
                     (dcfm check lists where the small steps are)",
                    region.region,
                    region.added,
                    region.added_fraction,
                    region.mass,
                    region.elements,
                    region.largest_factor
                ),
            ));
        }
        if region.elements > 0 {
            by_region.push(region);
        }
    }
    summary.added_fraction = if summary.total_mass > 0.0 {
        summary.added_mass / summary.total_mass
    } else {
        0.0
    };
    summary.by_region = by_region;
    for (step, &f) in model.element_steps.iter_mut().zip(&factor) {
        if f > 1.0 {
            *step = target;
        }
    }
    model.mass_factor = factor;
    model.mass = model.lumped_masses();
    model.refresh_inverse_mass();
    model.refresh_stable_step();
    model.mass_scaling = Some(summary.clone());
    Ok(summary)
}
