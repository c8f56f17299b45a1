//! How a run ends, as the binary shows it: the exit status and the one line on stderr. The
//! binary (`main.rs`) only calls these, so that the tests check the very mapping it uses.
//!
//! - 0: success; `--help` and `--version` print their text to stdout and end here too.
//! - 1: bad input, usage errors included (clap's several-line messages are folded into one
//!   line), and interruptions (130 by Ctrl-C or SIGTERM, see [`install_interrupt_handler`]).
//! - 2: a mesh was written but failed validation; the line names the first problem and where
//!   the report is.
//!
//! Every message is made one line here, whatever its source: line breaks and other control
//! characters are escaped and a line longer than [`MAX_LINE`] characters is cut.

use crate::outcome::{Finished, Outcome};

/// The longest message printed, in characters (a 1 MB line of input is not echoed whole).
pub const MAX_LINE: usize = 400;

/// Exit status of a run cut short by Ctrl-C or SIGTERM (128 + SIGINT, the shell convention).
pub const INTERRUPTED: u8 = 130;

/// What the binary does at the end.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Exit {
    /// The exit status.
    pub code: u8,
    /// The line printed on stderr, `error: ...`, if any.
    pub stderr: Option<String>,
}

/// The exit of a command-line that clap refused: `None` when clap only wants to print help or
/// the version (print it with `Error::print` and exit 0), else status 1 and one line.
pub fn of_usage_error(e: &clap::Error) -> Option<Exit> {
    use clap::error::ErrorKind;
    match e.kind() {
        ErrorKind::DisplayHelp | ErrorKind::DisplayVersion => return None,
        ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand | ErrorKind::MissingSubcommand => {
            return Some(bad_input(
                "no command given: use `mesh`, `move`, `quality` or `bench` (see --help)",
            ));
        }
        _ => {}
    }
    // clap renders "error: WHAT\n  detail\n\n  tip: ...\n\nUsage: ...\n\nFor more ...": keep the
    // first paragraph, joined into one line.
    let text = e.render().to_string();
    let first = text.split("\n\n").next().unwrap_or_default();
    let joined: Vec<&str> = first
        .lines()
        .map(str::trim)
        .filter(|l| !l.is_empty())
        .collect();
    let what = joined.join(" ");
    let what = what.strip_prefix("error: ").unwrap_or(&what);
    Some(bad_input(&format!("{what} (see --help)")))
}

/// The exit of a command that ran: success, bad input (status 1, the error's context chain
/// on one line), or a mesh that failed validation (status 2 and its line).
pub fn of_run(result: &anyhow::Result<Finished>) -> Exit {
    match result {
        Ok(Finished {
            outcome: Outcome::Valid,
            ..
        }) => Exit {
            code: 0,
            stderr: None,
        },
        Ok(Finished {
            outcome: Outcome::Invalid,
            problem,
        }) => Exit {
            code: 2,
            stderr: Some(line(problem.as_deref().unwrap_or(
                "the mesh was written but failed validation: see the report",
            ))),
        },
        // `{:#}` joins the context chain: "what: why: root cause".
        Err(e) => bad_input(&format!("{e:#}")),
    }
}

/// Status 1 with `message` as its line.
fn bad_input(message: &str) -> Exit {
    Exit {
        code: 1,
        stderr: Some(line(message)),
    }
}

/// `error: MESSAGE` on one line: control characters escaped, cut after [`MAX_LINE`] characters.
pub fn line(message: &str) -> String {
    let mut out = String::from("error: ");
    let total = message.chars().count();
    for (shown, c) in message.chars().enumerate() {
        if shown == MAX_LINE {
            out.push_str(&format!("… ({} more characters)", total - shown));
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out
}

/// Installs the handler of Ctrl-C, SIGTERM and SIGHUP: every temporary output file not yet
/// renamed into place is removed (see `mesh_io::atomic::on_interrupt`), one line is printed
/// and the process exits with status [`INTERRUPTED`]. Outputs are then as they were before
/// the run, or (when the signal came during the final renames) the complete new set.
pub fn install_interrupt_handler() {
    // Failing to install (a handler already set) leaves the default behaviour: killed, with
    // stale temporaries that the next run in the same folder removes.
    let _ = ctrlc::set_handler(|| {
        mesh_io::atomic::on_interrupt(|_removed| {
            eprintln!("{}", line("interrupted: unfinished output files removed"));
            std::process::exit(i32::from(INTERRUPTED))
        })
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_line_is_one_line_and_bounded() {
        assert_eq!(line("a\nb\rc"), "error: a\\nb\\rc");
        let long = "x".repeat(1_000_000);
        let l = line(&long);
        assert!(l.chars().count() < MAX_LINE + 60, "{}", l.len());
        assert!(l.ends_with("(999600 more characters)"), "{l}");
    }
}
