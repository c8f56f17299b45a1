//! The shared mesh data model: node coordinates, mixed linear and high-order cells in Gmsh's
//! node order, boundary facets grouped in patches with a role (wall, far field), and the
//! per-cell layer index and "pipe" that the curving and movement stages need, with the rest of
//! the layers (node layers and parents, pipe columns) in [`Layering`].
//!
//! It owns the types, the topology built once per mesh ([`topology`]: unique edges and faces
//! with their cells), the checks ([`validate()`], [`first_problem`],
//! [`first_structural_problem`]: one walk, structural then geometric, 2D and 3D) and the
//! polyhedral cells between a 3D mesher and the cut into standard cells ([`poly`]), and
//! nothing else: no file formats (that is `mesh-io`) and no meshing algorithm.
//!
//! # Example
//!
//! The unit square as two linear triangles, its four sides one far-field patch, checked;
//! then one triangle turned clockwise, which [`validate()`] reports:
//!
//! ```
//! use mesh_model::{CellType, Dim, Mesh, Patch, Role, Shape, validate};
//!
//! let mut mesh = Mesh::new(Dim::Two, 1);
//! mesh.nodes = vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]];
//! let tri = CellType::new(Shape::Tri, 1);
//! mesh.cells.push(tri, &[0, 1, 2]); // counter-clockwise
//! mesh.cells.push(tri, &[0, 2, 3]);
//! let line = CellType::new(Shape::Line, 1);
//! for k in 0..4 {
//!     mesh.boundary.push(line, &[k, (k + 1) % 4]); // the domain on the left
//!     mesh.boundary_patch.push(0);
//! }
//! mesh.patches.push(Patch { name: "farfield".into(), role: Role::Farfield });
//!
//! assert!(validate(&mesh).is_empty());
//! assert_eq!(mesh.linear_area(), 1.0);
//!
//! mesh.cells.nodes_mut(1).swap(1, 2); // [0, 3, 2]: clockwise
//! let problems = validate(&mesh);
//! assert!(!problems.is_empty());
//! println!("{}", problems[0]); // each problem names the cell or facet at fault
//! ```

pub mod cell;
pub mod cells;
pub mod layering;
pub mod measure;
pub mod measure3d;
pub mod mesh;
pub mod poly;
pub mod reference;
pub mod topology;
pub mod validate;

pub use cell::{CellType, Shape};
pub use cells::{CellRef, Cells};
/// The signed area of a polygon (shoelace formula), shared with every crate.
pub use geom_predicates::polygon_area;
pub use layering::{LayeredMesh, Layering};
pub use mesh::{Dim, Mesh, NONE, OUTER_GROUP, Patch, Role, is_positive_polygon};
pub use topology::Topology;
pub use validate::{Problem, first_problem, first_structural_problem, is_positive_tet, validate};
