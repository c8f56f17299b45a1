//! Validity of high-order (curved) cells: Lagrange shape functions of Gmsh's reference
//! cells ([`lagrange`]), the Jacobian of the reference-to-physical map ([`mod@jacobian`]), and a
//! **certified** check of the sign of its determinant from Bernstein coefficients with
//! adaptive subdivision ([`certify`], after Johnen, Remacle & Geuzaine, "Geometrical
//! validity of curvilinear finite elements", J. Comput. Phys. 2013), next to the sampled
//! check the dissertation used; plus the area of a curved 2D mesh by exact quadrature and
//! the volume of a curved 3D mesh from the Bernstein coefficients ([`area`]), and the fraction of edges a curved mesh bends ([`curved`]).
//!
//! Node order everywhere is Gmsh's (the data model's). The crate reads meshes and node
//! coordinates and reports; it never moves a node, and does no file IO.
//!
//! # Example
//!
//! Certify a hand-made P3 triangle whose bottom edge bows outward (a cell on a curved wall),
//! then the same triangle with that edge's two nodes swapped, which folds it back on itself:
//!
//! ```
//! use jacobian_check::{Certificate, CertifyParams, certify_cell};
//! use mesh_model::{CellType, Shape};
//!
//! // Gmsh's node order: the 3 corners, 2 nodes on each edge (0→1, 1→2, 2→0), the interior
//! let t = 1.0 / 3.0;
//! let mut nodes = [
//!     [0.0, 0.0], [1.0, 0.0], [0.0, 1.0],
//!     [t, -0.08], [2.0 * t, -0.08],   // edge 0→1, bowed down by 0.08
//!     [2.0 * t, t], [t, 2.0 * t],     // edge 1→2, straight
//!     [0.0, 2.0 * t], [0.0, t],       // edge 2→0, straight
//!     [t, t],                         // interior
//! ];
//! let p3 = CellType::new(Shape::Tri, 3);
//! let params = CertifyParams::default();
//!
//! let good = certify_cell(p3, &nodes, &params)?;
//! assert!(good.is_valid()); // proved: det J > 0 everywhere in the cell
//! // min J / max J, certified from below (1 for a straight-sided triangle)
//! let sj = good.scaled_jacobian_lower_bound().unwrap();
//! assert!(sj > 0.3 && sj < 1.0, "{sj}");
//!
//! nodes.swap(3, 4); // the bottom edge now doubles back: the cell is folded
//! let folded = certify_cell(p3, &nodes, &params)?;
//! let Certificate::Invalid { at } = folded else { panic!("{folded:?}") };
//! // `at` is a reference point (ξ, η) where det J ≤ 0, here on or near the bottom edge
//! assert!(at[1] < 0.5, "{at:?}");
//! # Ok::<(), jacobian_check::JacobianError>(())
//! ```
//!
//! For a whole mesh, [`check_mesh`] certifies every cell (on all cores) and returns the
//! invalid and undecided cells and each cell's scaled Jacobian.
//!
//! One API for 2D and 3D: every per-cell function is generic over the dimension `D` of the
//! node coordinates (`[f64; 2]` or `[f64; 3]`), and [`types`] is the one table of the cell
//! types the crate knows and what it offers for each ([`capabilities`]): every type with
//! shape functions is certified — triangles, quadrilaterals, tetrahedra, prisms, hexahedra
//! and pyramids of order 1–3 (Gmsh's complete cells: the 20-node tetrahedron, the 40-node
//! prism, the 64-node hexahedron, the 14- and 30-node pyramids). A straight-sided high-order
//! pyramid (every node where the linear pyramid puts it) *is* its linear pyramid and is
//! certified (and integrated) as one; a curved one in Gmsh's own (Bergot) space, its
//! determinant expanded in the pyramid's collapsed coordinates (Johnen & Geuzaine 2015).
//!
//! ```
//! use jacobian_check::{CertifyParams, certify_cell, reference_nodes};
//! use mesh_model::{CellType, Shape};
//!
//! // Gmsh's 18-node prism with the node on its top edge 3–4 lifted: still valid
//! let p2 = CellType::new(Shape::Prism, 2);
//! let mut prism = reference_nodes(p2)?;
//! prism[12][2] += 0.3;
//! assert!(certify_cell(p2, &prism, &CertifyParams::default())?.is_valid());
//! // the linear pyramid with its apex below the base: proved folded
//! let p1 = CellType::new(Shape::Pyramid, 1);
//! let mut pyramid = reference_nodes(p1)?;
//! pyramid[4] = [0.5, 0.2, -0.3];
//! assert!(!certify_cell(p1, &pyramid, &CertifyParams::default())?.is_valid());
//! # Ok::<(), jacobian_check::JacobianError>(())
//! ```
//!
//! Modules, bottom up (each uses only modules before it): the leaves `error`, `linalg`,
//! `matrix`, `gauss`, `measure`, `point` and [`curved`]; then [`types`], `pyramid`,
//! [`lagrange`], [`mod@jacobian`], `bernstein`, `straight`, [`certify`], [`area`].

pub mod area;
mod bernstein;
pub mod certify;
pub mod curved;
pub mod error;
mod gauss;
pub mod jacobian;
pub mod lagrange;
mod linalg;
mod matrix;
mod measure;
mod point;
mod pyramid;
mod straight;
pub mod types;

pub use area::{
    cell_area, cell_volume, enclosed_area, enclosed_volume, integrate_area, integrate_volume,
};
pub use certify::{
    Certificate, CertifyParams, MeshValidity, SampledCheck, certify_cell, check_mesh,
    determinant_bernstein_coefficients, sampled_check,
};
pub use curved::curved_edge_fraction;
pub use error::JacobianError;
pub use jacobian::{Jacobian, jacobian, physical_from_reference};
pub use lagrange::{reference_nodes, shape_functions, shape_gradients};
pub use matrix::matrix_from_gradients;
pub use types::{Capabilities, capabilities, supported_types};
