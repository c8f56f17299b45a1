//! VTK XML unstructured grid (`.vtu`, ASCII), for looking at meshes in ParaView.
//!
//! The domain cells are written first, then the boundary facets (lines in 2D, linear or VTK
//! Lagrange curves 68, ends first as in Gmsh; faces in 3D). Linear cells use the linear VTK
//! types (triangle 5, quad 9, tetra 10, hexahedron 12, wedge 13, pyramid 14); orders 2 and 3
//! use VTK's Lagrange cells (triangle 69, quadrilateral 70, tetra 71, hexahedron 72, wedge 73)
//! with the nodes permuted from Gmsh's order by [`crate::node_order::vtu_from_gmsh`] (the file
//! format 1.0's order: a hexahedron's edges 10 and 11 as VTK before 9.1 numbered them); the
//! 14-node pyramid as VTK's 13-node quadratic pyramid (27) when its base node is the
//! serendipity point of its base's edges (else [`IoError::Unsupported`]). VTK has no cubic
//! pyramid: a straight-sided 30-node pyramid (every node where the linear pyramid puts it) is
//! written as VTK's linear pyramid (14), which is the same cell, and a curved one gives
//! [`IoError::Unsupported`].
//!
//! Cell data: `layer` and `pipe` (as `Int64`, −1 for [`mesh_model::NONE`] and for facets) when
//! the mesh has them, `order` (the polynomial order of each cell or facet), and
//! `boundary_group`: −1 for a domain cell, for a facet the index of its boundary group
//! ([`crate::groups`]: `slat`, `main`, `flap`, `farfield`). No point data. To look at the domain
//! alone, threshold `boundary_group` at −1.
//!
//! Field data: the group names, one `Int64` array of one tuple per group, named
//! `boundary_group:` and the group's name, holding the group's index (so
//! `boundary_group:farfield` holds 3 on the 30P30N), in index order, e.g.
//! `<DataArray type="Int64" Name="boundary_group:slat" NumberOfTuples="1" format="ascii">0</DataArray>`.
//! Numeric field data is read by VTK and ParaView and by meshio
//! (`mesh.field_data["boundary_group:slat"] == [0]`); VTK's own string array
//! (`<Array type="String">`) is not: meshio refuses the whole file. The name is
//! XML-escaped in the attribute; a name with a control character other than tab, line feed and
//! carriage return (XML 1.0 cannot carry one) gives [`IoError::Unsupported`]. A mesh without
//! boundary groups has no field data. (meshio 5.3.5 cannot read VTK's quadratic pyramid
//! itself: a file with P2 pyramids fails there with `KeyError: 'pyramid13'`, its own gap.)

use std::io::{self, Write};
use std::path::Path;

use mesh_model::{Mesh, NONE};

use crate::IoError;
use crate::atomic::write_atomic;
use crate::check::check_writable;
use crate::groups::{Group, boundary_groups};
use crate::node_order::{vtk_cell_type, vtu_from_gmsh};
use crate::text::{push_int, write_points, write_records};

/// The start of the name of each field-data array that names a boundary group (module doc).
pub const GROUP_PREFIX: &str = "boundary_group:";

/// Writes the domain cells of `mesh` to `path` as a VTK XML unstructured grid, atomically.
///
/// Errors: [`IoError::NonFiniteNode`] or [`IoError::InvalidMesh`] for a mesh that breaks the
/// data model's invariants, [`IoError::Unsupported`] for a cell type without a VTK ordering or
/// a group name XML cannot carry, all before anything is written; [`IoError::Io`] when the
/// file cannot be written.
pub fn write(path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    write_atomic(path, |w| {
        body(w, mesh, &groups).map_err(|e| IoError::io(path, e))
    })
}

/// Writes the `.vtu` to any writer; `path` only names the destination in errors. Not atomic.
pub fn write_to(out: &mut dyn Write, mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    body(out, mesh, &groups).map_err(|e| IoError::io(path, e))
}

