//! Bad input: every fault gets a one-line error naming it, no panic, and no output file.

use std::path::Path;

use end_to_end::{assert_one_line_naming, run_into};

/// Runs `cargo xtask mesh CASE --out DIR/out.msh --report DIR/out.json` and returns the error
/// message, checking that nothing was written.
fn mesh_error(dir: &Path, case: &str, extra: &[&str]) -> String {
    let (out, report) = (dir.join("out.msh"), dir.join("out.json"));
    let err = run_into(dir, "out", "mesh", case, extra).expect_err("bad input must be an error");
    let msg = format!("{err:#}");
    assert_one_line_naming(&msg, &[]);
    assert!(
        !out.exists() && !report.exists(),
        "no output file on bad input ({msg})"
    );
    let leftovers: Vec<_> = std::fs::read_dir(dir)
        .unwrap()
        .filter_map(|e| e.ok())
        .filter(|e| e.file_name().to_string_lossy().contains("out."))
        .collect();
    assert!(
        leftovers.is_empty(),
        "no temporary file left: {leftovers:?}"
    );
    msg
}

/// A case with one wall loop from `dat` (written as wall.dat) in a circular far field.
fn case_with_dat(dir: &Path, dat: &str) -> String {
    std::fs::write(dir.join("wall.dat"), dat).unwrap();
    let case = "[[loop]]\nrole = \"wall\"\nfile = \"wall.dat\"\n\n[[loop]]\nrole = \"farfield\"\n\
                circle = { center = [0.0, 0.0], radius = 20.0 }\n";
    let path = dir.join("case.toml");
    std::fs::write(&path, case).unwrap();
    path.to_str().unwrap().to_string()
}

fn case_text(dir: &Path, text: &str) -> String {
    let path = dir.join("case.toml");
    std::fs::write(&path, text).unwrap();
    path.to_str().unwrap().to_string()
}

const SQUARE_WALL: &str = "[[loop]]\nrole = \"wall\"\npoints = [[0,0],[1,0],[1,1],[0,1]]\n";
const FARFIELD: &str =
    "[[loop]]\nrole = \"farfield\"\ncircle = { center = [0.5, 0.5], radius = 20.0 }\n";

fn expect(msg: &str, words: &[&str]) {
    for w in words {
        assert!(msg.contains(w), "message {msg:?} should mention {w:?}");
    }
}

#[test]
fn missing_case_file() {
    let dir = tempfile::tempdir().unwrap();
    let case = dir.path().join("nope.toml");
    let msg = mesh_error(dir.path(), case.to_str().unwrap(), &[]);
    expect(&msg, &["cannot read case file", "nope.toml"]);
}

#[test]
fn unknown_case_name() {
    let dir = tempfile::tempdir().unwrap();
    let msg = mesh_error(dir.path(), "no-such-case", &[]);
    expect(&msg, &["no-such-case", "built-in", "naca0012"]);
}

#[test]
fn missing_data_file() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_with_dat(dir.path(), "title\n0 0\n1 0\n0 1\n");
    std::fs::remove_file(dir.path().join("wall.dat")).unwrap();
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["cannot read", "wall.dat"]);
}

#[test]
fn malformed_line_is_named_with_its_number() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_with_dat(dir.path(), "title\n0 0\n1 0\n1 zero\n0 1\n");
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["wall.dat", "line 4", "1 zero"]);
}

#[test]
fn nan_coordinate() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_with_dat(dir.path(), "title\n0 0\n1 NaN\n1 1\n0 1\n");
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["line 3", "not finite"]);
}

#[test]
fn fewer_than_three_points() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_with_dat(dir.path(), "title\n0 0\n1 0\n");
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["at least 3 points"]);
}

#[test]
fn duplicate_consecutive_points() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_with_dat(dir.path(), "title\n0 0\n1 0\n1 0\n1 1\n0 1\n");
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["points 1 and 2 coincide"]);
}

