//! Tests of the MSH writer and reader: round trips, what PyFR and Gmsh need, and one test per
//! kind of malformed input.

use std::collections::{HashMap, HashSet};
use std::path::Path;

use mesh_model::{Mesh, Patch, Role};
use proptest::prelude::*;

use super::*;
use crate::IoError;
use crate::testkit::{AnnulusParams, annulus, reference_cells_3d};

fn to_text(mesh: &Mesh) -> String {
    let mut out = Vec::new();
    write_to(&mut out, mesh, Path::new("mem.msh")).unwrap();
    String::from_utf8(out).unwrap()
}

fn from_text(text: &str) -> Result<Mesh, IoError> {
    parse(text.as_bytes(), Path::new("mem.msh"))
}

/// What a round trip must give back: everything but the layer and pipe records.
fn without_records(mesh: &Mesh) -> Mesh {
    let mut m = mesh.clone();
    m.cell_layer.clear();
    m.cell_pipe.clear();
    m
}

/// 1-based number of the first line equal to `line`.
fn line_of(text: &str, line: &str) -> usize {
    text.lines().position(|l| l == line).unwrap() + 1
}

/// Replaces line number `n` (1-based).
fn replace_line(text: &str, n: usize, by: &str) -> String {
    let mut lines: Vec<&str> = text.lines().collect();
    lines[n - 1] = by;
    lines.join("\n") + "\n"
}

/// Removes a section, header to end line included.
fn remove_section(text: &str, name: &str) -> String {
    let start = text.find(&format!("${name}\n")).unwrap();
    let end_tag = format!("$End{name}\n");
    let end = text.find(&end_tag).unwrap() + end_tag.len();
    format!("{}{}", &text[..start], &text[end..])
}

fn small() -> Mesh {
    annulus(&AnnulusParams {
        order: 1,
        radial_cells: 1,
        angular_cells: 3,
        ..AnnulusParams::default()
    })
}

#[test]
fn annuli_of_order_1_2_3_round_trip_through_a_file() {
    let dir = tempfile::tempdir().unwrap();
    for order in 1..=3 {
        for mask in [vec![], vec![true], vec![true, false, true, false, false]] {
            let m = annulus(&AnnulusParams {
                order,
                triangle_mask: mask.clone(),
                ..AnnulusParams::default()
            });
            let path = dir.path().join(format!("p{order}.msh"));
            write(&path, &m).unwrap();
            let back = read(&path).unwrap();
            assert_eq!(back, without_records(&m), "P{order} mask {mask:?}");
            assert_eq!(mesh_model::validate(&back), vec![]);
        }
    }
}

#[test]
fn rings_around_real_airfoils_round_trip_bit_for_bit() {
    let dir = concat!(env!("CARGO_MANIFEST_DIR"), "/../../fixtures/geometry/");
    for file in [
        "naca0012.dat",
        "rae2822.dat",
        "naca0012-sharp-te-generated.dat",
    ] {
        let text = std::fs::read_to_string(format!("{dir}{file}")).unwrap();
        let points = crate::testkit::selig_points(&text);
        for order in 1..=3 {
            let m = crate::testkit::airfoil_ring(
                &points,
                &crate::testkit::RingParams {
                    order,
                    layers: 3,
                    thickness: 1e-3,
                    triangle_mask: vec![false, false, true],
                },
            );
            let back = from_text(&to_text(&m)).unwrap();
            assert_eq!(back, without_records(&m), "{file} P{order}");
        }
    }
}

/// A mixed P3 mesh written by Gmsh itself (`tests/python/make_gmsh_fixture.py`): nodes on
/// point and curve entities with parametric flags, bounding points, physical tags other than
/// ours, trailing spaces.
#[test]
fn a_p3_mesh_written_by_gmsh_reads_as_a_valid_mesh() {
    let path = Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/gmsh_ring_p3.msh"
    ));
    let m = read(path).unwrap();
    assert_eq!((m.dim, m.order), (mesh_model::Dim::Two, 3));
    assert_eq!(m.count(mesh_model::Shape::Tri), 15);
    assert_eq!(m.count(mesh_model::Shape::Quad), 47);
    assert_eq!(m.nodes.len(), 537);
    assert_eq!(mesh_model::validate(&m), vec![]);
    let roles: Vec<Role> = m.patches.iter().map(|p| p.role).collect();
    assert_eq!(roles, vec![Role::Wall, Role::Farfield]);
    assert_eq!(m.patch_facets(0).count(), 8);
    assert_eq!(m.patch_facets(1).count(), 23);
    // Gmsh puts every node of a boundary facet, high-order ones included, on its circle.
    for (j, f) in m.boundary.iter().enumerate() {
        let r = if m.boundary_patch[j] == 0 { 1.0 } else { 3.0 };
        for &v in f.nodes {
            let [x, y] = m.xy(v);
            assert!((x.hypot(y) - r).abs() < 1e-6, "facet {j} node {v}");
        }
    }
    // And what we write of it, Gmsh's reader and ours read back unchanged.
    assert_eq!(from_text(&to_text(&m)).unwrap(), m);
}

