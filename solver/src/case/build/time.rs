//! `[time]`: end time, safety factor and the time step.

use crate::case::schema::TimeSection;
use crate::error::{DcfmError, Result};

use super::checks::finite_positive;

/// Check the fields of `[time]` that do not need the model.
pub(super) fn check_time(section: &TimeSection, label: &str) -> Result<()> {
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
    Ok(())
}