fn prepare(mesh: &Mesh, path: &Path) -> Result<(Vec<Group>, Vec<usize>), IoError> {
    check_writable(mesh, path)?;
    for (i, ty) in mesh
        .cells
        .types()
        .iter()
        .chain(mesh.boundary.types())
        .enumerate()
    {
        if vtk_cell_type(*ty).is_none() {
            return Err(IoError::Unsupported {
                path: path.to_path_buf(),
                format: "vtu",
                what: format!(
                    "cell {i}, a {} of order {} (no verified VTK Lagrange node ordering)",
                    ty.shape.name(),
                    ty.order
                ),
            });
        }
    }
    check_pyramids(mesh, path)?;
    let groups = boundary_groups(mesh).map_err(|message| IoError::InvalidMesh {
        path: path.to_path_buf(),
        message,
    })?;
    if let Some(g) = groups.0.iter().find(|g| !xml_can_hold(&g.name)) {
        return Err(IoError::Unsupported {
            path: path.to_path_buf(),
            format: "vtu",
            what: format!(
                "the boundary group name {:?} (a control character XML 1.0 cannot carry)",
                g.name
            ),
        });
    }
    Ok(groups)
}

/// Whether XML 1.0 can carry `s` in an attribute (as characters or character references).
fn xml_can_hold(s: &str) -> bool {
    s.chars().all(|c| {
        (c >= ' ' || matches!(c, '\t' | '\n' | '\r')) && !matches!(c, '\u{fffe}' | '\u{ffff}')
    })
}

/// `s` escaped for a double-quoted XML attribute; tab, line feed and carriage return as
/// character references, which attribute-value normalisation leaves alone.
fn xml_attribute(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\t' | '\n' | '\r' => out.push_str(&format!("&#{};", u32::from(c))),
            c => out.push(c),
        }
    }
    out
}

/// Refuses a 14-node pyramid whose base node is not the serendipity point of its base's
/// edges, and a curved 30-node pyramid: VTK's quadratic and linear pyramids, which leave
/// those nodes out, would change their shape.
fn check_pyramids(mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let pyramid14 = mesh_model::CellType::new(mesh_model::Shape::Pyramid, 2);
    let pyramid30 = mesh_model::CellType::new(mesh_model::Shape::Pyramid, 3);
    for (i, c) in mesh.cells.iter().enumerate() {
        if c.ty == pyramid30 && !straight_pyramid(mesh, c.nodes) {
            return Err(IoError::Unsupported {
                path: path.to_path_buf(),
                format: "vtu",
                what: format!(
                    "cell {i}, a curved 30-node pyramid (VTK has no cubic pyramid; a straight \
                     one is written as VTK's linear pyramid)"
                ),
            });
        }
        if c.ty != pyramid14 {
            continue;
        }
        let x = |j: usize| mesh.nodes[c.nodes[j] as usize];
        // Gmsh's base edge nodes: 0-1 (5), 0-3 (6), 1-2 (8), 2-3 (10)
        let centre = x(13);
        let scale = (0..14).flat_map(&x).fold(0.0f64, |m, v| m.max(v.abs()));
        let off = (0..3).any(|d| {
            let at = 0.5 * (x(5)[d] + x(6)[d] + x(8)[d] + x(10)[d])
                - 0.25 * (x(0)[d] + x(1)[d] + x(2)[d] + x(3)[d]);
            (centre[d] - at).abs() > 64.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE)
        });
        if off {
            return Err(IoError::Unsupported {
                path: path.to_path_buf(),
                format: "vtu",
                what: format!(
                    "cell {i}, a 14-node pyramid whose base node is not the serendipity point of \
                     its base (VTK's quadratic pyramid has no base node)"
                ),
            });
        }
    }
    Ok(())
}

