//! Progress of a solve: a bar over the load steps with the current Newton iteration, relative
//! residual and energy, drawn on stderr once a solve has run for a moment; and the statistics a
//! failure message needs (the load step reached, the largest residual in it).
//!
//! Each solve gets its own [`Tracker`]; the solver reports to it through a closure
//! ([`Tracker::hook`]) in its settings, so there is no process-wide state.

use std::io::IsTerminal;
use std::sync::{Arc, Mutex};
use std::time::{Duration, Instant};

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::solver::Progress;

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

struct State {
    steps: usize,
    show: bool,
    started: Instant,
    bar: Option<ProgressBar>,
    summary: Summary,
}

/// The progress of one solve, shared with the solver's hook.
#[derive(Clone)]
pub struct Tracker(Arc<Mutex<State>>);

impl Tracker {
    /// Starts tracking a solve of `steps` load steps; the bar is drawn only if `show`.
    pub fn begin(steps: usize, show: bool) -> Tracker {
        Tracker(Arc::new(Mutex::new(State {
            steps: steps.max(1),
            show,
            started: Instant::now(),
            bar: None,
            summary: Summary::default(),
        })))
    }

    fn lock(&self) -> std::sync::MutexGuard<'_, State> {
        // A panic while holding the lock cannot leave the tracker inconsistent in a way that
        // matters for a progress display.
        self.0.lock().unwrap_or_else(|e| e.into_inner())
    }

    /// The solver's progress hook for this solve (see `NewtonSettings::progress`).
    pub fn hook(&self) -> Progress {
        let t = self.clone();
        Arc::new(move |step, iteration, residual, energy| {
            t.report(Sample {
                step,
                iteration,
                residual,
                energy,
            })
        })
    }

    fn report(&self, s: Sample) {
        let mut t = self.lock();
        let sm = &mut t.summary;
        let new_step = sm.last.is_none_or(|l| l.step != s.step);
        // NaN never compares larger, so a residual that turns NaN is recorded explicitly.
        if new_step
            || sm
                .largest_in_step
                .is_none_or(|b| s.residual.is_nan() || s.residual > b.residual)
        {
            sm.largest_in_step = Some(s);
        }
        sm.last = Some(s);
        if !t.show {
            return;
        }
        if t.bar.is_none() && t.started.elapsed() >= SHOW_AFTER {
            t.bar = Some(new_bar(t.steps));
        }
        if let Some(bar) = &t.bar {
            bar.set_position(s.step as u64);
            bar.set_message(format!(
                "iteration {}  residual {:.3e}  energy {:.5e} J",
                s.iteration, s.residual, s.energy
            ));
        }
    }

    /// Stops tracking, clears the bar and returns what was reported.
    pub fn finish(&self) -> Summary {
        let mut t = self.lock();
        if let Some(bar) = t.bar.take() {
            bar.finish_and_clear();
        }
        t.summary
    }
}

fn new_bar(steps: usize) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(Some(steps as u64), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template("{elapsed:>4} [{bar:20}] load step {pos}/{len} {wide_msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_keeps_the_largest_residual_of_the_last_step() {
        let t = Tracker::begin(3, false);
        let hook = t.hook();
        hook(1, 0, 5.0, -1.0);
        hook(1, 1, 1e-12, -2.0);
        hook(2, 2, 0.5, -3.0);
        hook(2, 3, 2.0, -4.0);
        hook(2, 4, 1e-3, -5.0);
        let s = t.finish();
        assert_eq!(s.last.unwrap().iteration, 4);
        let big = s.largest_in_step.unwrap();
        assert_eq!((big.step, big.iteration, big.residual), (2, 3, 2.0));
        let t = Tracker::begin(1, false);
        let hook = t.hook();
        hook(1, 0, 1.0, 0.0);
        hook(1, 1, f64::NAN, f64::NAN);
        assert!(t.finish().largest_in_step.unwrap().residual.is_nan());
        assert_eq!(Tracker::begin(1, false).finish(), Summary::default());
    }
}
