//! A 3D `.su2`: one cell of each type (tetrahedron, pyramid, prism, hexahedron), each with its
//! faces as boundary facets in two markers, written and read back as text. Every cell must be
//! positive as SU2 reads it — judged from the written corner order alone, by the volume its
//! outward faces enclose (SU2's face tables) and by the corner tetrahedra SU2's
//! `Check_IntElem_Orientation` tests — and every facet turned into its cell, as SU2's
//! `Check_BoundElem_Orientation` wants. At order 2 the file is the linear mesh's.

use std::path::Path;

use mesh_model::{CellType, Dim, Mesh, Patch, Role, Shape};
use testkit::su2::{orientation_tests, tet6};

/// The four cells, apart, each a sheared copy of Gmsh's reference cell; their outward faces
/// (`Shape::faces`) as boundary facets: the tetrahedron's and the hexahedron's in a wall
/// patch `body`, the others' in the far field.
fn mixed() -> Mesh {
    let mut m = Mesh::new(Dim::Three, 1);
    m.patches = vec![
        Patch {
            name: "body".into(),
            role: Role::Wall,
        },
        Patch {
            name: "box".into(),
            role: Role::Farfield,
        },
    ];
    let shapes = [Shape::Tet, Shape::Pyramid, Shape::Prism, Shape::Hex];
    for (k, shape) in shapes.into_iter().enumerate() {
        let first = m.nodes.len() as u32;
        for p in mesh_model::reference::corners(shape) {
            // a shear of positive determinant (1 × 1.1 × 0.9), then apart along x
            let [x, y, z] = *p;
            m.nodes.push([
                x + 0.2 * y + 0.1 * z + 4.0 * k as f64,
                1.1 * y + 0.3 * z,
                0.9 * z - 0.05 * x,
            ]);
        }
        let nodes: Vec<u32> = (first..m.nodes.len() as u32).collect();
        m.cells.push(CellType::new(shape, 1), &nodes);
        let patch = u32::from(matches!(shape, Shape::Pyramid | Shape::Prism));
        for f in shape.faces() {
            let facet = if f.len() == 3 {
                Shape::Tri
            } else {
                Shape::Quad
            };
            let k: Vec<u32> = f.iter().map(|&j| nodes[j]).collect();
            m.boundary.push(CellType::new(facet, 1), &k);
            m.boundary_patch.push(patch);
        }
    }
    assert_eq!(mesh_model::validate(&m), vec![], "the test mesh is sound");
    m
}

/// `mesh` of order 2: every cell and facet gets its complete P2 node count, the nodes past
/// the corners new (where they sit does not matter to a linear writer).
fn order_2(mesh: &Mesh) -> Mesh {
    let mut m = mesh.clone();
    m.order = 2;
    let mut nodes = m.nodes.clone();
    let lift = |cells: &mesh_model::Cells, nodes: &mut Vec<[f64; 3]>| {
        let mut out = mesh_model::Cells::new();
        for c in cells.iter() {
            let ty = CellType::new(c.ty.shape, 2);
            let mut k = c.nodes.to_vec();
            while k.len() < ty.node_count() {
                k.push(nodes.len() as u32);
                nodes.push(mesh.nodes[c.nodes[0] as usize]);
            }
            out.push(ty, &k);
        }
        out
    };
    m.cells = lift(&mesh.cells, &mut nodes);
    m.boundary = lift(&mesh.boundary, &mut nodes);
    m.nodes = nodes;
    m
}

fn su2(mesh: &Mesh) -> String {
    let mut out = Vec::new();
    mesh_io::su2::write_to(&mut out, mesh, Path::new("mixed.su2")).unwrap();
    String::from_utf8(out).unwrap()
}

/// The numbers on the lines after `KEY= n`: the n lines.
fn block(text: &str, key: &str) -> Vec<Vec<f64>> {
    let mut lines = text.lines();
    let n: usize = lines
        .by_ref()
        .find_map(|l| l.strip_prefix(key))
        .unwrap_or_else(|| panic!("no {key}"))
        .trim()
        .parse()
        .unwrap();
    lines
        .take(n)
        .map(|l| l.split_whitespace().map(|t| t.parse().unwrap()).collect())
        .collect()
}

/// SU2's faces of its cells, each outward by the right-hand rule (the `Faces` of
/// `CTetrahedronConnectivity`, `CPyramidConnectivity`, `CPrismConnectivity`,
/// `CHexahedronConnectivity`, up to where each face's cycle starts), by VTK type. They are
/// VTK's faces too, but for the prism: VTK 9.7's `vtkWedge` is SU2's mirror image.
fn su2_faces(ty: u8) -> &'static [&'static [usize]] {
    match ty {
        10 => &[&[0, 1, 3], &[1, 2, 3], &[2, 0, 3], &[0, 2, 1]],
        14 => &[
            &[0, 3, 2, 1],
            &[0, 1, 4],
            &[1, 2, 4],
            &[2, 3, 4],
            &[3, 0, 4],
        ],
        13 => &[
            &[0, 1, 2],
            &[3, 5, 4],
            &[0, 3, 4, 1],
            &[1, 4, 5, 2],
            &[2, 5, 3, 0],
        ],
        12 => &[
            &[0, 4, 7, 3],
            &[1, 2, 6, 5],
            &[0, 1, 5, 4],
            &[3, 7, 6, 2],
            &[0, 3, 2, 1],
            &[4, 5, 6, 7],
        ],
        _ => panic!("no VTK cell {ty}"),
    }
}

