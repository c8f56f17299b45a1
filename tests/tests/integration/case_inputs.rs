//! One set of inputs, either way in: a case file takes what airfoil files take on the command
//! line (`aoa`, `farfield` in chords, `[layers] yplus` and `re`), the airfoil route takes the
//! layers' keys (`--first-height`, `--growth`, `--layers`), both give the same mesh of the same
//! inputs, and the report echoes the inputs the run used.

use std::path::{Path, PathBuf};

use end_to_end::{Outcome, assert_one_line_naming, read_json, s, xtask};

fn fixture(rel: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../fixtures/geometry")
        .join(rel)
}

/// Meshes `args` at P1 into `dir/NAME.msh` and `.json`; the mesh's file and the report.
fn mesh(dir: &Path, name: &str, args: &[&str]) -> anyhow::Result<(Vec<u8>, serde_json::Value)> {
    let (msh, json) = (
        dir.join(format!("{name}.msh")),
        dir.join(format!("{name}.json")),
    );
    let mut all = vec!["mesh", "--quiet", "--order", "1"];
    all.extend(args);
    all.extend(["--out", s(&msh), "--report", s(&json)]);
    assert_eq!(xtask(&all)?, Outcome::Valid);
    Ok((std::fs::read(&msh)?, read_json(&json)))
}

/// A case file of the NACA 0012 fixture with the top-level and `[layers]` lines given.
fn case_file(dir: &Path, name: &str, top: &str, layers: &str) -> PathBuf {
    let path = dir.join(format!("{name}.toml"));
    let text = format!(
        "{top}\n[[loop]]\nrole = \"wall\"\nfile = \"{}\"\n[layers]\n{layers}\n",
        fixture("naca0012.dat").display()
    );
    std::fs::write(&path, text).unwrap();
    path
}

#[test]
fn a_case_file_and_an_airfoil_file_give_the_same_mesh_of_the_same_inputs() {
    let dir = tempfile::tempdir().unwrap();
    let dat = fixture("naca0012.dat");
    let (by_flags, flags_report) = mesh(
        dir.path(),
        "flags",
        &[
            s(&dat),
            "--aoa",
            "4",
            "--yplus",
            "2",
            "--re",
            "3e6",
            "--farfield",
            "25",
        ],
    )
    .unwrap();
    let case = case_file(
        dir.path(),
        "keys",
        "aoa = 4.0\nfarfield = 25.0",
        "yplus = 2.0\nre = 3e6",
    );
    let (by_keys, keys_report) = mesh(dir.path(), "keys", &[s(&case)]).unwrap();
    assert!(by_flags == by_keys, "the two routes wrote different meshes");
    let inputs = &keys_report["inputs"];
    assert_eq!(inputs, &flags_report["inputs"]);
    assert_eq!(inputs["aoa_deg"], 4.0);
    assert_eq!(inputs["yplus"], 2.0);
    assert_eq!(inputs["re"], 3e6);
    assert_eq!(inputs["farfield_chords"], 25.0);
    let h = inputs["first_height"].as_f64().unwrap();
    let want = curvemesh::airfoil::first_height(2.0, 3e6, 1.0);
    assert!((h - want).abs() <= 1e-12 * want, "{h} against {want}");
}

#[test]
fn the_airfoil_route_takes_the_layers_keys() {
    let dir = tempfile::tempdir().unwrap();
    let dat = fixture("naca0012.dat");
    let args = [
        s(&dat),
        "--first-height",
        "2e-4",
        "--growth",
        "1.25",
        "--layers",
        "20",
    ];
    let (by_flags, report) = mesh(dir.path(), "flags", &args).unwrap();
    let inputs = &report["inputs"];
    assert_eq!(inputs["first_height"], 2e-4);
    assert_eq!(inputs["growth"], 1.25);
    assert_eq!(inputs["max_layers"], 20);
    assert!(inputs.get("yplus").is_none(), "{inputs}");
    let layers = "first_height = 2e-4\ngrowth = 1.25\nmax_layers = 20";
    let case = case_file(dir.path(), "keys", "farfield = 30.0", layers);
    let (by_keys, _) = mesh(dir.path(), "keys", &[s(&case)]).unwrap();
    assert!(by_flags == by_keys, "the two routes wrote different meshes");
}

#[test]
fn conflicting_or_bad_inputs_are_refused_on_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let dat = fixture("naca0012.dat");
    let bad_case = |name: &str, top: &str, layers: &str| {
        let case = case_file(dir.path(), name, top, layers);
        let e = mesh(dir.path(), name, &[s(&case)]).expect_err("refused");
        format!("{e:#}")
    };
    let msg = bad_case(
        "both",
        "farfield = 30.0",
        "first_height = 1e-5\nyplus = 1.0",
    );
    assert_one_line_naming(&msg, &["first_height and yplus/re both"]);
    let msg = bad_case("aoa", "aoa = 120.0\nfarfield = 30.0", "");
    assert_one_line_naming(&msg, &["aoa = 120", "[-90, 90]"]);
    let msg = bad_case("no-farfield", "", "yplus = 1.0");
    assert_one_line_naming(&msg, &["exactly one farfield loop"]);
    let msg = bad_case("re", "farfield = 30.0", "re = 10.0");
    assert_one_line_naming(&msg, &["re = 10", "at least 1e3"]);
    for (flags, words) in [
        (&["--yplus", "-1"][..], &["--yplus -1", "positive"][..]),
        (&["--growth", "0.5"], &["--growth 0.5"]),
        (&["--first-height", "1e-5", "--yplus", "2"], &["not both"]),
    ] {
        let mut args = vec![s(&dat)];
        args.extend(flags);
        let e = mesh(dir.path(), "flags", &args).expect_err("refused");
        assert_one_line_naming(&format!("{e:#}"), words);
    }
}
