//! House rules checked on the whole workspace: every source file of every crate opens with a
//! `//!` paragraph saying what it owns, and no stub or ignored test is left behind.

use std::path::{Path, PathBuf};

fn workspace() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("workspace root")
        .to_path_buf()
}

/// Every `.rs` file below `dir`.
fn rust_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() {
            rust_files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

fn sources() -> Vec<PathBuf> {
    let root = workspace();
    let mut files = Vec::new();
    rust_files(&root.join("xtask/src"), &mut files);
    for krate in std::fs::read_dir(root.join("crates"))
        .expect("crates folder")
        .flatten()
    {
        rust_files(&krate.path().join("src"), &mut files);
    }
    files
}

#[test]
fn every_module_opens_with_a_doc_paragraph() {
    let files = sources();
    assert!(files.len() > 40, "only {} source files found", files.len());
    let missing: Vec<_> = files
        .iter()
        .filter(|p| {
            !std::fs::read_to_string(p)
                .unwrap_or_default()
                .trim_start()
                .starts_with("//!")
        })
        .collect();
    assert!(
        missing.is_empty(),
        "files without a //! paragraph: {missing:?}"
    );
}

#[test]
fn no_stubs_or_ignored_tests() {
    let root = workspace();
    let mut files = sources();
    rust_files(&root.join("tests/tests"), &mut files);
    for krate in std::fs::read_dir(root.join("crates"))
        .expect("crates folder")
        .flatten()
    {
        rust_files(&krate.path().join("tests"), &mut files);
    }
    let banned = [
        concat!("todo", "!("),
        concat!("unimplemented", "!("),
        concat!("#[", "ignore"),
    ];
    for path in files {
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        for word in banned {
            assert!(!text.contains(word), "{} contains {word}", path.display());
        }
    }
}

/// The crates named in a manifest's `[dependencies]` table (not dev- or build-dependencies).
fn dependencies(krate: &str) -> Vec<String> {
    let path = workspace().join("crates").join(krate).join("Cargo.toml");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{path:?}: {e}"));
    let mut out = Vec::new();
    let mut inside = false;
    for line in text.lines().map(str::trim) {
        if line.starts_with('[') {
            inside = line == "[dependencies]";
        } else if inside && !line.is_empty() && !line.starts_with('#') {
            let name = line.split(['=', '.', ' ']).next().unwrap_or_default();
            out.push(name.to_string());
        }
    }
    out
}

/// The layering of the workspace (docs/architecture.md, "Invariants"): the data model and the
/// predicates know no algorithm; movement depends on no mesher; only `mesh-io` (and `xtask`)
/// touch files; only `xtask` serialises the report (it alone uses `serde_json`).
#[test]
fn crates_depend_only_on_what_the_architecture_allows() {
    let ours = |deps: Vec<String>| -> Vec<String> {
        let crates = workspace().join("crates");
        deps.into_iter()
            .filter(|d| crates.join(d).is_dir())
            .collect()
    };
    assert_eq!(ours(dependencies("geom-predicates")), Vec::<String>::new());
    assert_eq!(ours(dependencies("mesh-model")), ["geom-predicates"]);
    let meshers = ["boundary1d", "afsf2d", "afsf3d", "vector-adding"];
    for dep in ours(dependencies("mesh-move")) {
        assert!(
            !meshers.contains(&dep.as_str()),
            "mesh-move depends on {dep}"
        );
    }
    if workspace().join("crates/topo-cut").is_dir() {
        for dep in ours(dependencies("topo-cut")) {
            assert!(
                ["mesh-model", "geom-predicates"].contains(&dep.as_str()),
                "topo-cut depends on {dep}"
            );
        }
    }
    for krate in std::fs::read_dir(workspace().join("crates"))
        .unwrap()
        .flatten()
    {
        let name = krate.file_name().to_string_lossy().to_string();
        if !krate.path().join("Cargo.toml").is_file() {
            continue;
        }
        let deps = dependencies(&name);
        assert!(
            !deps.iter().any(|d| d == "serde_json" || d == "anyhow"),
            "{name}: only xtask serialises the report and uses anyhow"
        );
        if name != "mesh-io" {
            assert!(
                !deps.iter().any(|d| d == "bincode" || d == "tempfile"),
                "{name}: only mesh-io writes files"
            );
        }
    }
}
