//! What the report and the summary say is about the mesh they name: the angle figures are
//! those of the linear mesh at every order, a `.su2` written at order 3 is reported as the
//! linear mesh it holds, and the worst scaled-Jacobian cell is located.

use std::path::Path;

use end_to_end::{Outcome, xtask_ok as run};
use serde_json::Value;

fn report(dir: &Path, name: &str, extra: &[&str]) -> Value {
    let json = dir.join(format!("{name}.json"));
    let msh = dir.join(format!("{name}.msh"));
    let mut args = vec![
        "mesh",
        "naca0012",
        "--quiet",
        "--out",
        msh.to_str().unwrap(),
        "--report",
        json.to_str().unwrap(),
    ];
    args.extend(extra);
    assert_eq!(run(&args), Outcome::Valid);
    serde_json::from_slice(&std::fs::read(json).unwrap()).unwrap()
}

#[test]
fn the_angle_figures_do_not_depend_on_the_order() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let runs = [
        report(d, "p1", &["--order", "1"]),
        report(d, "p2", &["--order", "2"]),
        report(d, "p3", &["--order", "3"]),
        report(d, "p1t", &["--order", "1", "--triangles"]),
        report(d, "p3t", &["--order", "3", "--triangles"]),
    ];
    let q0 = &runs[0]["quality"];
    assert!(q0["obtuse_hist"].as_array().unwrap().len() == 5);
    for r in &runs[1..] {
        let q = &r["quality"];
        assert_eq!(q["max_angle_deg"], q0["max_angle_deg"], "{q}");
        assert_eq!(q["obtuse_hist"], q0["obtuse_hist"], "{q} {}", r["order"]);
        assert!(q["angles_of"].as_str().unwrap().contains("linear mesh"));
    }
}

#[test]
fn an_su2_at_order_3_is_reported_as_the_linear_mesh_it_holds() {
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let (msh, su2, json) = (d.join("m.msh"), d.join("m.su2"), d.join("m.json"));
    let args = [
        "mesh",
        "naca0012",
        "--quiet",
        "--order",
        "3",
        "--out",
        msh.to_str().unwrap(),
        "--out",
        su2.to_str().unwrap(),
        "--report",
        json.to_str().unwrap(),
    ];
    assert_eq!(run(&args), Outcome::Valid);
    let r: Value = serde_json::from_slice(&std::fs::read(json).unwrap()).unwrap();
    let meshes = r["meshes"].as_array().unwrap();
    let order_of = |ext: &str| {
        meshes
            .iter()
            .find(|m| m["file"].as_str().unwrap().ends_with(ext))
            .map(|m| m["order"].as_u64().unwrap())
    };
    assert_eq!(order_of(".msh"), Some(3));
    assert_eq!(order_of(".su2"), Some(1));
    let notes = r["notes"].to_string();
    assert!(
        notes.contains("m.su2") && notes.contains("linear"),
        "{notes}"
    );
}

#[test]
fn one_case_makes_one_mesh() {
    // the fill's diagonal flips once ran in a HashMap's random order
    let dir = tempfile::tempdir().unwrap();
    let bytes: Vec<Vec<u8>> = (0..4)
        .map(|i| {
            let m = dir.path().join(format!("{i}.msh"));
            let args = ["mesh", "naca0012", "--quiet", "--order", "1", "--out"];
            let mut args = args.to_vec();
            args.push(m.to_str().unwrap());
            assert_eq!(run(&args), Outcome::Valid);
            std::fs::read(m).unwrap()
        })
        .collect();
    assert!(bytes.windows(2).all(|w| w[0] == w[1]));
}

#[test]
fn the_worst_cells_are_located_and_gmsh_min_sj_is_its_definition() {
    let dir = tempfile::tempdir().unwrap();
    let r = report(dir.path(), "p1", &["--order", "1"]);
    let mesh = mesh_io::read_msh(&dir.path().join("p1.msh")).unwrap();
    // Gmsh's minSJ of a linear cell: min det J / det J at the centre; for a bilinear quad the
    // corner determinants are the extremes and the centre's is their mean; 1 for a triangle
    let mut best = (f64::INFINITY, 0);
    for (i, c) in mesh.cells.iter().enumerate() {
        let k: Vec<[f64; 2]> = c.corners().iter().map(|&v| mesh.xy(v)).collect();
        let v = if k.len() == 4 {
            let det: Vec<f64> = (0..4)
                .map(|j| {
                    let (p, a, b) = (k[j], k[(j + 1) % 4], k[(j + 3) % 4]);
                    (a[0] - p[0]) * (b[1] - p[1]) - (a[1] - p[1]) * (b[0] - p[0])
                })
                .collect();
            det.iter().copied().fold(f64::INFINITY, f64::min) / (det.iter().sum::<f64>() / 4.0)
        } else {
            1.0
        };
        if v < best.0 {
            best = (v, i);
        }
    }
    let g = &r["quality"]["min_sj_gmsh"];
    assert!(
        (g["value"].as_f64().unwrap() - best.0).abs() < 1e-9,
        "{g} {best:?}"
    );
    assert_eq!(g["cell"].as_u64().unwrap() as usize, best.1);
    // the worst cell of our measure is named with its place: the mean of its corners
    let w = &r["quality"]["worst_cell"];
    let c = mesh.cells.get(w["cell"].as_u64().unwrap() as usize);
    let n = c.corners().len() as f64;
    let x: f64 = c.corners().iter().map(|&v| mesh.xy(v)[0]).sum::<f64>() / n;
    assert!((w["x"].as_f64().unwrap() - x).abs() < 1e-12, "{w}");
    assert_eq!(w["value"], r["quality"]["min_scaled_jacobian"]);
    assert!(
        r["quality"]["scaled_jacobian_of"]
            .as_str()
            .unwrap()
            .contains("min det J / max det J")
    );
}

#[test]
fn every_stage_of_the_run_is_timed() {
    let dir = tempfile::tempdir().unwrap();
    let r = report(dir.path(), "p3", &["--order", "3"]);
    let t = r["timings_s"].as_object().unwrap();
    for key in [
        "setup", "boundary", "linear", "curving", "describe", "validity", "write", "total",
    ] {
        assert!(t[key].as_f64().unwrap() >= 0.0, "timings_s.{key}");
    }
    // the stages fit in the whole run, the overlap counted once. (How much of the run goes
    // untimed is not asserted: that is a timing, and a loaded machine stretches the gaps
    // between stages; the keys above name every stage the run has.)
    let stages: f64 = t
        .iter()
        .filter(|(k, _)| k.as_str() != "total")
        .map(|(_, v)| v.as_f64().unwrap())
        .sum();
    let total = t["total"].as_f64().unwrap();
    // the mesh is written while the report describes and certifies it: those two overlap
    let (write, check) = (
        t["write"].as_f64().unwrap(),
        t["describe"].as_f64().unwrap() + t["validity"].as_f64().unwrap(),
    );
    let sequential = stages - write.min(check);
    assert!(sequential <= total, "{sequential} s of stages in {total} s");
}
