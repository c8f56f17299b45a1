//! Progress on stderr: a spinner per stage while it runs, hidden when stderr is not a
//! terminal (indicatif draws nothing then) or with `--quiet`.

use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

/// A running stage; finishing (or dropping) it clears its line.
pub struct Stage(ProgressBar);

/// Starts the spinner of a stage named `what`.
pub fn stage(quiet: bool, what: &str) -> Stage {
    let target = if quiet {
        ProgressDrawTarget::hidden()
    } else {
        ProgressDrawTarget::stderr()
    };
    let bar = ProgressBar::with_draw_target(None, target);
    if let Ok(style) = ProgressStyle::with_template("{spinner} {msg} {elapsed}") {
        bar.set_style(style);
    }
    bar.set_message(what.to_string());
    bar.enable_steady_tick(Duration::from_millis(100));
    Stage(bar)
}

impl Drop for Stage {
    fn drop(&mut self) {
        self.0.finish_and_clear();
    }
}

/// Runs `work` on `report` as a stage shown as `what` (its spinner on stderr unless `quiet`)
/// and records its time in seconds in the report's timings under `key`.
pub fn timed<T>(
    report: &mut crate::report::Report,
    quiet: bool,
    (key, what): (&'static str, &str),
    work: impl FnOnce(&mut crate::report::Report) -> T,
) -> T {
    let t = std::time::Instant::now();
    let progress = stage(quiet, what);
    let out = work(report);
    drop(progress);
    report.timings_s.insert(key, t.elapsed().as_secs_f64());
    out
}
