//! The installed `curvemesh` binary: `--version`, help that names the command and lists its
//! subcommands (the development tasks are `cargo xtask`'s only), usage errors on one line,
//! and default outputs in `out/` below the folder the user stands in.

use std::path::Path;
use std::process::{Command, Output};

fn run(bin: &str, args: &[&str], dir: &Path) -> Output {
    Command::new(bin)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

const CURVEMESH: &str = env!("CARGO_BIN_EXE_curvemesh");

#[test]
fn version_names_the_binary() {
    let here = std::env::temp_dir();
    let out = run(CURVEMESH, &["--version"], &here);
    assert!(out.status.success());
    assert_eq!(
        text(&out.stdout).trim(),
        format!("curvemesh {}", env!("CARGO_PKG_VERSION"))
    );
}

#[test]
fn help_names_the_command_and_lists_its_subcommands() {
    let here = std::env::temp_dir();
    for (bin, name, other) in [(CURVEMESH, "curvemesh", "cargo xtask")] {
        let help = text(&run(bin, &["--help"], &here).stdout);
        assert!(help.contains(&format!("Usage: {name} <COMMAND>")), "{help}");
        assert!(!help.contains(other), "{help}");
        for sub in ["mesh", "move", "quality"] {
            assert!(
                help.contains(&format!("\n  {sub} ")),
                "{sub} missing:\n{help}"
            );
        }
        let sub_help = text(&run(bin, &["mesh", "--help"], &here).stdout);
        assert!(
            sub_help.contains(&format!("Usage: {name} mesh ")),
            "{sub_help}"
        );
        // usage errors name the command too, on one line, exit 1
        let bad = run(bin, &["mesh", "--no-such-flag"], &here);
        assert_eq!(bad.status.code(), Some(1));
        assert_eq!(
            text(&bad.stderr).lines().count(),
            1,
            "{}",
            text(&bad.stderr)
        );
    }
}

#[test]
fn development_tasks_are_not_curvemesh_commands() {
    let here = std::env::temp_dir();
    let help = text(&run(CURVEMESH, &["--help"], &here).stdout);
    for task in ["bench", "figures"] {
        assert!(
            !help.contains(&format!("\n  {task} ")),
            "{task} listed:\n{help}"
        );
    }
}

#[test]
fn default_outputs_go_below_the_folder_the_user_stands_in() {
    let dir = tempfile::tempdir().unwrap();
    let sub = dir.path().join("crates");
    std::fs::create_dir(&sub).unwrap();
    let out = run(
        CURVEMESH,
        &["mesh", "naca0012", "--order", "1", "--quiet"],
        &sub,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    // at an order other than the case's (3), the name says so: no P3 mesh is replaced
    assert!(sub.join("out/naca0012-p1.msh").is_file());
    assert!(sub.join("out/naca0012-p1.json").is_file());
    assert!(!dir.path().join("out").exists());
}
