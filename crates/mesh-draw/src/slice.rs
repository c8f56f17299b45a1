//! A plane cut through a 3D mesh as a 2D mesh the drawer draws: every linear cell the plane
//! `x = c`, `y = c` or `z = c` crosses becomes the polygon where they meet (a triangle or a
//! quadrilateral; a pentagon or hexagon is split from its first corner into a quadrilateral
//! and a triangle, or two quadrilaterals), every boundary facet it crosses a line of its
//! patch. Points in the plane are `(y, z)` for `x = c`, `(z, x)` for `y = c`, `(x, y)` for
//! `z = c` (right-handed, seen from the positive side of the axis).
//!
//! A node exactly on the plane counts as above it, and the point on an edge is computed from
//! its two ends in increasing node order, so neighbouring cells agree on every shared point:
//! the polygons of neighbours share their sides, as the cells share their faces.

use std::collections::HashMap;

use mesh_model::{CellType, Dim, Mesh, Shape};

use crate::error::DrawError;

/// The plane `x = at` (axis 0), `y = at` (1) or `z = at` (2).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// 0, 1 or 2: the axis normal to the plane.
    pub axis: usize,
    /// Where the plane crosses it.
    pub at: f64,
}

/// The cut: a 2D mesh and, for each of its cells, the 3D cell it lies in.
#[derive(Debug, Clone)]
pub struct Sliced {
    /// The polygons (triangles and quadrilaterals, `cell_layer` of their 3D cells when the
    /// 3D mesh has layers) and the boundary lines, with the 3D mesh's patches.
    pub mesh: Mesh,
    /// For each 2D cell, its 3D cell's index.
    pub cell_of: Vec<u32>,
}

/// The cut of the linear 3D `mesh` by `plane`. Errors when the mesh is not 3D, the plane is not
/// finite or its axis is not 0, 1 or 2, or the plane crosses no cell.
pub fn slice(mesh: &Mesh, plane: Plane) -> Result<Sliced, DrawError> {
    if mesh.dim != Dim::Three || plane.axis > 2 || !plane.at.is_finite() {
        return Err(DrawError::BadSlice {
            axis: plane.axis,
            at: plane.at,
            reason: "it needs a 3D mesh and a finite plane x, y or z",
        });
    }
    let mut cut = Cutter {
        mesh,
        plane,
        points: HashMap::new(),
        out: Mesh::new(Dim::Two, 1),
    };
    cut.out.patches = mesh.patches.clone();
    let mut cell_of = Vec::new();
    let layered = mesh.cell_layer.len() == mesh.cells.len();
    for i in 0..mesh.cells.len() {
        let c = mesh.cells.get(i);
        let polygon = cut.polygon(c.ty.shape, c.corners());
        for piece in split(&polygon) {
            let shape = if piece.len() == 3 {
                Shape::Tri
            } else {
                Shape::Quad
            };
            cut.out.cells.push(CellType::new(shape, 1), &piece);
            cell_of.push(i as u32);
            if layered {
                cut.out.cell_layer.push(mesh.cell_layer[i]);
            }
        }
    }
    if cell_of.is_empty() {
        return Err(DrawError::BadSlice {
            axis: plane.axis,
            at: plane.at,
            reason: "it crosses no cell",
        });
    }
    for (f, &patch) in mesh.boundary.iter().zip(&mesh.boundary_patch) {
        let crossing = cut.crossings(f.ty.shape, f.corners());
        // two distinct points (`crossings` lists each once): the facet's line in the plane
        if let [a, b] = crossing[..] {
            cut.out
                .boundary
                .push(CellType::new(Shape::Line, 1), &[a, b]);
            cut.out.boundary_patch.push(patch);
        }
    }
    Ok(Sliced {
        mesh: cut.out,
        cell_of,
    })
}

/// The state of a cut: the points made so far, by the edge (or node) they lie on.
struct Cutter<'a> {
    mesh: &'a Mesh,
    plane: Plane,
    /// (lower node, higher node) of an edge, or (node, node) for a node on the plane.
    points: HashMap<(u32, u32), u32>,
    out: Mesh,
}

