//! `cargo xtask`: the command-line tool. It composes the crates of the pipeline —
//! `geom-curve` → `boundary1d` → the domain meshers → `mesh-io` — into the commands of
//! `../shared/design/interface.md`. Flags are parsed in [`cli`]; each subcommand has its own
//! module with a `run`. This is the only crate (with `mesh-io`) that touches files, and the
//! only one that uses `anyhow`.
//!
//! The library half holds everything, so that the end-to-end tests in `tests/` can drive the
//! commands in-process; `main.rs` only parses the flags and turns the outcome into an exit
//! status.
//!
//! Exit status ([`exit`]): 0 on success, 1 on bad input (one line on stderr naming the fault,
//! no output file left behind), 2 when a mesh was made but failed validation (written, with
//! one line on stderr). Every output of a run — meshes, snapshot, pictures, report — is
//! reserved before the work starts and replaced together at the end, or not at all
//! ([`mesh_io::atomic::Transaction`], see [`outputs`]).

mod airfoil;
mod bench3d;
mod bench_cmd;
mod bench_vs;
pub mod builtin;
pub mod case;
pub mod case3d;
pub mod cli;
pub mod entry;
mod estimate;
pub mod exit;
pub mod figures_cmd;
mod mesh3d_cmd;
mod mesh_cmd;
mod move_cmd;
mod move_sens;
pub mod outputs;
mod perf_doc;
mod pictures;
pub mod pipeline;
pub mod pipeline3d;
mod pool;
mod probe;
mod progress;
mod quality_cmd;
mod report;
mod resources;
pub mod stages;
mod summary;
pub mod wing;

/// The case loader from TOML text, for the fuzz target (`xtask/fuzz`).
pub use case::parse_case_str;

/// How a run that did not fail on bad input ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Outcome {
    /// Everything was made and passed validation.
    Valid,
    /// A mesh was written, but it failed validation (named in the report).
    Invalid,
}

/// How a run ended, with the line for stderr when the mesh failed validation.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Finished {
    /// Valid or not.
    pub outcome: Outcome,
    /// For [`Outcome::Invalid`]: what failed and where the report is, on one line.
    pub problem: Option<String>,
}

impl Finished {
    /// A valid run.
    pub fn valid() -> Finished {
        Finished {
            outcome: Outcome::Valid,
            problem: None,
        }
    }
}

/// Runs one parsed command. An `Err` is bad input (exit status 1); its `{:#}` display is the
/// one-line message for the user.
pub fn execute(cli: cli::Cli) -> anyhow::Result<Outcome> {
    run(cli).map(|f| f.outcome)
}

/// Runs one parsed command, as [`execute`], keeping the line that describes an invalid mesh
/// (see [`exit::of_run`]).
pub fn run(cli: cli::Cli) -> anyhow::Result<Finished> {
    match cli.command {
        cli::Command::Mesh(args) => mesh_cmd::run(&args),
        cli::Command::Move(args) => move_cmd::run(&args),
        cli::Command::Quality(args) => quality_cmd::run(&args),
        cli::Command::Bench(args) => bench_cmd::run(&args).map(|_| Finished::valid()),
        cli::Command::Figures(args) => figures_cmd::run(&args),
    }
}
