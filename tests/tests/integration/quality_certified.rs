//! `cargo xtask quality` certifies every cell of a high-order `.msh`: a valid curved mesh
//! passes, and a mesh with one folded P2 cell is written up as invalid with exit status 2.

use end_to_end::{Outcome, assert_problem, read_json, s, xtask_ok};

fn quality(msh: &std::path::Path, json: &std::path::Path) -> (Outcome, serde_json::Value) {
    let outcome = xtask_ok(&["quality", s(msh), "--quiet", "--report", s(json)]);
    (outcome, read_json(json))
}

#[test]
fn a_folded_cell_is_found_and_named() {
    let dir = tempfile::tempdir().unwrap();
    let params = mesh_io::testkit::AnnulusParams {
        order: 2,
        ..Default::default()
    };
    let good = mesh_io::testkit::annulus(&params);
    let msh = dir.path().join("good.msh");
    mesh_io::write(&msh, &good).unwrap();
    let (outcome, report) = quality(&msh, &dir.path().join("good.json"));
    assert_eq!(outcome, Outcome::Valid);
    assert_eq!(report["quality"]["invalid_cells"].as_u64(), Some(0));
    assert_eq!(report["quality"]["certified"].as_bool(), Some(true));
    let f = report["curved_edge_fraction"].as_f64().unwrap();
    assert!(f > 0.0 && f < 1.0, "the circular edges are curved: {f}");

    // push the mid-edge node of the first cell's first edge across the cell: it folds, yet
    // every corner stays where it was (a linear check would see nothing)
    let mut bad = good.clone();
    let cell = bad.cells.get(0);
    let (a, b, mid) = (cell.nodes[0], cell.nodes[1], cell.nodes[4]);
    let (xa, xb) = (bad.xy(a), bad.xy(b));
    let c = bad.xy(cell.nodes[2]);
    let m = &mut bad.nodes[mid as usize];
    let pull = [c[0] - 0.5 * (xa[0] + xb[0]), c[1] - 0.5 * (xa[1] + xb[1])];
    m[0] += 1.5 * pull[0];
    m[1] += 1.5 * pull[1];
    let msh = dir.path().join("bad.msh");
    mesh_io::write(&msh, &bad).unwrap();
    let (outcome, report) = quality(&msh, &dir.path().join("bad.json"));
    assert_eq!(outcome, Outcome::Invalid, "exit status 2");
    assert!(report["quality"]["invalid_cells"].as_u64().unwrap() >= 1);
    assert_problem(&report, "invalid by the certified Jacobian check");
}
