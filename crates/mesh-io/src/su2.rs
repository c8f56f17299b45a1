//! SU2 native mesh format (`.su2`), linear only, 2D and 3D.
//!
//! SU2 has no high-order cells, so for a mesh of order 2 or 3 this writer writes the linear
//! mesh underneath: the corner nodes of every cell and facet, renumbered densely in their
//! original order, with straight edges. (It does not refuse, so that one pipeline run can
//! write `.msh` and `.su2` side by side; the curvature is in the `.msh`.)
//!
//! Layout: `NDIME=`, `NELEM=` with one line per cell (VTK linear type, corner indices, cell
//! index), `NPOIN=` with one line per point (coordinates, index; z only in 3D), `NMARK=` with
//! one marker per boundary group ([`crate::groups`]: each wall body by its name, `slat`,
//! `main`, `flap`, and `farfield`), `MARKER_TAG=` the group's name, `MARKER_ELEMS=` and one
//! line per facet (line 3 in 2D; triangle 5 or quadrilateral 9 in 3D). Indices are 0-based.
//!
//! Cell types are VTK's linear cells, as SU2 numbers them: triangle 5, quadrilateral 9,
//! tetrahedron 10, hexahedron 12, prism (wedge) 13, pyramid 14. Corners are in the order and
//! orientation SU2's reader checks (`CPhysicalGeometry::Check_IntElem_Orientation`, which
//! swaps the nodes of a cell it finds inverted): the data model's (Gmsh's) for the
//! triangle, quadrilateral, tetrahedron, pyramid and hexahedron; for the prism SU2 wants the
//! tetrahedron 0-2-1-3 positive, the first triangle 0-1-2 turned away from the second, the
//! mirror image of Gmsh's, so a prism is written 0, 2, 1, 3, 5, 4 ([`su2_corners`]) — as
//! Gmsh's own SU2 export writes it (`MPrism::getVertexVTK`, the orientation of VTK's
//! documented wedge; VTK 9.7's `vtkWedge` itself takes Gmsh's orientation as positive, which
//! is why the `.vtu` writer does not permute). Boundary facets are written as SU2 orients
//! them (`Check_BoundElem_Orientation`): in 2D a line with the domain on its left, as in the
//! data model; in 3D a triangle or quadrilateral whose normal points into the domain, the
//! reverse of the data model's outward facets. In that order SU2 re-orients nothing.

use std::io::{self, Write};
use std::path::Path;

use mesh_model::{Mesh, Shape};

use crate::groups::{Group, boundary_groups};

use crate::IoError;
use crate::atomic::write_atomic;
use crate::check::check_writable;
use crate::text::{push_f64, push_int, write_records};

/// Writes the linear mesh underneath `mesh` to `path` in SU2 format, atomically.
///
/// Errors: [`IoError::NonFiniteNode`] or [`IoError::InvalidMesh`] before anything is
/// written, [`IoError::Io`] when the file cannot be written.
pub fn write(path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    write_atomic(path, |w| {
        body(w, mesh, &groups).map_err(|e| IoError::io(path, e))
    })
}

/// Checks the mesh and returns its boundary groups and the group of each patch.
fn prepare(mesh: &Mesh, path: &Path) -> Result<(Vec<Group>, Vec<usize>), IoError> {
    check_writable(mesh, path)?;
    boundary_groups(mesh).map_err(|message| IoError::InvalidMesh {
        path: path.to_path_buf(),
        message,
    })
}

/// Writes the `.su2` to any writer; `path` only names the destination in errors. Not atomic.
pub fn write_to(out: &mut dyn Write, mesh: &Mesh, path: &Path) -> Result<(), IoError> {
    let groups = prepare(mesh, path)?;
    body(out, mesh, &groups).map_err(|e| IoError::io(path, e))
}

/// The corners of a cell (`facet` false) or boundary facet (`facet` true) of `shape` in the
/// order SU2 reads them: written corner `k` is the data model's corner `order[k]` (see the
/// module's documentation).
pub fn su2_corners(shape: Shape, facet: bool) -> &'static [usize] {
    match (shape, facet) {
        (Shape::Prism, false) => &[0, 2, 1, 3, 5, 4],
        // 3D boundary facets turned into the domain
        (Shape::Tri, true) => &[0, 2, 1],
        (Shape::Quad, true) => &[0, 3, 2, 1],
        _ => &[0, 1, 2, 3, 4, 5, 6, 7][..shape.corners()],
    }
}

/// VTK linear type number of a shape (SU2 uses VTK's).
fn vtk_linear(shape: Shape) -> u8 {
    match shape {
        Shape::Line => 3,
        Shape::Tri => 5,
        Shape::Quad => 9,
        Shape::Tet => 10,
        Shape::Hex => 12,
        Shape::Prism => 13,
        Shape::Pyramid => 14,
    }
}

