//! The P3 nodes of the 3D curving (`curve3d`, `march3d`) beyond the edges': the faces'
//! interior nodes, the cells' interior nodes, and the P3 mesh assembled from them.
//!
//! A wall edge's two nodes go onto the true surface at equal arc length along the surface's
//! curve over the edge ([`SurfaceProjector::edge_point`]), as the 2D curving spaces them
//! along its curves: the straight points at a third and two thirds, projected,
//! would crowd towards the middle of a curved edge (a radial projection spaces them by
//! the tangent of the angle) and the cubic through them would swing off the surface more
//! than the P2 edge does — on a sphere's edge of 0.13 rad, 2.1e-5 off against 8.9e-6 at P2,
//! and 2.3e-6 at equal arc length.
//!
//! A face's interior nodes follow its edges — a triangle's centre node is
//! `¼·Σ edge nodes − ⅙·Σ corners` (the cubic triangle then reproduces any quadratic map), a
//! quadrilateral's four nodes are its Coons patch at (⅓, ⅓) … (⅔, ⅔) — plus a residual: on
//! the wall the true surface's point minus that blend (the blend projected by the
//! [`SurfaceProjector`]: its place in the face follows the edges' spacing), above it the residual of the face
//! below (the face between its corners' parents, as an edge reads the edge below it), none
//! where there is no face below or every edge of the face is straight. Inheriting the
//! residual is Vector-Adding for the face node: where the edges carry their full
//! displacement, the node moves by the displacement of the node below it.
//!
//! A cell's interior nodes are fixed linear blends of its boundary nodes (`interior_recipe`):
//! the hexahedron's the transfinite (Boolean sum) interpolation of its faces, the prism's the
//! triangle's blend on the ring of side nodes at its height plus the bottom and top faces'
//! residuals blended along the axis, the pyramid's the Coons point of its section at a third
//! of its height; each reproduces the straight cell. A tetrahedron has none at P3.

use std::sync::OnceLock;

use mesh_model::topology::{Edges, Faces};
use mesh_model::{CellType, Cells, Mesh, NONE, Shape};

use super::{Layers, March, add, scale};
use crate::projector::SurfaceProjector;

/// The faces' interior nodes at P3: each face's corners in cyclic order and the residuals of
/// its interior nodes from the blend of its edges (module docs).
pub(crate) struct FaceNodes<'a> {
    pub(crate) table: &'a Faces,
    /// Face `f`'s residuals are `res[start[f]..start[f + 1]]`: one for a triangle, four for a
    /// quadrilateral (the node nearest cyclic corner `t` at `t`).
    start: Vec<u32>,
    /// Per face: its corners in cyclic order as its first cell lists them (a triangle's last
    /// is [`NONE`]).
    cyclic: Vec<[u32; 4]>,
    pub(crate) res: Vec<[f64; 3]>,
    /// The faces above the wall by increasing level (the highest layer of their corners).
    by_level: Vec<(u32, u32)>,
    /// How many of `by_level` have inherited their residuals.
    done: usize,
}

