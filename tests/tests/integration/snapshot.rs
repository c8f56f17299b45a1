//! `--snapshot FILE.bin`: the intermediate stages are saved and load back as they were.

use end_to_end::xtask as run;

#[test]
fn snapshot_holds_the_stages_and_loads_back() {
    let dir = tempfile::tempdir().unwrap();
    let msh = dir.path().join("m.msh").to_str().unwrap().to_string();
    let bin = dir.path().join("m.bin").to_str().unwrap().to_string();
    run(&[
        "mesh",
        "bat",
        "--quiet",
        "--order",
        "1",
        "--out",
        &msh,
        "--snapshot",
        &bin,
    ])
    .unwrap();
    let stages: curvemesh::Snapshot = mesh_io::snapshot::load(std::path::Path::new(&bin)).unwrap();
    let written = mesh_io::read_msh(std::path::Path::new(&msh)).unwrap();
    assert_eq!(stages.case, "bat");
    assert_eq!(stages.layered.mesh.nodes, written.nodes);
    assert_eq!(stages.layered.mesh.cells, written.cells);
    assert_eq!(
        stages.layered.mesh.cell_layer.len(),
        stages.layered.mesh.cells.len()
    );
    assert_eq!(stages.layered.layering.check(&stages.layered.mesh), None);
    let boundary_nodes: usize = stages.boundary.iter().map(|b| b.points.len()).sum();
    assert_eq!(
        stages.layered.mesh.boundary.len(),
        boundary_nodes,
        "one facet per boundary node"
    );
}
