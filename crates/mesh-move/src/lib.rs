//! Mesh movement in 2D, the parts that need no mesher: motions of boundary loops (a rigid
//! motion with uniform scaling, Hicks–Henne bumps of a wall section) with their checks
//! (values, and moved loops that cross each other or leave the far field), two baseline
//! movers of the nodes of a linear mesh that follow its moved boundary (rotation-aware
//! inverse-distance weighting and radial basis functions, Wendland C2 or thin-plate spline),
//! and the measures that compare movers (scaled Jacobians, worst-cell ratio, inverted cells,
//! first-layer drift). The spring mover ([`springs`], [`move_layered`]) also takes the mesh's
//! layers and keeps the original layer geometry near the walls.
//!
//! It owns no meshing and no IO: it takes a [`mesh_model::Mesh`] of order 1 and returns one
//! with the same topology and new node positions. The boundary nodes are those of the
//! boundary facets; each patch is a loop named after the patch; loops without a motion stay.
//!
//! # Example
//!
//! A square body in a square far field, with one ring of interior nodes between them: the
//! body turned by 10° about its centre, the interior nodes moved by both movers, the result
//! compared with the original; then a motion that would push the body through the far field.
//!
//! ```
//! use mesh_model::{CellType, Dim, Mesh, Patch, Role, Shape};
//! use mesh_move::{
//!     IdwParams, LoopMotion, Method, Motion, RbfParams, RigidMotion, boundary_motion, compare,
//!     move_mesh,
//! };
//!
//! let mut mesh = Mesh::new(Dim::Two, 1);
//! for s in [1.0, 2.0, 3.0] {
//!     // corners 4r..4r+3 of the square of half-side s, counter-clockwise
//!     for [x, y] in [[-s, -s], [s, -s], [s, s], [-s, s]] {
//!         mesh.nodes.push([x, y, 0.0]);
//!     }
//! }
//! let (quad, line) = (CellType::new(Shape::Quad, 1), CellType::new(Shape::Line, 1));
//! for k in 0..4u32 {
//!     let k1 = (k + 1) % 4;
//!     mesh.cells.push(quad, &[k, 4 + k, 4 + k1, k1]); // body to middle ring
//!     mesh.cells.push(quad, &[4 + k, 8 + k, 8 + k1, 4 + k1]); // middle ring to far field
//!     mesh.boundary.push(line, &[k1, k]); // the domain on each facet's left
//!     mesh.boundary_patch.push(0);
//!     mesh.boundary.push(line, &[8 + k, 8 + k1]);
//!     mesh.boundary_patch.push(1);
//! }
//! mesh.patches = vec![
//!     Patch { name: "body".into(), role: Role::Wall },
//!     Patch { name: "farfield".into(), role: Role::Farfield },
//! ];
//!
//! let turn = LoopMotion {
//!     loop_name: "body".into(),
//!     motion: Motion::rigid(RigidMotion::rotation(10.0, [0.0, 0.0])),
//! };
//! let boundary = boundary_motion(&mesh, &[turn])?;
//! for method in [Method::Idw(IdwParams::default()), Method::Rbf(RbfParams::default())] {
//!     let moved = move_mesh(&mesh, &boundary, &method)?;
//!     assert_eq!(moved.stats.interior_nodes, 4);
//!     let c = compare(&mesh, &moved.mesh)?;
//!     assert_eq!(c.inverted_cells, 0);
//!     assert!(c.worst_cell_ratio > 0.6, "{method:?}: {}", c.worst_cell_ratio);
//! }
//!
//! let too_big = LoopMotion {
//!     loop_name: "body".into(),
//!     motion: Motion::rigid(RigidMotion { translate: [3.0, 0.0], ..RigidMotion::IDENTITY }),
//! };
//! let err = boundary_motion(&mesh, &[too_big]).unwrap_err();
//! assert!(err.to_string().starts_with("moved loops body and farfield cross"), "{err}");
//! # Ok::<(), mesh_move::MoveError>(())
//! ```

pub mod balance;
mod boundary;
mod error;
pub mod motion;
pub mod movers;
mod outcome;
mod params;
pub mod quality;
pub mod springs;

pub use balance::{Sensitivity, ShapeField};
pub use boundary::{BoundaryMotion, boundary_motion, mesh_loops, patch_loop};
pub use error::MoveError;
pub use motion::{
    BoundaryLoop, HicksHenne, LoopMotion, Motion, RigidMotion, Section, Surface, check_loops,
    move_loops,
};
pub use movers::{IdwParams, Kernel, Method, MoveStats, Moved, RbfParams, move_mesh};
pub use quality::{Comparison, FirstLayerDrift, compare, scaled_jacobian};
pub use springs::{
    Fill, SpringMoveParams, SpringStats, StartAndBalance, Strategy, Warm, move_layered,
    move_layered_from, move_layered_in,
};
