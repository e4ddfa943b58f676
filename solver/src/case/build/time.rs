//! `[time]`: end time, safety factor, the time step and the step budget.

use crate::case::schema::{TimeSection, DEFAULT_MAX_STEPS};
use crate::error::{DcfmError, Result};

use super::checks::finite_positive;

/// Most steps a run can count: beyond 2⁵³ steps t + Δt rounds back to t in double
/// precision and the simulated time stops advancing.
const MAX_COUNTABLE_STEPS: f64 = 9_007_199_254_740_992.0;

/// Check the fields of `[time]` that do not need the model; the step budget
/// (`time.max_steps`, default [`DEFAULT_MAX_STEPS`]).
pub(super) fn check_time(section: &TimeSection, label: &str) -> Result<u64> {
    finite_positive(label, "time.end", section.end, "s")?;
    if !(section.safety.is_finite() && section.safety > 0.0 && section.safety <= 1.0) {
        return Err(DcfmError::invalid(
            label,
            "time.safety",
            section.safety,
            "must be in (0, 1]",
        ));
    }
    if let Some(dt) = section.dt {
        finite_positive(label, "time.dt", dt, "s")?;
    }
    match section.max_steps {
        None => Ok(DEFAULT_MAX_STEPS),
        Some(m) if m.is_finite() && m >= 1.0 && m.fract() == 0.0 && m <= MAX_COUNTABLE_STEPS => {
            Ok(m as u64)
        }
        Some(m) => Err(DcfmError::invalid(
            label,
            "time.max_steps",
            m,
            "a whole number of steps from 1 to 2^53",
        )),
    }
}

/// `time.stable_step`: `"element"` (the default) or `"shared_mass"`.
pub(super) fn step_bound(section: &TimeSection, label: &str) -> Result<crate::model::StepBound> {
    use crate::model::StepBound;
    match section.stable_step.as_deref() {
        None => Ok(StepBound::Element),
        Some(name) => StepBound::parse(name).ok_or_else(|| {
            DcfmError::invalid(
                label,
                "time.stable_step",
                format!("\"{name}\""),
                StepBound::CHOICES,
            )
        }),
    }
}

/// The `max_level` of `time.subcycling`: `None` for `"off"` or no entry, else a whole
/// number from 1 to [`crate::stage::subcycling::MAX_LEVEL`] given as `{ max_level = N }`.
pub(super) fn subcycling_level(section: &TimeSection, label: &str) -> Result<Option<u8>> {
    use crate::stage::subcycling::MAX_LEVEL;
    let expected = format!(
        "\"off\" or a table {{ max_level = N }} with N a whole number from 1 to {MAX_LEVEL} \
         (steps up to 2^N Δt)"
    );
    let Some(value) = &section.subcycling else {
        return Ok(None);
    };
    let bad = |field: &str, v: &dyn std::fmt::Display| {
        DcfmError::invalid(label, field, v.to_string(), expected.clone())
    };
    match value {
        toml::Value::String(s) if s == "off" => Ok(None),
        toml::Value::Table(t) => {
            if let Some(k) = t.keys().find(|k| k.as_str() != "max_level") {
                return Err(bad(&format!("time.subcycling.{k}"), &"an unknown key"));
            }
            match t.get("max_level") {
                Some(toml::Value::Integer(n)) if (1..=MAX_LEVEL as i64).contains(n) => {
                    Ok(Some(*n as u8))
                }
                Some(v) => Err(bad("time.subcycling.max_level", v)),
                None => Err(bad("time.subcycling.max_level", &"missing")),
            }
        }
        v => Err(bad("time.subcycling", v)),
    }
}

/// The settings of `time.mass_scaling`: `None` for `"off"` or no entry, else a table
/// `{ min_element_step = Δt_min, max_added_fraction = f }` (the fraction optional, default
/// [`crate::mass_scaling::DEFAULT_MAX_ADDED_FRACTION`]); the values themselves are checked
/// where they are applied (`crate::mass_scaling::apply_mass_scaling`).
pub(super) fn mass_scaling_settings(
    section: &TimeSection,
    label: &str,
) -> Result<Option<crate::mass_scaling::MassScalingSettings>> {
    use crate::mass_scaling::{MassScalingSettings, DEFAULT_MAX_ADDED_FRACTION};
    let expected = "\"off\" or a table { min_element_step = Δt_min (s), max_added_fraction = f } \
                    (f optional, default 0.05 of a region's mass): elements whose own step is \
                    below Δt_min are made heavy enough to step at it";
    let Some(value) = &section.mass_scaling else {
        return Ok(None);
    };
    let bad = |field: &str, v: &dyn std::fmt::Display| {
        DcfmError::invalid(label, field, v.to_string(), expected)
    };
    let number = |t: &toml::map::Map<String, toml::Value>, key: &str| -> Result<Option<f64>> {
        match t.get(key) {
            None => Ok(None),
            Some(toml::Value::Float(x)) => Ok(Some(*x)),
            Some(toml::Value::Integer(n)) => Ok(Some(*n as f64)),
            Some(v) => Err(bad(&format!("time.mass_scaling.{key}"), v)),
        }
    };
    match value {
        toml::Value::String(s) if s == "off" => Ok(None),
        toml::Value::Table(t) => {
            if let Some(k) = t
                .keys()
                .find(|k| !matches!(k.as_str(), "min_element_step" | "max_added_fraction"))
            {
                return Err(bad(&format!("time.mass_scaling.{k}"), &"an unknown key"));
            }
            let Some(min_element_step) = number(t, "min_element_step")? else {
                return Err(bad("time.mass_scaling.min_element_step", &"missing"));
            };
            let max_added_fraction =
                number(t, "max_added_fraction")?.unwrap_or(DEFAULT_MAX_ADDED_FRACTION);
            Ok(Some(MassScalingSettings {
                min_element_step,
                max_added_fraction,
            }))
        }
        v => Err(bad("time.mass_scaling", v)),
    }
}

