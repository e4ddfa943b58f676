//! The steps of a run from t = 0 to its end time: full steps Δt, the last one shortened
//! so that the run ends exactly on `end` (docs/outputs.md, "Times").
//!
//! An `end` within 10⁻⁹ Δt of a whole number of steps is that number of full steps (the
//! last one lands on `end` itself, not on N·Δt rounded); otherwise the run takes
//! ⌊end/Δt⌋ full steps and one step of the remainder h = end − ⌊end/Δt⌋·Δt, with the
//! variable-step central difference ([`crate::stage::Simulation::step_to`]).

/// Relative tolerance (of Δt) within which `end` counts as a multiple of Δt.
const SNAP: f64 = 1e-9;

/// The steps from t = 0 to `end`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct StepSchedule {
    /// Number of steps, the last included.
    pub steps: u64,
    /// End time (s): the time after the last step.
    pub end: f64,
    /// Length of the last step (s): Δt, or less when `end` is not a multiple of Δt.
    pub last_step: f64,
}

impl StepSchedule {
    /// The schedule of a run to `end` with step `dt` (both finite and > 0).
    pub fn new(end: f64, dt: f64) -> Self {
        let ratio = end / dt;
        let nearest = ratio.round();
        if nearest >= 1.0 && (ratio - nearest).abs() <= SNAP * nearest.max(1.0) {
            return Self {
                steps: nearest as u64,
                end,
                last_step: dt,
            };
        }
        let full = ratio.floor();
        Self {
            steps: full as u64 + 1,
            end,
            last_step: end - full * dt,
        }
    }

    /// Whether the last step is shorter than Δt.
    pub fn shortened(&self, dt: f64) -> bool {
        self.last_step < dt * (1.0 - SNAP)
    }
}

/// Whether a step from `t` to `t_end` is a full step `dt` (within the tolerance).
pub(crate) fn is_full_step(t: f64, t_end: f64, dt: f64) -> bool {
    ((t_end - t) - dt).abs() <= SNAP * dt
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_multiple_of_the_step_takes_whole_steps() {
        // 0.3 / 0.1 = 2.9999999999999996 in binary: still 3 full steps.
        let s = StepSchedule::new(0.3, 0.1);
        assert_eq!(s.steps, 3);
        assert_eq!(s.last_step, 0.1);
        assert!(!s.shortened(0.1));
        let s = StepSchedule::new(0.7, 0.1);
        assert_eq!((s.steps, s.last_step), (7, 0.1));
    }

    #[test]
    fn a_remainder_is_one_shortened_last_step() {
        let s = StepSchedule::new(0.25, 0.1);
        assert_eq!(s.steps, 3);
        assert!((s.last_step - 0.05).abs() < 1e-15);
        assert!(s.shortened(0.1));
        // An end below one step: a single step of the end time.
        let s = StepSchedule::new(1e-5, 2.5e-4);
        assert_eq!((s.steps, s.last_step), (1, 1e-5));
        assert!(s.shortened(2.5e-4));
    }
}
