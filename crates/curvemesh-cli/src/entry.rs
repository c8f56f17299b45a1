//! The entry point of the binaries: `curvemesh` (this crate's) and `xtask` (run as `cargo
//! xtask`, which adds its development tasks to the same commands). It installs the interrupt
//! handler, parses the flags under the name the user typed (so help, usage lines and
//! `--version` name the right command), runs the command and turns the outcome into the exit
//! status and the line on stderr ([`crate::exit`]): 0 success, 1 bad input or a usage error,
//! 2 a mesh was written but failed validation, 130 interrupted.

use std::process::ExitCode;

use clap::{CommandFactory, FromArgMatches};

use crate::exit;
use crate::outcome::Finished;

/// The name the installed binary prints.
pub const CURVEMESH: &str = "curvemesh";

/// Parses the command line as the command `name` with the flags of `C`, runs it with `run`
/// and returns the exit status.
pub fn main<C: CommandFactory + FromArgMatches>(
    name: &'static str,
    run: impl FnOnce(C) -> anyhow::Result<Finished>,
) -> ExitCode {
    exit::install_interrupt_handler();
    let end = match parse::<C, _, _>(name, std::env::args_os()) {
        Ok(cli) => exit::of_run(&run(cli)),
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
pub fn parse<C, I, T>(name: &'static str, args: I) -> Result<C, clap::Error>
where
    C: CommandFactory + FromArgMatches,
    I: IntoIterator<Item = T>,
    T: Into<std::ffi::OsString> + Clone,
{
    let mut command = C::command().name(name).bin_name(name);
    let matches = command.try_get_matches_from_mut(args)?;
    C::from_arg_matches(&matches).map_err(|e| e.format(&mut command))
}
