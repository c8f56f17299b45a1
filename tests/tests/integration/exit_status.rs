//! What the binary prints and returns, through the very functions `main.rs` calls
//! (`xtask::exit`): usage errors exit 1 with one line (not clap's 2 with several), `--help` and
//! `--version` print as usual, negative numbers parse in list values, and a mesh that fails
//! validation exits 2 with one line naming the first problem and the report — found by the
//! certified check even when the structural check fails too.

use clap::Parser;
use curvemesh_cli::cli::{Cli, Command};
use curvemesh_cli::exit::{self, Exit};
use curvemesh_cli::{Outcome, run};
use end_to_end::{assert_one_line_naming, assert_problem, cli, read_json, s};

fn usage(args: &[&str]) -> Option<Exit> {
    let mut all = vec!["cargo xtask"];
    all.extend(args);
    let err = Cli::try_parse_from(&all).expect_err("clap refuses these flags");
    exit::of_usage_error(&err)
}

fn one_line_error(e: &Exit, code: u8, words: &[&str]) {
    assert_eq!(e.code, code, "{e:?}");
    let line = e.stderr.as_deref().expect("a line on stderr");
    assert!(line.starts_with("error: "), "{line}");
    assert_one_line_naming(line, words);
}

#[test]
fn usage_errors_exit_1_with_one_line() {
    let cases: [(&[&str], &[&str]); 7] = [
        (&["mesh", "--order", "4"], &["--order", "4"]),
        (&["mesh", "--frobnicate"], &["--frobnicate"]),
        (&["mesh", "--width", "3"], &["--width", "3"]),
        (&["mesh", "--colour", "pink"], &["pink", "layer"]),
        (&["quality"], &["<MESH>"]),
        (&["nonsense"], &["nonsense"]),
        (&[], &["no command", "mesh"]),
    ];
    for (args, words) in cases {
        let e = usage(args).unwrap_or_else(|| panic!("{args:?} is an error"));
        one_line_error(&e, 1, words);
    }
}

#[test]
fn help_and_version_are_not_errors() {
    for args in [
        &["--help"][..],
        &["--version"],
        &["mesh", "--help"],
        &["help"],
    ] {
        assert_eq!(usage(args), None, "{args:?}");
    }
}

#[test]
fn negative_numbers_parse_in_views() {
    let cli = Cli::try_parse_from([
        "cargo xtask",
        "mesh",
        "--view",
        "-0.1,-0.15,0.1,0.05",
        "--png",
        "out/a.png@-0.1,-0.1,0.1,0.1",
        "--svg",
        "-b.svg@-1,-1,1,1",
    ])
    .expect("negative numbers are values");
    let Command::Mesh(m) = cli.command else {
        panic!("mesh")
    };
    assert_eq!(m.pictures.view.as_deref(), Some("-0.1,-0.15,0.1,0.05"));
    assert_eq!(m.pictures.pngs, vec!["out/a.png@-0.1,-0.1,0.1,0.1"]);
    assert_eq!(m.pictures.svgs, vec!["-b.svg@-1,-1,1,1"]);
}

#[test]
fn a_negative_view_draws() {
    let dir = tempfile::tempdir().unwrap();
    let png = dir.path().join("a.png");
    let png_arg = format!("{}@-0.1,-0.1,0.1,0.1", png.display());
    let msh = dir.path().join("m.msh");
    let args = [
        "mesh",
        "lshape",
        "--quiet",
        "--order",
        "1",
        "--out",
        s(&msh),
    ];
    let end = exit::of_run(&run(cli(&[
        &args[..],
        &["--png", &png_arg, "--width", "128"],
    ]
    .concat())));
    assert_eq!(
        end,
        Exit {
            code: 0,
            stderr: None
        }
    );
    assert!(png.exists());
}

#[test]
fn bad_input_is_one_bounded_line() {
    let e = exit::of_run(&Err(anyhow::anyhow!("line 1\nline 2 {}", "x".repeat(5000))));
    one_line_error(&e, 1, &["line 1\\nline 2", "more characters"]);
    assert!(e.stderr.unwrap().chars().count() < exit::MAX_LINE + 60);
}

/// A P1 mesh (the test kit's annulus) with cell 0 turned inside out by reversing its nodes.
fn mesh_with_a_reversed_cell(dir: &std::path::Path) -> std::path::PathBuf {
    let mut m = mesh_io::testkit::annulus(&mesh_io::testkit::AnnulusParams::default());
    let nodes: Vec<u32> = m.cells.get(0).nodes.to_vec();
    let ty = m.cells.get(0).ty;
    let mut cells = mesh_model::Cells::default();
    for (i, c) in m.cells.iter().enumerate() {
        if i == 0 {
            let mut rev = nodes.clone();
            rev.reverse();
            cells.push(ty, &rev);
        } else {
            cells.push(c.ty, c.nodes);
        }
    }
    m.cells = cells;
    let msh = dir.join("bad.msh");
    mesh_io::write(&msh, &m).unwrap();
    msh
}

#[test]
fn an_invalid_mesh_exits_2_with_one_line_and_is_certified_anyway() {
    let dir = tempfile::tempdir().unwrap();
    let msh = mesh_with_a_reversed_cell(dir.path());
    let json = dir.path().join("bad.json");
    let result = run(cli(&["quality", s(&msh), "--quiet", "--report", s(&json)]));
    assert_eq!(result.as_ref().unwrap().outcome, Outcome::Invalid);
    let e = exit::of_run(&result);
    one_line_error(
        &e,
        2,
        &[
            "bad.msh failed validation",
            "not positively oriented",
            "bad.json",
        ],
    );
    // the structural problem no longer hides the certified check
    let report = read_json(&json);
    assert_eq!(
        report["quality"]["invalid_cells"].as_u64(),
        Some(1),
        "{report}"
    );
    assert!(report["quality"]["max_angle_deg"].as_f64().unwrap() > 0.0);
    assert_problem(
        &report,
        "1 cells invalid by the certified Jacobian check (first: 0;",
    );
}
