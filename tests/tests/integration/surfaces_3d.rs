//! Bodies no case was tuned for (issue 47; `fixtures/surfaces/make.py` made them with Gmsh's
//! OpenCASCADE kernel): a swept, tapered wing with flat tips and a sharp trailing edge, a
//! capsule with a thin plate fin, a torus, two fused spheres, a box with a tower and two
//! spheres 0.1 apart, each grown at the default keys with 15 layers from 2e-3 (growth 1.2,
//! `fixtures/cases3d/`). Where a column cannot take its next layer it stops, and the rest
//! grow on: every run is valid (conforming, every cell positive by the exact corner test,
//! the volumes balanced), read back valid by `quality`, and reports its coverage, the least
//! layers per boundary group and where columns stopped and why; below `[layers]
//! min_coverage` the run stops with one line naming where and why. No built-in 3D case sets an
//! expert key.

use std::path::{Path, PathBuf};

use curvemesh_cli::exit::{self, Exit};
use end_to_end::{Outcome, assert_one_line_naming, cli, read_json, run_into, s, xtask_ok};
use serde_json::Value;

/// The case file of fixture body `name`.
fn fixture(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join(format!("../fixtures/cases3d/{name}.toml"))
}

/// A copy of fixture body `name`'s case in `dir` with `extra` appended (its surface named by
/// its full path).
fn variant(dir: &Path, name: &str, extra: &str) -> PathBuf {
    let stl = Path::new(env!("CARGO_MANIFEST_DIR")).join("../fixtures/surfaces");
    let text = std::fs::read_to_string(fixture(name))
        .unwrap()
        .replace("../surfaces", s(&stl));
    let path = dir.join(format!("{name}.toml"));
    std::fs::write(&path, format!("{text}\n{extra}\n")).unwrap();
    path
}

/// Meshes `case` into `dir` as `name` with `rest`, which must be valid; its report, and the
/// mesh read back by `quality` must be valid too.
fn meshed(dir: &Path, name: &str, case: &Path, rest: &[&str]) -> Value {
    let outcome = run_into(dir, name, "mesh", s(case), rest).unwrap();
    let report = read_json(&dir.join(format!("{name}.json")));
    assert_eq!(outcome, Outcome::Valid, "{name}: {:?}", report["problems"]);
    let msh = dir.join(format!("{name}.msh"));
    let json = dir.join(format!("{name}-read.json"));
    let read = xtask_ok(&["quality", s(&msh), "--quiet", "--report", s(&json)]);
    assert_eq!(read, Outcome::Valid, "{name}: read back");
    report
}

/// The report's columns: coverage at least `floor`, the same as the top-level `coverage`, the
/// least layers per group between `least` and 15, every stopped column listed with its layer,
/// why and where; returns how many stopped.
fn check_columns(name: &str, r: &Value, floor: f64, least: u64) -> u64 {
    let c = &r["columns"];
    let coverage = c["coverage"].as_f64().unwrap();
    assert!(coverage >= floor, "{name}: coverage {coverage}");
    assert_eq!(r["coverage"], c["coverage"], "{name}");
    assert_eq!(c["min_coverage"], 0.9, "{name}");
    let groups = c["least_layers"].as_object().unwrap();
    assert!(!groups.is_empty(), "{name}");
    for (g, n) in groups {
        let n = n.as_u64().unwrap();
        assert!((least..=15).contains(&n), "{name}: {g} keeps {n} layers");
    }
    let (wall, full) = (
        c["wall_nodes"].as_u64().unwrap(),
        c["full"].as_u64().unwrap(),
    );
    assert!(
        (coverage - full as f64 / wall as f64).abs() < 1e-12,
        "{name}"
    );
    let stopped = wall - full;
    let by_why: u64 = c["stopped_by_why"]
        .as_object()
        .unwrap()
        .values()
        .map(|v| v.as_u64().unwrap())
        .sum();
    assert_eq!(by_why, stopped, "{name}");
    let listed = c["first_stopped"].as_array().unwrap();
    assert_eq!(listed.len() as u64, stopped.min(10), "{name}");
    for l in listed {
        assert!(l["layer"].as_u64().unwrap() < 15, "{name}: {l}");
        assert!(!l["why"].as_str().unwrap().is_empty(), "{name}: {l}");
        assert_eq!(l["at"].as_array().unwrap().len(), 3, "{name}: {l}");
    }
    stopped
}

