//! Every example of the README and `docs/user-guide.md` runs as written from a fresh clone:
//! each ```sh block's commands run in order in a scratch copy of `fixtures/` (so `out/` is
//! made there), `cargo xtask` being this build's binary (and `curvemesh CMD`, the same
//! command); each ```toml block
//! is meshed as a case file placed in `fixtures/cases/` (a motion file, first line
//! `# fixtures/motions/NAME.toml`, is that fixture word for word), and the README's case file is
//! `fixtures/cases/example.toml` word for word. Only the commands in [`SKIPPED`] are not run,
//! each for the reason given. The figures the docs show are exactly those `figures` makes.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Commands (by their start) the docs show but this test does not run, and why.
const SKIPPED: &[(&str, &str)] = &[
    ("bash tests/run.sh", "the test command itself"),
    (
        "bash tests/python/",
        "installs the checkers (tests/python/test_install.sh tests it)",
    ),
    ("bash fuzz/run.sh", "needs nightly Rust and cargo-fuzz"),
    (
        "RANDOM_GEOMETRY_CASES=",
        "a long test run (the normal test run does a short one)",
    ),
    ("cargo install", "installs into the user's ~/.cargo/bin"),
    (
        "python3 -m venv",
        "builds the Python package into a virtual environment; python/test.sh tests it",
    ),
    (
        "cargo xtask figures",
        "rewrites docs/figures; run by figures_match_the_docs",
    ),
];

const DOCS: &[&str] = &["README.md", "docs/user-guide.md"];

fn root() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .unwrap()
        .to_path_buf()
}

/// The blocks fenced as ```LANG in `text`, each as its lines.
fn blocks(text: &str, lang: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    let mut current: Option<Vec<String>> = None;
    for line in text.lines() {
        let fence = line.trim_start().strip_prefix("```");
        match (&mut current, fence) {
            (None, Some(info)) if info.split_whitespace().next() == Some(lang) => {
                current = Some(Vec::new())
            }
            (Some(_), Some("")) => out.push(current.take().unwrap()),
            (Some(lines), _) => lines.push(line.to_string()),
            _ => {}
        }
    }
    out
}

/// The commands of a ```sh block: continuation lines joined, blank and comment lines dropped.
fn commands(block: &[String]) -> Vec<String> {
    let mut out = Vec::new();
    let mut pending = String::new();
    for line in block {
        if let Some(head) = line.trim_end().strip_suffix('\\') {
            pending.push_str(head);
            continue;
        }
        pending.push_str(line);
        let command = std::mem::take(&mut pending);
        let trimmed = command.trim();
        if !trimmed.is_empty() && !trimmed.starts_with('#') {
            out.push(trimmed.to_string());
        }
    }
    out
}

fn copy_dir(from: &Path, to: &Path) {
    std::fs::create_dir_all(to).unwrap();
    for entry in std::fs::read_dir(from).unwrap().flatten() {
        let target = to.join(entry.file_name());
        if entry.path().is_dir() {
            copy_dir(&entry.path(), &target);
        } else {
            std::fs::copy(entry.path(), target).unwrap();
        }
    }
}

/// A fresh folder holding what a clone has that the examples read, plus the ```toml blocks of
/// `doc` whose first line names where the reader saves them (`# fixtures/cases/NAME.toml`).
fn scratch_clone(doc: &str) -> tempfile::TempDir {
    let dir = tempfile::tempdir().unwrap();
    copy_dir(&root().join("fixtures"), &dir.path().join("fixtures"));
    for block in blocks(doc, "toml") {
        if let Some(path) = block.first().and_then(|l| l.strip_prefix("# "))
            && path.ends_with(".toml")
            && !path.contains(' ')
        {
            std::fs::write(dir.path().join(path), block.join("\n")).unwrap();
        }
    }
    dir
}

fn run_in(dir: &Path, command: &str) -> std::process::Output {
    Command::new("bash")
        .args(["-c", &format!("set -eo pipefail; {command}")])
        .current_dir(dir)
        .env("XTASK", env!("CARGO_BIN_EXE_xtask"))
        // `curvemesh CMD` is `cargo xtask CMD` (the same commands, forwarded); the
        // `curvemesh` binary itself is curvemesh-cli's, tested there
        .env("CURVEMESH", env!("CARGO_BIN_EXE_xtask"))
        .output()
        .unwrap()
}

/// `command` with the tool's names replaced by this build's binaries, or `None` when skipped.
fn runnable(command: &str, used: &mut Vec<&'static str>) -> Option<String> {
    if let Some((start, _)) = SKIPPED.iter().find(|(s, _)| command.starts_with(s)) {
        used.push(start);
        return None;
    }
    let shell = if let Some(rest) = command.strip_prefix("cargo xtask ") {
        format!("\"$XTASK\" {rest}")
    } else if let Some(rest) = command.strip_prefix("curvemesh ") {
        format!("\"$CURVEMESH\" {rest}")
    } else {
        panic!("`{command}`: not a command of the tool; run it here or add it to SKIPPED");
    };
    Some(shell)
}

