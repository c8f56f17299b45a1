//! What a move returns: the moved mesh and its figures, those of every mover
//! ([`MoveStats`]) and those of the spring mover ([`SpringStats`]).

use mesh_model::Mesh;
use springfield::NewtonOutcome;

use crate::params::Fill;

/// What a move did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct MoveStats {
    /// Largest displacement of any node.
    pub largest_displacement: f64,
    /// Largest displacement of a boundary node.
    pub largest_boundary_displacement: f64,
    /// Boundary nodes (placed at their targets).
    pub boundary_nodes: usize,
    /// Other nodes (placed by the mover).
    pub interior_nodes: usize,
    /// Cells inverted or degenerate after the move ([`crate::quality::inverted_cells`]): a
    /// move with any is a failure, whatever the mover.
    pub inverted_cells: usize,
    /// RBF only: the largest difference between the interpolant and the boundary
    /// displacement at a boundary node (the solve's accuracy); 0 for IDW.
    pub interpolation_residual: f64,
    /// Springs only: the spring solve's figures.
    pub springs: Option<SpringStats>,
}

/// The moved mesh (same topology, new node positions) and what the move did.
#[derive(Debug, Clone, PartialEq)]
pub struct Moved {
    /// The moved mesh.
    pub mesh: Mesh,
    /// Figures of the move.
    pub stats: MoveStats,
    /// The spring mover: where its shape balance started (the fill), with the balanced nodes
    /// the warm start of the next step of a sequence ([`crate::move_layered_from`]).
    pub start: Option<Vec<[f64; 2]>>,
}

/// Figures of a spring move.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct SpringStats {
    /// Spring solves done (1, or one per layer plus one).
    pub solves: usize,
    /// Solver iterations over all solves.
    pub iterations: usize,
    /// True when every solve converged.
    pub converged: bool,
    /// Largest move of a node in the last iteration of the last solve, relative to its
    /// original extrusion length.
    pub residual: f64,
    /// Springs (extrusion, neighbour, angle).
    pub springs: usize,
    /// Layer nodes (moved by the predictor and the springs).
    pub layer_nodes: usize,
    /// Nodes of the filled region.
    pub fill_nodes: usize,
    /// As-rigid-as-possible iterations done.
    pub arap_iterations: usize,
    /// The fill used.
    pub fill: Fill,
    /// The shape balance's Newton solve (`None` when the fill inverted a cell: the balance
    /// needs an uninverted start, and the move is reported as failed).
    pub newton: Option<NewtonOutcome>,
}