impl<'a> FaceNodes<'a> {
    pub(crate) fn new(mesh: &Mesh, table: &'a Faces, layers: &Layers) -> FaceNodes<'a> {
        let mut start = vec![0u32];
        let mut cyclic = Vec::with_capacity(table.len());
        let mut by_level = Vec::new();
        for f in 0..table.len() as u32 {
            let u = table.cells(f)[0];
            let cell = mesh.cells.get(u.cell as usize);
            let local = cell.ty.shape.faces()[u.local as usize];
            let mut k = [NONE; 4];
            for (slot, &j) in k.iter_mut().zip(local) {
                *slot = cell.nodes[j];
            }
            let count = if local.len() == 3 { 1 } else { 4 };
            start.push(start[f as usize] + count);
            cyclic.push(k);
            let level = local.iter().map(|&j| layers.layer[cell.nodes[j] as usize]);
            let level = level.max().unwrap_or(0);
            if level > 0 {
                by_level.push((level, f));
            }
        }
        by_level.sort_unstable();
        let res = vec![[0.0; 3]; *start.last().unwrap_or(&0) as usize];
        FaceNodes {
            table,
            start,
            cyclic,
            res,
            by_level,
            done: 0,
        }
    }

    /// The corners of face `f` in cyclic order.
    fn corners(&self, f: u32) -> &[u32] {
        let k = &self.cyclic[f as usize];
        &k[..if k[3] == NONE { 3 } else { 4 }]
    }

    /// The residual of face `f`'s node nearest cyclic corner `t` (a triangle's: `t` = 0).
    fn residual(&self, f: u32, t: usize) -> [f64; 3] {
        self.res[self.start[f as usize] as usize + t]
    }

    /// The position in face `f`'s cyclic order of its corner `node`.
    fn position(&self, f: u32, node: u32) -> usize {
        self.corners(f)
            .iter()
            .position(|&k| k == node)
            .expect("a face's corner")
    }
}

/// The unit coordinates (u, v), in thirds, of a quadrilateral's interior node nearest its
/// cyclic corner `t` (u from corner 0 to 1, v from corner 0 to 3).
const QUAD_THIRDS: [(usize, usize); 4] = [(1, 1), (2, 1), (2, 2), (1, 2)];

impl March<'_> {
    fn faces3(&self) -> &FaceNodes<'_> {
        self.faces.as_ref().expect("P3 faces")
    }

    /// The straight place of inner node `i` of edge `e`, from its lower-numbered end.
    pub(crate) fn straight_point(&self, e: u32, i: usize) -> [f64; 3] {
        let [a, b] = self.ends(e);
        let (xa, xb) = (self.x(a), self.x(b));
        let s = (i + 1) as f64 / (self.per + 1) as f64;
        [0, 1, 2].map(|k| xa[k] + s * (xb[k] - xa[k]))
    }

    /// Inner node `i` of edge `e` as it stands now.
    fn edge_slot(&self, e: u32, i: usize) -> [f64; 3] {
        add(self.straight_point(e, i), self.slots(e)[i])
    }

    /// The point `k` thirds along the edge from `a` to `b` (a corner at 0 and 3).
    fn along(&self, a: u32, b: u32, k: usize) -> [f64; 3] {
        match k {
            0 => self.x(a),
            3 => self.x(b),
            _ => {
                let e = self.edges.find(&[a, b]).expect("a face's side is an edge");
                let i = if self.ends(e)[0] == a { k - 1 } else { 2 - k };
                self.edge_slot(e, i)
            }
        }
    }

    /// Whether every side of the face with cyclic corners `k` is straight.
    fn flat(&self, k: &[u32]) -> bool {
        (0..k.len()).all(|i| {
            let e = self.edges.find(&[k[i], k[(i + 1) % k.len()]]);
            self.is_straight(e.expect("a face's side is an edge"))
        })
    }

    /// The blend of a triangle's edges at its centre: ¼ Σ edge nodes − ⅙ Σ corners.
    fn tri_blend(&self, k: &[u32]) -> [f64; 3] {
        let mut p = [0.0; 3];
        for i in 0..3 {
            let (a, b) = (k[i], k[(i + 1) % 3]);
            p = add(
                p,
                scale(add(self.along(a, b, 1), self.along(a, b, 2)), 0.25),
            );
            p = add(p, scale(self.x(a), -1.0 / 6.0));
        }
        p
    }

    /// The Coons patch of a quadrilateral's edges (cyclic corners `k`) at its interior node
    /// nearest corner `t`.
    fn quad_blend(&self, k: &[u32], t: usize) -> [f64; 3] {
        let (i, j) = QUAD_THIRDS[t];
        let (u, v) = (i as f64 / 3.0, j as f64 / 3.0);
        let sides = [
            (self.along(k[0], k[1], i), 1.0 - v),
            (self.along(k[3], k[2], i), v),
            (self.along(k[0], k[3], j), 1.0 - u),
            (self.along(k[1], k[2], j), u),
        ];
        let corners = [(1.0 - u) * (1.0 - v), u * (1.0 - v), u * v, (1.0 - u) * v];
        let mut p = [0.0; 3];
        for (x, w) in sides {
            p = add(p, scale(x, w));
        }
        for (c, w) in k.iter().zip(corners) {
            p = add(p, scale(self.x(*c), -w));
        }
        p
    }

    /// Interior node `t` of face `f` as it stands now (module docs).
    fn face_point(&self, f: u32, t: usize) -> [f64; 3] {
        let faces = self.faces3();
        let k = faces.corners(f);
        let blend = if k.len() == 3 {
            self.tri_blend(k)
        } else {
            self.quad_blend(k, t)
        };
        if self.flat(k) {
            blend
        } else {
            add(blend, faces.residual(f, t))
        }
    }

    /// The residuals of the wall faces (every corner in layer 0, one cell): the blend
    /// projected onto the true surface, minus the blend.
    pub(crate) fn place_wall_faces(&mut self, surface: &dyn SurfaceProjector) {
        let mut faces = self.faces.take().expect("P3 faces");
        for f in 0..faces.table.len() as u32 {
            let uses = faces.table.cells(f);
            let k = faces.corners(f).to_vec();
            if uses.len() != 1 || k.iter().any(|&n| self.layers.layer[n as usize] != 0) {
                continue;
            }
            let pipe = self.mesh.cell_pipe.get(uses[0].cell as usize).copied();
            let Some(facet) = pipe.filter(|&p| p != NONE) else {
                continue;
            };
            let at = faces.start[f as usize] as usize;
            for t in 0..faces.start[f as usize + 1] as usize - at {
                let blend = if k.len() == 3 {
                    self.tri_blend(&k)
                } else {
                    self.quad_blend(&k, t)
                };
                let on = surface.project(blend, facet as usize);
                faces.res[at + t] = [0, 1, 2].map(|d| on[d] - blend[d]);
            }
        }
        self.faces = Some(faces);
    }

    /// The faces at `level` take the residuals of the faces below them: the mean over the
    /// faces whose corners are those their corners come from (`Layers::lower`), each node
    /// reading the node nearest the corner below its own; none without such a face.
    pub(crate) fn inherit_faces(&mut self, level: u32) {
        let mut faces = self.faces.take().expect("P3 faces");
        while let Some(&(l, f)) = faces.by_level.get(faces.done) {
            if l > level {
                break;
            }
            faces.done += 1;
            let k: Vec<u32> = faces.corners(f).to_vec();
            let lists: Vec<&[u32]> = k.iter().map(|n| self.layers.lower(n, l)).collect();
            let n = if k.len() == 3 { 1 } else { 4 };
            let (mut sum, mut count) = ([[0.0; 3]; 4], 0);
            for below in combinations(&lists) {
                let Some(g) = distinct(&below).then(|| faces.table.find(&below)).flatten() else {
                    continue;
                };
                if faces.corners(g).len() != k.len() {
                    continue;
                }
                for (t, s) in sum.iter_mut().enumerate().take(n) {
                    let from = if n == 1 {
                        0
                    } else {
                        faces.position(g, below[t])
                    };
                    *s = add(*s, faces.residual(g, from));
                }
                count += 1;
            }
            if count > 0 {
                let at = faces.start[f as usize] as usize;
                for (r, s) in faces.res[at..at + n].iter_mut().zip(sum) {
                    *r = scale(s, 1.0 / count as f64);
                }
            }
        }
        self.faces = Some(faces);
    }

    /// The P3 nodes of cell `c` as the edges stand now, in Gmsh order, into `out`.
    pub(crate) fn cell_nodes_p3(&self, c: usize, out: &mut Vec<[f64; 3]>) {
        let cell = self.mesh.cells.get(c);
        let shape = cell.ty.shape;
        let k = cell.corners();
        let faces = self.faces3();
        out.clear();
        out.extend(k.iter().map(|&n| self.x(n)));
        for (j, &e) in self.edges.of_cell(c).iter().enumerate() {
            let [p, _] = shape.edges()[j];
            let along = self.ends(e)[0] == k[p];
            for i in 0..2 {
                out.push(self.edge_slot(e, if along { i } else { 1 - i }));
            }
        }
        for (j, &f) in faces.table.of_cell(c).iter().enumerate() {
            let local = shape.faces()[j];
            if local.len() == 3 {
                out.push(self.face_point(f, 0));
            } else {
                for &corner in local {
                    out.push(self.face_point(f, faces.position(f, k[corner])));
                }
            }
        }
        push_interior(shape, out);
    }
}

