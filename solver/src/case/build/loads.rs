//! `[loads]`, `[damping]` and `[initial]`: nodal loads, gravity, Rayleigh damping and
//! initial velocities.

use crate::case::schema::{DampingSection, InitialSection, LoadSection, RegionSection};
use crate::error::{DcfmError, Result};
use crate::load::{Gravity, NodalLoad, TimeFunction};
use crate::model::{Model, Rayleigh};

use super::checks::{finite_components, nodes_of};

/// Nodal loads and gravity of `[loads]`.
pub(super) fn build_loads(model: &mut Model, section: &LoadSection, label: &str) -> Result<()> {
    let unit = TimeFunction::Constant { value: 1.0 };
    for (k, l) in section.nodal.iter().enumerate() {
        let field = format!("loads.nodal[{k}]");
        finite_components(label, &format!("{field}.force"), &l.force, "N")?;
        let history = l.history.clone().unwrap_or(unit.clone());
        history.validate(label, &format!("{field}.history"))?;
        let nodes = nodes_of(&model.mesh, label, &format!("{field}.set"), &l.set)?;
        model.nodal_loads.push(NodalLoad {
            nodes,
            force: l.force,
            history,
        });
    }
    if let Some(g) = &section.gravity {
        finite_components(label, "loads.gravity.acceleration", &g.acceleration, "m/s²")?;
        let history = g.history.clone().unwrap_or(unit.clone());
        history.validate(label, "loads.gravity.history")?;
        model.gravity = Some(Gravity {
            acceleration: g.acceleration,
            history,
        });
    }
    Ok(())
}

/// Checked Rayleigh coefficients of a damping table at `field`.
fn rayleigh(section: &DampingSection, label: &str, field: &str) -> Result<Rayleigh> {
    for (name, v, most, unit) in [
        ("alpha", section.alpha, MAX_ALPHA, "1/s"),
        ("beta", section.beta, MAX_BETA, "s"),
    ] {
        if !(v.is_finite() && v >= 0.0) {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.{name}"),
                v,
                "must be finite and ≥ 0",
            ));
        }
        if v > most {
            return Err(DcfmError::invalid(
                label,
                format!("{field}.{name}"),
                format!("{v:e}"),
                format!(
                    "at most {most:e} {unit}: beyond it no mode of any model is damped less \
                     than critically (ξ = α/2ω + βω/2 = 1 at a 100 MHz mode for α, at a \
                     0.3 mHz mode for β), and the damped stable step overflows; a units slip?"
                ),
            ));
        }
    }
    Ok(Rayleigh {
        alpha: section.alpha,
        beta: section.beta,
    })
}

/// Largest α (1/s): ξ = α/(2ω) = 1 at ω = 5e8 rad/s (a 100 MHz mode, far above the
/// highest mode of any mesh); larger values only make the damped stable step vanish, and
/// near 1e154 overflow it (issue 13: refused at the field, not as `time.dt = inf`).
const MAX_ALPHA: f64 = 1e9;
/// Largest β (s): ξ = βω/2 = 1 at ω = 2e-3 rad/s (a 0.3 mHz mode, below the lowest mode of
/// any model); larger values only make the damped stable step vanish.
const MAX_BETA: f64 = 1e3;

/// Rayleigh coefficients of `[damping]` and of the regions with their own.
pub(super) fn build_damping(
    model: &mut Model,
    section: &DampingSection,
    regions: &[RegionSection],
    label: &str,
) -> Result<()> {
    model.damping = rayleigh(section, label, "damping")?;
    for (k, r) in regions.iter().enumerate() {
        if let Some(d) = &r.damping {
            let own = rayleigh(d, label, &format!("regions[{k}].damping"))?;
            model.region_damping.insert(r.name.clone(), own);
        }
    }
    Ok(())
}

/// Initial velocities of `[initial]`.
pub(super) fn build_initial(
    model: &mut Model,
    section: &InitialSection,
    label: &str,
) -> Result<()> {
    for (k, iv) in section.velocity.iter().enumerate() {
        finite_components(
            label,
            &format!("initial.velocity[{k}].value"),
            &iv.value,
            "m/s",
        )?;
        let nodes = nodes_of(
            &model.mesh,
            label,
            &format!("initial.velocity[{k}].set"),
            &iv.set,
        )?;
        model.initial_velocity.push((nodes, iv.value));
    }
    Ok(())
}
