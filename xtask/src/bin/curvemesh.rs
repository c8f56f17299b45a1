//! The `curvemesh` binary, what `cargo install --path xtask` installs: the same command as
//! `cargo xtask` ([`xtask::entry`]), naming itself `curvemesh` in help and usage lines.

/// jemalloc with one arena (`.cargo/config.toml`): glibc gives the second thread an arena of
/// its own, which kept the 1M-cell run's peak memory 10 % higher with two threads.
#[cfg(unix)]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

fn main() -> std::process::ExitCode {
    xtask::entry::main(xtask::entry::CURVEMESH)
}
