//! Cell types: the shape, the polynomial order, and what follows from them (node counts,
//! corner edges). Node ordering everywhere in the data model is Gmsh's: corners first, then
//! edge nodes edge by edge, then face nodes, then interior nodes.

use serde::{Deserialize, Serialize};

/// The shape of a cell, independent of its order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub enum Shape {
    /// Two-node segment (a boundary facet in 2D).
    Line,
    /// Triangle.
    Tri,
    /// Quadrilateral.
    Quad,
    /// Tetrahedron.
    Tet,
    /// Pyramid with a quadrilateral base.
    Pyramid,
    /// Triangular prism (wedge).
    Prism,
    /// Hexahedron.
    Hex,
}

impl Shape {
    /// Topological dimension of the shape.
    pub fn dim(self) -> u8 {
        match self {
            Shape::Line => 1,
            Shape::Tri | Shape::Quad => 2,
            Shape::Tet | Shape::Pyramid | Shape::Prism | Shape::Hex => 3,
        }
    }

    /// Number of corner (vertex) nodes.
    pub fn corners(self) -> usize {
        match self {
            Shape::Line => 2,
            Shape::Tri => 3,
            Shape::Quad => 4,
            Shape::Tet => 4,
            Shape::Pyramid => 5,
            Shape::Prism => 6,
            Shape::Hex => 8,
        }
    }

    /// Lower-case name used in reports (`tri`, `quad`, …).
    pub fn name(self) -> &'static str {
        match self {
            Shape::Line => "line",
            Shape::Tri => "tri",
            Shape::Quad => "quad",
            Shape::Tet => "tet",
            Shape::Pyramid => "pyramid",
            Shape::Prism => "prism",
            Shape::Hex => "hex",
        }
    }

    /// The edges of the shape as pairs of local corner indices, in Gmsh's edge order
    /// (which is also the order of the edge nodes of high-order cells).
    pub fn edges(self) -> &'static [[usize; 2]] {
        match self {
            Shape::Line => &[[0, 1]],
            Shape::Tri => &[[0, 1], [1, 2], [2, 0]],
            Shape::Quad => &[[0, 1], [1, 2], [2, 3], [3, 0]],
            Shape::Tet => &[[0, 1], [1, 2], [2, 0], [3, 0], [3, 2], [3, 1]],
            Shape::Pyramid => &[
                [0, 1],
                [0, 3],
                [0, 4],
                [1, 2],
                [1, 4],
                [2, 3],
                [2, 4],
                [3, 4],
            ],
            Shape::Prism => &[
                [0, 1],
                [0, 2],
                [0, 3],
                [1, 2],
                [1, 4],
                [2, 5],
                [3, 4],
                [3, 5],
                [4, 5],
            ],
            Shape::Hex => &[
                [0, 1],
                [0, 3],
                [0, 4],
                [1, 2],
                [1, 5],
                [2, 3],
                [2, 6],
                [3, 7],
                [4, 5],
                [4, 7],
                [5, 6],
                [6, 7],
            ],
        }
    }

    /// The faces of a 3D shape as lists of local corner indices, in Gmsh's face order, each
    /// oriented outward (counter-clockwise seen from outside the cell); empty for lines,
    /// triangles and quadrilaterals. Source: Gmsh's element classes (`faces_tetra`,
    /// `faces_pyramid`, `faces_prism`, `faces_hexa` in `src/geo/MTetrahedron.h`, `MPyramid.h`,
    /// `MPrism.h`, `MHexahedron.h`); the outward orientation is checked on the reference cells
    /// by a unit test.
    pub fn faces(self) -> &'static [&'static [usize]] {
        match self {
            Shape::Line | Shape::Tri | Shape::Quad => &[],
            Shape::Tet => &[&[0, 2, 1], &[0, 1, 3], &[0, 3, 2], &[3, 1, 2]],
            Shape::Pyramid => &[
                &[0, 1, 4],
                &[3, 0, 4],
                &[1, 2, 4],
                &[2, 3, 4],
                &[0, 3, 2, 1],
            ],
            Shape::Prism => &[
                &[0, 2, 1],
                &[3, 4, 5],
                &[0, 1, 4, 3],
                &[0, 3, 5, 2],
                &[1, 2, 5, 4],
            ],
            Shape::Hex => &[
                &[0, 3, 2, 1],
                &[0, 1, 5, 4],
                &[0, 4, 7, 3],
                &[1, 2, 6, 5],
                &[2, 3, 7, 6],
                &[4, 5, 6, 7],
            ],
        }
    }

    /// For each corner `c` of a linear 3D shape where three edges meet, a tetrahedron of local
    /// corners `[c, p, n, d]` whose signed volume has the sign of the cell's Jacobian at `c`
    /// (positive on the reference cell): `p` and `n` come before and after `c` on an outward
    /// face through it, `d` is `c`'s third neighbour, off that face, inside. Derived from
    /// [`Shape::faces`] and [`Shape::edges`]; a pyramid's apex (four edges, a singular
    /// Jacobian) has none, and a tetrahedron, its own corner tetrahedron, gives one. Nothing
    /// for 1D and 2D shapes.
    pub fn corner_tets(self) -> impl Iterator<Item = [usize; 4]> {
        let simplex = self == Shape::Tet;
        (0..self.corners())
            .filter_map(move |c| {
                let face = self.faces().iter().find(|f| f.contains(&c))?;
                let at = face.iter().position(|&v| v == c)?;
                let p = face[(at + face.len() - 1) % face.len()];
                let n = face[(at + 1) % face.len()];
                let mut others = self.edges().iter().filter_map(|e| match *e {
                    [a, b] if a == c && !face.contains(&b) => Some(b),
                    [a, b] if b == c && !face.contains(&a) => Some(a),
                    _ => None,
                });
                let d = others.next()?;
                others.next().is_none().then_some([c, p, n, d])
            })
            .take(if simplex { 1 } else { usize::MAX })
    }
}