/// Every combination of one node from each list.
fn combinations(lists: &[&[u32]]) -> Vec<Vec<u32>> {
    let mut out = vec![Vec::new()];
    for list in lists {
        out = out
            .into_iter()
            .flat_map(|prefix| {
                list.iter().map(move |&n| {
                    let mut p = prefix.clone();
                    p.push(n);
                    p
                })
            })
            .collect();
    }
    out
}

/// Whether the nodes are pairwise distinct.
fn distinct(nodes: &[u32]) -> bool {
    (0..nodes.len()).all(|i| !nodes[i + 1..].contains(&nodes[i]))
}

/// The cell's interior nodes, blended from its boundary nodes `out` (Gmsh order), appended.
fn push_interior(shape: Shape, out: &mut Vec<[f64; 3]>) {
    for recipe in interior_recipe(shape) {
        let p = recipe
            .iter()
            .fold([0.0; 3], |p, &(j, w)| add(p, scale(out[j], w)));
        out.push(p);
    }
}

/// The weights of the nodes one interior node is blended from: (index in Gmsh order, weight).
type Recipe = Vec<(usize, f64)>;

/// Per interior node of the P3 cell of `shape` (in Gmsh order), the weights of the boundary
/// nodes it is blended from (module docs).
fn interior_recipe(shape: Shape) -> &'static [Recipe] {
    static CACHE: [OnceLock<Vec<Recipe>>; 4] = [const { OnceLock::new() }; 4];
    let slot = match shape {
        Shape::Tet => 0,
        Shape::Prism => 1,
        Shape::Hex => 2,
        _ => 3,
    };
    CACHE[slot].get_or_init(|| {
        let refs = mesh_model::reference::reference_nodes(CellType::new(shape, 3))
            .expect("P3 reference nodes");
        let at = |r: [f64; 3]| {
            refs.iter()
                .position(|q| (0..3).all(|d| (q[d] - r[d]).abs() < 1e-9))
                .unwrap_or_else(|| panic!("{shape:?}: no node at {r:?}"))
        };
        let boundary = refs.len() - interior_count(shape);
        refs[boundary..]
            .iter()
            .map(|&r| match shape {
                Shape::Hex => hex_recipe(r, &at),
                Shape::Prism => prism_recipe(r, &at),
                _ => pyramid_recipe(&at),
            })
            .collect()
    })
}

