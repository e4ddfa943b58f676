//! The progress bar of `dcfm run`: step, simulated time, throughput and the estimated
//! time left. The simulated time is computed from the bar's own step count when the line
//! is drawn (t = step · Δt), so that the two always belong to the same redraw; the
//! throughput comes with the message, updated every few steps.

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressState, ProgressStyle};

/// A bar of `total` steps of `dt` drawn on `target`, starting at step `start`.
pub fn run_bar(target: ProgressDrawTarget, total: u64, start: u64, dt: f64) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(total), target);
    bar.set_style(
        ProgressStyle::with_template("{bar:30} step {pos}/{len} t = {simtime} s {msg} ETA {eta}")
            .expect("valid template")
            .with_key(
                "simtime",
                move |state: &ProgressState, w: &mut dyn std::fmt::Write| {
                    let _ = write!(w, "{:.4e}", state.pos() as f64 * dt);
                },
            ),
    );
    bar.set_position(start);
    bar
}

/// Show step `step` and the throughput `rate` (element updates per second): the message
/// first, so that the redraw the new position triggers shows both.
pub fn update(bar: &ProgressBar, step: u64, rate: f64) {
    bar.set_message(format!("{rate:.3e} element-updates/s"));
    bar.set_position(step);
}