fn body(
    w: &mut dyn Write,
    mesh: &Mesh,
    (groups, group_of): &(Vec<Group>, Vec<usize>),
) -> io::Result<()> {
    // Dense renumbering of the corner nodes, in their original order.
    let mut new_index = vec![u32::MAX; mesh.nodes.len()];
    for c in mesh.cells.iter().chain(mesh.boundary.iter()) {
        for &v in c.corners() {
            new_index[v as usize] = 0;
        }
    }
    let mut kept = Vec::new();
    for (old, slot) in new_index.iter_mut().enumerate() {
        if *slot == 0 {
            *slot = kept.len() as u32;
            kept.push(old);
        }
    }

    let d = mesh.dim.as_u8();
    writeln!(w, "NDIME= {d}")?;
    writeln!(w, "NELEM= {}", mesh.cells.len())?;
    write_records(w, mesh.cells.len(), |i, b| {
        let c = mesh.cells.get(i);
        push_int(b, vtk_linear(c.ty.shape));
        let k = c.corners();
        for &j in su2_corners(c.ty.shape, false) {
            b.push(b' ');
            push_int(b, new_index[k[j] as usize]);
        }
        b.push(b' ');
        push_int(b, i);
        b.push(b'\n');
    })?;
    writeln!(w, "NPOIN= {}", kept.len())?;
    let coordinates = usize::from(d);
    write_records(w, kept.len(), |i, b| {
        for &x in &mesh.nodes[kept[i]][..coordinates] {
            push_f64(b, x);
            b.push(b' ');
        }
        push_int(b, i);
        b.push(b'\n');
    })?;
    writeln!(w, "NMARK= {}", groups.len())?;
    for (k, group) in groups.iter().enumerate() {
        let facets: Vec<usize> = (0..mesh.boundary.len())
            .filter(|&j| group_of[mesh.boundary_patch[j] as usize] == k)
            .collect();
        writeln!(w, "MARKER_TAG= {}", group.name)?;
        writeln!(w, "MARKER_ELEMS= {}", facets.len())?;
        write_records(w, facets.len(), |k, b| {
            let f = mesh.boundary.get(facets[k]);
            push_int(b, vtk_linear(f.ty.shape));
            let k = f.corners();
            for &j in su2_corners(f.ty.shape, true) {
                b.push(b' ');
                push_int(b, new_index[k[j] as usize]);
            }
            b.push(b'\n');
        })?;
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::{AnnulusParams, annulus};

    fn to_string(mesh: &Mesh) -> String {
        let mut out = Vec::new();
        write_to(&mut out, mesh, Path::new("mem.su2")).unwrap();
        String::from_utf8(out).unwrap()
    }

    /// The lines after `KEY= n`, and n.
    fn block<'a>(text: &'a str, key: &str) -> (usize, Vec<&'a str>) {
        let mut lines = text.lines();
        let n: usize = lines
            .by_ref()
            .find_map(|l| l.strip_prefix(key))
            .unwrap()
            .trim()
            .parse()
            .unwrap();
        (n, lines.take(n).collect())
    }

    #[test]
    fn a_p3_annulus_is_written_as_its_linear_mesh() {
        let m = annulus(&AnnulusParams {
            order: 3,
            ..AnnulusParams::default()
        });
        let linear = annulus(&AnnulusParams {
            order: 1,
            ..AnnulusParams::default()
        });
        let text = to_string(&m);
        let (npoin, points) = block(&text, "NPOIN=");
        assert_eq!(npoin, linear.nodes.len());
        // The corner points are the linear mesh's points (same lattice, same order).
        for (line, p) in points.iter().zip(&linear.nodes) {
            let v: Vec<f64> = line
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect();
            assert!((v[0] - p[0]).abs() < 1e-14 && (v[1] - p[1]).abs() < 1e-14);
        }
        // Cells and markers are the P1 mesh's, index for index.
        let without_points = |t: &str| -> String {
            let (a, b) = (t.find("NPOIN=").unwrap(), t.find("NMARK=").unwrap());
            format!("{}{}", &t[..a], &t[b..])
        };
        assert_eq!(without_points(&text), without_points(&to_string(&linear)));
        let (nelem, cells) = block(&text, "NELEM=");
        assert_eq!(nelem, m.cells.len());
        for (line, c) in cells.iter().zip(m.cells.iter()) {
            let v: Vec<u32> = line
                .split_whitespace()
                .map(|t| t.parse().unwrap())
                .collect();
            assert_eq!(v[0], u32::from(vtk_linear(c.ty.shape)));
            assert_eq!(v.len(), 2 + c.ty.shape.corners());
            assert!(v[1..v.len() - 1].iter().all(|&k| (k as usize) < npoin));
        }
        assert!(text.contains("NDIME= 2\n"));
        assert!(text.contains("NMARK= 2\n"));
    }

    #[test]
    fn patches_of_one_role_are_merged_into_one_marker() {
        let mut m = annulus(&AnnulusParams::default());
        // Split the outer circle into two far-field patches.
        m.patches.push(mesh_model::Patch {
            name: "outer-b".into(),
            role: mesh_model::Role::Farfield,
        });
        let outer: Vec<usize> = m.patch_facets(1).collect();
        for &j in &outer[outer.len() / 2..] {
            m.boundary_patch[j] = 2;
        }
        let text = to_string(&m);
        assert!(text.contains("NMARK= 2\n"));
        let after = |tag: &str| &text[text.find(tag).unwrap()..];
        let (n, lines) = block(after("MARKER_TAG= farfield\n"), "MARKER_ELEMS=");
        assert_eq!(n, outer.len());
        assert!(lines.iter().all(|l| l.starts_with("3 ")));
        let wall = format!("MARKER_TAG= {}\n", m.patches[0].name);
        let (n, _) = block(after(&wall), "MARKER_ELEMS=");
        assert_eq!(n, m.patch_facets(0).count());
    }
}