#[test]
fn every_untuned_body_grows_at_the_default_keys() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // (body, least layers of any group, whether some columns stop)
    let bodies = [
        ("swept-wing", 8, true),
        ("capsule-fin", 10, true),
        ("torus", 15, false),
        ("fused-spheres", 15, false),
        ("box-tower", 12, true),
        ("two-spheres", 10, true),
    ];
    for (name, least, stops) in bodies {
        let start = std::time::Instant::now();
        let r = meshed(d, name, &fixture(name), &["--order", "1"]);
        let stopped = check_columns(name, &r, 0.95, least);
        // the swept wing's 16° trailing edge grows fans (three columns or more per node)
        let fans = &r["columns"];
        let (nodes, columns) = (fans["fanned_nodes"].as_u64(), fans["fan_columns"].as_u64());
        if name == "swept-wing" {
            assert!(
                nodes.unwrap() > 0 && columns.unwrap() >= 2 * nodes.unwrap(),
                "{fans}"
            );
        }
        assert_eq!(stopped > 0, stops, "{name}: {stopped} columns stopped");
        assert_eq!(r["problems"].as_array().unwrap().len(), 0, "{name}");
        // the mixed cut's prisms keep the default corner floor, 0.2; on the smooth bodies,
        // issue 47's 0.5 where the wall allows it (a prism's corner is at most its wall
        // triangle's corner sine: 0.63 on the torus, 0.50 on the fused spheres, 0.45 on the
        // two spheres), kept by the reshaping of the fronts (torus 0.56, fused spheres 0.45;
        // 0.37 and 0.21 without)
        let floor = match name {
            "torus" => 0.5,
            "fused-spheres" | "two-spheres" => 0.4,
            _ => 0.2,
        };
        let sj = &r["quality"]["min_corner_scaled_jacobian"]["value"];
        assert!(sj.as_f64().unwrap() >= floor, "{name}: {sj}");
        let worst = r["quality"]["max_dihedral_deg"].as_f64().unwrap();
        assert!(worst <= MAX_DIHEDRAL_DEG, "{name}: {worst}");
        let note = r["notes"].as_array().unwrap().iter();
        let noted = note
            .filter_map(Value::as_str)
            .any(|n| n.contains("columns stopped"));
        assert_eq!(noted, stops, "{name}");
        eprintln!(
            "{name}: coverage {}, least layers {}, cells {}, {:.1} s",
            r["columns"]["coverage"],
            r["columns"]["least_layers"],
            r["cells"],
            start.elapsed().as_secs_f64()
        );
    }
}

/// The bar on every tetrahedron: a largest dihedral angle of 160°.
const MAX_DIHEDRAL_DEG: f64 = 160.0;

#[test]
fn the_untuned_bodies_cut_into_tetrahedra_under_160_degrees() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for name in ["swept-wing", "capsule-fin", "box-tower", "two-spheres"] {
        let case = variant(d, name, "[cut]\ncells = \"tets\"");
        let r = meshed(d, &format!("{name}-tets"), &case, &["--order", "1"]);
        check_columns(name, &r, 0.95, 8);
        let worst = r["quality"]["max_dihedral_deg"].as_f64().unwrap();
        assert!(worst <= MAX_DIHEDRAL_DEG, "{name}: {worst}");
        eprintln!(
            "{name} tets: {} cells, max dihedral {worst:.1}°",
            r["cells"]
        );
    }
}

