//! The `cargo xtask` binary: installs the interrupt handler, parses the flags, runs the
//! command (all in the library, see `lib.rs`) and turns the outcome into the exit status and
//! the line on stderr ([`xtask::exit`]): 0 success, 1 bad input or a usage error, 2 a mesh was
//! written but failed validation, 130 interrupted.

use std::process::ExitCode;

use clap::Parser;
use xtask::{cli::Cli, exit};

fn main() -> ExitCode {
    exit::install_interrupt_handler();
    let end = match Cli::try_parse() {
        Ok(cli) => exit::of_run(&xtask::run(cli)),
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
