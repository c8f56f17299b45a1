//! `cargo xtask quality` on the 3D meshes `mesh` writes: each built-in 3D case (sphere, cube
//! and step at order 1, the sphere at order 2) read back is valid with the counts, the volume,
//! the volume its boundary encloses and the largest dihedral angle of `mesh`'s own report,
//! and at order 2 the same certified check; a slice is drawn from the read mesh; a mesh with
//! one tetrahedron turned inside out is written up as invalid with exit status 2.

use std::path::Path;

use curvemesh_cli::{exit, run};
use end_to_end::{
    Outcome, assert_one_line_naming, assert_problem, cli, read_json, run_into, s, xtask_ok,
};
use serde_json::Value;

fn quality(msh: &Path, json: &Path, rest: &[&str]) -> (Outcome, Value) {
    let args = [&["quality", s(msh), "--quiet", "--report", s(json)], rest].concat();
    let outcome = xtask_ok(&args);
    (outcome, read_json(json))
}

/// `a` and `b` within `rel` of each other.
fn near(a: &Value, b: &Value, rel: f64) -> bool {
    let (a, b) = (a.as_f64().unwrap(), b.as_f64().unwrap());
    (a - b).abs() <= rel * a.abs().max(b.abs())
}

#[test]
fn the_3d_builtins_read_back_are_valid_with_the_figures_of_their_run() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    for (case, order) in [
        ("sphere", "1"),
        ("cube", "1"),
        ("step", "1"),
        ("sphere", "2"),
    ] {
        let name = format!("{case}-p{order}");
        let outcome = run_into(d, &name, "mesh", case, &["--order", order]);
        assert_eq!(outcome.unwrap(), Outcome::Valid, "{name}");
        let made = read_json(&d.join(format!("{name}.json")));
        let msh = d.join(format!("{name}.msh"));
        let json = d.join(format!("{name}-quality.json"));
        let picture = d.join(format!("{name}.png"));
        let (outcome, read) = quality(&msh, &json, &["--png", s(&picture)]);
        assert_eq!(outcome, Outcome::Valid, "{name}: {:?}", read["problems"]);
        assert!(picture.is_file(), "{name}: a slice drawn");

        assert_eq!(read["dimension"], 3, "{name}");
        assert_eq!(read["order"], made["order"], "{name}");
        for key in ["nodes", "cells", "boundary_facets", "boundary_groups"] {
            assert_eq!(read[key], made[key], "{name}: {key}");
        }
        assert!(read["problems"].as_array().unwrap().is_empty(), "{name}");
        assert!(near(&read["volume"], &made["volume"], 1e-12), "{name}");
        let between = "between_wall_and_front";
        assert!(
            near(
                &read["volume_check"][between],
                &made["volume_check"][between],
                1e-12
            ),
            "{name}: {} vs {}",
            read["volume_check"],
            made["volume_check"]
        );
        let (q, m) = (&read["quality"], &made["quality"]);
        assert_eq!(q["max_dihedral_deg"], m["max_dihedral_deg"], "{name}");
        assert!(
            near(&q["min_cell_volume"], &m["min_cell_volume"], 1e-12),
            "{name}"
        );
        let sj = "min_corner_scaled_jacobian";
        assert_eq!(q[sj]["value"], m[sj]["value"], "{name}");
        // table 7 (the tetrahedra's dihedral angles) is the mesh's; 5 and 6 need the growth
        let table_7 = |r: &Value| {
            r["histograms"]
                .as_array()
                .unwrap()
                .iter()
                .find(|h| h["name"] == "tet max dihedral")
                .cloned()
                .unwrap()
        };
        assert_eq!(table_7(q), table_7(m), "{name}");
        assert_eq!(q["histograms"].as_array().unwrap().len(), 1, "{name}");
        assert!(read.get("coverage").is_none() && read.get("layers").is_none());
        if order == "2" {
            for key in ["min_scaled_jacobian", "invalid_cells", "certified"] {
                assert_eq!(q[key], m[key], "{name}: {key}");
            }
            assert_eq!(q["certified"], true);
            let f = read["curved_edge_fraction"].as_f64().unwrap();
            assert!(
                f > 0.0 && f < 1.0,
                "{name}: the sphere's edges are curved: {f}"
            );
        } else {
            assert!(q.get("min_scaled_jacobian").is_none(), "{name}: P1 as mesh");
        }
    }
}

#[test]
fn a_tetrahedron_turned_inside_out_fails_with_exit_2() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    // the step has tetrahedra (its mixed cut round the concave edges)
    assert_eq!(
        run_into(d, "step", "mesh", "step", &["--order", "1"]).unwrap(),
        Outcome::Valid
    );
    let text = std::fs::read_to_string(d.join("step.msh")).unwrap();
    let bad = swap_first_tet(&text);
    let msh = d.join("bad.msh");
    std::fs::write(&msh, bad).unwrap();
    let (outcome, report) = quality(&msh, &d.join("bad.json"), &[]);
    assert_eq!(outcome, Outcome::Invalid, "exit status 2");
    assert_problem(&report, "inverted or degenerate at its corner");
    assert_problem(&report, "the cell volumes sum to");
    // exit 2 with one line naming the cell
    let end = exit::of_run(&run(cli(&["quality", s(&msh), "--quiet"])));
    assert_eq!(end.code, 2);
    let line = end.stderr.expect("a line on stderr");
    assert_one_line_naming(
        &line,
        &["bad.msh", "failed validation", "inverted", "cell "],
    );
}

/// The `.msh` text with the second and third nodes of its first linear tetrahedron (Gmsh
/// element type 4) swapped: the cell turned inside out, its faces still those of its
/// neighbours.
fn swap_first_tet(text: &str) -> String {
    let mut lines: Vec<String> = text.lines().map(String::from).collect();
    let start = lines.iter().position(|l| l == "$Elements").unwrap() + 2;
    let mut i = start;
    loop {
        // an entity block: dimension, entity tag, element type, count
        let head: Vec<usize> = lines[i]
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect();
        if head[2] == 4 {
            let mut tet: Vec<&str> = lines[i + 1].split_whitespace().collect();
            tet.swap(2, 3);
            lines[i + 1] = tet.join(" ");
            return lines.join("\n") + "\n";
        }
        i += head[3] + 1;
    }
}