/// The prism cut (`[cut] cells = "prisms"`, no pyramid for PyFR): the smooth bodies keep
/// every prism at the mixed cut's corners; where every layer has a cell to cut (the swept
/// wing) no prism is kept and the layers are grown again unreshaped, as for the tetrahedral
/// cut, its tetrahedra under the bar.
#[test]
fn the_untuned_bodies_cut_into_prisms_have_no_pyramid() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (name, floor) in [("torus", 0.5), ("fused-spheres", 0.4), ("swept-wing", 0.0)] {
        let case = variant(d, name, "[cut]\ncells = \"prisms\"");
        let r = meshed(d, &format!("{name}-prisms"), &case, &["--order", "1"]);
        let cells = &r["cells"];
        assert_eq!(
            (&cells["pyramid"], &cells["hex"]),
            (&0.into(), &0.into()),
            "{name}"
        );
        let regrown = r["notes"]
            .as_array()
            .unwrap()
            .iter()
            .filter_map(Value::as_str)
            .any(|n| n.contains("kept no prism"));
        if floor > 0.0 {
            assert_eq!(cells["tet"], 0, "{name}: {cells}");
            let sj = &r["quality"]["min_corner_scaled_jacobian"]["value"];
            assert!(sj.as_f64().unwrap() >= floor, "{name}: {sj}");
            assert!(!regrown, "{name}");
        } else {
            assert_eq!(cells["prism"], 0, "{name}: {cells}");
            assert!(regrown, "{name}: {:?}", r["notes"]);
        }
        let worst = r["quality"]["max_dihedral_deg"].as_f64().unwrap_or(0.0);
        assert!(worst <= MAX_DIHEDRAL_DEG, "{name}: {worst}");
        eprintln!("{name} prisms: {cells}, max dihedral {worst:.1}°");
    }
}

#[test]
fn every_untuned_body_curves_to_p2_with_every_cell_certified() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let bodies = [
        "swept-wing",
        "capsule-fin",
        "torus",
        "fused-spheres",
        "box-tower",
        "two-spheres",
    ];
    for name in bodies {
        let r = meshed(d, &format!("{name}-p2"), &fixture(name), &["--order", "2"]);
        check_columns(name, &r, 0.95, 8);
        assert_eq!(r["order"], 2, "{name}");
        assert_eq!(r["quality"]["certified"], true, "{name}: {}", r["quality"]);
    }
}

#[test]
fn coverage_below_min_coverage_stops_the_run_naming_where_and_why() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let case = variant(d, "two-spheres", "# not every column\n");
    let text = std::fs::read_to_string(&case)
        .unwrap()
        .replace("max_layers = 15", "max_layers = 15\nmin_coverage = 0.999");
    std::fs::write(&case, text).unwrap();
    let out = d.join("x.msh");
    let end = exit::of_run(&curvemesh_cli::run(cli(&[
        "mesh",
        s(&case),
        "--quiet",
        "--out",
        s(&out),
    ])));
    let Exit { code, stderr } = end;
    let line = stderr.expect("a line on stderr");
    assert_eq!(code, 1, "{line}");
    assert_one_line_naming(
        &line,
        &["coverage", "min_coverage = 0.999", "layer", "front crosses"],
    );
    assert!(!out.exists(), "{line}");
}

#[test]
fn no_built_in_3d_case_sets_an_expert_key() {
    let expert = [
        "max_aspect",
        "merge_rows",
        "stand_off",
        "smoothing",
        "min_coverage",
        "max_lean_deg",
        "min_corner_sj",
    ];
    for name in curvemesh::builtin::names_3d() {
        let text = curvemesh::builtin::case_text(name).unwrap();
        for line in text.lines().map(str::trim_start) {
            let key = line.split('=').next().unwrap_or("").trim();
            assert!(!expert.contains(&key), "{name}: {line}");
        }
    }
}
