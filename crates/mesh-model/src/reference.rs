//! Gmsh's reference cells: the reference coordinates of every node of a cell type, in Gmsh's
//! node order, which is the data model's. Readers, writers and shape functions all build on
//! this one definition. It owns the reference geometry only: no shape function, no file format.
//!
//! Domains: lines on [−1, 1]; triangles and tetrahedra on the unit simplex; quadrilaterals
//! and hexahedra on [−1, 1]ⁿ; prisms on the unit triangle × [−1, 1]; pyramids on the base
//! [−1, 1]² with the apex at (0, 0, 1). Unused coordinates are 0.

use crate::cell::{CellType, Shape};

/// Corners of Gmsh's reference cells.
pub fn corners(shape: Shape) -> &'static [[f64; 3]] {
    match shape {
        Shape::Line => &[[-1.0, 0.0, 0.0], [1.0, 0.0, 0.0]],
        Shape::Tri => &[[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        Shape::Quad => &[
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
        ],
        Shape::Tet => &[
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
        Shape::Hex => &[
            [-1.0, -1.0, -1.0],
            [1.0, -1.0, -1.0],
            [1.0, 1.0, -1.0],
            [-1.0, 1.0, -1.0],
            [-1.0, -1.0, 1.0],
            [1.0, -1.0, 1.0],
            [1.0, 1.0, 1.0],
            [-1.0, 1.0, 1.0],
        ],
        Shape::Prism => &[
            [0.0, 0.0, -1.0],
            [1.0, 0.0, -1.0],
            [0.0, 1.0, -1.0],
            [0.0, 0.0, 1.0],
            [1.0, 0.0, 1.0],
            [0.0, 1.0, 1.0],
        ],
        Shape::Pyramid => &[
            [-1.0, -1.0, 0.0],
            [1.0, -1.0, 0.0],
            [1.0, 1.0, 0.0],
            [-1.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ],
    }
}

fn lerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    [
        a[0] + (b[0] - a[0]) * t,
        a[1] + (b[1] - a[1]) * t,
        a[2] + (b[2] - a[2]) * t,
    ]
}

fn mean(points: &[[f64; 3]]) -> [f64; 3] {
    let mut m = [0.0; 3];
    for p in points {
        for k in 0..3 {
            m[k] += p[k] / points.len() as f64;
        }
    }
    m
}

/// Gmsh's nodes of a triangle of order `p` with the given corners (recursive interior).
fn gmsh_triangle(p: usize, c: [[f64; 3]; 3], out: &mut Vec<[f64; 3]>) {
    if p == 0 {
        out.push(mean(&c));
        return;
    }
    out.extend_from_slice(&c);
    for (a, b) in [(0, 1), (1, 2), (2, 0)] {
        for i in 1..p {
            out.push(lerp(c[a], c[b], i as f64 / p as f64));
        }
    }
    if p >= 3 {
        // The interior nodes form a triangle of order p − 3 inset by one lattice step.
        let at = |i: f64, j: f64| {
            let u = lerp(c[0], c[1], i / p as f64);
            let v = lerp(c[0], c[2], j / p as f64);
            [
                u[0] + v[0] - c[0][0],
                u[1] + v[1] - c[0][1],
                u[2] + v[2] - c[0][2],
            ]
        };
        let q = p as f64;
        gmsh_triangle(
            p - 3,
            [at(1.0, 1.0), at(q - 2.0, 1.0), at(1.0, q - 2.0)],
            out,
        );
    }
}

/// Gmsh's nodes of a quadrilateral of order `p` with the given corners (recursive interior).
fn gmsh_quad(p: usize, c: [[f64; 3]; 4], out: &mut Vec<[f64; 3]>) {
    if p == 0 {
        out.push(mean(&c));
        return;
    }
    out.extend_from_slice(&c);
    for (a, b) in [(0, 1), (1, 2), (2, 3), (3, 0)] {
        for i in 1..p {
            out.push(lerp(c[a], c[b], i as f64 / p as f64));
        }
    }
    if p >= 2 {
        let t = 1.0 / p as f64;
        let inset = |k: usize| lerp(c[k], c[(k + 2) % 4], t);
        gmsh_quad(p - 2, [inset(0), inset(1), inset(2), inset(3)], out);
    }
}

/// The reference coordinates of the nodes of a Gmsh cell, in Gmsh's node order (which is the
/// data model's): lines on [−1, 1]; triangles and tetrahedra on the unit simplex;
/// quadrilaterals and hexahedra on [−1, 1]ⁿ; prisms on the unit triangle × [−1, 1]; pyramids
/// on the base [−1, 1]² with the apex at (0, 0, 1). Unused coordinates are 0.
///
/// Available for every shape of order 1 to 3; `None` otherwise.
pub fn reference_nodes(ty: CellType) -> Option<Vec<[f64; 3]>> {
    let c = corners(ty.shape);
    let p = ty.order as usize;
    let mut out = Vec::with_capacity(ty.node_count());
    match (ty.shape, p) {
        (_, 1) => out.extend_from_slice(c),
        (Shape::Line, 2 | 3) => {
            out.extend_from_slice(c);
            for i in 1..p {
                out.push(lerp(c[0], c[1], i as f64 / p as f64));
            }
        }
        (Shape::Tri, 2 | 3) => gmsh_triangle(p, [c[0], c[1], c[2]], &mut out),
        (Shape::Quad, 2 | 3) => gmsh_quad(p, [c[0], c[1], c[2], c[3]], &mut out),
        (Shape::Tet | Shape::Hex | Shape::Prism | Shape::Pyramid, 2) => {
            out.extend_from_slice(c);
            for e in ty.shape.edges() {
                out.push(lerp(c[e[0]], c[e[1]], 0.5));
            }
            // the P2 face nodes: one at the centre of each quadrilateral face, in face order
            for f in ty.shape.faces().iter().filter(|f| f.len() == 4) {
                out.push(mean(&[c[f[0]], c[f[1]], c[f[2]], c[f[3]]]));
            }
            if ty.shape == Shape::Hex {
                out.push(mean(c));
            }
        }
        (Shape::Tet | Shape::Hex | Shape::Prism | Shape::Pyramid, 3) => {
            solid_p3(ty.shape, &mut out)
        }
        _ => return None,
    }
    Some(out)
}

/// Gmsh's nodes of a 3D cell of order 3: the corners; two nodes on each edge, at a third and
/// two thirds from its first corner; each face's interior in face order (a triangle's
/// centroid; a quadrilateral's four nodes a third in from its corners, the one nearest the
/// face's first corner first, then round the face as it is listed); then the interior — a
/// hexahedron's the order-1 hexahedron at a third of the reference one, a prism's two nodes
/// at the triangle's centroid, ζ = −⅓ then ⅓, a pyramid's one node at (0, 0, ⅓), none in a
/// tetrahedron. Checked against Gmsh's own nodes (`mesh-io`'s tests).
fn solid_p3(shape: Shape, out: &mut Vec<[f64; 3]>) {
    let c = corners(shape);
    out.extend_from_slice(c);
    for e in shape.edges() {
        for i in 1..3 {
            out.push(lerp(c[e[0]], c[e[1]], i as f64 / 3.0));
        }
    }
    let mut face = Vec::new();
    for f in shape.faces() {
        // the face as a cell of its own, its boundary nodes left out
        face.clear();
        if let [a, b, d] = **f {
            gmsh_triangle(3, [c[a], c[b], c[d]], &mut face);
            out.extend_from_slice(&face[9..]);
        } else {
            gmsh_quad(3, [c[f[0]], c[f[1]], c[f[2]], c[f[3]]], &mut face);
            out.extend_from_slice(&face[12..]);
        }
    }
    let t = 1.0 / 3.0;
    match shape {
        Shape::Hex => out.extend(c.iter().map(|x| x.map(|v| v * t))),
        Shape::Prism => out.extend([[t, t, -t], [t, t, t]]),
        Shape::Pyramid => out.push([0.0, 0.0, t]),
        _ => {}
    }
}
