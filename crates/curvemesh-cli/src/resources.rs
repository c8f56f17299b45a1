//! What a process used: its peak memory (for the report) and the CPU time of the child
//! processes it has waited for (for `cargo xtask bench --vs-gmsh`), from `getrusage`. Not
//! available off Unix (`None`).

/// The peak resident memory of this process so far, in bytes (Linux: `ru_maxrss` in KiB, the
/// `VmHWM` of `/proc/self/status`).
pub fn peak_memory_bytes() -> Option<u64> {
    #[cfg(target_os = "linux")]
    {
        use nix::sys::resource::{UsageWho, getrusage};
        let usage = getrusage(UsageWho::RUSAGE_SELF).ok()?;
        u64::try_from(usage.max_rss()).ok().map(|kib| kib * 1024)
    }
    #[cfg(not(target_os = "linux"))]
    {
        None
    }
}

/// User plus system CPU seconds of every child process waited for so far: the difference
/// across one `wait` is that child's CPU time (its own threads and children included).
pub fn children_cpu_s() -> Option<f64> {
    #[cfg(unix)]
    {
        use nix::sys::resource::{UsageWho, getrusage};
        let usage = getrusage(UsageWho::RUSAGE_CHILDREN).ok()?;
        let seconds = |t: nix::sys::time::TimeVal| t.tv_sec() as f64 + t.tv_usec() as f64 * 1e-6;
        Some(seconds(usage.user_time()) + seconds(usage.system_time()))
    }
    #[cfg(not(unix))]
    {
        None
    }
}
