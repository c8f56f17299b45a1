//! The Spring-Field: spring models between mesh nodes and the damped explicit pseudo-time
//! solver that balances them, shared by the 2D and 3D advancing-front meshers.
//!
//! It owns three things:
//! - [`SpringParams`]: the spring coefficients (defaults are the dissertation's, §3.2.2.1 and
//!   §4.1), deserialisable from a case file;
//! - [`solve()`]: a solver generic over the node dimension `D` that takes a force-assembly
//!   callback, so that a 3D mesher reuses it with its own springs;
//! - [`springs`]: the spring models themselves, written as data (which nodes, which ideal
//!   length) plus an assembly function that turns them into forces and stiffnesses.
//!
//! It does not own the mesh topology: which nodes are linked by which springs, which nodes
//! may move, and what a node's length scale is are decided by the mesher (`afsf2d`).

mod error;
mod params;
mod solver;
pub mod springs;
mod vec;

pub use error::SpringError;
pub use params::{SolverParams, SpringParams};
pub use solver::{Active, Influence, SolveOutcome, solve, solve_active};
pub use springs::{
    AngleSpring, ExtrusionSpring, NeighbourSpring, SpringIndex2d, SpringSet2d, assemble_2d,
    assemble_2d_active,
};