#[test]
fn every_3d_cell_type_of_order_1_and_2_round_trips() {
    for order in 1..=2 {
        let m = reference_cells_3d(order);
        let text = to_text(&m);
        assert_eq!(from_text(&text).unwrap(), without_records(&m), "P{order}");
        // The type numbers in the element block headers are Gmsh's.
        for c in m.cells.iter() {
            let id = gmsh_type_id(c.ty).unwrap();
            assert!(text.contains(&format!("\n3 1 {id} 1\n")), "{:?}", c.ty);
        }
    }
}

#[test]
fn patch_names_with_quotes_backslashes_and_unicode_survive() {
    let mut m = small();
    m.patches[0].name = r#"sl"at \ main "#.into();
    m.patches[1].name = "far – field ✈".into();
    assert_eq!(from_text(&to_text(&m)).unwrap(), without_records(&m));
}

#[test]
fn empty_patches_survive_and_cell_order_is_kept() {
    let mut m = annulus(&AnnulusParams {
        triangle_mask: vec![true, false],
        ..AnnulusParams::default()
    });
    m.patches.push(Patch {
        name: "unused".into(),
        role: Role::Wall,
    });
    let back = from_text(&to_text(&m)).unwrap();
    assert_eq!(back, without_records(&m));
    assert_eq!(back.patches.len(), 3);
}

#[test]
fn without_our_patch_section_patches_are_named_after_their_group() {
    let m = small();
    let text = remove_section(&to_text(&m), PATCH_SECTION);
    let back = from_text(&text).unwrap();
    let names: Vec<&str> = back.patches.iter().map(|p| p.name.as_str()).collect();
    // the wall's group is named after the wall patch; the far field's group is `farfield`
    assert_eq!(names, vec![m.patches[0].name.as_str(), "farfield"]);
    let roles: Vec<Role> = back.patches.iter().map(|p| p.role).collect();
    assert_eq!(roles, vec![Role::Wall, Role::Farfield]);
    assert_eq!(back.boundary_patch, m.boundary_patch);
}

#[test]
fn each_wall_patch_is_a_physical_group_named_after_it() {
    let mut m = small();
    m.patches[0].name = "main".into();
    let text = to_text(&m);
    assert!(text.contains("1 2 \"main\"\n") && text.contains("1 3 \"farfield\"\n"));
    let back = from_text(&text).unwrap();
    assert_eq!(back.patches, m.patches);
    // two walls of one name make one group
    m.patches[1] = Patch {
        name: "main".into(),
        role: Role::Wall,
    };
    let text = to_text(&m);
    assert!(text.contains("$PhysicalNames\n2\n"), "{text}");
}

#[test]
fn unknown_sections_are_skipped() {
    let text = to_text(&small()).replacen(
        "$Nodes\n",
        "$Comments\nmade by hand $Nodes is not here\n$EndComments\n$Nodes\n",
        1,
    );
    assert_eq!(from_text(&text).unwrap(), without_records(&small()));
}

