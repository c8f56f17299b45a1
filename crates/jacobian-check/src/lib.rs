//! Validity of high-order (curved) cells: Lagrange shape functions of Gmsh's reference
//! cells ([`lagrange`]), the Jacobian of the reference-to-physical map ([`jacobian`]), and a
//! **certified** check of the sign of its determinant from Bernstein coefficients with
//! adaptive subdivision ([`certify`], after Johnen, Remacle & Geuzaine, "Geometrical
//! validity of curvilinear finite elements", J. Comput. Phys. 2013), next to the sampled
//! check the dissertation used; plus the area of a curved 2D mesh by exact quadrature
//! ([`area`]), and the fraction of edges a curved mesh bends ([`curved`]).
//!
//! Node order everywhere is Gmsh's (the data model's). The crate reads meshes and node
//! coordinates and reports; it never moves a node, and does no file IO.

pub mod area;
mod bernstein;
pub mod certify;
pub mod curved;
pub mod error;
pub mod jacobian;
pub mod lagrange;
mod linalg;
mod straight;

pub use area::{cell_area, enclosed_area, integrate_area};
pub use certify::{
    Certificate, CertifyParams, MeshValidity, SampledCheck, certify_cell, certify_cell_3d,
    check_mesh, determinant_bernstein_coefficients, sampled_check, sampled_check_3d,
};
pub use curved::curved_edge_fraction;
pub use error::JacobianError;
pub use jacobian::{Jacobian2, Jacobian3, jacobian_2d, jacobian_3d, physical_from_reference_2d};
pub use lagrange::{reference_nodes, shape_functions, shape_gradients, supported_types};
