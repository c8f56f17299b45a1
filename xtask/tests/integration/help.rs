//! The `xtask` binary (`cargo xtask`): help that names the command typed and lists the
//! `curvemesh` commands beside the development tasks; the workspace lists its members one by
//! one, so an `out/` folder made in `crates/` cannot break it.

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

const XTASK: &str = env!("CARGO_BIN_EXE_xtask");

#[test]
fn help_names_the_command_typed_and_every_subcommand() {
    let here = std::env::temp_dir();
    for (bin, name, other) in [(XTASK, "cargo xtask", "curvemesh ")] {
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
