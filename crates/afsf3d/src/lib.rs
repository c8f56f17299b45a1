//! The advancing-front spring-field mesher in 3D (dissertation §5.2.1–5.2.2): layers grown
//! from the wall facets of a closed [`Surface`], one child per node per layer, balanced by
//! the 3D springs of `springfield` ([`springfield::SpringField3d`]), every layer checked and
//! shrunk where it fails.
//!
//! Layer k (from 0) has the height `first_height × growth^k`. Each front node's ideal
//! direction is the angle-weighted normal of the front facets around it; its ideal length is
//! the layer height, divided, at a concave node, by the smallest cosine between the direction
//! and the normals of its facets (so that the child stands the layer height off every facet
//! there; see `docs/afsf3d.md`). The children start at their ideal places and are balanced
//! twice: by the extrusion, neighbour and angle springs, then with the tension springs added
//! (ideal length 0.9 × the length after the first balance). Then every cell is checked: each
//! corner tetrahedron of the cell (a corner, its two neighbours on the bottom or top face and
//! the node above or below) must be positive by the exact `orient3d`, and the new front must
//! not intersect itself (facet pairs by sort-and-sweep, the exact triangle test). The children
//! of a failing cell or facet pair are moved halfway back to their parents, and the check
//! repeated, at most [`LayerParams::max_shrinks`] times; then the growth fails with the
//! layer and facet.
//!
//! The result ([`Grown3d`]) is a [`PolyMesh`] of the raw layer cells with `cell_layer` and
//! `cell_pipe` (the wall facet each cell descends from), the column of every wall node (its
//! node and its children, bottom-up: the layering record), and the final front, the outer
//! boundary of the near-body mesh the layers make. Each cell's faces follow the contract with
//! `topo-cut`: face 0 the bottom (on the previous front, outward of the cell: towards the
//! wall), face 1 the top, then the side faces in the order of the bottom's edges.
//!
//! Not yet: neighbour merging (Coe_shrink) — every wall node keeps its full column, so the
//! cells are hexahedra over quads and prisms over triangles; front closing between bodies.
//!
//! ```
//! use afsf3d::{LayerParams, grow_layers};
//! use geom_surface::Surface;
//!
//! let sphere = Surface::sphere(1.0, 2);
//! let params = LayerParams { first_height: 0.01, growth: 1.2, layers: 5, ..LayerParams::default() };
//! let grown = grow_layers(&sphere, &params)?;
//! assert_eq!(grown.mesh.cell_count(), 5 * sphere.facets.len());
//! assert!(grown.mesh.validate().is_empty());
//! assert!(grown.columns.iter().all(|c| c.len() == 6)); // every node keeps its five children
//! # Ok::<(), afsf3d::GrowError>(())
//! ```

mod check;
mod front;
mod grow;

pub use grow::grow_layers;

use geom_surface::{Surface, SurfaceError};
use mesh_model::poly::PolyMesh;
use springfield::{SolverParams, SpringError, SpringParams3d};

/// What to grow.
#[derive(Debug, Clone, PartialEq)]
pub struct LayerParams {
    /// Height of the first layer.
    pub first_height: f64,
    /// Ratio of each layer's height to the one below (≥ 1).
    pub growth: f64,
    /// Number of layers.
    pub layers: usize,
    /// The spring coefficients.
    pub springs: SpringParams3d,
    /// The balance's solver settings.
    pub solver: SolverParams,
    /// How many times the children of a failing cell are moved halfway back before the growth
    /// fails.
    pub max_shrinks: usize,
    /// Rounds of smoothing of the ideal directions over the front (each direction replaced
    /// by the normalised sum of its own and its neighbours'): fans the directions out of
    /// concave edges, so the front there spreads instead of folding. Default 8.
    pub smoothing: usize,
}

impl Default for LayerParams {
    fn default() -> Self {
        LayerParams {
            first_height: 1e-3,
            growth: 1.2,
            layers: 30,
            springs: SpringParams3d::default(),
            solver: SolverParams {
                max_iterations: 300,
                tolerance: 1e-3,
                ..SolverParams::default()
            },
            max_shrinks: 8,
            smoothing: 8,
        }
    }
}

/// Why the layers could not be grown.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GrowError {
    /// The surface fails its checks.
    #[error("bad surface: {0}")]
    Surface(#[from] SurfaceError),
    /// A parameter is out of range.
    #[error("bad layer parameter: {0}")]
    Params(String),
    /// Far-field facets on the surface: growth from part of a surface is not supported yet.
    #[error("facet {facet} is not a wall: layers grow from closed wall surfaces only")]
    NotWall {
        /// The first such facet.
        facet: usize,
    },
    /// The spring solver failed.
    #[error("spring balance of layer {layer}: {source}")]
    Spring {
        /// The layer (from 0).
        layer: usize,
        /// The solver's error.
        source: SpringError,
    },
    /// A layer stays invalid however much its children are shrunk.
    #[error("layer {layer} cannot be grown over wall facet {facet}: {what}")]
    LayerFailed {
        /// The layer (from 0).
        layer: usize,
        /// The wall facet of the pipe where it fails.
        facet: usize,
        /// What fails.
        what: &'static str,
    },
}

/// Measures of a growth.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct GrowStats {
    /// How many times some children were moved halfway back.
    pub shrinks: usize,
    /// Children moved back (counted once per shrink).
    pub shrunk_nodes: usize,
    /// Whether every balance converged.
    pub converged: bool,
}

/// Grown layers.
#[derive(Debug, Clone)]
pub struct Grown3d {
    /// The layer cells (see the crate's doc for the order of their faces); node `i` of the
    /// surface is node `i` here, the children of layer k follow, `n` per layer.
    pub mesh: PolyMesh,
    /// For each surface node, its node and its children, bottom-up (`layers + 1` nodes).
    pub columns: Vec<Vec<u32>>,
    /// The final front: the surface's facets over the top children (node `i` of the front is
    /// the top of column `i`), the outer boundary of the layers.
    pub front: Surface,
    /// Measures of the growth.
    pub stats: GrowStats,
}
