//! `cargo xtask move`: moved meshes keep the topology of the unmoved one and are certified
//! valid at order 3, with the movement in the report; bad motions are refused with one line
//! before any file is written.

use std::path::Path;

use end_to_end::{Outcome, assert_one_line_naming, mesh, read_json, run_into, s, tree, xtask};
use serde_json::Value;

/// `cargo xtask move CASE --quiet --out DIR/NAME.msh --report DIR/NAME.json ARGS…`.
fn run_move(dir: &Path, name: &str, case: &str, args: &[&str]) -> anyhow::Result<Outcome> {
    run_into(dir, name, "move", case, args)
}

/// [`run_move`] that must succeed: its outcome and its report.
fn moved(dir: &Path, name: &str, case: &str, args: &[&str]) -> (Outcome, Value) {
    let outcome = run_move(dir, name, case, args).unwrap_or_else(|e| panic!("{args:?}: {e:#}"));
    assert!(dir.join(format!("{name}.msh")).exists());
    (outcome, read_json(&dir.join(format!("{name}.json"))))
}

fn assert_certified(r: &Value) {
    let q = &r["quality"];
    assert_eq!(q["invalid_cells"], 0, "{q}");
    assert_eq!(q["certified"], true, "{q}");
    assert!(q["min_scaled_jacobian"].as_f64().unwrap() > 0.0, "{q}");
    assert!(
        r["problems"].as_array().unwrap().is_empty(),
        "{}",
        r["problems"]
    );
}

#[test]
fn naca0012_rotated_10_deg_keeps_its_topology_and_every_cell_valid() {
    let dir = tempfile::tempdir().unwrap();
    let unmoved = dir.path().join("unmoved.json");
    assert_eq!(
        mesh(
            "naca0012",
            "3",
            &[
                "--out",
                s(&dir.path().join("u.msh")),
                "--report",
                s(&unmoved)
            ]
        )
        .unwrap(),
        Outcome::Valid
    );
    let unmoved = read_json(&unmoved);
    for method in ["springs", "idw", "rbf"] {
        let args = [
            "--rotate", "10", "--about", "0.25,0", "--method", method, "--order", "3",
        ];
        let (outcome, r) = moved(dir.path(), method, "naca0012", &args);
        assert_eq!(outcome, Outcome::Valid, "{method}");
        assert_certified(&r);
        assert_eq!(r["order"], 3);
        assert_eq!(r["nodes"], unmoved["nodes"], "{method}");
        assert_eq!(r["cells"], unmoved["cells"], "{method}");
        // re-curved with the unmoved mesh's decisions: its pipes, curved as deep
        let deepest = |r: &Value| r["curving"]["deepest_curved_layer"].as_u64().unwrap();
        assert!(deepest(&unmoved) > 0, "{}", unmoved["curving"]);
        assert_eq!(deepest(&r), deepest(&unmoved), "{method}: {}", r["curving"]);
        if r["curving_decisions_changed"] == 0 {
            assert_eq!(
                r["curving"]["stops"], unmoved["curving"]["stops"],
                "{method}"
            );
        }
        let m = &r["movement"];
        assert_eq!(m["method"], method);
        assert_eq!(m["motion"][0]["loop"], "naca0012");
        assert_eq!(m["motion"][0]["rigid"]["rotate_deg"], 10.0);
        assert_eq!(m["inverted_linear_cells"], 0);
        // the README of mesh-move measures 0.908 (IDW) and 0.959 (RBF) on this motion
        let ratio = m["worst_cell_ratio"].as_f64().unwrap();
        assert!(ratio > 0.85 && ratio <= 1.0 + 1e-12, "{method}: {ratio}");
        // the trailing edge moves by 0.75 · sin 10° ≈ 0.13
        let d = m["largest_boundary_displacement"].as_f64().unwrap();
        assert!((0.12..0.14).contains(&d), "{d}");
        for side in ["before", "after"] {
            assert_eq!(m[side]["obtuse_hist"].as_array().unwrap().len(), 5);
            assert!(m[side]["min_scaled_jacobian"].as_f64().unwrap() > 0.0);
        }
    }
}

#[test]
fn bumps_on_both_surfaces_morph_the_wall() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--bump",
        "0.3,0.005",
        "--bump",
        "0.7,-0.004,2,lower",
        "--order",
        "2",
    ];
    let (outcome, r) = moved(dir.path(), "bump", "naca0012", &args);
    assert_eq!(outcome, Outcome::Valid);
    assert_certified(&r);
    let bumps = &r["movement"]["motion"][0]["bumps"];
    assert_eq!(bumps[1], serde_json::json!([0.7, -0.004, 2.0, "lower"]));
    let d = r["movement"]["largest_boundary_displacement"]
        .as_f64()
        .unwrap();
    assert!(d > 0.003 && d < 0.006, "{d}");
}