/// The file has the structure PyFR's Gmsh reader needs: `4.1 0 8`; physical names as
/// `dim tag "name"` with unique tags and names, one of them `fluid`; every entity that holds
/// elements in exactly one physical group; element counts that add up.
#[test]
fn written_file_has_what_pyfr_needs() {
    let m = annulus(&AnnulusParams::default());
    let text = to_text(&m);
    let lines: Vec<&str> = text.lines().collect();
    let at = |name: &str| lines.iter().position(|l| *l == name).unwrap();
    assert_eq!(lines[at("$MeshFormat") + 1], "4.1 0 8");

    let p = at("$PhysicalNames");
    let n: usize = lines[p + 1].parse().unwrap();
    let mut names = HashMap::new();
    for l in &lines[p + 2..p + 2 + n] {
        let mut it = l.splitn(3, ' ');
        let (_dim, tag, name) = (it.next().unwrap(), it.next().unwrap(), it.next().unwrap());
        assert!(name.starts_with('"') && name.ends_with('"'), "{l}");
        assert!(
            names.insert(tag.to_string(), name.to_string()).is_none(),
            "{l}"
        );
    }
    let unique: HashSet<&String> = names.values().collect();
    assert_eq!(unique.len(), names.len());
    assert!(names.values().any(|v| v == "\"fluid\""));
    assert_eq!(lines[p + 2 + n], "$EndPhysicalNames");

    let e = at("$Entities");
    let counts: Vec<usize> = lines[e + 1]
        .split(' ')
        .map(|t| t.parse().unwrap())
        .collect();
    let mut entity_group = HashMap::new();
    for (k, l) in lines[e + 2..e + 2 + counts.iter().sum::<usize>()]
        .iter()
        .enumerate()
    {
        let dim = (1..=3)
            .find(|&d| k < counts[..=d].iter().sum::<usize>())
            .unwrap();
        let t: Vec<&str> = l.split(' ').collect();
        assert_eq!(t[7], "1", "one physical tag per entity: {l}");
        assert!(names.contains_key(t[8]), "{l}");
        entity_group.insert((dim, t[0].to_string()), names[t[8]].clone());
    }

    let el = at("$Elements");
    let header: Vec<usize> = lines[el + 1]
        .split(' ')
        .map(|t| t.parse().unwrap())
        .collect();
    let mut row = el + 2;
    let mut total = 0;
    let mut facets_per_group: HashMap<String, usize> = HashMap::new();
    for _ in 0..header[0] {
        let b: Vec<usize> = lines[row].split(' ').map(|t| t.parse().unwrap()).collect();
        let group = &entity_group[&(b[0], b[1].to_string())];
        if b[0] == 1 {
            *facets_per_group.entry(group.clone()).or_default() += b[3];
        } else {
            assert_eq!(group, "\"fluid\"");
        }
        total += b[3];
        row += 1 + b[3];
    }
    assert_eq!(total, header[1]);
    assert_eq!(lines[row], "$EndElements");
    let wall = format!("\"{}\"", m.patches[0].name);
    assert_eq!(facets_per_group[&wall], m.patch_facets(0).count());
    assert_eq!(facets_per_group["\"farfield\""], m.patch_facets(1).count());
}

#[test]
fn a_surface_of_triangles_reads_as_a_3d_boundary() {
    // Two triangles of a tetrahedron's surface in a "wall" group, as Gmsh would save them.
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n\
        $PhysicalNames\n1\n2 7 \"Wall\"\n$EndPhysicalNames\n\
        $Entities\n0 0 1 0\n3 0 0 0 1 1 1 1 7 0\n$EndEntities\n\
        $Nodes\n1 4 10 13\n2 3 0 4\n10\n11\n12\n13\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n$EndNodes\n\
        $Elements\n1 2 5 6\n2 3 2 2\n6 10 12 11\n5 10 11 13\n$EndElements\n";
    let m = from_text(text).unwrap();
    assert_eq!(m.dim, mesh_model::Dim::Three);
    assert!(m.cells.is_empty());
    assert_eq!(m.boundary.len(), 2);
    // Element tag order: tag 5 first.
    assert_eq!(m.boundary.get(0).nodes, &[0, 1, 3]);
    assert_eq!(m.boundary.get(1).nodes, &[0, 2, 1]);
    assert_eq!(m.patches[0].role, Role::Wall);
}

#[test]
fn a_non_finite_node_is_refused_and_no_file_is_left() {
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("bad.msh");
    let mut m = small();
    m.nodes[2][1] = f64::NAN;
    let err = write(&path, &m).unwrap_err();
    assert!(
        matches!(err, IoError::NonFiniteNode { node: 2, .. }),
        "{err}"
    );
    assert!(err.to_string().contains("bad.msh"), "{err}");
    assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
}

#[test]
fn a_structurally_broken_mesh_is_refused_with_the_fault_named() {
    let mut m = small();
    m.boundary_patch[0] = 9;
    let err = write_to(&mut Vec::new(), &m, Path::new("x.msh")).unwrap_err();
    assert!(matches!(err, IoError::InvalidMesh { .. }), "{err}");
    assert!(err.to_string().contains("patch 9"), "{err}");
    let mut m = small();
    m.cells.nodes_mut(0)[1] = 999;
    let err = write_to(&mut Vec::new(), &m, Path::new("x.msh")).unwrap_err();
    assert!(err.to_string().contains("node 999"), "{err}");
}

