//! The expected wall time of a run, for `dcfm check`: a few steps of the case's own model
//! are timed on this machine and the throughput (element updates per second) scaled to
//! the case's step count. The static stage is not included, nor the outputs.

use std::time::{Duration, Instant};

use dcfm::case::Case;
use dcfm::error::Result;
use dcfm::stage::Simulation;

/// Steps timed at most, and the wall time after which the timing stops.
const MAX_TIMED_STEPS: u64 = 200;
const TIMING_BUDGET: Duration = Duration::from_millis(300);

/// A measured throughput and what it predicts.
#[derive(Clone, Copy, Debug)]
pub struct WallEstimate {
    /// Steps timed.
    pub steps_timed: u64,
    /// Element updates per second over them.
    pub element_updates_per_s: f64,
    /// Steps of the run (⌈end/Δt⌉).
    pub steps: f64,
    /// Predicted wall time of the dynamic stage (s).
    pub wall_s: f64,
    /// Worker threads the steps ran on.
    pub threads: usize,
}

/// Time a few steps of the case's model (after one untimed step) and scale them to its
/// step count. Consumes the case: `dcfm check` has printed everything else.
pub fn estimate_wall_time(case: Case) -> Result<WallEstimate> {
    let steps = case.step_count();
    let elements = case.model.n_elements().max(1) as f64;
    let mut sim = Simulation::new(case.model, case.dt, case.safety)?;
    sim.step()?;
    let t0 = Instant::now();
    let mut timed = 0;
    while timed < 3 || (timed < MAX_TIMED_STEPS && t0.elapsed() < TIMING_BUDGET) {
        sim.step()?;
        timed += 1;
    }
    let per_step = t0.elapsed().as_secs_f64().max(1e-12) / timed as f64;
    Ok(WallEstimate {
        steps_timed: timed,
        element_updates_per_s: elements / per_step,
        steps,
        wall_s: steps * per_step,
        threads: rayon::current_num_threads(),
    })
}
