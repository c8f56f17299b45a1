//! `cargo xtask mesh A.dat [B.dat ...]`: Selig and Lednicer files mesh with the defaults;
//! `--aoa` turns the airfoil nose up about the quarter chord; the first height follows
//! `--yplus` and `--re`; several files make a multi-element airfoil, one wall group each.

use std::path::{Path, PathBuf};

use end_to_end::{Outcome, s, xtask};
use serde_json::Value;

fn fixture(rel: &str) -> String {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures/geometry")
        .join(rel)
        .display()
        .to_string()
}

/// Runs `mesh` with `args` at order 1 into `dir`; returns the report and the mesh read back.
fn run(dir: &Path, args: &[&str]) -> anyhow::Result<(Value, mesh_model::Mesh)> {
    let (msh, json): (PathBuf, PathBuf) = (dir.join("m.msh"), dir.join("m.json"));
    let mut all = vec!["mesh", "--quiet", "--order", "1"];
    all.extend(args);
    all.extend(["--out", s(&msh), "--report", s(&json)]);
    let outcome = xtask(&all)?;
    assert_eq!(outcome, Outcome::Valid);
    let report = serde_json::from_slice(&std::fs::read(json)?)?;
    Ok((report, mesh_io::read_msh(&msh)?))
}

/// The wall node furthest right (the trailing edge).
fn trailing_edge(m: &mesh_model::Mesh) -> [f64; 2] {
    let wall = m
        .patches
        .iter()
        .position(|p| p.role == mesh_model::Role::Wall)
        .unwrap();
    let mut te = [f64::NEG_INFINITY, 0.0];
    for (j, f) in m.boundary.iter().enumerate() {
        if m.boundary_patch[j] as usize == wall {
            for &v in f.corners() {
                let p = m.xy(v);
                if p[0] > te[0] {
                    te = p;
                }
            }
        }
    }
    te
}

#[test]
fn a_selig_file_meshes_nose_up_with_the_first_height_of_its_y_plus() {
    let dir = tempfile::tempdir().unwrap();
    let dat = fixture("naca0012.dat");
    let (report, mesh) = run(
        dir.path(),
        &[&dat, "--aoa", "10", "--yplus", "1", "--re", "6e6"],
    )
    .expect("a .dat meshes");
    assert_eq!(report["case"], "naca0012");
    assert_eq!(
        report["boundary_groups"]["naca0012"],
        report["loops"][0]["nodes"]
    );
    // nose up: the trailing edge (x = 1, 0.75 chord behind the quarter chord) goes down
    let te = trailing_edge(&mesh);
    let a = 10f64.to_radians();
    assert!((te[1] + 0.75 * a.sin()).abs() < 2e-3, "{te:?}");
    assert!((te[0] - (0.25 + 0.75 * a.cos())).abs() < 2e-3, "{te:?}");
    // the thinnest boundary segment is the first height at the corners: 4.46e-6
    let h = report["loops"][0]["spacing_min"].as_f64().unwrap();
    assert!((h / 4.455e-6 - 1.0).abs() < 0.05, "{h}");
    // far field: 30 chords about the quarter chord by default
    let far = mesh
        .patches
        .iter()
        .position(|p| p.name == "farfield")
        .unwrap();
    let f = mesh
        .boundary
        .iter()
        .enumerate()
        .find(|(j, _)| mesh.boundary_patch[*j] as usize == far);
    let p = mesh.xy(f.unwrap().1.corners()[0]);
    let r = (p[0] - 0.25).hypot(p[1]);
    assert!((r - 30.0).abs() < 0.01, "{r}");
}

#[test]
fn a_lednicer_file_gives_the_mesh_of_the_same_selig_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(fixture("naca0012.dat")).unwrap();
    let pts: Vec<&str> = text
        .lines()
        .skip(1)
        .filter(|l| !l.trim().is_empty())
        .collect();
    let x = |l: &str| l.split_whitespace().next().unwrap().parse::<f64>().unwrap();
    let le = (0..pts.len())
        .min_by(|&a, &b| x(pts[a]).total_cmp(&x(pts[b])))
        .unwrap();
    // Lednicer: both surfaces from the leading edge to the trailing edge
    let upper: Vec<&str> = pts[..=le].iter().rev().copied().collect();
    let lower: Vec<&str> = pts[le..].to_vec();
    let lednicer = format!(
        "NACA 0012 LEDNICER\n{}. {}.\n\n{}\n\n{}\n",
        upper.len(),
        lower.len(),
        upper.join("\n"),
        lower.join("\n")
    );
    let (sel, led) = (
        dir.path().join("selig.dat"),
        dir.path().join("lednicer.dat"),
    );
    std::fs::write(&sel, &text).unwrap();
    std::fs::write(&led, lednicer).unwrap();
    let (a, _) = run(dir.path(), &[sel.to_str().unwrap()]).unwrap();
    let (b, _) = run(dir.path(), &[led.to_str().unwrap()]).unwrap();
    assert_eq!(a["cells"], b["cells"]);
    assert_eq!(a["loops"][0]["nodes"], b["loops"][0]["nodes"]);
}

#[test]
fn three_files_make_a_three_element_airfoil_with_a_group_each() {
    let dir = tempfile::tempdir().unwrap();
    let files = ["30p30n/slat.dat", "30p30n/main.dat", "30p30n/flap.dat"].map(fixture);
    let mut args: Vec<&str> = files.iter().map(String::as_str).collect();
    args.extend(["--yplus", "100", "--re", "1e6"]);
    let (report, mesh) = run(dir.path(), &args).expect("three .dat files mesh");
    let groups = report["boundary_groups"].as_object().unwrap();
    let names: Vec<&str> = groups.keys().map(String::as_str).collect();
    assert_eq!(names, ["farfield", "flap", "main", "slat"]);
    assert_eq!(mesh.patches.len(), 4);
}

#[test]
fn airfoil_flags_with_a_case_and_mixed_inputs_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let dat = fixture("naca0012.dat");
    for (args, want) in [
        (
            vec!["naca0012", "--aoa", "4"],
            "--aoa applies to airfoil coordinate files (.dat, .txt) only",
        ),
        // a misspelt file name is said to be missing, not taken for a case
        (
            vec!["naca4412.dta", "--aoa", "4"],
            "naca4412.dta: no such file (with --aoa, give airfoil coordinates",
        ),
        (
            vec!["naca4412.dta"],
            "nor airfoil coordinates (.dat or .txt)",
        ),
        (vec!["naca0012", &dat], "not both"),
        (vec![&dat, "--aoa", "-120"], "--aoa -120"),
        (vec![&dat, "--re", "0"], "--re 0"),
        (vec!["missing.dat"], "cannot read missing.dat"),
    ] {
        let err = run(dir.path(), &args).expect_err(want);
        let msg = format!("{err:#}");
        assert!(msg.contains(want) && !msg.contains('\n'), "{msg}");
    }
}

/// Airfoil sites often serve coordinates as `.txt`: read as the same `.dat` would be.
#[test]
fn coordinates_in_a_txt_file_are_read_as_a_dat_file() {
    let dir = tempfile::tempdir().unwrap();
    let txt = dir.path().join("naca0012.txt");
    std::fs::copy(fixture("naca0012.dat"), &txt).unwrap();
    let (a, _) = run(dir.path(), &[txt.to_str().unwrap()]).expect("a .txt airfoil meshes");
    let (b, _) = run(dir.path(), &[&fixture("naca0012.dat")]).unwrap();
    assert_eq!(a["cells"], b["cells"]);
}