#[test]
fn binary_files_of_other_machines_are_refused_with_advice() {
    for (size, one) in [(8, 1i32.to_be_bytes()), (4, 1i32.to_le_bytes())] {
        let mut bytes = format!("$MeshFormat\n4.1 1 {size}\n").into_bytes();
        bytes.extend_from_slice(&one);
        bytes.extend_from_slice(b"\n$EndMeshFormat\n\x00\xff\x13");
        let err = parse(&bytes, Path::new("b.msh")).unwrap_err();
        assert!(matches!(err, IoError::BinaryMsh { line: 2, .. }), "{err}");
        assert!(err.to_string().contains("save as ASCII"), "{err}");
    }
}

fn to_binary(mesh: &Mesh) -> Vec<u8> {
    let mut out = Vec::new();
    write_binary_to(&mut out, mesh, Path::new("mem.msh")).unwrap();
    out
}

#[test]
fn binary_files_round_trip_bit_for_bit() {
    for order in 1..=3 {
        let m = annulus(&AnnulusParams {
            order,
            radial_cells: 3,
            angular_cells: 17,
            triangle_mask: vec![true, false],
            ..AnnulusParams::default()
        });
        let bytes = to_binary(&m);
        assert!(bytes.starts_with(b"$MeshFormat\n4.1 1 8\n\x01\x00\x00\x00\n$EndMeshFormat\n"));
        let back = parse(&bytes, Path::new("b.msh")).unwrap();
        assert_eq!(back, without_records(&m), "order {order}");
        // the same mesh as the ASCII file gives
        assert_eq!(back, from_text(&to_text(&m)).unwrap());
    }
    for order in [1, 2] {
        let m = reference_cells_3d(order);
        let back = parse(&to_binary(&m), Path::new("b.msh")).unwrap();
        assert_eq!(back, without_records(&m));
    }
}

#[test]
fn a_cut_binary_file_is_an_error_not_a_panic() {
    let bytes = to_binary(&small());
    for cut in (40..bytes.len()).step_by(7) {
        assert!(
            parse(&bytes[..cut], Path::new("b.msh")).is_err(),
            "cut at {cut}"
        );
    }
}

#[test]
fn other_versions_are_refused() {
    for v in ["2.2", "4", "4.0", "41"] {
        let text = to_text(&small()).replacen("4.1 0 8", &format!("{v} 0 8"), 1);
        let err = from_text(&text).unwrap_err();
        match err {
            IoError::UnsupportedVersion { line, version, .. } => {
                assert_eq!((line, version.as_str()), (2, v));
            }
            other => panic!("{v}: {other}"),
        }
    }
}

#[test]
fn missing_sections_are_named() {
    let text = to_text(&small());
    for (section, expected) in [
        ("MeshFormat", "MeshFormat"),
        ("Nodes", "Nodes"),
        ("Elements", "Elements"),
        ("Entities", "Entities"),
    ] {
        let err = from_text(&remove_section(&text, section)).unwrap_err();
        assert!(
            matches!(err, IoError::MissingSection { section, .. } if section == expected),
            "{section}: {err}"
        );
    }
    let err = from_text("").unwrap_err();
    assert!(matches!(err, IoError::MissingSection { .. }), "{err}");
}

#[test]
fn unknown_element_types_are_named_with_their_line() {
    let text = to_text(&small());
    // The block of linear triangles: "2 1 2 <count>"; make it serendipity quads (16).
    let n = text.lines().position(|l| l.starts_with("2 1 2 ")).unwrap() + 1;
    let count = text.lines().nth(n - 1).unwrap().rsplit(' ').next().unwrap();
    let err = from_text(&replace_line(&text, n, &format!("2 1 16 {count}"))).unwrap_err();
    assert!(
        matches!(err, IoError::UnknownElementType { line, type_id: 16, .. } if line == n),
        "{err}"
    );
}