/// The number of interior nodes of the P3 cell of `shape`.
fn interior_count(shape: Shape) -> usize {
    match shape {
        Shape::Hex => 8,
        Shape::Prism => 2,
        Shape::Pyramid => 1,
        _ => 0,
    }
}

/// The transfinite interpolation of a hexahedron at the reference point `r`: Σ faces − Σ
/// edges + Σ corners, each weighted by the linear blends in the other directions.
fn hex_recipe(r: [f64; 3], at: &dyn Fn([f64; 3]) -> usize) -> Recipe {
    let w = |d: usize, side: f64| 0.5 * (1.0 + side * r[d]);
    let mut out = Vec::new();
    for d in 0..3 {
        for side in [-1.0, 1.0] {
            let mut q = r;
            q[d] = side;
            out.push((at(q), w(d, side)));
        }
    }
    for (d1, d2) in [(0, 1), (0, 2), (1, 2)] {
        for s1 in [-1.0, 1.0] {
            for s2 in [-1.0, 1.0] {
                let mut q = r;
                (q[d1], q[d2]) = (s1, s2);
                out.push((at(q), -w(d1, s1) * w(d2, s2)));
            }
        }
    }
    for s in 0..8 {
        let q = [0, 1, 2].map(|d| if s >> d & 1 == 1 { 1.0 } else { -1.0 });
        out.push((at(q), w(0, q[0]) * w(1, q[1]) * w(2, q[2])));
    }
    out
}

