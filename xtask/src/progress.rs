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

/// Runs `work` as a stage named `what` (its spinner on stderr unless `quiet`) and records its
/// time in seconds under `key` in `timings`.
pub fn timed<T>(
    quiet: bool,
    what: &str,
    (key, timings): (
        &'static str,
        &mut std::collections::BTreeMap<&'static str, f64>,
    ),
    work: impl FnOnce() -> T,
) -> T {
    let t = std::time::Instant::now();
    let progress = stage(quiet, what);
    let out = work();
    drop(progress);
    timings.insert(key, t.elapsed().as_secs_f64());
    out
}