#[test]
fn malformed_content_gives_the_line_and_the_fault() {
    let m = small();
    let text = to_text(&m);
    let first_coords = line_of(&text, "$Nodes") + 3 + m.nodes.len();
    let first_element = line_of(&text, "$Elements") + 3;
    let nodes_header = line_of(&text, "$Nodes") + 1;
    let elements_header = line_of(&text, "$Elements") + 1;
    let n = m.nodes.len();
    let cases: Vec<(String, usize, &str)> = vec![
        (
            replace_line(&text, first_coords, "1.0 abc 0"),
            first_coords,
            "expected a coordinate, found 'abc'",
        ),
        (
            replace_line(&text, first_coords, "1.0 nan 0"),
            first_coords,
            "non-finite coordinate",
        ),
        (
            replace_line(&text, first_element, "1 1 2 99"),
            first_element,
            "names node 99, which is not in $Nodes",
        ),
        (
            replace_line(&text, nodes_header, &format!("1 {} 1 {n}", n + 1)),
            nodes_header,
            "announces",
        ),
        (
            {
                let h = text.lines().nth(elements_header - 1).unwrap();
                let mut t: Vec<usize> = h.split(' ').map(|x| x.parse().unwrap()).collect();
                t[1] += 1;
                let h: Vec<String> = t.iter().map(|x| x.to_string()).collect();
                replace_line(&text, elements_header, &h.join(" "))
            },
            elements_header,
            "announces",
        ),
        (
            text[..text.find("$EndNodes").unwrap() - 20].to_string(),
            0,
            "unexpected end of file",
        ),
        (text.clone() + "garbage", 0, "expected a section header"),
        (
            text.clone() + "$Unclosed\n1 2\n",
            0,
            "section $Unclosed has no $EndUnclosed",
        ),
        (
            text.replacen("$EndNodes", "0 0 0\n$EndNodes", 1),
            0,
            "expected $EndNodes",
        ),
    ];
    for (bad, line, fault) in cases {
        let err = from_text(&bad).unwrap_err();
        let IoError::Malformed {
            line: got, message, ..
        } = &err
        else {
            panic!("{fault}: got {err}");
        };
        assert!(message.contains(fault), "expected '{fault}', got '{err}'");
        if line != 0 {
            assert_eq!(*got, line, "{err}");
        }
        assert!(err.to_string().starts_with("mem.msh:"), "{err}");
    }
}

#[test]
fn a_file_that_does_not_exist_is_an_io_error_naming_it() {
    let err = read(Path::new("/no/such/file.msh")).unwrap_err();
    assert!(matches!(err, IoError::Io { .. }));
    assert!(err.to_string().contains("/no/such/file.msh"), "{err}");
}

/// Arbitrary finite coordinates, including subnormals and extreme exponents.
fn finite() -> impl Strategy<Value = f64> {
    any::<f64>().prop_filter("finite", |v| v.is_finite())
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(48))]

    #[test]
    fn random_small_meshes_round_trip_exactly(
        order in 1u8..=3,
        radial in 1usize..=3,
        angular in 3usize..=6,
        mask in proptest::collection::vec(any::<bool>(), 0..5),
        coords in proptest::collection::vec((finite(), finite()), 200),
        names in proptest::collection::vec("[^\\p{Cc}]{0,12}", 2),
    ) {
        let mut m = annulus(&AnnulusParams {
            order,
            radial_cells: radial,
            angular_cells: angular,
            triangle_mask: mask,
            ..AnnulusParams::default()
        });
        // Coordinates do not matter to the format: replace them by arbitrary finite values
        // (z stays 0, so the mesh stays 2D).
        for (k, p) in m.nodes.iter_mut().enumerate() {
            let (x, y) = coords[k % coords.len()];
            *p = [x, y, 0.0];
        }
        m.patches[0].name = names[0].clone();
        m.patches[1].name = names[1].clone();
        let back = from_text(&to_text(&m)).unwrap();
        prop_assert_eq!(back, without_records(&m));
    }
}

#[test]
fn node_coordinates_are_written_as_debug_prints_them() {
    // the fast formatting (zmij, laid out as `{:?}`) keeps the bytes of `{:?}` at its edges
    let mut m = small();
    let odd = [
        -0.0,
        1e-5,
        1.5e16,
        1e15,
        5e-324,
        f64::from_bits(0x4317_9085_685d_83c9), // 1658206780088562.25, halfway
        f64::MAX,
        0.1 + 0.2,
    ];
    let n = m.nodes.len();
    for (k, x) in odd.into_iter().enumerate() {
        m.nodes[k % n][k % 2] = x;
    }
    let text = to_text(&m);
    let start = line_of(&text, "$Nodes") + 2 + m.nodes.len();
    let lines: Vec<&str> = text.lines().collect();
    for (i, p) in m.nodes.iter().enumerate() {
        assert_eq!(
            lines[start + i],
            format!("{:?} {:?} {:?}", p[0], p[1], p[2])
        );
    }
    let back = from_text(&text).unwrap();
    let bits = |m: &Mesh| -> Vec<u64> { m.nodes.iter().flatten().map(|x| x.to_bits()).collect() };
    assert_eq!(bits(&back), bits(&m));
}