impl Cutter<'_> {
    /// The signed height of node `v` over the plane.
    fn height(&self, v: u32) -> f64 {
        self.mesh.nodes[v as usize][self.plane.axis] - self.plane.at
    }

    /// The 2D point where edge `a b` (one end below, the other on or above) meets the plane.
    fn point(&mut self, a: u32, b: u32) -> u32 {
        let (a, b) = (a.min(b), a.max(b));
        let (ha, hb) = (self.height(a), self.height(b));
        // a node on the plane is the point itself
        let key = if ha == 0.0 {
            (a, a)
        } else if hb == 0.0 {
            (b, b)
        } else {
            (a, b)
        };
        if let Some(&p) = self.points.get(&key) {
            return p;
        }
        let (pa, pb) = (
            self.mesh.nodes[key.0 as usize],
            self.mesh.nodes[key.1 as usize],
        );
        let t = if key.0 == key.1 { 0.0 } else { ha / (ha - hb) };
        let x: [f64; 3] = std::array::from_fn(|d| pa[d] + t * (pb[d] - pa[d]));
        let (u, v) = ((self.plane.axis + 1) % 3, (self.plane.axis + 2) % 3);
        self.out.nodes.push([x[u], x[v], 0.0]);
        let p = (self.out.nodes.len() - 1) as u32;
        self.points.insert(key, p);
        p
    }

    /// The points where the edges of a cell or facet of `shape` with corners `k` cross the
    /// plane, in the order of the shape's edges; none when it lies on one side.
    fn crossings(&mut self, shape: Shape, k: &[u32]) -> Vec<u32> {
        let below = |c: &Self, v: u32| c.height(v) < 0.0;
        let mut out = Vec::new();
        for e in shape.edges() {
            let (a, b) = (k[e[0]], k[e[1]]);
            if below(self, a) != below(self, b) {
                let p = self.point(a, b);
                if !out.contains(&p) {
                    out.push(p);
                }
            }
        }
        out
    }

    /// The polygon where a cell meets the plane, counter-clockwise in the plane; empty when
    /// they meet in less than a polygon of positive area.
    fn polygon(&mut self, shape: Shape, k: &[u32]) -> Vec<u32> {
        let mut p = self.crossings(shape, k);
        if p.len() < 3 {
            return Vec::new();
        }
        // a convex section: its corners in order of their angle about the centroid
        let xy = |q: u32| self.out.nodes[q as usize];
        let n = p.len() as f64;
        let c = p
            .iter()
            .fold([0.0; 2], |s, &q| [s[0] + xy(q)[0] / n, s[1] + xy(q)[1] / n]);
        let angle = |q: u32| (xy(q)[1] - c[1]).atan2(xy(q)[0] - c[0]);
        p.sort_by(|&a, &b| angle(a).total_cmp(&angle(b)));
        let pts: Vec<[f64; 2]> = p.iter().map(|&q| [xy(q)[0], xy(q)[1]]).collect();
        if geom_predicates::polygon_area(pts.iter().copied()) > 0.0 {
            p
        } else {
            Vec::new()
        }
    }
}

/// A convex polygon as triangles and quadrilaterals: itself up to four corners, else a
/// quadrilateral from its first corner and the rest split again.
fn split(polygon: &[u32]) -> Vec<Vec<u32>> {
    let mut out = Vec::new();
    let mut start = 0;
    while polygon.len() - start >= 3 {
        let left = polygon.len() - start;
        if left <= 4 {
            let mut last = vec![polygon[0]];
            last.extend(&polygon[start + 1..]);
            out.push(last);
            break;
        }
        out.push(vec![
            polygon[0],
            polygon[start + 1],
            polygon[start + 2],
            polygon[start + 3],
        ]);
        start += 2;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::{Patch, Role};

    fn cube() -> Mesh {
        let mut m = Mesh::new(Dim::Three, 1);
        for z in [0.0, 1.0] {
            m.nodes
                .extend([[0.0, 0.0, z], [1.0, 0.0, z], [1.0, 1.0, z], [0.0, 1.0, z]]);
        }
        m.cells
            .push(CellType::new(Shape::Hex, 1), &[0, 1, 2, 3, 4, 5, 6, 7]);
        m.boundary
            .push(CellType::new(Shape::Quad, 1), &[0, 1, 5, 4]);
        m.boundary_patch.push(0);
        m.patches.push(Patch {
            name: "wall".into(),
            role: Role::Wall,
        });
        m
    }

    #[test]
    fn a_hexahedron_cut_across_is_a_square() {
        let s = slice(&cube(), Plane { axis: 2, at: 0.5 }).unwrap();
        assert_eq!(s.mesh.cells.len(), 1);
        assert_eq!(s.mesh.cells.get(0).ty.shape, Shape::Quad);
        assert_eq!(s.mesh.boundary.len(), 1);
        let angle = mesh_model::measure::cell_max_angle_deg(&s.mesh, 0);
        assert!((angle - 90.0).abs() < 1e-9);
        assert!(
            mesh_model::validate(&s.mesh)
                .iter()
                .all(|p| !p.is_structural())
        );
    }

    #[test]
    fn a_corner_cut_is_a_triangle_and_a_diagonal_cut_a_hexagon() {
        // x + y + z = 0.5 is not an axis plane: tilt the cube instead
        let mut m = cube();
        let tilt = |p: [f64; 3]| [p[0], p[1], p[2] + 0.3 * p[0] + 0.3 * p[1]];
        m.nodes = m.nodes.iter().map(|&p| tilt(p)).collect();
        let corner = slice(&m, Plane { axis: 2, at: 0.1 }).unwrap();
        assert_eq!(corner.mesh.cells.get(0).ty.shape, Shape::Tri);
        let on_face = slice(&cube(), Plane { axis: 2, at: 0.0 });
        assert!(on_face.is_err(), "a plane through a face cuts nothing");
        assert!(slice(&cube(), Plane { axis: 0, at: 2.0 }).is_err());
        assert_eq!(
            split(&[0, 1, 2, 3, 4, 5]),
            vec![vec![0, 1, 2, 3], vec![0, 3, 4, 5]]
        );
        assert_eq!(
            split(&[0, 1, 2, 3, 4]),
            vec![vec![0, 1, 2, 3], vec![0, 3, 4]]
        );
    }
}