#[test]
fn the_motion_file_of_the_readme_moves_two_loops_and_draws_them() {
    let dir = tempfile::tempdir().unwrap();
    let file = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/motions/two-element.toml");
    let png = dir.path().join("gap.png");
    let png_at = format!("{}@flap-gap", s(&png));
    let args = ["--motion", s(&file), "--png", &png_at, "--width", "200"];
    let (outcome, r) = moved(dir.path(), "two", "two-element", &args);
    assert_eq!(outcome, Outcome::Valid);
    assert!(png.exists(), "the picture of the moved mesh");
    assert_certified(&r);
    let m = &r["movement"]["motion"];
    assert_eq!(m[0]["loop"], "flap");
    assert_eq!(m[1]["loop"], "main");
    assert_eq!(m[1]["bumps"][0][3], "upper");
}

#[test]
fn bad_motions_are_one_line_before_any_file() {
    let cases: &[(&str, &[&str], &[&str])] = &[
        (
            "naca0012",
            &["--rotate", "NaN"],
            &["rotate_deg", "finite", "NaN"],
        ),
        (
            "naca0012",
            &["--loop", "flap", "--rotate", "3"],
            &["no loop named \"flap\"", "naca0012"],
        ),
        (
            "naca0012",
            &["--translate", "30,0"],
            &["naca0012", "outside the far field"],
        ),
        (
            "naca0012",
            &["--scale", "0"],
            &["scale must be positive", "0"],
        ),
        (
            "naca0012",
            &["--scale", "-2"],
            &["scale must be positive", "-2"],
        ),
        (
            "naca0012",
            &["--bump", "0.3"],
            &["--bump 0.3", "POSITION,AMPLITUDE"],
        ),
        (
            "naca0012",
            &["--bump", "1.2,0.01"],
            &["bump position", "1.2"],
        ),
        ("naca0012", &[], &["no motion given"]),
        (
            "two-element",
            &["--rotate", "3"],
            &["--loop NAME", "main, flap"],
        ),
        (
            "two-element",
            &["--loop", "flap", "--translate", "-0.6,0.05"],
            &["main and flap cross"],
        ),
        (
            "naca0012",
            &["--rotate", "3", "--method", "rbf", "--radius", "-1"],
            &["support radius", "-1"],
        ),
        (
            "naca0012",
            &["--rotate", "3", "--motion", "m.toml"],
            &["either --motion", "not both"],
        ),
    ];
    for (case, args, words) in cases {
        let dir = tempfile::tempdir().unwrap();
        let err = run_move(dir.path(), "m", case, args).expect_err("a bad motion is an error");
        assert_one_line_naming(&format!("{err:#}"), words);
        assert!(
            tree(dir.path()).is_empty(),
            "{args:?}: {:?}",
            tree(dir.path())
        );
    }
}

#[test]
fn a_bad_motion_file_names_its_line() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("motion.toml");
    std::fs::write(&file, "[[motion]]\nloop = \"naca0012\"\nrotate = 3.0\n").unwrap();
    let out = dir.path().join("m.msh");
    let err = xtask(&[
        "move",
        "naca0012",
        "--quiet",
        "--motion",
        s(&file),
        "--out",
        s(&out),
    ])
    .expect_err("unknown key");
    assert_one_line_naming(&format!("{err:#}"), &["motion.toml, line 3", "rotate"]);
    assert!(!out.exists());
}

#[test]
fn a_snapshot_of_the_case_is_moved_as_the_case_itself() {
    let dir = tempfile::tempdir().unwrap();
    let bin = dir.path().join("n.bin");
    let m = dir.path().join("n.msh");
    assert_eq!(
        mesh("naca0012", "1", &["--out", s(&m), "--snapshot", s(&bin)]).unwrap(),
        Outcome::Valid
    );
    let args = ["--rotate", "20", "--about", "0.25,0", "--order", "3"];
    let (_, direct) = moved(dir.path(), "direct", "naca0012", &args);
    let (outcome, from_bin) = moved(
        dir.path(),
        "bin",
        "naca0012",
        &[&args[..], &["--snapshot", s(&bin)]].concat(),
    );
    assert_eq!(outcome, Outcome::Valid);
    assert_eq!(
        std::fs::read(dir.path().join("direct.msh")).unwrap(),
        std::fs::read(dir.path().join("bin.msh")).unwrap()
    );
    assert_eq!(
        direct["movement"]["worst_cell_ratio"],
        from_bin["movement"]["worst_cell_ratio"]
    );
    let x = dir.path().join("x.msh");
    let args = [
        "move",
        "bat",
        "--quiet",
        "--rotate",
        "2",
        "--snapshot",
        s(&bin),
        "--out",
        s(&x),
    ];
    let err = xtask(&args).expect_err("a snapshot of another case");
    assert_one_line_naming(&format!("{err:#}"), &["--snapshot", "naca0012", "bat"]);
}