/// The volume of a cell of VTK type `ty` with corners `x` in SU2's order: the divergence
/// theorem over its outward faces (each fanned from its centroid); negative when the order
/// is SU2's mirror image.
fn su2_volume(ty: u8, x: &[[f64; 3]]) -> f64 {
    let o = x[0];
    let mut sum = 0.0;
    for f in su2_faces(ty) {
        let n = f.len() as f64;
        let c = [0, 1, 2].map(|d| f.iter().map(|&j| x[j][d]).sum::<f64>() / n);
        for i in 0..f.len() {
            sum += tet6(o, c, x[f[i]], x[f[(i + 1) % f.len()]]);
        }
    }
    sum / 6.0
}

#[test]
fn every_cell_of_a_mixed_3d_mesh_is_positive_as_su2_reads_it() {
    let mesh = mixed();
    let text = su2(&mesh);
    assert!(text.starts_with("NDIME= 3\n"), "{text}");
    let points: Vec<[f64; 3]> = block(&text, "NPOIN=")
        .iter()
        .map(|p| {
            assert_eq!(p.len(), 4, "x y z index: {p:?}");
            [p[0], p[1], p[2]]
        })
        .collect();
    assert_eq!(points.len(), mesh.nodes.len());
    let cells = block(&text, "NELEM=");
    let types: Vec<u8> = cells.iter().map(|c| c[0] as u8).collect();
    assert_eq!(types, [10, 14, 13, 12]);
    let mut corners_of = Vec::new();
    for (i, c) in cells.iter().enumerate() {
        let ty = types[i];
        let k: Vec<usize> = c[1..c.len() - 1].iter().map(|&v| v as usize).collect();
        assert_eq!(c[c.len() - 1] as usize, i, "the cell's index ends its line");
        assert_eq!(k.len(), mesh.cells.get(i).ty.shape.corners());
        let x: Vec<[f64; 3]> = k.iter().map(|&v| points[v]).collect();
        let v = su2_volume(ty, &x);
        let ours = mesh_model::measure3d::cell_volume(&mesh, i);
        assert!(
            ours > 0.0 && (v - ours).abs() < 1e-12 * ours,
            "type {ty}: SU2's volume {v}, ours {ours}"
        );
        for t in orientation_tests(ty) {
            let s = tet6(x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
            assert!(s > 0.0, "type {ty}: SU2 flips it (tetrahedron {t:?}: {s})");
        }
        corners_of.push(k);
    }

    // markers: the groups in order, their facets' types, each facet turned into its cell
    let marker = |tag: &str| {
        let at = text
            .find(&format!("MARKER_TAG= {tag}\n"))
            .unwrap_or_else(|| panic!("no marker {tag}: {text}"));
        block(&text[at..], "MARKER_ELEMS=")
    };
    assert!(text.contains("NMARK= 2\n"));
    assert!(text.find("MARKER_TAG= body").unwrap() < text.find("MARKER_TAG= farfield").unwrap());
    for (tag, tris, quads) in [("body", 4, 6), ("farfield", 4 + 2, 1 + 3)] {
        let facets = marker(tag);
        let count = |t: f64| facets.iter().filter(|f| f[0] == t).count();
        assert_eq!((count(5.0), count(9.0)), (tris, quads), "{tag}");
        for f in &facets {
            let k: Vec<usize> = f[1..].iter().map(|&v| v as usize).collect();
            assert_eq!(k.len(), if f[0] == 5.0 { 3 } else { 4 }, "{f:?}");
            let cell = corners_of
                .iter()
                .find(|c| k.iter().all(|v| c.contains(v)))
                .expect("a facet of a cell");
            let n = cell.len() as f64;
            let inside = [0, 1, 2].map(|d| cell.iter().map(|&v| points[v][d]).sum::<f64>() / n);
            // every corner's triangle (the quadrilaterals are planar here) sees the inside
            for i in 0..k.len() {
                let [a, b, c] = [0, 1, 2].map(|j| points[k[(i + j) % k.len()]]);
                assert!(tet6(a, b, c, inside) > 0.0, "{tag}: {f:?} turned out");
            }
        }
    }
}

#[test]
fn a_p2_mixed_3d_mesh_is_written_as_its_linear_mesh() {
    let linear = mixed();
    let p2 = order_2(&linear);
    assert!(p2.nodes.len() > linear.nodes.len());
    assert_eq!(mesh_model::first_structural_problem(&p2), None);
    assert_eq!(su2(&p2), su2(&linear));
}
