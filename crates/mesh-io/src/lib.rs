//! Mesh files: Gmsh MSH 4.1 ASCII and binary (write and read), VTK XML `.vtu` with Lagrange
//! cells, SU2 native (linear), binary snapshots of intermediate stages, and STL surfaces
//! (read). Every file is written
//! atomically ([`atomic`]): a failed write leaves no partial file; a set of files written by
//! one [`atomic::Transaction`] is replaced together or not at all.
//!
//! This crate owns the file formats and nothing else: the data model is `mesh-model`, and no
//! meshing, geometry or quality computation happens here. It is, with `xtask`, the only crate
//! that touches files. The node order of the data model is Gmsh's; the `.vtu` writer permutes
//! high-order nodes into VTK's Lagrange order ([`node_order`]).
//!
//! Entry points: [`write()`] and [`write_to`] (format chosen by the extension), [`read_msh`],
//! [`atomic::Transaction`], and the modules
//! [`msh`], [`vtu`], [`su2`], [`snapshot`], and [`stl`] (closed surfaces in: STL and
//! triangulated `.msh`). Test meshes for this and other crates are in
//! `testkit`, behind the cargo feature `testkit`.
//!
//! # Example
//!
//! Write a small mesh (the unit square as two triangles, its sides a far-field patch) as
//! Gmsh MSH 4.1 in a temporary folder and read it back:
//!
//! ```
//! use mesh_model::{CellType, Dim, Mesh, Patch, Role, Shape};
//!
//! let mut mesh = Mesh::new(Dim::Two, 1);
//! mesh.nodes = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! mesh.cells.push(CellType::new(Shape::Tri, 1), &[0, 1, 2]);
//! mesh.cells.push(CellType::new(Shape::Tri, 1), &[0, 2, 3]);
//! for k in 0..4 {
//!     mesh.boundary.push(CellType::new(Shape::Line, 1), &[k, (k + 1) % 4]);
//!     mesh.boundary_patch.push(0);
//! }
//! mesh.patches.push(Patch { name: "farfield".into(), role: Role::Farfield });
//!
//! let dir = tempfile::tempdir()?;
//! let path = dir.path().join("square.msh");
//! mesh_io::write(&path, &mesh)?; // the extension picks the format: .msh, .vtu or .su2
//! let text = std::fs::read_to_string(&path)?;
//! assert!(text.starts_with("$MeshFormat\n4.1 0 8\n"));
//! assert!(text.contains("farfield")); // a physical group per role
//!
//! let back = mesh_io::read_msh(&path)?;
//! assert_eq!(back.nodes, mesh.nodes);
//! assert_eq!(back.cells, mesh.cells);
//! assert_eq!(back.patches[0].role, Role::Farfield);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

pub mod atomic;
mod check;
mod error;
pub mod groups;
pub mod msh;
pub mod node_order;
pub mod sensitivities;
pub mod snapshot;
pub mod stl;
pub mod su2;
#[cfg(any(test, feature = "testkit"))]
pub mod testkit;
mod text;
pub mod vtu;

use std::path::Path;

pub use error::IoError;
use mesh_model::Mesh;

/// The mesh file formats [`write()`] knows, by extension.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Format {
    /// `.msh`: Gmsh MSH 4.1 ASCII ([`msh`]).
    Msh,
    /// `.vtu`: VTK XML unstructured grid ([`vtu`]).
    Vtu,
    /// `.su2`: SU2 native, linear ([`su2`]).
    Su2,
}

impl Format {
    /// The format named by the extension of `path` (case ignored), if any.
    pub fn from_path(path: &Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "msh" => Some(Format::Msh),
            "vtu" => Some(Format::Vtu),
            "su2" => Some(Format::Su2),
            _ => None,
        }
    }
}

/// Writes `mesh` to `path` in the format named by its extension (`.msh`, `.vtu`, `.su2`),
/// atomically.
///
/// Errors: [`IoError::UnknownExtension`] for any other extension; otherwise those of
/// [`msh::write()`], [`vtu::write()`], [`su2::write()`].
pub fn write(path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    match Format::from_path(path) {
        Some(Format::Msh) => msh::write(path, mesh),
        Some(Format::Vtu) => vtu::write(path, mesh),
        Some(Format::Su2) => su2::write(path, mesh),
        None => Err(IoError::UnknownExtension {
            path: path.to_path_buf(),
        }),
    }
}

/// Writes `mesh` to any writer (for example a file of an [`atomic::Transaction`]) in the
/// format named by the extension of `path`, which otherwise only names the destination in
/// errors. Not atomic by itself.
///
/// Errors: as [`write()`].
pub fn write_to(out: &mut dyn std::io::Write, path: &Path, mesh: &Mesh) -> Result<(), IoError> {
    match Format::from_path(path) {
        Some(Format::Msh) => msh::write_to(out, mesh, path),
        Some(Format::Vtu) => vtu::write_to(out, mesh, path),
        Some(Format::Su2) => su2::write_to(out, mesh, path),
        None => Err(IoError::UnknownExtension {
            path: path.to_path_buf(),
        }),
    }
}

/// Reads a Gmsh MSH 4.1 file, ASCII or binary (see [`msh::read`] for what becomes what).
pub fn read_msh(path: &Path) -> Result<Mesh, IoError> {
    msh::read(path)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testkit::{AnnulusParams, annulus};

    #[test]
    fn the_extension_chooses_the_format() {
        let dir = tempfile::tempdir().unwrap();
        let m = annulus(&AnnulusParams::default());
        for (name, head) in [
            ("m.msh", "$MeshFormat\n4.1 0 8\n"),
            ("M.VTU", "<?xml"),
            ("m.su2", "NDIME= 2\n"),
        ] {
            let path = dir.path().join(name);
            write(&path, &m).unwrap();
            let text = std::fs::read_to_string(&path).unwrap();
            assert!(text.starts_with(head), "{name}");
        }
        let back = read_msh(&dir.path().join("m.msh")).unwrap();
        assert_eq!(back.cells, m.cells);
    }

    #[test]
    fn an_unknown_extension_is_an_error_and_writes_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let m = annulus(&AnnulusParams::default());
        for name in ["m.stl", "m", "m.msh.bak"] {
            let path = dir.path().join(name);
            let err = write(&path, &m).unwrap_err();
            assert!(matches!(err, IoError::UnknownExtension { .. }), "{err}");
            assert!(err.to_string().contains(name), "{err}");
        }
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0);
    }

    #[test]
    fn a_failed_write_keeps_the_previous_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("m.vtu");
        let good = annulus(&AnnulusParams::default());
        write(&path, &good).unwrap();
        let before = std::fs::read(&path).unwrap();
        let mut bad = good.clone();
        bad.nodes[0][2] = f64::INFINITY;
        let err = write(&path, &bad).unwrap_err();
        assert!(
            matches!(err, IoError::NonFiniteNode { node: 0, .. }),
            "{err}"
        );
        assert_eq!(std::fs::read(&path).unwrap(), before);
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 1);
    }
}