#[test]
fn a_mover_that_inverts_cells_writes_the_mesh_and_fails() {
    // a compact Wendland support (R = 0.5) cannot follow a 30° pitch: mesh-move's README
    // measures 78 inverted cells on this motion
    let dir = tempfile::tempdir().unwrap();
    let args = [
        "--rotate", "30", "--about", "0.25,0", "--method", "rbf", "--radius", "0.5",
    ];
    let (outcome, r) = moved(dir.path(), "inv", "naca0012", &args);
    assert_eq!(outcome, Outcome::Invalid);
    let inverted = r["movement"]["inverted_linear_cells"].as_u64().unwrap();
    assert!(inverted > 0);
    assert_eq!(r["order"], 1, "an inverted mesh is written linear");
    assert!(r["quality"]["invalid_cells"].as_u64().unwrap() > 0);
    assert!(!r["problems"].as_array().unwrap().is_empty());
    let finished = curvemesh_cli::run(end_to_end::cli(&[
        "move",
        "naca0012",
        "--quiet",
        "--out",
        s(&dir.path().join("again.msh")),
        "--rotate",
        "30",
        "--about",
        "0.25,0",
        "--method",
        "rbf",
        "--radius",
        "0.5",
    ]))
    .unwrap();
    let line = curvemesh_cli::exit::of_run(&Ok(finished));
    assert_eq!(line.code, 2);
    assert_one_line_naming(
        line.stderr.as_deref().unwrap(),
        &[
            format!("the rbf mover inverted {inverted} linear cells").as_str(),
            "moved linear mesh was written but failed validation",
        ],
    );
}

#[test]
fn a_rigid_motion_of_every_loop_moves_every_node_of_the_p3_mesh_by_it() {
    // the boundary nodes on the refitted curves at their own parameters, the others moved by
    // the mover, the high-order nodes by the curving on the moved curves: with the far field
    // moved too, every node by the same rigid motion
    let dir = tempfile::tempdir().unwrap();
    let unmoved = dir.path().join("u.msh");
    assert_eq!(
        mesh("naca0012", "3", &["--out", s(&unmoved)]).unwrap(),
        Outcome::Valid
    );
    let motion = dir.path().join("rigid.toml");
    let rigid = "rotate_deg = 37.0\nabout = [0.25, 0.0]\ntranslate = [0.5, 0.25]";
    let text = format!(
        "[[motion]]\nloop = \"naca0012\"\n{rigid}\n[[motion]]\nloop = \"farfield\"\n{rigid}\n"
    );
    std::fs::write(&motion, text).unwrap();
    let (outcome, _) = moved(dir.path(), "r", "naca0012", &["--motion", s(&motion)]);
    assert_eq!(outcome, Outcome::Valid);
    let before = mesh_io::read_msh(&unmoved).unwrap();
    let after = mesh_io::read_msh(&dir.path().join("r.msh")).unwrap();
    assert_eq!(before.nodes.len(), after.nodes.len());
    assert_eq!(before.cells, after.cells);
    let (sin, cos) = 37f64.to_radians().sin_cos();
    let worst = before
        .nodes
        .iter()
        .zip(&after.nodes)
        .map(|(b, a)| {
            let (x, y) = (b[0] - 0.25, b[1]);
            let expected = [0.25 + cos * x - sin * y + 0.5, sin * x + cos * y + 0.25];
            (a[0] - expected[0]).abs().max((a[1] - expected[1]).abs())
        })
        .fold(0.0f64, f64::max);
    assert!(worst < 1e-9, "a node misses the rigid motion by {worst:e}");
}

