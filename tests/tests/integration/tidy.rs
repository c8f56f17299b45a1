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
/// predicates know no algorithm; movement depends on no mesher; only `mesh-io` writes files;
/// only the `curvemesh` library serialises the report (`serde_json`); only the command-line
/// crate uses `anyhow`, and the library has no command-line dependency.
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
            name == "curvemesh" || !deps.iter().any(|d| d == "serde_json"),
            "{name}: only the curvemesh library serialises the report"
        );
        assert!(
            name == "curvemesh-cli" || !deps.iter().any(|d| d == "anyhow" || d == "curvemesh-cli"),
            "{name}: only the command-line crate uses anyhow, and no library depends on it"
        );
        if name != "mesh-io" {
            assert!(
                !deps.iter().any(|d| d == "bincode" || d == "tempfile"),
                "{name}: only mesh-io writes files"
            );
        }
    }
}

/// The library of the whole pipeline is a library: no flag parser, progress bar, `anyhow` or
/// global allocator (those are the command's, `curvemesh-cli`).
#[test]
fn the_library_has_no_command_line_dependency() {
    let deps = dependencies("curvemesh");
    for banned in [
        "clap",
        "indicatif",
        "anyhow",
        "tikv-jemallocator",
        "ctrlc",
        "nix",
    ] {
        assert!(
            !deps.iter().any(|d| d == banned),
            "curvemesh depends on {banned}"
        );
    }
}

/// `docs/architecture.md` keeps the map of crates: every crate folder is named in it (and in
/// the README's crate table).
#[test]
fn every_crate_is_named_in_the_architecture_and_the_readme() {
    let root = workspace();
    for doc in ["docs/architecture.md", "README.md"] {
        let text = std::fs::read_to_string(root.join(doc)).unwrap();
        for krate in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
            if !krate.path().join("Cargo.toml").is_file() {
                continue;
            }
            let name = krate.file_name().to_string_lossy().to_string();
            assert!(
                text.contains(&format!("`{name}`")),
                "{doc} does not name `{name}`"
            );
        }
    }
}

/// The modules of one crate's `src/` and the modules each imports (`crate::a::b` paths, the
/// names of `use crate::{...}` lists, `super::x` in nested modules; an item of the crate root
/// as `ROOT`), test modules left out.
fn module_graph(src: &Path) -> std::collections::BTreeMap<String, Vec<String>> {
    let mut files = Vec::new();
    rust_files(src, &mut files);
    let mut texts = std::collections::BTreeMap::new();
    for path in &files {
        let rel = path.strip_prefix(src).unwrap().with_extension("");
        let mut parts: Vec<String> = rel.iter().map(|p| p.to_string_lossy().into()).collect();
        if parts.first().is_some_and(|p| p == "bin") {
            continue;
        }
        if parts
            .last()
            .is_some_and(|p| ["mod", "lib", "main"].contains(&p.as_str()))
        {
            parts.pop();
        }
        let name = if parts.is_empty() {
            "ROOT".to_string()
        } else {
            parts.join("::")
        };
        let text = std::fs::read_to_string(path).unwrap();
        let text = text.split("#[cfg(test)]").next().unwrap_or_default();
        let code: String = text
            .lines()
            .map(|l| l.split("//").next().unwrap_or_default())
            .collect::<Vec<_>>()
            .join("\n");
        texts.insert(name, code);
    }
    let is_ident = |c: char| c.is_ascii_alphanumeric() || c == '_' || c == ':';
    let mut graph = std::collections::BTreeMap::new();
    for (name, code) in &texts {
        let mut deps = std::collections::BTreeSet::new();
        let parent = name.rsplit_once("::").map(|(p, _)| p.to_string());
        for (prefix, base) in [("crate::", None), ("super::", parent.clone())] {
            for (at, _) in code.match_indices(prefix) {
                let rest = &code[at + prefix.len()..];
                if let Some(list) = rest.strip_prefix('{') {
                    let list = list.split('}').next().unwrap_or_default();
                    for item in list
                        .split(',')
                        .map(|i| i.trim().split("::").next().unwrap_or_default())
                    {
                        let full = base
                            .as_ref()
                            .map_or(item.to_string(), |b| format!("{b}::{item}"));
                        if texts.contains_key(&full) {
                            deps.insert(full);
                        } else if item.starts_with(char::is_uppercase) && base.is_none() {
                            deps.insert("ROOT".to_string());
                        }
                    }
                    continue;
                }
                let path: String = rest.chars().take_while(|&c| is_ident(c)).collect();
                let segments: Vec<&str> = path.split("::").filter(|s| !s.is_empty()).collect();
                let found = (1..=segments.len()).rev().find_map(|k| {
                    let joined = segments[..k].join("::");
                    let full = base
                        .as_ref()
                        .map_or(joined.clone(), |b| format!("{b}::{joined}"));
                    texts.contains_key(&full).then_some(full)
                });
                match found {
                    Some(full) => {
                        deps.insert(full);
                    }
                    None if base.is_none() && path.starts_with(char::is_uppercase) => {
                        deps.insert("ROOT".to_string());
                    }
                    None => {}
                }
            }
        }
        deps.remove(name);
        if name == "ROOT" {
            deps.clear();
        }
        graph.insert(name.clone(), deps.into_iter().collect());
    }
    graph
}

