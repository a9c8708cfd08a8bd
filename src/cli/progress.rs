//! Progress of a solve: a bar over the load steps with the current Newton iteration, relative
//! residual and energy, drawn on stderr once a solve has run for a moment; and the statistics a
//! failure message needs (the load step reached, the largest residual in it).
//!
//! The solver reports through `NewtonSettings::progress`, a plain `fn` pointer without context,
//! so the tracker lives in a process-wide mutex. One solve runs at a time per process; a second
//! `begin` simply replaces the tracker.

use std::io::IsTerminal;
use std::sync::Mutex;
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// Short solves finish before the bar would be readable; they print only the summary line.
const SHOW_AFTER: Duration = Duration::from_millis(400);

/// Whether to draw the bar: not with --quiet, and only on a terminal.
pub fn show_progress(quiet: bool) -> bool {
    !quiet && std::io::stderr().is_terminal()
}

/// One progress report of the solver.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sample {
    pub step: usize,
    /// Newton iterations so far over all load steps.
    pub iteration: usize,
    pub residual: f64,
    pub energy: f64,
}

/// What the reports of one solve add up to.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Summary {
    pub last: Option<Sample>,
    /// The largest relative residual reported during the last load step reached.
    pub largest_in_step: Option<Sample>,
}

struct Tracker {
    steps: usize,
    show: bool,
    started: Instant,
    bar: Option<ProgressBar>,
    summary: Summary,
}

static TRACKER: Mutex<Option<Tracker>> = Mutex::new(None);

fn lock() -> std::sync::MutexGuard<'static, Option<Tracker>> {
    // A panic while holding the lock cannot leave the tracker inconsistent in a way that
    // matters for a progress display.
    TRACKER.lock().unwrap_or_else(|e| e.into_inner())
}

/// Starts tracking a solve of `steps` load steps; the bar is drawn only if `show`.
pub fn begin(steps: usize, show: bool) {
    *lock() = Some(Tracker {
        steps: steps.max(1),
        show,
        started: Instant::now(),
        bar: None,
        summary: Summary::default(),
    });
}

/// The solver's progress hook (see `NewtonSettings::progress`).
pub fn hook(step: usize, iteration: usize, residual: f64, energy: f64) {
    let mut guard = lock();
    let Some(t) = guard.as_mut() else { return };
    let s = Sample {
        step,
        iteration,
        residual,
        energy,
    };
    let sm = &mut t.summary;
    let new_step = sm.last.is_none_or(|l| l.step != step);
    // NaN never compares larger, so a residual that turns NaN is recorded explicitly.
    if new_step
        || sm
            .largest_in_step
            .is_none_or(|b| residual.is_nan() || residual > b.residual)
    {
        sm.largest_in_step = Some(s);
    }
    sm.last = Some(s);
    if !t.show {
        return;
    }
    if t.bar.is_none() && t.started.elapsed() >= SHOW_AFTER {
        let bar = ProgressBar::with_draw_target(Some(t.steps as u64), ProgressDrawTarget::stderr());
        bar.set_style(
            ProgressStyle::with_template(
                "{elapsed:>4} [{bar:20}] load step {pos}/{len} {wide_msg}",
            )
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
        );
        t.bar = Some(bar);
    }
    if let Some(bar) = &t.bar {
        bar.set_position(step as u64);
        bar.set_message(format!(
            "iteration {iteration}  residual {residual:.3e}  energy {energy:.5e} J"
        ));
    }
}

/// Stops tracking, clears the bar and returns what was reported.
pub fn finish() -> Summary {
    match lock().take() {
        Some(t) => {
            if let Some(bar) = t.bar {
                bar.finish_and_clear();
            }
            t.summary
        }
        None => Summary::default(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_keeps_the_largest_residual_of_the_last_step() {
        begin(3, false);
        hook(1, 0, 5.0, -1.0);
        hook(1, 1, 1e-12, -2.0);
        hook(2, 2, 0.5, -3.0);
        hook(2, 3, 2.0, -4.0);
        hook(2, 4, 1e-3, -5.0);
        let s = finish();
        assert_eq!(s.last.unwrap().iteration, 4);
        let big = s.largest_in_step.unwrap();
        assert_eq!((big.step, big.iteration, big.residual), (2, 3, 2.0));
        begin(1, false);
        hook(1, 0, 1.0, 0.0);
        hook(1, 1, f64::NAN, f64::NAN);
        assert!(finish().largest_in_step.unwrap().residual.is_nan());
        assert_eq!(finish(), Summary::default());
    }
}
