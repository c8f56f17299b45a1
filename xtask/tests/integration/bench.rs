//! `cargo xtask bench --vs-gmsh --scaling --3d` on its tiny configuration, run as a user runs it:
//! it works, prints one line per row and point, skips Gmsh's side in one line when there is
//! no Python with Gmsh, and writes its parts of the document (the hand-written rest kept) and
//! the plot. No timing is checked.

use std::process::Command;

#[test]
fn bench_vs_gmsh_and_scaling_work_on_a_tiny_configuration() {
    let dir = tempfile::tempdir().unwrap();
    let doc = dir.path().join("docs/performance.md");
    std::fs::create_dir_all(doc.parent().unwrap()).unwrap();
    std::fs::write(&doc, "# Performance\n\nWritten by hand.\n").unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(["bench", "--vs-gmsh", "--scaling", "--3d", "--tiny", "--doc"])
        .arg(&doc)
        .env("CHECKERS_VENV", dir.path().join("no-venv"))
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        out.status.success(),
        "{stdout}\n{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let skip: Vec<&str> = stdout.lines().filter(|l| l.contains("skipped")).collect();
    assert_eq!(skip.len(), 1, "{stdout}");
    assert!(
        skip[0].starts_with("Gmsh's side skipped: no Python with Gmsh at"),
        "{stdout}"
    );
    assert_eq!(
        stdout.lines().filter(|l| l.contains(" cells ")).count(),
        3,
        "{stdout}"
    );

    let text = std::fs::read_to_string(&doc).unwrap();
    assert!(
        text.starts_with("# Performance\n\nWritten by hand.\n"),
        "{text}"
    );
    for needle in [
        "<!-- vs-gmsh:begin -->",
        "| naca0012 | 1e-3 |",
        "Gmsh's side was skipped",
        "<!-- scaling:end -->",
        "Fitted exponent",
        "<!-- threads:begin -->",
        "| 2 |",
        "Two threads over one",
        "cross-core round trip",
        "<!-- 3d:begin -->",
        "| step | 808 tets, 1240 pyramids, 6652 hexes |",
    ] {
        assert!(text.contains(needle), "no {needle:?} in {text}");
    }
    let plot = std::fs::read_to_string(dir.path().join("docs/figures/performance-scaling.svg"));
    assert!(plot.unwrap().contains("<polyline"));
    // a second run replaces the parts, it does not add them again
    let again = Command::new(env!("CARGO_BIN_EXE_xtask"))
        .args(["bench", "--scaling", "--tiny", "--doc"])
        .arg(&doc)
        .output()
        .unwrap();
    assert!(again.status.success());
    let text = std::fs::read_to_string(&doc).unwrap();
    assert_eq!(text.matches("<!-- scaling:begin -->").count(), 1, "{text}");
    assert_eq!(text.matches("<!-- threads:begin -->").count(), 1, "{text}");
}