/// A cycle of `graph`, if it has one.
fn find_cycle(graph: &std::collections::BTreeMap<String, Vec<String>>) -> Option<Vec<String>> {
    fn visit(
        node: &str,
        graph: &std::collections::BTreeMap<String, Vec<String>>,
        state: &mut std::collections::BTreeMap<String, u8>,
        stack: &mut Vec<String>,
    ) -> Option<Vec<String>> {
        state.insert(node.to_string(), 1);
        stack.push(node.to_string());
        for next in graph.get(node).into_iter().flatten() {
            match state.get(next).copied().unwrap_or(0) {
                1 => {
                    let from = stack.iter().position(|n| n == next).unwrap();
                    return Some(stack[from..].to_vec());
                }
                0 => {
                    if let Some(cycle) = visit(next, graph, state, stack) {
                        return Some(cycle);
                    }
                }
                _ => {}
            }
        }
        stack.pop();
        state.insert(node.to_string(), 2);
        None
    }
    let mut state = std::collections::BTreeMap::new();
    for node in graph.keys() {
        if state.get(node).copied().unwrap_or(0) == 0
            && let Some(cycle) = visit(node, graph, &mut state, &mut Vec::new())
        {
            return Some(cycle);
        }
    }
    None
}

/// No module cycles inside a crate: each module imports only modules that do not import it
/// back, directly or through others (shared types sit in leaf modules). The crate root, which
/// declares the modules, is left out as an importer.
#[test]
fn no_crate_has_a_module_cycle() {
    let root = workspace();
    let mut srcs = vec![root.join("xtask/src")];
    for krate in std::fs::read_dir(root.join("crates")).unwrap().flatten() {
        srcs.push(krate.path().join("src"));
    }
    let mut cycles = Vec::new();
    for src in srcs.iter().filter(|s| s.is_dir()) {
        let graph = module_graph(src);
        if let Some(cycle) = find_cycle(&graph) {
            cycles.push(format!("{}: {}", src.display(), cycle.join(" -> ")));
        }
    }
    assert!(cycles.is_empty(), "module cycles:\n{}", cycles.join("\n"));
}

/// The checker sees a cycle where there is one.
#[test]
fn the_module_cycle_check_finds_a_cycle() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("lib.rs"), "//! root\nmod a;\nmod b;\n").unwrap();
    std::fs::write(
        dir.path().join("a.rs"),
        "//! a\nuse crate::b::B;\npub struct A;\n",
    )
    .unwrap();
    std::fs::write(
        dir.path().join("b.rs"),
        "//! b\nuse crate::{a};\npub struct B;\n",
    )
    .unwrap();
    let graph = module_graph(dir.path());
    assert!(find_cycle(&graph).is_some(), "{graph:?}");
    std::fs::write(dir.path().join("b.rs"), "//! b\npub struct B;\n").unwrap();
    assert!(find_cycle(&module_graph(dir.path())).is_none());
}
