//! A wall read from an STL file is curved at P2 onto the smooth surface rebuilt from its
//! triangles (issue 47, item 3): an icosphere written as ASCII STL, meshed at order 2 through
//! the library, every cell certified, and its wall mid-edge nodes at least 5× nearer the true
//! sphere than the edges' midpoints (where they were when the wall was taken as flat).

use std::fmt::Write as _;

use geom_surface::Surface;
use mesh_model::Role;

/// The ASCII STL of `s`'s triangles.
fn ascii_stl(s: &Surface) -> String {
    let mut text = String::from("solid sphere\n");
    for f in &s.facets {
        let k = f.nodes();
        let n = geom_surface::unit(geom_surface::fan_normal(&s.nodes, k));
        writeln!(
            text,
            "  facet normal {:e} {:e} {:e}\n    outer loop",
            n[0], n[1], n[2]
        )
        .unwrap();
        for &v in k {
            let p = s.nodes[v as usize];
            writeln!(text, "      vertex {:e} {:e} {:e}", p[0], p[1], p[2]).unwrap();
        }
        text.push_str("    endloop\n  endfacet\n");
    }
    text.push_str("endsolid sphere\n");
    text
}

/// `s` written as `body.stl` beside a P2 case growing `layers` layers from it, meshed through
/// the library and checked valid (every cell certified): the P2 mesh.
fn mesh_stl_at_p2(s: &Surface, first_height: f64, layers: usize) -> mesh_model::Mesh {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("body.stl"), ascii_stl(s)).unwrap();
    let case_file = dir.path().join("stl-body.toml");
    std::fs::write(
        &case_file,
        format!(
            "dimension = 3\n\n[surface]\nfile = \"body.stl\"\n\n[layers]\n\
             first_height = {first_height:e}\ngrowth = 1.2\nmax_layers = {layers}\n\n\
             [cut]\ncells = \"mixed\"\n\n[curving]\norder = 2\n"
        ),
    )
    .unwrap();
    let case = curvemesh::load(case_file.to_str().unwrap()).unwrap();
    let options = curvemesh::Options::default();
    let meshed = curvemesh::mesh(&case, &options, &mut curvemesh::Silent).unwrap();
    assert!(meshed.report.is_valid(), "{:?}", meshed.report.problems);
    assert!(
        meshed
            .report
            .notes
            .iter()
            .any(|n| n.contains("smooth surface")),
        "{:?}",
        meshed.report.notes
    );
    assert_eq!(meshed.mesh.order, 2);
    meshed.mesh
}

/// Each wall triangle's three (edge midpoint, mid-edge node) pairs (Gmsh order: corners 0–2,
/// then edges 01, 12, 20).
fn wall_mid_nodes(m: &mesh_model::Mesh) -> Vec<([f64; 3], [f64; 3])> {
    let mut pairs = Vec::new();
    for (i, facet) in m.boundary.iter().enumerate() {
        if m.patches[m.boundary_patch[i] as usize].role != Role::Wall {
            continue;
        }
        let x = |j: usize| m.nodes[facet.nodes[j] as usize];
        for (e, [a, b]) in [[0, 1], [1, 2], [2, 0]].into_iter().enumerate() {
            let mid: [f64; 3] = std::array::from_fn(|d| 0.5 * (x(a)[d] + x(b)[d]));
            pairs.push((mid, x(3 + e)));
        }
    }
    pairs
}

#[test]
fn an_stl_sphere_gets_its_p2_wall_nodes_onto_the_smooth_surface() {
    // the sphere: the chords' midpoints 0.43 × the first height inside
    let sphere = Surface::sphere(1.0, 4);
    let m = mesh_stl_at_p2(&sphere, 2e-3, 6);
    let off = |p: [f64; 3]| (1.0 - (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt()).abs();
    let pairs = wall_mid_nodes(&m);
    assert_eq!(pairs.len(), 3 * sphere.facets.len());
    let flat = pairs.iter().map(|&(mid, _)| off(mid)).fold(0.0, f64::max);
    let smooth = pairs.iter().map(|&(_, node)| off(node)).fold(0.0, f64::max);
    println!("wall mid-edge nodes off the unit sphere: flat {flat:.3e}, smooth {smooth:.3e}");
    assert!(smooth * 5.0 < flat, "flat {flat:e}, smooth {smooth:e}");
}

#[test]
fn an_stl_cube_keeps_its_flat_faces_at_p2() {
    // sharp edges and flat faces: every mid-edge node stays at its edge's midpoint
    let m = mesh_stl_at_p2(&Surface::cube(1.0, 4, true), 1e-2, 4);
    for (mid, node) in wall_mid_nodes(&m) {
        let d = (0..3).map(|k| (mid[k] - node[k]).abs()).fold(0.0, f64::max);
        assert!(d < 1e-14, "{mid:?} went to {node:?}");
    }
}