/// Whether every node of the 30-node pyramid `nodes` is where its corners' linear pyramid
/// puts it: `(1 − w)·B(u / (1 − w), v / (1 − w)) + w·apex` at its reference point (u, v, w),
/// B the bilinear map of the base.
fn straight_pyramid(mesh: &Mesh, nodes: &[u32]) -> bool {
    let ty = mesh_model::CellType::new(mesh_model::Shape::Pyramid, 3);
    let refs = mesh_model::reference::reference_nodes(ty).expect("the 30-node pyramid's nodes");
    let x = |j: usize| mesh.nodes[nodes[j] as usize];
    let scale = (0..nodes.len())
        .flat_map(&x)
        .fold(0.0f64, |m, v| m.max(v.abs()));
    let tolerance = 64.0 * f64::EPSILON * scale.max(f64::MIN_POSITIVE);
    refs.iter().enumerate().skip(5).all(|(j, r)| {
        let t = 1.0 - r[2];
        let (a, b) = (0.5 * (1.0 + r[0] / t), 0.5 * (1.0 + r[1] / t));
        let w = [(1.0 - a) * (1.0 - b), a * (1.0 - b), a * b, (1.0 - a) * b];
        (0..3).all(|d| {
            let base: f64 = (0..4).map(|k| w[k] * x(k)[d]).sum();
            (x(j)[d] - (t * base + r[2] * x(4)[d])).abs() <= tolerance
        })
    })
}

fn int_array(
    w: &mut dyn Write,
    name: &str,
    n: usize,
    value: impl Fn(usize) -> i64 + Sync,
) -> io::Result<()> {
    writeln!(
        w,
        r#"        <DataArray type="Int64" Name="{name}" format="ascii">"#
    )?;
    write_records(w, n, |k, b| {
        push_int(b, value(k));
        b.push(if k % 16 == 15 { b'\n' } else { b' ' });
    })?;
    writeln!(w, "\n        </DataArray>")
}

fn record(v: u32) -> i64 {
    if v == NONE { -1 } else { i64::from(v) }
}

/// The field data: per boundary group, an `Int64` array `boundary_group:NAME` of one tuple,
/// the group's index (see the module doc). Nothing when there is no group.
fn group_name_arrays(w: &mut dyn Write, groups: &[Group]) -> io::Result<()> {
    if groups.is_empty() {
        return Ok(());
    }
    writeln!(w, "    <FieldData>")?;
    for (k, g) in groups.iter().enumerate() {
        writeln!(
            w,
            r#"      <DataArray type="Int64" Name="{GROUP_PREFIX}{}" NumberOfTuples="1" format="ascii">{k}</DataArray>"#,
            xml_attribute(&g.name)
        )?;
    }
    writeln!(w, "    </FieldData>")
}

