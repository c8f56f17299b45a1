//! The STL reader: ASCII and binary, welding, the groups of solids and `.msh` physical
//! groups, and a clear error for each malformed or degenerate input.

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
            "s.stl:2: facet 1 (line 2): degenerate (zero area): two of its vertices are equal",
        ),
        (
            good.replacen("vertex 0e0 1e0 0e0", "vertex 2e0 0e0 0e0", 1)
                .into_bytes(),
            "s.stl:2: facet 1 (line 2): degenerate (zero area): its three vertices are on one line",
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
    assert_eq!(
        read_surface(&bad).unwrap_err().to_string(),
        format!(
            "{}: unknown surface file extension (expected .stl or .msh)",
            bad.display()
        )
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

/// An ASCII STL of the tetrahedron's facets in solids: `(name, facets)` each, `None` for a
/// `solid` line without a name.
fn solids(parts: &[(Option<&str>, &[usize])]) -> String {
    let mut s = String::new();
    for (name, facets) in parts {
        let name = name.unwrap_or("");
        s += &format!("solid {name}\n");
        for &f in *facets {
            s += "facet normal 0 0 0\nouter loop\n";
            for p in tet()[f] {
                s += &format!("vertex {} {} {}\n", p[0], p[1], p[2]);
            }
            s += "endloop\nendfacet\n";
        }
        s += &format!("endsolid {name}\n");
    }
    s
}

fn grouped(text: &str) -> GroupedSurface {
    parse_grouped(text.as_bytes(), Path::new("t.stl")).unwrap()
}

fn names(s: &GroupedSurface) -> Vec<&str> {
    s.groups.iter().map(|g| g.name.as_str()).collect()
}

#[test]
fn each_named_solid_is_a_group() {
    let s = grouped(&solids(&[
        (Some("upper part"), &[0, 1]),
        (Some("lower"), &[2, 3]),
    ]));
    assert_eq!(names(&s), ["upper part", "lower"]);
    assert_eq!(s.triangle_group, [0, 0, 1, 1]);
    assert_eq!(s.nodes.len(), 4, "the corners are welded across solids");
    assert!(s.groups.iter().all(|g| g.role == Role::Wall));
}

#[test]
fn solids_of_one_name_share_a_group_and_unnamed_ones_do_not() {
    let s = grouped(&solids(&[
        (Some("a"), &[0]),
        (None, &[1]),
        (Some("a"), &[2]),
        (None, &[3]),
    ]));
    assert_eq!(names(&s), ["a", "", ""]);
    assert_eq!(s.triangle_group, [0, 1, 0, 2]);
}

#[test]
fn empty_solids_are_dropped_and_a_binary_stl_is_one_unnamed_group() {
    let s = grouped(&solids(&[(Some("empty"), &[]), (Some("b"), &[0, 1, 2, 3])]));
    assert_eq!(names(&s), ["b"]);
    assert_eq!(s.triangle_group, [0; 4]);
    let s = parse_grouped(&binary(&tet()), Path::new("t.stl")).unwrap();
    assert_eq!(names(&s), [""]);
    assert_eq!(s.triangle_group, [0; 4]);
}

/// A `.msh` surface of the tetrahedron: `$PhysicalNames` and one entity per facet, in the
/// physical group `groups[f]` (0: none).
fn msh_tet(names: &[&str], groups: [usize; 4]) -> String {
    let mut s = String::from("$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
    s += &format!("$PhysicalNames\n{}\n", names.len());
    for (i, n) in names.iter().enumerate() {
        s += &format!("2 {} \"{n}\"\n", i + 1);
    }
    s += "$EndPhysicalNames\n$Entities\n0 0 4 0\n";
    for (f, &g) in groups.iter().enumerate() {
        let tags = if g == 0 { "0".into() } else { format!("1 {g}") };
        s += &format!("{} 0 0 0 1 1 1 {tags} 0\n", f + 1);
    }
    s += "$EndEntities\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n";
    s += "0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n$Elements\n4 4 1 4\n";
    for (f, t) in [[1, 3, 2], [1, 2, 4], [1, 4, 3], [2, 3, 4]]
        .iter()
        .enumerate()
    {
        s += &format!("2 {} 2 1\n{} {} {} {}\n", f + 1, f + 1, t[0], t[1], t[2]);
    }
    s + "$EndElements\n"
}

#[test]
fn a_msh_surface_has_a_group_per_physical_surface_and_wall_for_the_rest() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.msh");
    std::fs::write(&path, msh_tet(&["top", "side"], [1, 2, 0, 1])).unwrap();
    let s = read_surface_grouped(&path).unwrap();
    assert_eq!(names(&s), ["top", "side", "wall"]);
    assert_eq!(s.triangle_group, [0, 1, 2, 0]);
    assert_eq!(s.triangles.len(), 4);
    // no physical group at all (as Gmsh saves a mesh without any): one wall
    std::fs::write(&path, msh_tet(&[], [0; 4])).unwrap();
    let s = read_surface_grouped(&path).unwrap();
    assert_eq!(names(&s), ["wall"]);
    assert_eq!(s.groups[0].role, Role::Wall);
}

#[test]
fn a_degenerate_msh_triangle_is_named_without_a_line() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("t.msh");
    let text = msh_tet(&["w"], [1; 4]).replace("0 0 1\n$EndNodes", "2 0 0\n$EndNodes");
    std::fs::write(&path, text).unwrap();
    assert_eq!(
        read_surface_grouped(&path).unwrap_err().to_string(),
        format!(
            "{}: triangle 2 (in element tag order): degenerate (zero area): its three vertices are on one line",
            path.display()
        )
    );
}

proptest::proptest! {
    /// However the facets of a surface are spread over solids, named or not, every facet
    /// is read, in order, with the group of its solid: one per name, one per unnamed solid.
    #[test]
    fn facets_keep_the_group_of_their_solid(
        solid_of in proptest::collection::vec(0usize..4, 4),
        named in proptest::collection::vec(proptest::bool::ANY, 4),
    ) {
        let labels = ["a", "b", "a", "c"];
        let parts: Vec<(Option<&str>, Vec<usize>)> = (0..4)
            .map(|k| {
                let facets = (0..4).filter(|&f| solid_of[f] == k).collect();
                (named[k].then_some(labels[k]), facets)
            })
            .collect();
        let parts: Vec<(Option<&str>, &[usize])> =
            parts.iter().map(|(n, f)| (*n, f.as_slice())).collect();
        let s = grouped(&solids(&parts));
        let order: Vec<usize> = parts.iter().flat_map(|p| p.1.iter().copied()).collect();
        proptest::prop_assert_eq!(s.triangles.len(), 4);
        proptest::prop_assert_eq!(s.nodes.len(), 4);
        for (i, &f) in order.iter().enumerate() {
            let k = solid_of[f];
            let want = if named[k] { labels[k] } else { "" };
            let g = &s.groups[s.triangle_group[i] as usize];
            proptest::prop_assert_eq!(g.name.as_str(), want);
            // facets of one solid share a group; so do named solids of one name
            for (j, &e) in order.iter().enumerate() {
                let same = solid_of[e] == k || (named[k] && named[solid_of[e]] && labels[solid_of[e]] == labels[k]);
                proptest::prop_assert_eq!(same, s.triangle_group[i] == s.triangle_group[j]);
            }
        }
    }
}