/// A cell type: a shape at a polynomial order (1 = linear). Only complete Lagrange cells
/// are represented (tri6/tri10, quad9/quad16, tet10, pyramid14, prism18, hex27).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct CellType {
    /// The shape.
    pub shape: Shape,
    /// Polynomial order, 1 to 3.
    pub order: u8,
}

impl CellType {
    /// A cell type of the given shape and order.
    pub const fn new(shape: Shape, order: u8) -> Self {
        CellType { shape, order }
    }

    /// Number of nodes of the complete Lagrange cell of this shape and order.
    pub fn node_count(self) -> usize {
        let p = self.order as usize;
        match self.shape {
            Shape::Line => p + 1,
            Shape::Tri => (p + 1) * (p + 2) / 2,
            Shape::Quad => (p + 1) * (p + 1),
            Shape::Tet => (p + 1) * (p + 2) * (p + 3) / 6,
            Shape::Pyramid => (p + 1) * (p + 2) * (2 * p + 3) / 6,
            Shape::Prism => (p + 1) * (p + 1) * (p + 2) / 2,
            Shape::Hex => (p + 1) * (p + 1) * (p + 1),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn node_counts_match_gmsh_complete_elements() {
        let cases = [
            (Shape::Line, 3, 4),
            (Shape::Tri, 2, 6),
            (Shape::Tri, 3, 10),
            (Shape::Quad, 2, 9),
            (Shape::Quad, 3, 16),
            (Shape::Tet, 2, 10),
            (Shape::Pyramid, 1, 5),
            (Shape::Pyramid, 2, 14),
            (Shape::Prism, 2, 18),
            (Shape::Hex, 2, 27),
        ];
        for (shape, order, n) in cases {
            assert_eq!(
                CellType::new(shape, order).node_count(),
                n,
                "{shape:?} P{order}"
            );
        }
    }

    const SOLIDS: [Shape; 4] = [Shape::Tet, Shape::Pyramid, Shape::Prism, Shape::Hex];

    fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
    }

    fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
        [
            a[1] * b[2] - a[2] * b[1],
            a[2] * b[0] - a[0] * b[2],
            a[0] * b[1] - a[1] * b[0],
        ]
    }

    fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
        a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
    }

    #[test]
    fn faces_point_outward_on_the_reference_cells() {
        for shape in SOLIDS {
            let x = crate::reference::corners(shape);
            let n = x.len() as f64;
            let centre = (0..3).map(|d| x.iter().map(|p| p[d]).sum::<f64>() / n);
            let centre: Vec<f64> = centre.collect();
            let centre = [centre[0], centre[1], centre[2]];
            for f in shape.faces() {
                // Newell's normal of the face, against the direction from the cell's centre
                let mut normal = [0.0; 3];
                for i in 0..f.len() {
                    let c = cross(x[f[i]], x[f[(i + 1) % f.len()]]);
                    normal = [normal[0] + c[0], normal[1] + c[1], normal[2] + c[2]];
                }
                assert!(dot(normal, sub(x[f[0]], centre)) > 0.0, "{shape:?} {f:?}");
            }
        }
    }

    #[test]
    fn every_edge_of_a_solid_is_on_two_of_its_faces() {
        for shape in SOLIDS {
            for e in shape.edges() {
                let on = |f: &&&[usize]| {
                    (0..f.len()).any(|i| {
                        let (a, b) = (f[i], f[(i + 1) % f.len()]);
                        (a, b) == (e[0], e[1]) || (a, b) == (e[1], e[0])
                    })
                };
                assert_eq!(shape.faces().iter().filter(on).count(), 2, "{shape:?}");
            }
        }
    }

    #[test]
    fn corner_tets_are_positive_on_the_reference_cells() {
        for shape in SOLIDS {
            let x = crate::reference::corners(shape);
            let tets: Vec<[usize; 4]> = shape.corner_tets().collect();
            let expected = match shape {
                Shape::Tet => 1,
                Shape::Pyramid => 4,
                _ => shape.corners(),
            };
            assert_eq!(tets.len(), expected, "{shape:?}");
            for t in tets {
                let (o, a, b, c) = (x[t[0]], x[t[1]], x[t[2]], x[t[3]]);
                let volume = dot(cross(sub(a, o), sub(b, o)), sub(c, o));
                assert!(volume > 0.0, "{shape:?} {t:?}");
            }
        }
    }

    #[test]
    fn edges_reference_existing_corners() {
        for shape in [
            Shape::Line,
            Shape::Tri,
            Shape::Quad,
            Shape::Tet,
            Shape::Pyramid,
            Shape::Prism,
            Shape::Hex,
        ] {
            for e in shape.edges() {
                assert!(e[0] < shape.corners() && e[1] < shape.corners());
            }
        }
    }
}
