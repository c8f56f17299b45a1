//! 3D meshes written as `.su2`: the sphere (prisms) and the step (hexahedra, pyramids,
//! tetrahedra) read back by a small parser hold the report's cells by type, nodes and
//! boundary facets by marker, every cell positive as SU2 judges it from the written corners
//! (`Check_IntElem_Orientation`'s corner tetrahedra) and every facet turned into the domain;
//! at order 2 the `.su2` holds the linear mesh and the report says so.

use std::collections::BTreeMap;
use std::path::Path;

use end_to_end::{Outcome, read_json, run_into, s};
use testkit::su2::{kept_as_written, orientation_tests, tet6};

/// An element as written: its VTK type and corner indices.
type Element = (u8, Vec<usize>);

/// A `.su2` file read back.
struct Su2 {
    dim: usize,
    /// VTK type and corner indices of each cell.
    cells: Vec<Element>,
    points: Vec<[f64; 3]>,
    /// Each marker's name and facets (VTK type, corners), in order.
    markers: Vec<(String, Vec<Element>)>,
}

/// The number after `KEY=` on the next line.
fn count(key: &str, lines: &mut std::str::Lines<'_>) -> usize {
    let l = lines.next().unwrap();
    let v = l.strip_prefix(key).unwrap_or_else(|| panic!("{key}: {l}"));
    v.trim().parse().unwrap()
}

fn read_su2(path: &Path) -> Su2 {
    let text = std::fs::read_to_string(path).unwrap();
    let mut lines = text.lines();
    let numbers =
        |l: &str| -> Vec<f64> { l.split_whitespace().map(|t| t.parse().unwrap()).collect() };
    let element = |v: &[f64]| (v[0] as u8, v[1..].iter().map(|&x| x as usize).collect());
    let dim = count("NDIME=", &mut lines);
    let mut su2 = Su2 {
        dim,
        cells: Vec::new(),
        points: Vec::new(),
        markers: Vec::new(),
    };
    for i in 0..count("NELEM=", &mut lines) {
        let v = numbers(lines.next().unwrap());
        assert_eq!(
            v[v.len() - 1] as usize,
            i,
            "a cell's line ends in its index"
        );
        su2.cells.push(element(&v[..v.len() - 1]));
    }
    for i in 0..count("NPOIN=", &mut lines) {
        let v = numbers(lines.next().unwrap());
        assert_eq!(v.len(), dim + 1);
        assert_eq!(v[dim] as usize, i);
        su2.points
            .push([v[0], v[1], if dim == 3 { v[2] } else { 0.0 }]);
    }
    for _ in 0..count("NMARK=", &mut lines) {
        let tag = lines.next().unwrap().strip_prefix("MARKER_TAG=").unwrap();
        let facets = (0..count("MARKER_ELEMS=", &mut lines))
            .map(|_| element(&numbers(lines.next().unwrap())))
            .collect();
        su2.markers.push((tag.trim().to_string(), facets));
    }
    assert_eq!(lines.next(), None, "nothing after the markers");
    su2
}

/// Meshes `case` at `order` into `dir` as `.su2` (and `.msh`), returns the report and the
/// `.su2` read back.
fn mesh(dir: &Path, case: &str, order: &str) -> (serde_json::Value, Su2) {
    let name = format!("{case}-p{order}");
    let su2 = dir.join(format!("{name}.su2"));
    let outcome = run_into(
        dir,
        &name,
        "mesh",
        case,
        &["--order", order, "--out", s(&su2)],
    );
    assert_eq!(outcome.unwrap(), Outcome::Valid, "{name}");
    (read_json(&dir.join(format!("{name}.json"))), read_su2(&su2))
}

#[test]
fn the_sphere_and_the_step_as_su2_hold_the_cells_and_markers_of_their_report() {
    let dir = tempfile::tempdir().unwrap();
    for case in ["sphere", "step"] {
        let (report, su2) = mesh(dir.path(), case, "1");
        assert_eq!(su2.dim, 3);
        assert_eq!(su2.points.len() as u64, report["nodes"].as_u64().unwrap());
        let mut by_type = BTreeMap::new();
        for (ty, k) in &su2.cells {
            let name = match ty {
                10 => "tet",
                14 => "pyramid",
                13 => "prism",
                12 => "hex",
                _ => panic!("{case}: VTK type {ty}"),
            };
            *by_type.entry(name).or_insert(0u64) += 1;
            let tests = orientation_tests(*ty);
            assert_eq!(k.len(), tests.iter().flatten().max().unwrap() + 1);
            let corners: Vec<[f64; 3]> = k.iter().map(|&v| su2.points[v]).collect();
            assert!(kept_as_written(*ty, &corners), "{case}: SU2 flips a {name}");
        }
        for (name, n) in report["cells"].as_object().unwrap() {
            let n = n.as_u64().unwrap();
            assert_eq!(
                by_type.get(name.as_str()).copied().unwrap_or(0),
                n,
                "{case}: {name}"
            );
        }
        if case == "step" {
            assert_eq!(by_type.len(), 3, "{case}: tets, pyramids and hexahedra");
        }

        // a marker per boundary group, in the report's counts; each facet into the domain:
        // the cells round a boundary node all lie on its facets' inner side
        let groups = report["boundary_groups"].as_object().unwrap();
        assert_eq!(su2.markers.len(), groups.len(), "{case}");
        let mut cells_of = vec![Vec::new(); su2.points.len()];
        for (i, (_, k)) in su2.cells.iter().enumerate() {
            for &v in k {
                cells_of[v].push(i);
            }
        }
        for (tag, facets) in &su2.markers {
            assert_eq!(
                facets.len() as u64,
                groups[tag].as_u64().unwrap(),
                "{case}: {tag}"
            );
            for (ty, k) in facets {
                assert!(
                    matches!((ty, k.len()), (5, 3) | (9, 4)),
                    "{case}: {ty} {k:?}"
                );
                let cell = cells_of[k[0]]
                    .iter()
                    .find(|&&c| k.iter().all(|v| su2.cells[c].1.contains(v)))
                    .expect("a facet of a cell");
                let inside = su2.cells[*cell].1.iter().find(|v| !k.contains(v)).unwrap();
                let mut p: Vec<[f64; 3]> = k.iter().map(|&v| su2.points[v]).collect();
                p.push(su2.points[*inside]);
                let n = p.len() - 1;
                assert!(
                    tet6(p[0], p[1], p[2], p[n]) > 0.0,
                    "{case}: {tag} facet {k:?} turned out"
                );
            }
        }
    }
}

#[test]
fn a_p2_step_as_su2_is_its_linear_mesh_and_says_so() {
    let dir = tempfile::tempdir().unwrap();
    let (p1, linear) = mesh(dir.path(), "step", "1");
    let (p2, su2) = mesh(dir.path(), "step", "2");
    assert!(p2["nodes"].as_u64() > p1["nodes"].as_u64());
    assert_eq!(su2.points, linear.points);
    assert_eq!(su2.cells, linear.cells);
    assert_eq!(su2.markers, linear.markers);
    let orders: Vec<(&str, u64)> = p2["meshes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| (m["format"].as_str().unwrap(), m["order"].as_u64().unwrap()))
        .collect();
    assert_eq!(orders, [("msh", 2), ("su2", 1)]);
    let notes = p2["notes"].to_string();
    assert!(
        notes.contains("step-p2.su2 holds the linear mesh")
            && notes.contains("SU2 reads linear cells only"),
        "{notes}"
    );
}
