//! The `curvemesh` command: turns flags into the options of the [`curvemesh`] library, shows
//! progress, prints the summary, draws pictures and maps errors to exit codes. Every mesh,
//! movement and check is the library's; this crate only reads the command line and presents
//! the results. `cargo xtask mesh|move|quality` run these same commands.
//!
//! Exit status ([`exit`]): 0 on success, 1 on bad input (one line on stderr naming the fault,
//! no output file left behind), 2 when a mesh was made but failed validation (written, with
//! one line on stderr). Every output of a run — meshes, snapshot, pictures, report — is
//! reserved before the work starts and replaced together at the end, or not at all
//! ([`curvemesh::outputs`]).
//!
//! Modules, each importing only those listed before it: [`outcome`], [`cli`], [`exit`],
//! [`pool`], [`resources`], [`progress`], [`summary`], [`pictures`], [`plan`]; then the
//! commands ([`mesh_cmd`], [`move_cmd`], [`quality_cmd`], none importing another), and
//! [`entry`].

pub mod cli;
pub mod entry;
pub mod exit;
pub mod mesh_cmd;
pub mod move_cmd;
pub mod outcome;
pub mod pictures;
pub mod plan;
pub mod pool;
pub mod progress;
pub mod quality_cmd;
pub mod resources;
pub mod summary;

pub use outcome::{Finished, Outcome};

/// Runs one parsed command. An `Err` is bad input (exit status 1); its `{:#}` display is the
/// one-line message for the user.
pub fn execute(cli: cli::Cli) -> anyhow::Result<Outcome> {
    run(cli).map(|f| f.outcome)
}

/// Runs one parsed command, as [`execute`], keeping the line that describes an invalid mesh
/// (see [`exit::of_run`]).
pub fn run(cli: cli::Cli) -> anyhow::Result<Finished> {
    run_command(cli.command)
}

/// Runs one subcommand.
pub fn run_command(command: cli::Command) -> anyhow::Result<Finished> {
    match command {
        cli::Command::Mesh(args) => mesh_cmd::run(&args),
        cli::Command::Move(args) => move_cmd::run(&args),
        cli::Command::Quality(args) => quality_cmd::run(&args),
    }
}
