//! The STL reader: ASCII and binary, welding, and a clear error for each malformed input.

use std::path::Path;

use super::*;

/// The unit tetrahedron's four outward triangles.
fn tet() -> [[[f64; 3]; 3]; 4] {
    let p = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]].map(|t| t.map(|i| p[i]))
}

fn ascii(facets: &[[[f64; 3]; 3]]) -> String {
    let mut s = String::from("solid tet made by a test\n");
    for t in facets {
        s += "  facet normal 0 0 0\n    outer loop\n";
        for p in t {
            s += &format!("      vertex {:e} {:e} {:e}\n", p[0], p[1], p[2]);
        }
        s += "    endloop\n  endfacet\n";
    }
    s + "endsolid tet made by a test\n"
}

fn binary(facets: &[[[f64; 3]; 3]]) -> Vec<u8> {
    // a header that starts like ASCII, as some exporters write it
    let mut b = b"solid binary".to_vec();
    b.resize(80, b' ');
    b.extend((facets.len() as u32).to_le_bytes());
    for t in facets {
        b.extend([0u8; 12]);
        for p in t {
            for x in p {
                b.extend((*x as f32).to_le_bytes());
            }
        }
        b.extend([0u8; 2]);
    }
    b
}

fn err(bytes: &[u8]) -> String {
    parse(bytes, Path::new("s.stl")).unwrap_err().to_string()
}

#[test]
fn ascii_and_binary_give_the_same_welded_surface() {
    for bytes in [ascii(&tet()).into_bytes(), binary(&tet())] {
        let (nodes, tris) = parse(&bytes, Path::new("t.stl")).unwrap();
        assert_eq!(nodes.len(), 4);
        assert_eq!(tris, vec![[0, 1, 2], [0, 2, 3], [0, 3, 1], [2, 1, 3]]);
        assert_eq!(nodes[3], [0.0, 0.0, 1.0]);
    }
}

#[test]
fn minus_zero_welds_with_zero() {
    let mut t = tet();
    t[1][0] = [-0.0, 0.0, -0.0];
    let (nodes, _) = parse(ascii(&t).as_bytes(), Path::new("t.stl")).unwrap();
    assert_eq!(nodes.len(), 4);
}

#[test]
fn every_malformed_input_has_a_one_line_error() {
    let good = ascii(&tet());
    let cases: Vec<(Vec<u8>, &str)> = vec![
        (
            b"".to_vec(),
            "s.stl: byte 0: truncated binary STL: 0 bytes, shorter than its 84-byte header",
        ),
        (
            binary(&tet())[..150].to_vec(),
            "s.stl: byte 84: truncated binary STL: the header counts 4 triangles (284 bytes) but the file has 150",
        ),
        (
            good.replace("outer loop", "outer lop").into_bytes(),
            "s.stl:3: malformed facet (line 2): expected `loop`, found `lop`",
        ),
        (
            good.replacen("vertex 1e0 0e0 0e0", "vertex 1e0 0e0", 1)
                .into_bytes(),
            "s.stl:7: malformed facet (line 2): expected a coordinate, found `endloop`",
        ),
        (
            good.replacen("vertex 1e0 0e0 0e0", "vertex NaN 0 0", 1)
                .into_bytes(),
            "s.stl:2: facet 1 (line 2): vertex [NaN, 0.0, 0.0] is not finite",
        ),
        (
            good.replacen("vertex 1e0 0e0 0e0", "vertex 0 0 0", 1)
                .into_bytes(),
            "s.stl:2: facet 1 (line 2): two of its vertices are equal",
        ),
        (
            good.as_bytes()[..good.len() - 60].to_vec(),
            "s.stl:27: malformed facet (line 23): the file ends where a coordinate was expected",
        ),
        (
            b"solid empty\nendsolid empty\n".to_vec(),
            "s.stl:2: no facet: the surface is empty",
        ),
        (
            b"solid x\nfacett normal 0 0 1\n".to_vec(),
            "s.stl:2: expected `facet`, `solid` or `endsolid`, found `facett`",
        ),
    ];
    for (bytes, want) in cases {
        let got = err(&bytes);
        assert_eq!(got, want);
        assert!(!got.contains('\n'));
    }
    let mut b = binary(&tet());
    b[84 + 12..84 + 16].copy_from_slice(&f32::INFINITY.to_le_bytes());
    assert_eq!(
        err(&b),
        "s.stl: byte 84: triangle 1: vertex [inf, 0.0, 0.0] is not finite"
    );
}

#[test]
fn files_are_read_by_extension() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.STL");
    std::fs::write(&path, binary(&tet())).unwrap();
    assert_eq!(read_surface(&path).unwrap().1.len(), 4);
    let bad = dir.path().join("t.obj");
    assert!(
        read_surface(&bad)
            .unwrap_err()
            .to_string()
            .contains("unknown mesh file extension")
    );
}

#[test]
fn a_msh_surface_gives_its_triangles() {
    use mesh_model::{CellType, Dim, Mesh, Patch, Role};
    let mut m = Mesh::new(Dim::Three, 1);
    m.nodes = vec![
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    m.cells.push(CellType::new(Shape::Tet, 1), &[0, 1, 2, 3]);
    for f in Shape::Tet.faces() {
        m.boundary.push(
            CellType::new(Shape::Tri, 1),
            &f.iter().map(|&i| i as u32).collect::<Vec<_>>(),
        );
        m.boundary_patch.push(0);
    }
    m.patches.push(Patch {
        name: "wall".into(),
        role: Role::Wall,
    });
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.msh");
    crate::write(&path, &m).unwrap();
    let (nodes, tris) = read_surface(&path).unwrap();
    assert_eq!((nodes.len(), tris.len()), (4, 4));
}

#[test]
fn the_fuzz_seeds_are_read() {
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    for name in ["tet_ascii.stl", "tet_binary.stl"] {
        let (nodes, tris) = read(&data.join(name)).unwrap();
        assert_eq!((nodes.len(), tris.len()), (4, 4), "{name}");
    }
}