/// Smallest `time.dt` accepted, as a fraction of the stable step: a step a billionth of
/// the stable one needs 10⁹ steps to cross one element, each moving the nodes by less
/// than the round-off of their coordinates — a vanishing step (1e-300, a units slip), not
/// a finer solution. Refused at `time.dt` (issue 13 item 3) rather than run as an
/// endless, or at some point unstable, simulation.
pub(super) const VANISHING_DT_FRACTION: f64 = 1e-9;

/// Refuse a time step `dt` that vanishes against the stable step `critical` (below
/// [`VANISHING_DT_FRACTION`] of it), or whose step count to `end` overflows 2⁵³ while it
/// is far below the stable step (below `small` × `critical`; an end time too large for a
/// sound step stays an error at `time.end`, [`check_step_budget`]). The error names
/// `time.dt` when it was `given`, else `time.safety` (Δt = safety × the stable step).
pub(super) fn check_vanishing_dt(
    label: &str,
    given: Option<f64>,
    step: (f64, f64),
    end: f64,
    critical: f64,
    small: f64,
) -> Result<()> {
    let (dt, safety) = step;
    let steps = step_count(end, dt);
    let vanishing = critical.is_finite() && dt < VANISHING_DT_FRACTION * critical;
    // No stable step (NaN: every element prescribed) leaves dt alone to blame.
    let floor = small * critical;
    let overflows =
        (steps.is_nan() || steps > MAX_COUNTABLE_STEPS) && (floor.is_nan() || dt < floor);
    if !(vanishing || overflows) {
        return Ok(());
    }
    let against = if critical.is_finite() {
        format!(
            "{} of the stable step {} s",
            crate::readable::engineering(dt / critical),
            crate::readable::engineering(critical)
        )
    } else {
        "every element is prescribed (no stable-step limit)".to_string()
    };
    let least = crate::readable::engineering(VANISHING_DT_FRACTION);
    let (field, value, fix) = match given {
        Some(d) => (
            "time.dt",
            d,
            format!(
                "give at least {least} × the stable step, or leave time.dt out for the \
                 safety factor × the stable step"
            ),
        ),
        None => (
            "time.safety",
            safety,
            format!("give a safety factor of at least {least} (0.9 is usual)"),
        ),
    };
    Err(DcfmError::invalid(
        label,
        field,
        crate::readable::engineering(value),
        format!(
            "a vanishing time step: Δt = {} s is {against}, {} steps to the end time {} s{}; \
             {fix} (a units slip?)",
            crate::readable::engineering(dt),
            crate::readable::engineering(steps),
            crate::readable::engineering(end),
            if steps > MAX_COUNTABLE_STEPS {
                " (beyond 2^53 steps t + Δt = t in double precision)"
            } else {
                ""
            },
        ),
    ))
}

/// Number of steps of a run from 0 to `end` with steps of `dt`: ⌈end/Δt⌉.
pub(super) fn step_count(end: f64, dt: f64) -> f64 {
    (end / dt).ceil()
}

/// Check the step count of `[time]` against the step budget `max_steps`: above it is an
/// error naming `time.end`, `time.max_steps` and the way to allow it (`allow_long`, the
/// `--allow-long` flag of `dcfm run`); above 2⁵³ steps it is an error even when allowed.
pub(super) fn check_step_budget(
    label: &str,
    end: f64,
    dt: f64,
    max_steps: u64,
    allow_long: bool,
) -> Result<u64> {
    let steps = step_count(end, dt);
    let count = format!(
        "{} steps of Δt = {dt:.4e} s",
        crate::readable::engineering(steps)
    );
    if steps > max_steps as f64 && !allow_long {
        return Err(DcfmError::invalid(
            label,
            "time.end",
            end,
            format!(
                "{count}, above the step budget time.max_steps = {}: check the end time and \
                 the units, raise time.max_steps, or run with --allow-long",
                crate::readable::engineering(max_steps as f64)
            ),
        ));
    }
    if steps.is_nan() || steps > MAX_COUNTABLE_STEPS {
        return Err(DcfmError::invalid(
            label,
            "time.end",
            end,
            format!(
                "{count}: more than 2^53 steps, after which t + Δt = t in double precision \
                 and the time stops advancing"
            ),
        ));
    }
    Ok(steps as u64)
}