/// A prism's interior node at the reference point `r` (the triangle's centroid at height
/// ζ): the triangle's blend on the ring of nodes at ζ, plus the bottom's and top's residuals
/// (centre minus blend) weighted by 1 − s and s, s = (1 + ζ) / 2.
fn prism_recipe(r: [f64; 3], at: &dyn Fn([f64; 3]) -> usize) -> Recipe {
    let t = 1.0 / 3.0;
    let corners = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
    let sides = [
        [t, 0.0],
        [2.0 * t, 0.0],
        [0.0, t],
        [0.0, 2.0 * t],
        [2.0 * t, t],
        [t, 2.0 * t],
    ];
    let s = 0.5 * (1.0 + r[2]);
    let mut out = Vec::new();
    // the ring at ζ (weight 1), the bottom's residual (1 − s), the top's (s)
    for (z, w, centre) in [(r[2], 1.0, false), (-1.0, 1.0 - s, true), (1.0, s, true)] {
        let sign = if centre { -1.0 } else { 1.0 };
        if centre {
            out.push((at([t, t, z]), w));
        }
        for [x, y] in sides {
            out.push((at([x, y, z]), sign * 0.25 * w));
        }
        for [x, y] in corners {
            out.push((at([x, y, z]), -sign * w / 6.0));
        }
    }
    out
}

/// A pyramid's interior node (0, 0, ⅓): the Coons point of its section at a third of its
/// height, ½ Σ the triangles' centre nodes − ¼ Σ the side edges' nodes at that height.
fn pyramid_recipe(at: &dyn Fn([f64; 3]) -> usize) -> Recipe {
    let (t, u) = (1.0 / 3.0, 2.0 / 3.0);
    let mut out = Vec::new();
    for [x, y] in [[0.0, -u], [-u, 0.0], [u, 0.0], [0.0, u]] {
        out.push((at([x, y, t]), 0.5));
    }
    for [x, y] in [[-u, -u], [u, -u], [u, u], [-u, u]] {
        out.push((at([x, y, t]), -0.25));
    }
    out
}