fn body(
    w: &mut dyn Write,
    mesh: &Mesh,
    (groups, group_of): &(Vec<Group>, Vec<usize>),
) -> io::Result<()> {
    let all = || mesh.cells.iter().chain(mesh.boundary.iter());
    let facets = mesh.boundary.len();
    writeln!(w, r#"<?xml version="1.0"?>"#)?;
    writeln!(
        w,
        r#"<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian" header_type="UInt64">"#
    )?;
    writeln!(w, "  <UnstructuredGrid>")?;
    group_name_arrays(w, groups)?;
    writeln!(
        w,
        r#"    <Piece NumberOfPoints="{}" NumberOfCells="{}">"#,
        mesh.nodes.len(),
        mesh.cells.len() + facets
    )?;
    writeln!(w, "      <Points>")?;
    writeln!(
        w,
        r#"        <DataArray type="Float64" Name="Points" NumberOfComponents="3" format="ascii">"#
    )?;
    write_points(w, &mesh.nodes)?;
    writeln!(w, "        </DataArray>\n      </Points>")?;

    writeln!(w, "      <Cells>")?;
    writeln!(
        w,
        r#"        <DataArray type="Int64" Name="connectivity" format="ascii">"#
    )?;
    let n_cells = mesh.cells.len();
    let element = |k: usize| {
        if k < n_cells {
            mesh.cells.get(k)
        } else {
            mesh.boundary.get(k - n_cells)
        }
    };
    let n = n_cells + facets;
    write_records(w, n, |k, b| {
        let c = element(k);
        let perm = vtu_from_gmsh(c.ty).unwrap_or(&[]);
        for (i, &g) in perm.iter().enumerate() {
            push_int(b, c.nodes[g]);
            b.push(if i + 1 == perm.len() { b'\n' } else { b' ' });
        }
    })?;
    writeln!(w, "        </DataArray>")?;
    let mut offset = 0i64;
    let offsets: Vec<i64> = all()
        .map(|c| {
            offset += vtu_from_gmsh(c.ty).map_or(c.nodes.len(), <[usize]>::len) as i64;
            offset
        })
        .collect();
    int_array(w, "offsets", n, |k| offsets[k])?;
    writeln!(
        w,
        r#"        <DataArray type="UInt8" Name="types" format="ascii">"#
    )?;
    write_records(w, n, |k, b| {
        push_int(b, vtk_cell_type(element(k).ty).unwrap_or(0));
        b.push(if k % 32 == 31 { b'\n' } else { b' ' });
    })?;
    writeln!(w, "\n        </DataArray>\n      </Cells>")?;

    writeln!(w, "      <CellData>")?;
    int_array(w, "order", n, |k| i64::from(element(k).ty.order))?;
    let per_cell = |values: &[u32], k: usize| values.get(k).map_or(-1, |&v| record(v));
    if !mesh.cell_layer.is_empty() {
        int_array(w, "layer", n, |k| per_cell(&mesh.cell_layer, k))?;
    }
    if !mesh.cell_pipe.is_empty() {
        int_array(w, "pipe", n, |k| per_cell(&mesh.cell_pipe, k))?;
    }
    int_array(w, "boundary_group", n, |k| {
        if k < n_cells {
            -1
        } else {
            group_of[mesh.boundary_patch[k - n_cells] as usize] as i64
        }
    })?;
    writeln!(w, "      </CellData>")?;
    writeln!(w, "    </Piece>\n  </UnstructuredGrid>\n</VTKFile>")?;
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::{AnnulusParams, annulus, reference_cells_3d};
    use mesh_model::Shape;

    fn to_string(mesh: &Mesh) -> Result<String, IoError> {
        let mut out = Vec::new();
        write_to(&mut out, mesh, Path::new("mem.vtu"))?;
        Ok(String::from_utf8(out).unwrap())
    }

    /// The numbers between `<DataArray … Name="name" …>` and `</DataArray>`.
    fn array(text: &str, name: &str) -> Vec<f64> {
        let start = text.find(&format!(r#"Name="{name}""#)).unwrap();
        let open = start + text[start..].find('>').unwrap() + 1;
        let close = open + text[open..].find("</DataArray>").unwrap();
        text[open..close]
            .split_ascii_whitespace()
            .map(|t| t.parse().unwrap())
            .collect()
    }

    #[test]
    fn p3_annulus_cells_are_lagrange_with_nodes_in_vtk_order() {
        let m = annulus(&AnnulusParams {
            order: 3,
            ..AnnulusParams::default()
        });
        let text = to_string(&m).unwrap();
        let types = array(&text, "types");
        let offsets = array(&text, "offsets");
        let conn = array(&text, "connectivity");
        let points = array(&text, "Points");
        assert_eq!(types.len(), m.cells.len() + m.boundary.len());
        assert!(
            types[m.cells.len()..].iter().all(|&t| t == 68.0),
            "P3 lines"
        );
        assert_eq!(points.len(), 3 * m.nodes.len());
        assert_eq!(*offsets.last().unwrap() as usize, conn.len());
        let mut start = 0;
        for (i, c) in m.cells.iter().enumerate() {
            let end = offsets[i] as usize;
            let expected_type = if c.ty.shape == Shape::Tri { 69.0 } else { 70.0 };
            assert_eq!(types[i], expected_type);
            let vtk: Vec<u32> = conn[start..end].iter().map(|&v| v as u32).collect();
            if c.ty.shape == Shape::Quad {
                // VTK runs edge 2 from corner 3 to corner 2 and edge 3 from corner 0 to 3:
                // its node 8 is next to corner 3, its node 10 next to corner 0.
                let d = |a: u32, b: u32| {
                    let (p, q) = (m.xy(a), m.xy(b));
                    (p[0] - q[0]).hypot(p[1] - q[1])
                };
                assert!(d(vtk[8], vtk[3]) < d(vtk[8], vtk[2]), "cell {i}");
                assert!(d(vtk[10], vtk[0]) < d(vtk[10], vtk[3]), "cell {i}");
            }
            let mut sorted_vtk = vtk.clone();
            sorted_vtk.sort_unstable();
            let mut sorted_gmsh = c.nodes.to_vec();
            sorted_gmsh.sort_unstable();
            assert_eq!(sorted_vtk, sorted_gmsh, "cell {i} nodes are a permutation");
            start = end;
        }
        let layers = array(&text, "layer");
        assert_eq!(layers.len(), m.cells.len() + m.boundary.len());
        assert_eq!(layers[0], f64::from(m.cell_layer[0]));
        // facets carry their group: an index into the names
        let group = array(&text, "boundary_group");
        assert!(group[..m.cells.len()].iter().all(|&g| g == -1.0));
        for (j, &p) in m.boundary_patch.iter().enumerate() {
            assert_eq!(group[m.cells.len() + j], p as f64, "facet {j}");
        }
        let names = group_names(&text);
        assert_eq!(names.len(), m.patches.len());
        assert_eq!(names[1], "farfield");
        // no VTK string array: meshio cannot read one
        assert!(!text.contains(r#"type="String""#));
    }

    /// The boundary group names from the field data, by index (`boundary_group:NAME`, one
    /// tuple, the index), undoing the XML escapes; checks the arrays' form on the way.
    fn group_names(text: &str) -> Vec<String> {
        let field = &text[text.find("<FieldData>").unwrap()..text.find("</FieldData>").unwrap()];
        let mut named = Vec::new();
        for line in field.lines().skip(1).filter(|l| !l.trim().is_empty()) {
            let open = r#"<DataArray type="Int64" Name=""#;
            let rest = line.trim().strip_prefix(open).expect(line);
            let (name, rest) = rest.split_once('"').expect(line);
            let index = rest
                .strip_prefix(r#" NumberOfTuples="1" format="ascii">"#)
                .and_then(|r| r.strip_suffix("</DataArray>"))
                .expect(line);
            let name = name.strip_prefix(GROUP_PREFIX).expect(line);
            let mut unescaped = name.to_string();
            for (from, to) in [
                ("&lt;", "<"),
                ("&gt;", ">"),
                ("&quot;", "\""),
                ("&#9;", "\t"),
                ("&#10;", "\n"),
                ("&#13;", "\r"),
                ("&amp;", "&"),
            ] {
                unescaped = unescaped.replace(from, to);
            }
            named.push((index.parse::<usize>().unwrap(), unescaped));
        }
        named.sort();
        assert!(
            named.iter().enumerate().all(|(k, (i, _))| *i == k),
            "{named:?}"
        );
        named.into_iter().map(|(_, name)| name).collect()
    }

    #[test]
    fn group_names_round_trip_through_numeric_field_data() {
        let mut m = annulus(&AnnulusParams::default());
        m.patches[0].name = "a \"b\" & <c>\td".into();
        m.patches.push(mesh_model::Patch {
            name: "slat".into(),
            role: mesh_model::Role::Wall,
        });
        m.boundary_patch[0] = 2;
        let text = to_string(&m).unwrap();
        let (groups, _) = boundary_groups(&m).unwrap();
        let want: Vec<&str> = groups.iter().map(|g| g.name.as_str()).collect();
        assert_eq!(want, ["a \"b\" & <c>\td", "farfield", "slat"]);
        assert_eq!(group_names(&text), want);
        assert!(
            text.contains(r#"Name="boundary_group:a &quot;b&quot; &amp; &lt;c&gt;&#9;d""#),
            "{text:.800}"
        );
        // every field-data array is numeric (meshio reads no other type)
        let field = &text[text.find("<FieldData>").unwrap()..text.find("</FieldData>").unwrap()];
        assert_eq!(field.matches("<DataArray").count(), 3);
        assert_eq!(field.matches(r#"type="Int64""#).count(), 3);
        // the facet of the third group points at it
        assert_eq!(array(&text, "boundary_group")[m.cells.len()], 2.0);
    }

    #[test]
    fn a_group_name_xml_cannot_carry_is_refused_before_writing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.vtu");
        let mut m = annulus(&AnnulusParams::default());
        m.patches[0].name = "bell\u{7}".into();
        let err = write(&path, &m).unwrap_err();
        assert!(matches!(err, IoError::Unsupported { .. }), "{err}");
        assert!(err.to_string().contains("bell"), "{err}");
        assert!(!path.exists());
    }

    #[test]
    fn a_mesh_without_groups_has_no_field_data() {
        let mut m = annulus(&AnnulusParams::default());
        m.patches.clear();
        m.boundary = Default::default();
        m.cell_pipe.clear();
        m.boundary_patch.clear();
        let text = to_string(&m).unwrap();
        assert!(!text.contains("FieldData"));
    }

    #[test]
    fn coordinates_are_written_to_full_precision() {
        let mut m = annulus(&AnnulusParams::default());
        m.nodes[1][0] = 0.1 + 0.2;
        let text = to_string(&m).unwrap();
        let points = array(&text, "Points");
        for (k, p) in m.nodes.iter().enumerate() {
            assert_eq!(points[3 * k..3 * k + 3], p[..], "node {k}");
        }
    }

    #[test]
    fn p2_pyramids_are_quadratic_pyramids_and_a_bent_base_is_refused_before_writing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.vtu");
        let mut m = reference_cells_3d(2);
        let text = to_string(&m).unwrap();
        let types = array(&text, "types");
        assert_eq!(types[..4], [71.0, 27.0, 73.0, 72.0]);
        let offsets = array(&text, "offsets");
        assert_eq!(offsets[..4], [10.0, 23.0, 41.0, 68.0]);
        // the pyramid's VTK nodes: corners, then edges 0-1, 1-2, 2-3, 3-0, 0-4, 1-4, 2-4, 3-4
        let conn = array(&text, "connectivity");
        let p = m.cells.get(1).nodes.to_vec();
        let vtk: Vec<u32> = conn[10..23].iter().map(|&v| v as u32).collect();
        let gmsh = [0, 1, 2, 3, 4, 5, 8, 10, 6, 7, 9, 11, 12].map(|j| p[j]);
        assert_eq!(vtk, gmsh);
        // its base node moved off the base: refused
        let base = m.cells.get(1).nodes[13] as usize;
        m.nodes[base][2] += 0.1;
        let err = write(&path, &m).unwrap_err();
        assert!(matches!(err, IoError::Unsupported { .. }), "{err}");
        assert!(err.to_string().contains("pyramid"), "{err}");
        assert!(!path.exists());
        let linear = reference_cells_3d(1);
        let text = to_string(&linear).unwrap();
        let types = array(&text, "types");
        assert_eq!(types[..4], [10.0, 14.0, 13.0, 12.0]);
        // then the boundary faces
        assert!(
            types[4..].iter().all(|&t| t == 5.0 || t == 9.0),
            "{types:?}"
        );
    }

    #[test]
    fn p3_solids_are_lagrange_cells_and_a_curved_pyramid_is_refused_before_writing() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.vtu");
        let mut m = reference_cells_3d(3);
        let text = to_string(&m).unwrap();
        let types = array(&text, "types");
        // the straight 30-node pyramid as VTK's linear pyramid, its corners alone
        assert_eq!(types[..4], [71.0, 14.0, 73.0, 72.0]);
        let offsets = array(&text, "offsets");
        assert_eq!(offsets[..4], [20.0, 25.0, 65.0, 129.0]);
        let conn = array(&text, "connectivity");
        let prism = m.cells.get(2).nodes.to_vec();
        let vtk: Vec<u32> = conn[25..65].iter().map(|&v| v as u32).collect();
        let perm = crate::node_order::vtk_from_gmsh(m.cells.get(2).ty).unwrap();
        assert_eq!(vtk, perm.iter().map(|&j| prism[j]).collect::<Vec<_>>());
        // a node of the pyramid's edge 0-4 off its place: refused
        let bent = m.cells.get(1).nodes[9] as usize;
        m.nodes[bent][0] += 0.05;
        let err = write(&path, &m).unwrap_err();
        assert!(matches!(err, IoError::Unsupported { .. }), "{err}");
        assert!(err.to_string().contains("30-node pyramid"), "{err}");
        assert!(!path.exists());
    }

    #[test]
    fn missing_layer_records_write_no_layer_array() {
        let mut m = annulus(&AnnulusParams::default());
        m.cell_layer.clear();
        m.cell_pipe[0] = NONE;
        let text = to_string(&m).unwrap();
        assert!(!text.contains(r#"Name="layer""#));
        assert_eq!(array(&text, "pipe")[0], -1.0);
    }
}
