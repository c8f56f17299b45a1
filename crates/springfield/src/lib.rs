//! The Spring-Field: spring models between mesh nodes and the damped explicit pseudo-time
//! solver that balances them, shared by the 2D and 3D advancing-front meshers.
//!
//! It owns three things:
//! - [`SpringParams`]: the spring coefficients (defaults are the dissertation's, §3.2.2.1 and
//!   §4.1), deserialisable from a case file;
//! - [`solve()`]: a solver generic over the node dimension `D` that takes a force-assembly
//!   callback, so that a 3D mesher reuses it with its own springs;
//! - [`springs`]: the spring models themselves, written as data (which nodes, which ideal
//!   length) plus an assembly function that turns them into forces and stiffnesses;
//! - [`model`]: the interface over the dimension that a solver sees ([`ForceModel`], one
//!   [`Spring`] per kind), with the forces' sparse Jacobian for a Newton solver, and the
//!   place where the 3D spring set goes; [`solve_model`] and [`solve_model_active`] take a
//!   model instead of a callback;
//! - [`shape`], [`length`], [`jump`], [`corner`] and [`newton`]: the springs of the shape
//!   balance (a cell held to its rest shape, an edge to its length, two cells to the same
//!   deformation, an extrusion edge to its angle with the wall; each the gradient of an energy) and Newton's method with a sparse Cholesky factorisation on such a
//!   conservative field, with its linearisation for sensitivities (mesh movement);
//! - [`problem`]: the local spring problem of a layered mesher (which nodes of the top
//!   layers move, local numbering, solve on copies, undo), shared by every mesher.
//!
//! It does not own the mesh topology: which nodes are linked by which springs, which nodes
//! may move, and what a node's length scale is are decided by the mesher (`afsf2d`).
//!
//! # Example
//!
//! One layer of three nodes grown from three fixed wall nodes on y = 0: each child is held
//! at 0.1 from its parent by an extrusion spring, and the middle one is kept halfway between
//! its neighbours by a neighbour spring. Started out of place, the solver balances them:
//!
//! ```
//! use springfield::{
//!     ExtrusionSpring, NeighbourSpring, SolverParams, SpringParams, SpringSet2d, assemble_2d,
//!     solve,
//! };
//!
//! // nodes 0..3: the wall (fixed); nodes 3..6: their children (free), out of place
//! let mut xy = [[0.0, 0.0], [1.0, 0.0], [2.0, 0.0], [0.0, 0.3], [1.3, 0.05], [2.0, 0.2]];
//! let movable = [false, false, false, true, true, true];
//! let scale = [0.1; 6]; // each node's length scale: moves and convergence are relative to it
//! let mut set = SpringSet2d::default();
//! for k in 0..3 {
//!     set.extrusion.push(ExtrusionSpring { lower: k, upper: k + 3, ideal_length: 0.1, lower_share: 1.0 });
//! }
//! set.neighbour.push(NeighbourSpring { left: 3, centre: 4, right: 5, parent: 1, left_share: 0.5 });
//!
//! let springs = SpringParams::default(); // the dissertation's coefficients
//! let solver = SolverParams { max_iterations: 2000, tolerance: 1e-6, ..SolverParams::default() };
//! let outcome = solve(&mut xy, &scale, &movable, &solver, |p, force, stiffness| {
//!     assemble_2d(&set, &springs, p, force, stiffness)
//! })?;
//! assert!(outcome.converged, "{outcome:?}");
//! assert_eq!(xy[1], [1.0, 0.0]); // fixed nodes never move
//! for (k, expected) in [(3, [0.0, 0.1]), (4, [1.0, 0.1]), (5, [2.0, 0.1])] {
//!     let d = ((xy[k][0] - expected[0]).powi(2) + (xy[k][1] - expected[1]).powi(2)).sqrt();
//!     assert!(d < 1e-3, "node {k} at {:?}", xy[k]);
//! }
//! # Ok::<(), springfield::SpringError>(())
//! ```

mod active;
pub mod corner;
mod error;
pub mod jump;
pub mod length;
pub mod model;
pub mod newton;
mod params;
pub mod problem;
pub mod quad;
pub mod shape;
mod solver;
pub mod springs;
pub mod springs3d;
mod vec;

pub use active::{Active, Influence};
pub use corner::CornerSpring;
pub use error::SpringError;
pub use jump::{JumpSpring, quad_jumps};
pub use length::{BalanceSpring, LengthSpring};
pub use model::{FiniteDifference, ForceModel, Spring, SpringList, Triplet};
pub use newton::{
    EnergyModel, Linearised, NewtonOutcome, NewtonParams, NewtonWorkspace, solve_newton,
    solve_newton_in,
};
pub use params::{SolverParams, SpringParams};
pub use problem::{LocalProblem, NO_NODE, Undo};
pub use quad::QuadSpring;
pub use shape::{ShapeLaw, ShapeSpring, shape_springs};
pub use solver::{SolveOutcome, solve, solve_active, solve_model, solve_model_active};
pub use springs::{
    AngleSpring, ExtrusionSpring, NeighbourSpring, SpringField2d, SpringIndex2d, SpringSet2d,
    assemble_2d, assemble_2d_active, bisector, left_normal,
};
pub use springs3d::{
    AngleSpring3d, NeighbourSpring3d, SpringField3d, SpringParams3d, SpringSet3d, TensionSpring,
};
