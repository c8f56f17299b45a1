//! The `xtask` binary, run as `cargo xtask` (the alias in `.cargo/config.toml`): the
//! development tasks and the `curvemesh` commands ([`xtask::run`]).

/// jemalloc with one arena (`.cargo/config.toml`): glibc gives the second thread an arena of
/// its own, which kept the 1M-cell run's peak memory 10 % higher with two threads.
#[cfg(unix)]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

fn main() -> std::process::ExitCode {
    curvemesh_cli::entry::main::<xtask::cli::Cli>(xtask::CARGO_XTASK, xtask::run)
}