#[test]
fn open_loop() {
    // The upper surface of an airfoil alone: the implied closing edge spans the chord.
    let dir = tempfile::tempdir().unwrap();
    let mut dat = String::from("upper surface only\n");
    for i in 0..=40 {
        let x = 1.0 - f64::from(i) / 40.0;
        let y = 0.6 * (0.2969 * x.sqrt() - 0.126 * x - 0.3516 * x * x + 0.2843 * x.powi(3));
        dat.push_str(&format!("{x} {}\n", y.max(0.0) + 1e-3 * (1.0 - x)));
    }
    let case = case_with_dat(dir.path(), &dat);
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["looks open"]);
}

#[test]
fn self_intersecting_loop() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_with_dat(dir.path(), "bow tie\n0 0\n1 1\n1 0\n0 1\n");
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["intersects itself"]);
}

#[test]
fn loops_that_cross() {
    let dir = tempfile::tempdir().unwrap();
    let other = "[[loop]]\nrole = \"wall\"\nname = \"other\"\npoints = [[0.5,0.5],[1.5,0.5],[1.5,1.5],[0.5,1.5]]\n";
    let case = case_text(dir.path(), &format!("{SQUARE_WALL}{other}{FARFIELD}"));
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["cross", "other"]);
}

#[test]
fn body_inside_another_body() {
    let dir = tempfile::tempdir().unwrap();
    let inner = "[[loop]]\nrole = \"wall\"\nname = \"inner\"\npoints = [[0.2,0.2],[0.4,0.2],[0.4,0.4],[0.2,0.4]]\n";
    let case = case_text(dir.path(), &format!("{SQUARE_WALL}{inner}{FARFIELD}"));
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["inner", "inside", "overlap"]);
}

#[test]
fn bad_farfields() {
    let cases: [(&str, &[&str]); 2] = [
        (
            "center = [50.0, 0.0], radius = 2.0",
            &["not inside the farfield"],
        ),
        // the radius's range is geom-curve's own check; the message names the loop and key
        (
            "center = [0.5, 0.5], radius = -2.0",
            &["loop 2", "circle", "radius = -2"],
        ),
    ];
    for (circle, words) in cases {
        let dir = tempfile::tempdir().unwrap();
        let far = format!("[[loop]]\nrole = \"farfield\"\ncircle = {{ {circle} }}\n");
        let case = case_text(dir.path(), &format!("{SQUARE_WALL}{far}"));
        expect(&mesh_error(dir.path(), &case, &[]), words);
    }
}

#[test]
fn unknown_key_is_named() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_text(
        dir.path(),
        &format!("{SQUARE_WALL}{FARFIELD}[layers]\nfirst_hieght = 1e-5\n"),
    );
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["first_hieght", "line"]);
}

#[test]
fn impossible_parameters() {
    let cases = [
        ("[boundary]\ngrowth = 1.0\n", "[boundary] growth"),
        ("[layers]\ngrowth = 0.9\n", "[layers] growth"),
        // the ranges are the crates' own checks (AfsfParams, SpacingParams), named by key
        ("[layers]\ngrowth = 1.0\n", "[layers] growth"),
        ("[layers]\nmax_layers = 0\n", "[layers] max_layers"),
        ("[boundary]\ngrowth = 50.0\n", "[boundary] growth"),
        ("[layers]\nfirst_height = -1e-5\n", "first_height"),
        ("[boundary]\nmax_spacing = 0.0\n", "max_spacing"),
        ("[boundary]\nrefine_angle_deg = 200.0\n", "refine_angle_deg"),
        ("[curving]\norder = 5\n", "order"),
        ("[curving]\nmin_curved_layers = 500\n", "min_curved_layers"),
        (
            "[curving]\nstop_scaled_jacobian = 0.0\n",
            "stop_scaled_jacobian",
        ),
        ("[curving]\nstrategy = \"three-vector\"\n", "three-vector"),
    ];
    for (section, words) in cases {
        let dir = tempfile::tempdir().unwrap();
        let case = case_text(dir.path(), &format!("{SQUARE_WALL}{FARFIELD}{section}"));
        let msg = mesh_error(dir.path(), &case, &[]);
        expect(&msg, &[words]);
    }
}

#[test]
fn no_farfield_without_inside() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_text(dir.path(), SQUARE_WALL);
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["farfield", "inside = true"]);
}

