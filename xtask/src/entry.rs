//! The entry point both binaries share: `xtask` (run as `cargo xtask`, the alias in
//! `.cargo/config.toml`) and `curvemesh` (what `cargo install --path xtask` puts on the PATH).
//! It installs the interrupt handler, parses the flags under the name the user typed (so help,
//! usage lines and `--version` name the right command), runs the command and turns the outcome
//! into the exit status and the line on stderr ([`crate::exit`]): 0 success, 1 bad input or a
//! usage error, 2 a mesh was written but failed validation, 130 interrupted.

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches};

use crate::{cli::Cli, exit};

/// The name `cargo xtask` prints in help and usage lines.
pub const CARGO_XTASK: &str = "cargo xtask";
/// The name the installed binary prints.
pub const CURVEMESH: &str = "curvemesh";

/// Parses the command line as the command `name`, runs it and returns the exit status.
pub fn main(name: &'static str) -> ExitCode {
    exit::install_interrupt_handler();
    let end = match parse(name, std::env::args_os()) {
        Ok(cli) => exit::of_run(&crate::run(cli)),
        Err(e) => match exit::of_usage_error(&e) {
            Some(end) => end,
            None => {
                // --help, --version: clap prints them as usual
                let _ = e.print();
                return ExitCode::SUCCESS;
            }
        },
    };
    if let Some(line) = &end.stderr {
        eprintln!("{line}");
    }
    ExitCode::from(end.code)
}

/// The flags of `args` (the first is the program) parsed as the command `name`.
pub fn parse<I, T>(name: &'static str, args: I) -> Result<Cli, clap::Error>
where
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let mut command = Cli::command().name(name).bin_name(name);
    let matches = command.try_get_matches_from_mut(args)?;
    Cli::from_arg_matches(&matches).map_err(|e| e.format(&mut command))
}
