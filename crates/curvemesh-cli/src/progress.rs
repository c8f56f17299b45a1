//! Progress on stderr: a spinner per stage while it runs, hidden when stderr is not a
//! terminal (indicatif draws nothing then) or with `--quiet`; the library's notes on a long
//! run printed on a terminal. The command's [`curvemesh::Observer`].

use std::io::IsTerminal;
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

/// The spinners of a run's stages, and its notes on stderr.
pub struct Spinners {
    quiet: bool,
    running: Option<Stage>,
}

impl Spinners {
    /// Spinners shown unless `quiet`.
    pub fn new(quiet: bool) -> Spinners {
        Spinners {
            quiet,
            running: None,
        }
    }
}

impl curvemesh::Observer for Spinners {
    fn stage_begun(&mut self, what: &str) {
        self.running = Some(stage(self.quiet, what));
    }
    fn stage_ended(&mut self, _what: &str, _seconds: f64) {
        self.running = None;
    }
    fn note(&mut self, text: &str) {
        if !self.quiet && std::io::stderr().is_terminal() {
            eprintln!("note: {text}");
        }
    }
}