#[test]
fn unknown_output_extension() {
    let dir = tempfile::tempdir().unwrap();
    let bad = dir.path().join("mesh.stl");
    let msg = mesh_error(dir.path(), "naca0012", &["--out", bad.to_str().unwrap()]);
    expect(&msg, &["mesh.stl", "unknown extension"]);
    assert!(!bad.exists());
}

#[test]
fn invalid_naca_digits() {
    let dir = tempfile::tempdir().unwrap();
    let wall = "[[loop]]\nrole = \"wall\"\nnaca = \"00x2\"\n";
    let case = case_text(dir.path(), &format!("{wall}{FARFIELD}"));
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["NACA", "00x2"]);
}

#[test]
fn a_point_of_three_numbers_is_refused_not_cut() {
    let dir = tempfile::tempdir().unwrap();
    let wall = "[[loop]]\nrole = \"wall\"\npoints = [[0,0],[1,0,7],[1,1],[0,1]]\n";
    let case = case_text(dir.path(), &format!("{wall}{FARFIELD}"));
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(&msg, &["loop 1", "point 2", "3 numbers", "[x, y]"]);
}

#[test]
fn fixed_length_lists_are_refused_at_any_other_length() {
    let far3 =
        "[[loop]]\nrole = \"farfield\"\ncircle = { center = [0.5, 0.5, 0.0], radius = 20.0 }\n";
    let cases = [
        (
            format!("{SQUARE_WALL}translate = [1.0, 2.0, 3.0]\n{FARFIELD}"),
            vec!["loop 1", "translate", "3 numbers"],
        ),
        (
            format!("{SQUARE_WALL}translate = [1.0]\n{FARFIELD}"),
            vec!["loop 1", "translate", "1 numbers"],
        ),
        (
            format!("{SQUARE_WALL}{far3}"),
            vec!["loop 2", "circle center", "3 numbers"],
        ),
        (
            format!("{SQUARE_WALL}{FARFIELD}[views]\nle = [0, 0, 1]\n"),
            vec!["[views] le", "3 numbers", "x0, y0, x1, y1"],
        ),
    ];
    for (text, words) in cases {
        let dir = tempfile::tempdir().unwrap();
        let case = case_text(dir.path(), &text);
        let msg = mesh_error(dir.path(), &case, &[]);
        expect(&msg, &words);
    }
}

#[test]
fn huge_generated_point_counts_are_refused_before_allocation() {
    // before: an abort on allocation failure (exit 134, no message)
    let far = "[[loop]]\nrole = \"farfield\"\n\
               circle = { center = [0.5, 0], radius = 20, points = 1000000000000 }\n";
    let naca = "[[loop]]\nrole = \"wall\"\nnaca = \"0012\"\nnaca_points = 1000000000000\n";
    for (text, words) in [
        (
            format!("{SQUARE_WALL}{far}"),
            ["circle points = 1000000000000", "1000000"],
        ),
        (
            format!("{naca}{FARFIELD}"),
            ["naca_points = 1000000000000", "1000000"],
        ),
    ] {
        let dir = tempfile::tempdir().unwrap();
        let case = case_text(dir.path(), &text);
        let msg = mesh_error(dir.path(), &case, &[]);
        expect(&msg, &words);
    }
}

#[test]
fn a_boundary_too_fine_for_the_cell_limit_is_refused_before_it_is_made() {
    let dir = tempfile::tempdir().unwrap();
    let case = case_text(
        dir.path(),
        &format!("{SQUARE_WALL}{FARFIELD}[boundary]\nmax_spacing = 1e-9\n"),
    );
    let t = std::time::Instant::now();
    let msg = mesh_error(dir.path(), &case, &[]);
    expect(
        &msg,
        &["boundary", "max_spacing", "--max-cells", "20000000"],
    );
    assert!(t.elapsed().as_secs_f64() < 5.0, "refused at once");
}

#[test]
fn a_case_expected_above_the_cell_limit_is_refused_with_its_estimate() {
    let dir = tempfile::tempdir().unwrap();
    let msg = mesh_error(
        dir.path(),
        "naca0012",
        &["--order", "1", "--max-cells", "1000"],
    );
    expect(
        &msg,
        &[
            "cells expected",
            "boundary nodes",
            "limit 1000",
            "[boundary] max_spacing",
            "--max-cells",
        ],
    );
}
