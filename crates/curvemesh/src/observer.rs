//! How a caller follows a run: the stages as they begin and end, and notes worth telling a
//! person before a long run (a very large expected mesh). The CLI draws a spinner per stage;
//! a library caller may log, time or ignore them ([`Silent`]).

/// Told of a run's stages as they happen. Every method does nothing by default.
pub trait Observer {
    /// A stage begins; `what` names it for people ("linear layered mesh (AFSF)").
    fn stage_begun(&mut self, what: &str) {
        let _ = what;
    }
    /// The stage last begun has ended after `seconds`.
    fn stage_ended(&mut self, what: &str, seconds: f64) {
        let _ = (what, seconds);
    }
    /// Something worth telling before a long run ("about 23 million cells expected").
    fn note(&mut self, text: &str) {
        let _ = text;
    }
}

/// An observer that ignores everything.
#[derive(Debug, Clone, Copy, Default)]
pub struct Silent;

impl Observer for Silent {}

/// Runs `work` as the stage `what`, telling `observer` when it begins and ends; returns what
/// it made with its seconds.
pub(crate) fn stage<T>(
    observer: &mut dyn Observer,
    what: &str,
    work: impl FnOnce() -> T,
) -> (T, f64) {
    let t = std::time::Instant::now();
    observer.stage_begun(what);
    let out = work();
    let seconds = t.elapsed().as_secs_f64();
    observer.stage_ended(what, seconds);
    (out, seconds)
}
