//! VTK XML unstructured grid (`.vtu`, ASCII), for looking at meshes in ParaView.
//!
//! The domain cells are written first, then the boundary facets (lines in 2D, linear or VTK
//! Lagrange curves 68, ends first as in Gmsh; faces in 3D). Linear cells use the linear VTK
//! types (triangle 5, quad 9, tetra 10, hexahedron 12, wedge 13, pyramid 14); orders 2 and 3
//! use VTK's Lagrange cells (triangle 69, quadrilateral 70, tetra 71, hexahedron 72, wedge 73
//! at order 2) with the nodes permuted from Gmsh's order by [`crate::node_order`]; the
//! 14-node pyramid as VTK's 13-node quadratic pyramid (27) when its base node is the
//! serendipity point of its base's edges (else [`IoError::Unsupported`]). Pyramids of order 3
//! and order-3 prisms have no verified ordering and give [`IoError::Unsupported`].
//!
//! Cell data: `layer` and `pipe` (as `Int64`, −1 for [`mesh_model::NONE`] and for facets) when
//! the mesh has them, `order` (the polynomial order of each cell or facet), and
//! `boundary_group`: −1 for a domain cell, for a facet the index of its boundary group
//! ([`crate::groups`]) in the field-data string array `boundary_group_names` (`slat`, `main`,
//! `flap`, `farfield`). No point data. To look at the domain alone, threshold
//! `boundary_group` at −1.

use std::io::{self, Write};
use std::path::Path;

use mesh_model::{Mesh, NONE};

use crate::IoError;
use crate::atomic::write_atomic;
use crate::check::check_writable;
use crate::groups::{Group, boundary_groups};
use crate::node_order::{vtk_cell_type, vtk_from_gmsh};
use crate::text::{push_int, write_points, write_records};

/// Writes the domain cells of `mesh` to `path` as a VTK XML unstructured grid, atomically.
///
/// Errors: [`IoError::NonFiniteNode`] or [`IoError::InvalidMesh`] for a mesh that breaks the
/// data model's invariants, [`IoError::Unsupported`] for a cell type without a VTK ordering,
/// all before anything is written; [`IoError::Io`] when the file cannot be written.
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
    boundary_groups(mesh).map_err(|message| IoError::InvalidMesh {
        path: path.to_path_buf(),
        message,
    })
}

/// Refuses a 14-node pyramid whose base node is not the serendipity point of its base's
/// edges: VTK's quadratic pyramid, which leaves that node out, would change its shape.
fn check_pyramids(mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let pyramid14 = mesh_model::CellType::new(mesh_model::Shape::Pyramid, 2);
    for (i, c) in mesh.cells.iter().enumerate() {
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

/// The group names as a VTK string array: in ASCII, each string's bytes as numbers, then 0.
fn string_array(w: &mut dyn Write, name: &str, values: &[&str]) -> io::Result<()> {
    writeln!(
        w,
        r#"        <Array type="String" Name="{name}" NumberOfTuples="{}" format="ascii">"#,
        values.len()
    )?;
    for v in values {
        for b in v.bytes() {
            write!(w, "{b} ")?;
        }
        writeln!(w, "0")?;
    }
    writeln!(w, "        </Array>")
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
    writeln!(w, "    <FieldData>")?;
    let names: Vec<&str> = groups.iter().map(|g| g.name.as_str()).collect();
    string_array(w, "boundary_group_names", &names)?;
    writeln!(w, "    </FieldData>")?;
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
        let perm = vtk_from_gmsh(c.ty).unwrap_or(&[]);
        for (i, &g) in perm.iter().enumerate() {
            push_int(b, c.nodes[g]);
            b.push(if i + 1 == perm.len() { b'\n' } else { b' ' });
        }
    })?;
    writeln!(w, "        </DataArray>")?;
    let mut offset = 0i64;
    let offsets: Vec<i64> = all()
        .map(|c| {
            offset += vtk_from_gmsh(c.ty).map_or(c.nodes.len(), <[usize]>::len) as i64;
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
        let names = format!(
            "{} 0\n",
            "farfield"
                .bytes()
                .map(|b| b.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        );
        assert!(text.contains(&names), "{text:.600}");
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
    fn missing_layer_records_write_no_layer_array() {
        let mut m = annulus(&AnnulusParams::default());
        m.cell_layer.clear();
        m.cell_pipe[0] = NONE;
        let text = to_string(&m).unwrap();
        assert!(!text.contains(r#"Name="layer""#));
        assert_eq!(array(&text, "pipe")[0], -1.0);
    }
}
