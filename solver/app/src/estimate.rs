//! The expected wall time of a run, for `dcfm check`: a few steps of the case's own model
//! are timed on this machine and the throughput (element updates per second) scaled to
//! the case's step count. The static stage is not included, nor the outputs. A case with
//! `time.subcycling` is timed subcycled, over whole cycles (every element's evaluations
//! in proportion), and its levels are reported.

use std::time::{Duration, Instant};

use dcfm::case::Case;
use dcfm::error::Result;
use dcfm::stage::subcycling::SubcyclingSummary;
use dcfm::stage::Simulation;

/// Steps timed at most, and the wall time after which the timing stops.
const MAX_TIMED_STEPS: u64 = 200;
const TIMING_BUDGET: Duration = Duration::from_millis(300);

/// A measured throughput and what it predicts.
#[derive(Clone, Debug)]
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
    /// The levels of `time.subcycling` the steps ran with (`None`: single steps).
    pub subcycling: Option<SubcyclingSummary>,
}

/// Time a few steps of the case's model (after one untimed step, or cycle when
/// subcycled) and scale them to its step count. Consumes the case: `dcfm check` has
/// printed everything else. Errors: the case's subcycling refused (as `dcfm run` would),
/// a step failing.
pub fn estimate_wall_time(case: Case) -> Result<WallEstimate> {
    let steps = case.step_count();
    let elements = case.model.n_elements().max(1) as f64;
    let mut sim = Simulation::new(case.model, case.dt, case.safety)?;
    if let Some(max_level) = case.subcycling {
        sim.enable_subcycling(max_level, case.safety)?;
    }
    // Whole cycles (one step each without subcycling), so that every level's elements are
    // evaluated in proportion.
    let cycle = sim.cycle_steps();
    sim.run_steps(cycle)?;
    let t0 = Instant::now();
    let mut timed = 0;
    while timed < 3 || (timed < MAX_TIMED_STEPS.max(cycle) && t0.elapsed() < TIMING_BUDGET) {
        sim.run_steps(cycle)?;
        timed += cycle;
    }
    let per_step = t0.elapsed().as_secs_f64().max(1e-12) / timed as f64;
    Ok(WallEstimate {
        steps_timed: timed,
        element_updates_per_s: elements / per_step,
        steps,
        wall_s: steps * per_step,
        threads: rayon::current_num_threads(),
        subcycling: sim.subcycling().cloned(),
    })
}
