//! The outputs of a run are replaced together or not at all: an output that cannot be
//! written leaves every other one as it was (no mesh written before the failure, no temporary
//! file, no folder made for nothing); two outputs on one file are refused; stale temporary
//! files of killed runs are removed; a case name cannot steer the default outputs out of
//! `out/`.

use end_to_end::{Outcome, mesh, s, tree, xtask as run};

#[test]
fn an_unwritable_picture_leaves_the_meshes_as_they_were() {
    // `ro` is a regular file where a folder is needed: unwritable for root too
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    std::fs::create_dir(d.join("ok")).unwrap();
    std::fs::write(d.join("ok/m.msh"), b"old mesh").unwrap();
    std::fs::write(d.join("ro"), b"not a folder").unwrap();
    let before = tree(d);
    let (msh, vtu) = (d.join("ok/m.msh"), d.join("new/m.vtu"));
    let err = mesh(
        "lshape",
        "1",
        &[
            "--out",
            s(&msh),
            "--out",
            s(&vtu),
            "--png",
            s(&d.join("ro/p.png")),
        ],
    )
    .expect_err("the picture cannot be written");
    let msg = format!("{err:#}");
    assert!(!msg.contains('\n'), "{msg}");
    assert!(msg.contains("--png") && msg.contains("ro/p.png"), "{msg}");
    assert_eq!(std::fs::read(&msh).unwrap(), b"old mesh");
    assert_eq!(
        tree(d),
        before,
        "nothing written, no temporary, no new folder"
    );
}

#[test]
fn a_read_only_folder_leaves_the_meshes_as_they_were() {
    use std::os::unix::fs::PermissionsExt;
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let ro = d.join("ro");
    std::fs::create_dir(&ro).unwrap();
    std::fs::set_permissions(&ro, std::fs::Permissions::from_mode(0o555)).unwrap();
    if std::fs::write(ro.join("probe"), b"").is_ok() {
        // root ignores permissions: the test above covers this case with a file as folder
        std::fs::remove_file(ro.join("probe")).unwrap();
        return;
    }
    let msh = d.join("ok/m.msh");
    let err = mesh(
        "lshape",
        "1",
        &["--out", s(&msh), "--png", s(&ro.join("p.png"))],
    )
    .expect_err("read-only folder");
    assert!(format!("{err:#}").contains("ro/p.png"), "{err:#}");
    assert_eq!(tree(d), vec!["ro/"]);
}

#[test]
fn all_outputs_appear_together_on_success() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let outs = [
        d.join("a/m.msh"),
        d.join("b/m.vtu"),
        d.join("m.bin"),
        d.join("p/m.png"),
        d.join("r/m.json"),
    ];
    let outcome = mesh(
        "lshape",
        "1",
        &[
            "--out",
            s(&outs[0]),
            "--out",
            s(&outs[1]),
            "--snapshot",
            s(&outs[2]),
            "--png",
            s(&outs[3]),
            "--width",
            "200",
            "--report",
            s(&outs[4]),
        ],
    )
    .unwrap();
    assert_eq!(outcome, Outcome::Valid);
    assert_eq!(
        tree(d),
        vec![
            "a/", "a/m.msh", "b/", "b/m.vtu", "m.bin", "p/", "p/m.png", "r/", "r/m.json"
        ]
    );
    let report: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&outs[4]).unwrap()).unwrap();
    let files: Vec<&str> = report["files"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| f.as_str().unwrap())
        .collect();
    assert_eq!(files, outs.iter().map(|p| s(p)).collect::<Vec<_>>());
    assert!(report["estimated_cells"].as_u64().unwrap() > 0);
}

#[test]
fn two_outputs_on_one_file_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let msh = d.join("m.msh");
    let same = d.join("x/../m.msh");
    std::fs::create_dir(d.join("x")).unwrap();
    for (flags, words) in [
        (
            vec!["--out", s(&msh), "--snapshot", s(&msh)],
            ["--snapshot", "same file as --out"],
        ),
        (
            vec!["--out", s(&msh), "--out", s(&same)],
            ["--out", "same file as --out"],
        ),
    ] {
        let mut args = vec!["mesh", "lshape", "--quiet", "--order", "1"];
        args.extend(flags);
        let err = run(&args).expect_err("duplicate output");
        let msg = format!("{err:#}");
        for w in words {
            assert!(msg.contains(w), "{msg:?} should mention {w:?}");
        }
        assert_eq!(tree(d), vec!["x/"], "nothing written");
    }
}

#[test]
fn stale_temporaries_of_killed_runs_are_removed() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // a pid above Linux's largest: the run that left it is gone (killed with SIGKILL)
    let stale = d.join(".m.msh.tmp-99999999-0");
    std::fs::write(&stale, b"half a mesh").unwrap();
    let msh = d.join("m.msh");
    mesh("lshape", "1", &["--out", s(&msh)]).unwrap();
    assert_eq!(tree(d), vec!["m.msh"]);
}

#[test]
fn a_case_name_is_made_safe_for_the_default_file_names() {
    // The default outputs are relative to the working folder, which tests cannot change
    // safely; the binary test `a_case_name_cannot_escape_out` runs the whole command.
    for (name, stem) in [
        ("../escape", "_escape"),
        ("a\nb", "a_b"),
        ("...", "case"),
        ("NACA 0012 (clean)", "NACA_0012__clean_"),
        ("naca0012", "naca0012"),
    ] {
        assert_eq!(curvemesh::outputs::file_stem_of(name), stem, "{name:?}");
    }
}
