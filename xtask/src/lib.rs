//! `cargo xtask`: the development tasks of the workspace — `bench` (each stage timed, whole
//! runs side by side with Gmsh, the scaling and threads studies, 3D; written into
//! `docs/performance.md`) and `figures` (the pictures of the docs, from real runs) — beside
//! the `curvemesh` commands `mesh`, `move` and `quality`, forwarded as they are to
//! [`curvemesh_cli`] so that `cargo xtask mesh` is `curvemesh mesh`.
//!
//! Modules, each importing only those listed before it: [`cli`], `probe`, `perf_doc`,
//! `runs`, `bench3d`, `bench_vs`, `bench_cmd`, [`figures_cmd`].

mod bench3d;
mod bench_cmd;
mod bench_vs;
pub mod cli;
pub mod figures_cmd;
mod perf_doc;
mod probe;
mod runs;

pub use curvemesh_cli::{Finished, Outcome, exit};

/// The name `cargo xtask` prints in help and usage lines.
pub const CARGO_XTASK: &str = "cargo xtask";

/// Runs one parsed command. An `Err` is bad input (exit status 1); its `{:#}` display is the
/// one-line message for the user.
pub fn execute(cli: cli::Cli) -> anyhow::Result<Outcome> {
    run(cli).map(|f| f.outcome)
}

/// Runs one parsed command, as [`execute`], keeping the line that describes an invalid mesh
/// (see [`exit::of_run`]).
pub fn run(cli: cli::Cli) -> anyhow::Result<Finished> {
    match cli.command {
        cli::Command::Tool(command) => curvemesh_cli::run_command(command),
        cli::Command::Bench(args) => bench_cmd::run(&args).map(|_| Finished::valid()),
        cli::Command::Figures(args) => figures_cmd::run(&args),
    }
}