/// The P3 mesh: the linear nodes, two nodes per edge (edge order, from the lower-numbered
/// end), the faces' interior nodes (face order; a quadrilateral's by its cyclic corners),
/// then each cell's interior nodes as the cells come.
pub(crate) fn assemble_p3(mesh: &Mesh, edges: &Edges, m: &March<'_>) -> Mesh {
    let faces = m.faces3();
    let n0 = mesh.nodes.len() as u32;
    let mut out = Mesh {
        order: 3,
        cells: Cells::new(),
        boundary: Cells::new(),
        ..mesh.clone()
    };
    for e in 0..edges.len() as u32 {
        out.nodes.extend((0..2).map(|i| m.edge_slot(e, i)));
    }
    let mut face_start = Vec::with_capacity(faces.table.len());
    for f in 0..faces.table.len() as u32 {
        face_start.push(out.nodes.len() as u32);
        let n = faces.start[f as usize + 1] - faces.start[f as usize];
        out.nodes
            .extend((0..n as usize).map(|t| m.face_point(f, t)));
    }
    // edge a → b's two nodes, from a
    let edge_nodes = |e: u32, a: u32| {
        let first = n0 + 2 * e;
        if edges.nodes(e)[0] == a {
            [first, first + 1]
        } else {
            [first + 1, first]
        }
    };
    let mut buf = Vec::new();
    let mut x = Vec::new();
    for (c, cell) in mesh.cells.iter().enumerate() {
        let shape = cell.ty.shape;
        let k = cell.corners();
        buf.clear();
        buf.extend_from_slice(k);
        for (j, &e) in edges.of_cell(c).iter().enumerate() {
            buf.extend(edge_nodes(e, k[shape.edges()[j][0]]));
        }
        for (j, &f) in faces.table.of_cell(c).iter().enumerate() {
            let local = shape.faces()[j];
            if local.len() == 3 {
                buf.push(face_start[f as usize]);
            } else {
                buf.extend(
                    local
                        .iter()
                        .map(|&v| face_start[f as usize] + faces.position(f, k[v]) as u32),
                );
            }
        }
        x.clear();
        x.extend(buf.iter().map(|&n| out.nodes[n as usize]));
        push_interior(shape, &mut x);
        for p in &x[buf.len()..] {
            buf.push(out.nodes.len() as u32);
            out.nodes.push(*p);
        }
        out.cells.push(CellType::new(shape, 3), &buf);
    }
    for facet in mesh.boundary.iter() {
        let k = facet.corners();
        buf.clear();
        buf.extend_from_slice(k);
        for i in 0..k.len() {
            let e = edges.find(&[k[i], k[(i + 1) % k.len()]]);
            buf.extend(edge_nodes(
                e.expect("a boundary facet's edges are cell edges"),
                k[i],
            ));
        }
        let f = faces
            .table
            .find(k)
            .expect("a boundary facet is a cell face");
        if k.len() == 3 {
            buf.push(face_start[f as usize]);
        } else {
            buf.extend(
                k.iter()
                    .map(|&v| face_start[f as usize] + faces.position(f, v) as u32),
            );
        }
        out.boundary.push(CellType::new(facet.ty.shape, 3), &buf);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The recipes reproduce the interior nodes of the reference cells and of their images
    /// under a straight-sided map (trilinear hexahedron, sheared prism, slanted pyramid).
    #[test]
    fn interior_recipes_reproduce_straight_cells() {
        for shape in [Shape::Tet, Shape::Prism, Shape::Hex, Shape::Pyramid] {
            let ty = CellType::new(shape, 3);
            let refs = mesh_model::reference::reference_nodes(ty).unwrap();
            let map = |r: [f64; 3]| {
                [
                    r[0] + 0.2 * r[1] + 0.1 * r[0] * r[1],
                    r[1] - 0.3 * r[2] + 0.05 * r[1] * r[2],
                    0.9 * r[2] + 0.1 * r[0] + 0.07 * r[0] * r[2],
                ]
            };
            let identity = |r: [f64; 3]| r;
            for f in [&identity as &dyn Fn([f64; 3]) -> [f64; 3], &map] {
                let boundary = refs.len() - interior_count(shape);
                let mut x: Vec<[f64; 3]> = refs[..boundary].iter().map(|&r| f(r)).collect();
                push_interior(shape, &mut x);
                for (i, r) in refs.iter().enumerate().skip(boundary) {
                    let want = f(*r);
                    assert!(
                        (0..3).all(|d| (x[i][d] - want[d]).abs() < 1e-12),
                        "{shape:?} {i}"
                    );
                }
            }
        }
    }

    #[test]
    fn combinations_and_distinct() {
        let c = combinations(&[&[1, 2], &[3], &[4, 5]]);
        assert_eq!(
            c,
            vec![vec![1, 3, 4], vec![1, 3, 5], vec![2, 3, 4], vec![2, 3, 5]]
        );
        assert!(distinct(&[1, 2, 3]) && !distinct(&[1, 2, 1]));
    }
}
