//! The end-to-end test kit: the commands run in-process exactly as `main` parses them, and
//! the small checks the test files share (one place for "run the tool", "the outputs left in
//! a folder", "a report names this problem"). The tests themselves live in `tests/`.

use std::path::Path;

use clap::Parser;
pub use curvemesh_cli::Outcome;
use curvemesh_cli::{cli::Cli, execute};
use serde_json::Value;

/// The flags `cargo xtask ARGS…` parse to; panics when they do not (a test's fault).
pub fn cli(args: &[&str]) -> Cli {
    let mut all = vec!["cargo xtask"];
    all.extend(args);
    Cli::try_parse_from(&all).expect("flags parse")
}

/// Runs `cargo xtask ARGS…` in-process.
pub fn xtask(args: &[&str]) -> anyhow::Result<Outcome> {
    execute(cli(args))
}

/// `cargo xtask mesh CASE --quiet --order ORDER REST…`, the usual run of a test.
pub fn mesh(case: &str, order: &str, rest: &[&str]) -> anyhow::Result<Outcome> {
    xtask(&[&["mesh", case, "--quiet", "--order", order], rest].concat())
}

/// `cargo xtask COMMAND CASE --quiet --out DIR/NAME.msh --report DIR/NAME.json REST…`: a run
/// whose mesh and report go to a test folder.
pub fn run_into(
    dir: &Path,
    name: &str,
    command: &str,
    case: &str,
    rest: &[&str],
) -> anyhow::Result<Outcome> {
    let (out, report) = (
        dir.join(format!("{name}.msh")),
        dir.join(format!("{name}.json")),
    );
    let base = [
        command,
        case,
        "--quiet",
        "--out",
        s(&out),
        "--report",
        s(&report),
    ];
    xtask(&[&base[..], rest].concat())
}

/// [`xtask`] that must succeed; the panic names the arguments and the error.
pub fn xtask_ok(args: &[&str]) -> Outcome {
    xtask(args).unwrap_or_else(|e| panic!("{args:?}: {e:#}"))
}

/// `p` as a `&str` (test paths are UTF-8).
pub fn s(p: &Path) -> &str {
    p.to_str().expect("UTF-8 test path")
}

/// A JSON file read back (a report).
pub fn read_json(path: &Path) -> Value {
    serde_json::from_slice(&std::fs::read(path).expect("report written")).expect("valid JSON")
}

/// Every entry below `dir`, relative, sorted (folders end in `/`).
pub fn tree(dir: &Path) -> Vec<String> {
    fn walk(root: &Path, dir: &Path, out: &mut Vec<String>) {
        for e in std::fs::read_dir(dir).unwrap().flatten() {
            let rel = e.path().strip_prefix(root).unwrap().display().to_string();
            if e.file_type().unwrap().is_dir() {
                out.push(format!("{rel}/"));
                walk(root, &e.path(), out);
            } else {
                out.push(rel);
            }
        }
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out);
    out.sort();
    out
}

/// Asserts that one of the report's `problems` contains `needle`.
pub fn assert_problem(report: &Value, needle: &str) {
    let problems = report["problems"].as_array().expect("a problems list");
    assert!(
        problems
            .iter()
            .any(|p| p.as_str().is_some_and(|p| p.contains(needle))),
        "no problem mentions {needle:?}: {problems:?}"
    );
}

/// Asserts that `msg` is one line mentioning every one of `words`.
pub fn assert_one_line_naming(msg: &str, words: &[&str]) {
    assert!(!msg.contains('\n'), "one line: {msg:?}");
    for w in words {
        assert!(msg.contains(w), "{msg:?} should mention {w:?}");
    }
}
