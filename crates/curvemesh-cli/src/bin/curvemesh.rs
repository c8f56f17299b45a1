//! The `curvemesh` binary: everything is in the library ([`curvemesh_cli::entry`]).

/// jemalloc with one arena (`.cargo/config.toml`): glibc gives the second thread an arena of
/// its own, which kept the 1M-cell run's peak memory 10 % higher with two threads.
#[cfg(unix)]
#[global_allocator]
static ALLOCATOR: tikv_jemallocator::Jemalloc = tikv_jemallocator::Jemalloc;

fn main() -> std::process::ExitCode {
    curvemesh_cli::entry::main::<curvemesh_cli::cli::Cli>(
        curvemesh_cli::entry::CURVEMESH,
        curvemesh_cli::run,
    )
}
