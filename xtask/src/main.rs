//! The `cargo xtask` binary: parses the flags, runs the command (all in the library, see
//! `lib.rs`) and turns the outcome into the exit status: 0 success, 1 bad input (one line on
//! stderr), 2 a mesh was written but failed validation.

use std::process::ExitCode;

use clap::Parser;
use xtask::{Outcome, cli::Cli, execute};

fn main() -> ExitCode {
    match execute(Cli::parse()) {
        Ok(Outcome::Valid) => ExitCode::SUCCESS,
        Ok(Outcome::Invalid) => ExitCode::from(2),
        Err(e) => {
            // `{:#}` joins the context chain on one line: "what: why: root cause".
            eprintln!("error: {e:#}");
            ExitCode::from(1)
        }
    }
}
