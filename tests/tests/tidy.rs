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