#[test]
fn every_sh_example_runs_as_written() {
    let mut used = Vec::new();
    let mut ran = 0;
    for doc in DOCS {
        let text = std::fs::read_to_string(root().join(doc)).unwrap();
        let dir = scratch_clone(&text);
        for command in blocks(&text, "sh").iter().flat_map(|b| commands(b)) {
            let Some(shell) = runnable(&command, &mut used) else {
                continue;
            };
            let out = run_in(dir.path(), &shell);
            assert!(
                out.status.success(),
                "{doc}: `{command}` failed ({}):\n{}",
                out.status,
                String::from_utf8_lossy(&out.stderr)
            );
            ran += 1;
        }
    }
    assert!(ran >= 15, "only {ran} commands ran");
    for (start, why) in SKIPPED {
        assert!(
            used.contains(start),
            "SKIPPED `{start}` ({why}) matches no command of the docs"
        );
    }
}

#[test]
fn every_toml_example_is_a_case_that_meshes() {
    let readme = std::fs::read_to_string(root().join("README.md")).unwrap();
    let example = std::fs::read_to_string(root().join("fixtures/cases/example.toml")).unwrap();
    let readme_toml: Vec<Vec<String>> = blocks(&readme, "toml")
        .into_iter()
        .filter(|b| motion_file(b).is_none())
        .collect();
    assert_eq!(readme_toml.len(), 1, "the README shows one case file");
    assert_eq!(
        readme_toml[0].join("\n").trim(),
        example.trim(),
        "the README's case file is fixtures/cases/example.toml word for word"
    );
    for doc in DOCS {
        let text = std::fs::read_to_string(root().join(doc)).unwrap();
        let dir = scratch_clone(&text);
        for (i, block) in blocks(&text, "toml").iter().enumerate() {
            if let Some(path) = motion_file(block) {
                let file = std::fs::read_to_string(root().join(path)).unwrap();
                assert_eq!(
                    block.join("\n").trim(),
                    file.trim(),
                    "{doc}: the motion file shown is {path} word for word"
                );
                continue;
            }
            let case = dir.path().join(format!("fixtures/cases/docs-{i}.toml"));
            std::fs::write(&case, block.join("\n")).unwrap();
            let out = run_in(
                dir.path(),
                &format!(
                    "\"$XTASK\" mesh {} --order 1 --quiet --out m.msh",
                    case.display()
                ),
            );
            assert!(
                out.status.success(),
                "{doc}: toml block {} does not mesh:\n{}",
                i + 1,
                String::from_utf8_lossy(&out.stderr)
            );
        }
    }
}

/// The fixture a ```toml block shows when it is a motion file (`cargo xtask move --motion`):
/// its first line names it, `# fixtures/motions/NAME.toml`.
fn motion_file(block: &[String]) -> Option<&str> {
    block
        .first()
        .and_then(|l| l.strip_prefix("# "))
        .filter(|p| p.starts_with("fixtures/motions/") && p.ends_with(".toml"))
}

/// The `docs/figures/*.png` names `text` shows.
fn figures_shown(text: &str) -> Vec<String> {
    text.split("figures/")
        .skip(1)
        .filter_map(|rest| rest.split(".png").next())
        .filter(|name| !name.contains(char::is_whitespace) && !name.is_empty())
        .map(|name| format!("{name}.png"))
        .collect()
}

/// The docs beside the README and the guide whose figures `figures` may make (some of
/// theirs come from scripts of their own, e.g. `tests/python/p3_wall_figure.py`).
const FIGURE_DOCS: &[&str] = &["docs/3d.md", "docs/movement.md"];

#[test]
fn figures_match_the_docs() {
    let shown_in = |docs: &[&str]| -> Vec<String> {
        let mut shown: Vec<String> = docs
            .iter()
            .flat_map(|doc| figures_shown(&std::fs::read_to_string(root().join(doc)).unwrap()))
            .collect();
        shown.sort();
        shown.dedup();
        shown
    };
    let guides = shown_in(DOCS);
    let all = shown_in(&[DOCS, FIGURE_DOCS].concat());
    let mut made = xtask::figures_cmd::names();
    made.sort();
    for name in &guides {
        assert!(
            made.contains(name),
            "{name}, shown by the README or the guide, is not made by `figures`"
        );
    }
    for name in &made {
        assert!(
            all.contains(name),
            "`figures` makes {name}, which no doc shows"
        );
    }
    for name in &made {
        assert!(
            root().join("docs/figures").join(name).is_file(),
            "docs/figures/{name} is not committed: run cargo xtask figures"
        );
    }
    // `figures` itself, from a scratch copy: every figure made, 900 px wide
    let dir = scratch_clone("");
    let out = run_in(dir.path(), "\"$XTASK\" figures --dir pictures --quiet");
    assert!(
        out.status.success(),
        "figures failed:\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for name in &made {
        let png = std::fs::read(dir.path().join("pictures").join(name)).unwrap();
        let width = u32::from_be_bytes(png[16..20].try_into().unwrap());
        assert_eq!(width, 900, "{name}");
    }
}
