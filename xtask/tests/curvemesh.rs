//! The installable `curvemesh` binary (`cargo install --path xtask`) and where runs write:
//! `--version`, help that names the command the user typed (`curvemesh`, or `cargo xtask` for
//! the `xtask` binary) and lists only the subcommands that exist; default outputs go to `out/`
//! below the folder the user stands in; the workspace lists its members one by one, so an
//! `out/` folder made in `crates/` cannot break it.

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
const XTASK: &str = env!("CARGO_BIN_EXE_xtask");

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
fn help_names_the_command_typed_and_only_existing_subcommands() {
    let here = std::env::temp_dir();
    for (bin, name, other) in [
        (CURVEMESH, "curvemesh", "cargo xtask"),
        (XTASK, "cargo xtask", "curvemesh"),
    ] {
        let help = text(&run(bin, &["--help"], &here).stdout);
        assert!(help.contains(&format!("Usage: {name} <COMMAND>")), "{help}");
        assert!(!help.contains(other), "{help}");
        for sub in ["mesh", "move", "quality", "bench", "figures"] {
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
    assert!(sub.join("out/naca0012.msh").is_file());
    assert!(sub.join("out/naca0012.json").is_file());
    assert!(!dir.path().join("out").exists());
}

#[test]
fn workspace_members_are_listed_one_by_one() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).parent().unwrap();
    let manifest = std::fs::read_to_string(root.join("Cargo.toml")).unwrap();
    let table: toml::Table = manifest.parse().unwrap();
    let members: Vec<&str> = table["workspace"]["members"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| m.as_str().unwrap())
        .collect();
    for m in &members {
        assert!(!m.contains(['*', '?', '[']), "member `{m}` is a glob");
        assert!(root.join(m).join("Cargo.toml").is_file(), "member `{m}`");
    }
    // every crate folder is a member (a new crate must be added by hand)
    for entry in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
        if entry.path().join("Cargo.toml").is_file() {
            let name = format!("crates/{}", entry.file_name().to_string_lossy());
            assert!(members.contains(&name.as_str()), "{name} is not a member");
        }
    }
}
