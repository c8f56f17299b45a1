//! The real `xtask` binary, run as a user runs it: exit statuses and the one line on stderr,
//! interruptions (SIGTERM removes every temporary file and exits 130; SIGKILL leaves them, and
//! the next run in the folder removes them), and default output names made from hostile case
//! names. Only this crate's tests can start its binary (`CARGO_BIN_EXE_xtask`); the
//! in-process tests of the same behaviour are in `tests/tests/`.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

fn xtask() -> Command {
    Command::new(env!("CARGO_BIN_EXE_xtask"))
}

fn finish(child: Child) -> Output {
    child.wait_with_output().unwrap()
}

fn stderr_lines(out: &Output) -> Vec<String> {
    String::from_utf8_lossy(&out.stderr)
        .lines()
        .map(str::to_string)
        .collect()
}

fn names(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

fn temporaries(dir: &Path) -> Vec<String> {
    names(dir)
        .into_iter()
        .filter(|n| n.contains(".tmp-"))
        .collect()
}

/// Waits until `ready` holds for the folder (at most a minute).
fn wait_for(dir: &Path, ready: impl Fn(&Path) -> bool) {
    let start = Instant::now();
    while !ready(dir) {
        assert!(start.elapsed() < Duration::from_secs(60), "timed out");
        std::thread::sleep(Duration::from_millis(5));
    }
}

fn signal(child: &Child, sig: &str) {
    let ok = Command::new("kill")
        .args([sig, &child.id().to_string()])
        .status()
        .unwrap()
        .success();
    assert!(ok, "kill {sig}");
}

/// `mesh naca0012` at P2 writing four outputs into `dir`, which holds older versions.
fn start_run(dir: &Path) -> (Child, Vec<PathBuf>) {
    let outs: Vec<PathBuf> = ["m.msh", "m.vtu", "m.png", "m.json"]
        .iter()
        .map(|n| dir.join(n))
        .collect();
    for o in &outs {
        std::fs::write(o, b"old").unwrap();
    }
    let s = |i: usize| outs[i].to_str().unwrap().to_string();
    let child = xtask()
        .args(["mesh", "naca0012", "--quiet", "--order", "2"])
        .args([
            "--out",
            &s(0),
            "--out",
            &s(1),
            "--png",
            &s(2),
            "--report",
            &s(3),
        ])
        .args(["--width", "400"])
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    (child, outs)
}

/// The outputs are all old or all new, and no temporary file is left.
fn all_old_or_all_new(dir: &Path, outs: &[PathBuf]) -> bool {
    assert!(temporaries(dir).is_empty(), "{:?}", names(dir));
    let old: Vec<bool> = outs
        .iter()
        .map(|o| std::fs::read(o).unwrap() == b"old")
        .collect();
    assert!(old.iter().all(|&o| o) || old.iter().all(|&o| !o), "{old:?}");
    old[0]
}

#[test]
fn sigterm_while_meshing_leaves_the_old_files_and_no_temporary() {
    let dir = tempfile::tempdir().unwrap();
    let (child, outs) = start_run(dir.path());
    // the temporary files of every output exist from the start of the run
    wait_for(dir.path(), |d| temporaries(d).len() == 4);
    signal(&child, "-TERM");
    let out = finish(child);
    assert_eq!(out.status.code(), Some(130), "{:?}", stderr_lines(&out));
    assert_eq!(
        stderr_lines(&out),
        vec!["error: interrupted: unfinished output files removed"]
    );
    assert!(
        all_old_or_all_new(dir.path(), &outs),
        "interrupted: old files"
    );
}

#[test]
fn sigint_while_writing_leaves_all_old_or_all_new() {
    let dir = tempfile::tempdir().unwrap();
    let (child, outs) = start_run(dir.path());
    // content reaches a temporary file (the meshing is over, the writing has begun), or the
    // run is already done
    wait_for(dir.path(), |d| {
        temporaries(d)
            .iter()
            .any(|t| std::fs::metadata(d.join(t)).is_ok_and(|m| m.len() > 0))
            || std::fs::read(d.join("m.json")).is_ok_and(|b| b != b"old")
    });
    signal(&child, "-INT");
    let out = finish(child);
    let code = out.status.code();
    assert!(code == Some(130) || code == Some(0), "{code:?}");
    let old = all_old_or_all_new(dir.path(), &outs);
    if code == Some(0) {
        assert!(!old, "a finished run wrote the new set");
    }
}

#[test]
fn sigkill_leaves_temporaries_that_the_next_run_removes() {
    let dir = tempfile::tempdir().unwrap();
    let (child, outs) = start_run(dir.path());
    wait_for(dir.path(), |d| temporaries(d).len() == 4);
    signal(&child, "-KILL");
    let out = finish(child);
    assert_eq!(out.status.code(), None, "killed by a signal");
    assert_eq!(temporaries(dir.path()).len(), 4, "SIGKILL cannot clean up");
    assert!(outs.iter().all(|o| std::fs::read(o).unwrap() == b"old"));
    // a later run writing into the same folder removes them (their process is gone)
    let msh = dir.path().join("next.msh");
    let out = xtask()
        .args(["mesh", "lshape", "--quiet", "--order", "1", "--out"])
        .arg(&msh)
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{:?}", stderr_lines(&out));
    assert!(
        temporaries(dir.path()).is_empty(),
        "{:?}",
        names(dir.path())
    );
}

#[test]
fn usage_errors_exit_1_with_one_line_and_help_exits_0() {
    for args in [
        &["mesh", "--order", "4"][..],
        &["mesh", "--frobnicate"],
        &[],
    ] {
        let out = xtask().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(1), "{args:?}");
        let lines = stderr_lines(&out);
        assert_eq!(lines.len(), 1, "{lines:?}");
        assert!(lines[0].starts_with("error: "), "{lines:?}");
    }
    for args in [["--help"], ["--version"]] {
        let out = xtask().args(args).output().unwrap();
        assert_eq!(out.status.code(), Some(0), "{args:?}");
        assert!(!out.stdout.is_empty() && out.stderr.is_empty());
    }
}

#[test]
fn a_case_name_cannot_escape_out() {
    let dir = tempfile::tempdir().unwrap();
    let work = dir.path().join("work");
    std::fs::create_dir(&work).unwrap();
    let case = "name = \"../escape\\nx\"\n[[loop]]\nrole = \"wall\"\n\
                points = [[0,0],[1,0],[1,1],[0,1]]\n[[loop]]\nrole = \"farfield\"\n\
                circle = { center = [0.5, 0.5], radius = 20.0 }\n";
    std::fs::write(work.join("case.toml"), case).unwrap();
    let out = xtask()
        .current_dir(&work)
        .args(["mesh", "case.toml", "--quiet", "--order", "1"])
        .output()
        .unwrap();
    assert_eq!(out.status.code(), Some(0), "{:?}", stderr_lines(&out));
    assert_eq!(names(dir.path()), vec!["work"], "nothing outside work/");
    assert_eq!(names(&work), vec!["case.toml", "out"]);
    // (at an order other than the case's, the default name carries it)
    assert_eq!(
        names(&work.join("out")),
        vec!["_escape_x-p1.json", "_escape_x-p1.msh"]
    );
}
