//! The mesh: nodes, domain cells, boundary facets grouped in patches (one per boundary loop in
//! 2D), and the per-cell records the later stages need (layer index, pipe).

use geom_predicates::polygon_area;
use serde::{Deserialize, Serialize};

use crate::cell::Shape;
use crate::cells::Cells;

/// Marks a cell that belongs to no layer or descends from no boundary facet.
pub const NONE: u32 = u32::MAX;

/// What a boundary is, for the solver: it names the physical group in the written files.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Role {
    /// A solid body: no-slip wall, viscous layers grow from it.
    Wall,
    /// The outer boundary of the domain.
    Farfield,
}

/// The name of a 3D near-body mesh's outer boundary (the layers' final front): a patch of
/// role [`Role::Farfield`] so named is written as its own group `outer`, not `farfield`, where a
/// solver would put a far-field condition a few body lengths away.
pub const OUTER_GROUP: &str = "outer";

impl Role {
    /// The physical-group name written to files (`wall`, `farfield`).
    pub fn name(self) -> &'static str {
        match self {
            Role::Wall => "wall",
            Role::Farfield => "farfield",
        }
    }
}

/// A boundary patch: one closed loop in 2D, one surface in 3D.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Patch {
    /// A name for people (`slat`, `main`, `flap`, `farfield`); not necessarily unique.
    pub name: String,
    /// The patch's role, which names its physical group.
    pub role: Role,
}

/// Spatial dimension of a mesh.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum Dim {
    /// Planar mesh: nodes have z = 0, cells are triangles and quads, facets are lines.
    Two,
    /// Volume mesh: cells are tets, pyramids, prisms, hexes, facets are triangles and quads.
    Three,
}

impl Dim {
    /// 2 or 3.
    pub fn as_u8(self) -> u8 {
        match self {
            Dim::Two => 2,
            Dim::Three => 3,
        }
    }
}

/// A mixed, possibly high-order mesh.
///
/// Invariants (checked by [`crate::validate()`]): every node index is in range; `boundary_patch`
/// has one entry per boundary facet; `cell_layer` and `cell_pipe` are either empty or have one
/// entry per cell; 2D nodes have z = 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Mesh {
    /// 2D or 3D.
    pub dim: Dim,
    /// Polynomial order of the cells, 1 to 3.
    pub order: u8,
    /// Node coordinates; z = 0 in 2D.
    pub nodes: Vec<[f64; 3]>,
    /// Domain cells (triangles and quads in 2D).
    pub cells: Cells,
    /// Boundary facets (lines in 2D), oriented so that the domain lies on their left in 2D.
    pub boundary: Cells,
    /// For each boundary facet, the index of its patch in `patches`.
    pub boundary_patch: Vec<u32>,
    /// The boundary patches.
    pub patches: Vec<Patch>,
    /// For each cell, its layer index counted from the boundary it grew from (0 = touching
    /// it), or [`NONE`]; empty when unknown.
    pub cell_layer: Vec<u32>,
    /// For each cell, the boundary facet whose pipe it belongs to, or [`NONE`]; empty when
    /// unknown.
    pub cell_pipe: Vec<u32>,
}

impl Mesh {
    /// An empty mesh of the given dimension and order.
    pub fn new(dim: Dim, order: u8) -> Self {
        Mesh {
            dim,
            order,
            nodes: Vec::new(),
            cells: Cells::new(),
            boundary: Cells::new(),
            boundary_patch: Vec::new(),
            patches: Vec::new(),
            cell_layer: Vec::new(),
            cell_pipe: Vec::new(),
        }
    }

    /// The (x, y) coordinates of node `i`.
    pub fn xy(&self, i: u32) -> [f64; 2] {
        let p = self.nodes[i as usize];
        [p[0], p[1]]
    }

    /// Signed area of the linear 2D cell `i` (corners only), by the shoelace formula:
    /// positive when its corners run counter-clockwise.
    pub fn linear_cell_area(&self, i: usize) -> f64 {
        polygon_area(self.cells.get(i).corners().iter().map(|&n| self.xy(n)))
    }

    /// Sum of the signed areas of the linear 2D cells.
    pub fn linear_area(&self) -> f64 {
        (0..self.cells.len())
            .map(|i| self.linear_cell_area(i))
            .sum()
    }

    /// Count of cells of the given shape.
    pub fn count(&self, shape: Shape) -> usize {
        self.cells.count(shape)
    }

    /// The boundary facets of patch `patch`, in order.
    pub fn patch_facets(&self, patch: u32) -> impl Iterator<Item = usize> + '_ {
        self.boundary_patch
            .iter()
            .enumerate()
            .filter(move |(_, p)| **p == patch)
            .map(|(i, _)| i)
    }
}

/// Whether the linear polygon `corners` (a triangle or a convex quadrilateral's corners, in
/// order) is positively oriented with a positive Jacobian everywhere, decided exactly: every
/// corner turns left by the exact orientation predicate (`geom_predicates::orient2d`). A triangle is
/// positive when its one orientation is; a quadrilateral's bilinear map has a positive
/// Jacobian everywhere exactly when all four corners turn left.
pub fn is_positive_polygon(corners: &[[f64; 2]]) -> bool {
    let n = corners.len();
    (0..n).all(|i| {
        let (a, b, d) = (corners[(i + n - 1) % n], corners[i], corners[(i + 1) % n]);
        geom_predicates::orient2d(a, b, d) > 0.0
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::cell::CellType;

    #[test]
    fn unit_square_of_two_triangles_has_area_one() {
        let mut m = Mesh::new(Dim::Two, 1);
        m.nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
        ];
        let tri = CellType::new(Shape::Tri, 1);
        m.cells.push(tri, &[0, 1, 2]);
        m.cells.push(tri, &[0, 2, 3]);
        assert!((m.linear_area() - 1.0).abs() < 1e-15);
        assert_eq!(m.count(Shape::Tri), 2);
    }

    #[test]
    fn clockwise_polygon_has_negative_area() {
        let a = polygon_area([[0.0, 0.0], [0.0, 2.0], [3.0, 0.0]]);
        assert!((a + 3.0).abs() < 1e-15);
    }
}
