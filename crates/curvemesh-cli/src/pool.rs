//! The thread pool a command runs in: `--threads N` threads, or rayon's default (one per
//! core, or `RAYON_NUM_THREADS`), entered by the command's own thread. Used from a thread
//! that is not one of its own, rayon's global pool hands each fork over to its threads and
//! blocks the caller until it is done: the 1M-cell P3 mesh took some 0.1 s longer so (2.60
//! against 2.47 s, medians of 5 runs on two cores).

use anyhow::Result;

/// Runs `f` on a thread of a pool of `threads` threads (`None`: rayon's default number).
pub(crate) fn in_pool<R: Send>(threads: Option<u16>, f: impl FnOnce() -> R + Send) -> Result<R> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(threads.map_or(0, usize::from))
        .build()?;
    Ok(pool.install(f))
}
