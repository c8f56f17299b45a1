//! The quality measure of the cut: dihedral angles of tetrahedra, kept in
//! `mesh_model::measure3d` (one copy for the cut, the report and the tests) and re-exported
//! here.

pub use mesh_model::measure3d::{max_dihedral_deg, tet_dihedral_angles_deg};