#[test]
fn steps_write_the_sequence_each_as_the_one_step_move_and_a_half_turn_is_one() {
    // `--steps 3` of a pitch to 90° writes the unmoved mesh, then 30°, 60° and 90°, each the
    // mesh a one-step move to that angle writes (the balance does not depend on its warm
    // start); and a turn by exactly 180° is valid, as 179.999° is
    let dir = tempfile::tempdir().unwrap();
    let pitch = ["--rotate", "-90", "--about", "0.25,0", "--order", "2"];
    let args = [&pitch[..], &["--steps", "3"]].concat();
    assert_eq!(
        run_move(dir.path(), "seq", "naca0012", &args).unwrap(),
        Outcome::Valid
    );
    let (outcome, _) = moved(dir.path(), "one", "naca0012", &pitch);
    assert_eq!(outcome, Outcome::Valid);
    assert!(!dir.path().join("seq.msh").exists());
    let nodes = |name: &str| mesh_io::read_msh(&dir.path().join(name)).unwrap().nodes;
    let last = nodes("seq-003.msh");
    let worst = last
        .iter()
        .zip(&nodes("one.msh"))
        .map(|(a, b)| (a[0] - b[0]).abs().max((a[1] - b[1]).abs()))
        .fold(0.0f64, f64::max);
    assert!(
        worst < 1e-9,
        "the last step misses the one-step move by {worst:e}"
    );
    let first = read_json(&dir.path().join("seq-000.json"));
    assert_eq!(first["movement"]["largest_displacement"], 0.0);
    for k in 1..=3 {
        let r = read_json(&dir.path().join(format!("seq-{k:03}.json")));
        assert_certified(&r);
        let turn = r["movement"]["motion"][0]["rigid"]["rotate_deg"]
            .as_f64()
            .unwrap();
        assert!((turn + 30.0 * k as f64).abs() < 1e-12, "{turn}");
    }
    // exactly a half turn of the body in its far field, as 179.999°
    for (name, deg) in [("half", "180"), ("almost", "179.999")] {
        let args = ["--rotate", deg, "--about", "0.25,0", "--order", "2"];
        let (outcome, r) = moved(dir.path(), name, "naca0012", &args);
        assert_eq!(outcome, Outcome::Valid, "{deg}: {}", r["problems"]);
        assert_certified(&r);
        assert_eq!(r["movement"]["inverted_linear_cells"], 0);
    }
}

/// The written P3 mesh at bump amplitude `a` (every node, linear and high-order).
fn bumped_p3(dir: &Path, name: &str, a: f64, extra: &[&str]) -> Vec<[f64; 3]> {
    let bump = format!("0.3,{a}");
    let mut args = vec![
        "--bump",
        &bump,
        "--bump",
        "0.6,-0.004,3,lower",
        "--order",
        "3",
    ];
    args.extend_from_slice(extra);
    let (outcome, _) = moved(dir, name, "naca0012", &args);
    assert_eq!(outcome, Outcome::Valid);
    mesh_io::read_msh(&dir.join(format!("{name}.msh")))
        .unwrap()
        .nodes
}

#[test]
fn the_sensitivities_file_is_the_derivative_of_the_written_p3_mesh() {
    let dir = tempfile::tempdir().unwrap();
    let csv = dir.path().join("s.csv");
    let (a, e) = (0.005, 1e-5);
    let at = bumped_p3(dir.path(), "at", a, &["--sensitivities", s(&csv)]);
    let plus = bumped_p3(dir.path(), "plus", a + e, &[]);
    let minus = bumped_p3(dir.path(), "minus", a - e, &[]);
    let text = std::fs::read_to_string(&csv).unwrap();
    let mut lines = text.lines();
    assert_eq!(
        lines.next().unwrap(),
        "node,x,y,d_naca0012.bump1_x,d_naca0012.bump1_y,d_naca0012.bump2_x,d_naca0012.bump2_y"
    );
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|v| v.parse().unwrap()).collect())
        .collect();
    assert_eq!(
        rows.len(),
        at.len(),
        "one line per node of the written mesh"
    );
    let (mut diff, mut norm) = (0.0, 0.0);
    for (k, row) in rows.iter().enumerate() {
        assert_eq!([row[1], row[2]], [at[k][0], at[k][1]], "node {k}");
        for c in 0..2 {
            let fd = (plus[k][c] - minus[k][c]) / (2.0 * e);
            diff += (row[3 + c] - fd).powi(2);
            norm += fd * fd;
        }
    }
    let relative = (diff / norm).sqrt();
    println!(
        "|dX/da| {:.4e}, sensitivities against central differences: {relative:.2e}",
        norm.sqrt()
    );
    assert!(relative < 1e-6, "{relative:e}");
    assert!(norm.sqrt() > 1.0, "the bump moves the mesh");
}

#[test]
fn sensitivities_need_the_spring_mover_and_a_csv_name() {
    let dir = tempfile::tempdir().unwrap();
    let e = run_move(
        dir.path(),
        "x",
        "naca0012",
        &[
            "--rotate",
            "5",
            "--method",
            "idw",
            "--sensitivities",
            "s.csv",
        ],
    )
    .unwrap_err();
    assert_one_line_naming(&format!("{e:#}"), &["--sensitivities", "springs"]);
    let e = run_move(
        dir.path(),
        "x",
        "naca0012",
        &["--rotate", "5", "--sensitivities", "s.txt"],
    )
    .unwrap_err();
    assert_one_line_naming(&format!("{e:#}"), &["--sensitivities", "csv"]);
    assert!(tree(dir.path()).is_empty(), "{:?}", tree(dir.path()));
}
