//! The node coordinates of a curved cell in Gmsh order, from its corners and the inner points
//! of its edges: the interior nodes follow from the map the edges define (a Coons patch on a
//! quadrilateral; on a cubic triangle the centre node that reproduces every quadratic map).

use mesh_model::{CellType, Shape, reference};

/// The interior reference points of the quadrilaterals this crate builds, as lattice indices
/// (a, b): the point (u, v) = (a/p, b/p) of the unit square. They fall on the parameters of
/// the edge nodes, so the Coons patch there needs no curve evaluation.
#[derive(Debug, Clone)]
pub(crate) struct Interiors {
    quad: Vec<[usize; 2]>,
}

impl Interiors {
    /// The interior points of order-`p` quadrilaterals, in Gmsh's order.
    pub fn new(p: usize) -> Self {
        let ty = CellType::new(Shape::Quad, p as u8);
        let all = reference::reference_nodes(ty).expect("Gmsh quadrilaterals of order 2 and 3");
        let first = 4 + 4 * (p - 1);
        let lattice = |x: f64| (0.5 * (x + 1.0) * p as f64).round() as usize;
        let quad = all[first..]
            .iter()
            .map(|r| [lattice(r[0]), lattice(r[1])])
            .collect();
        Interiors { quad }
    }

    /// How many interior nodes [`cell_nodes`] gives a cell of `corners` corners at order `p`.
    pub(crate) fn count(&self, corners: usize, p: usize) -> usize {
        match (corners, p) {
            (3, 3) => 1,
            (4, _) => self.quad.len(),
            _ => 0,
        }
    }
}

/// Fills `out` with the Gmsh-ordered nodes of a cell of order `p`: `corners` (3 or 4), then
/// each edge's `p − 1` inner points from `edges` (edge after edge in Gmsh's edge order, each
/// listed from the edge's first corner to its second), then the interior nodes.
pub(crate) fn cell_nodes(
    p: usize,
    corners: &[[f64; 2]],
    edges: &[[f64; 2]],
    interiors: &Interiors,
    out: &mut Vec<[f64; 2]>,
) {
    out.clear();
    out.extend_from_slice(corners);
    let q = p - 1;
    out.extend_from_slice(&edges[..corners.len() * q]);
    match (corners.len(), p) {
        (3, 3) => {
            // the cubic's centre node that makes it reproduce any quadratic map exactly
            let mut c = [0.0; 2];
            for e in &edges[..6] {
                c[0] += 0.25 * e[0];
                c[1] += 0.25 * e[1];
            }
            for v in corners {
                c[0] -= v[0] / 6.0;
                c[1] -= v[1] / 6.0;
            }
            out.push(c);
        }
        (4, _) => {
            for &[a, b] in &interiors.quad {
                out.push(coons_on_lattice(p, corners, edges, a, b));
            }
        }
        _ => {}
    }
}

/// [`coons`] at (a/p, b/p), from the edge nodes themselves.
fn coons_on_lattice(p: usize, c: &[[f64; 2]], edges: &[[f64; 2]], a: usize, b: usize) -> [f64; 2] {
    let q = p - 1;
    // node i (0..=p) along edge k, from its first corner
    let node = |k: usize, i: usize| -> [f64; 2] {
        match i {
            0 => c[k],
            i if i == p => c[(k + 1) % 4],
            i => edges[k * q + i - 1],
        }
    };
    let (u, v) = (a as f64 / p as f64, b as f64 / p as f64);
    blend(
        c,
        u,
        v,
        [node(0, a), node(1, b), node(2, p - a), node(3, p - b)],
    )
}

/// The Coons combination at (u, v) of the four edge points there (bottom, right, top, left).
fn blend(c: &[[f64; 2]], u: f64, v: f64, sides: [[f64; 2]; 4]) -> [f64; 2] {
    let [bottom, right, top, left] = sides;
    let mut x = [0.0; 2];
    for d in 0..2 {
        let bilinear = (1.0 - u) * (1.0 - v) * c[0][d]
            + u * (1.0 - v) * c[1][d]
            + u * v * c[2][d]
            + (1.0 - u) * v * c[3][d];
        x[d] = (1.0 - v) * bottom[d] + v * top[d] + (1.0 - u) * left[d] + u * right[d] - bilinear;
    }
    x
}

/// The Coons patch of a quadrilateral at (u, v) ∈ [0, 1]²: the blend of its four edge curves
/// minus the bilinear map of its corners.
pub(crate) fn coons(p: usize, c: &[[f64; 2]], edges: &[[f64; 2]], u: f64, v: f64) -> [f64; 2] {
    let q = p - 1;
    let edge = |k: usize, s: f64| -> [f64; 2] {
        let inner = &edges[k * q..(k + 1) * q];
        lagrange_1d(p, c[k], inner, c[(k + 1) % 4], s)
    };
    blend(
        c,
        u,
        v,
        [edge(0, u), edge(1, v), edge(2, 1.0 - u), edge(3, 1.0 - v)],
    )
}

/// The degree-`p` curve through `a`, the `p − 1` equally spaced `inner` points and `b`, at
/// fraction `s`.
pub(crate) fn lagrange_1d(
    p: usize,
    a: [f64; 2],
    inner: &[[f64; 2]],
    b: [f64; 2],
    s: f64,
) -> [f64; 2] {
    let mut x = [0.0; 2];
    let (weights, _) = jacobian_check::lagrange::equispaced_line(p, s);
    for (j, &w) in weights.iter().enumerate().take(p + 1) {
        let pt = if j == 0 {
            a
        } else if j == p {
            b
        } else {
            inner[j - 1]
        };
        x[0] += w * pt[0];
        x[1] += w * pt[1];
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_straight_quadrilateral_gets_its_bilinear_interior() {
        let c = [[0.0, 0.0], [2.0, 0.0], [3.0, 1.0], [0.0, 2.0]];
        for p in [2, 3] {
            let mut edges = Vec::new();
            for k in 0..4 {
                for i in 1..p {
                    let s = i as f64 / p as f64;
                    let (a, b) = (c[k], c[(k + 1) % 4]);
                    edges.push([a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1])]);
                }
            }
            let interiors = Interiors::new(p);
            let mut out = Vec::new();
            cell_nodes(p, &c, &edges, &interiors, &mut out);
            let want = reference::reference_nodes(CellType::new(Shape::Quad, p as u8)).unwrap();
            for (x, r) in out.iter().zip(&want) {
                let (u, v) = (0.5 * (r[0] + 1.0), 0.5 * (r[1] + 1.0));
                let b = [
                    (1.0 - u) * (1.0 - v) * c[0][0]
                        + u * (1.0 - v) * c[1][0]
                        + u * v * c[2][0]
                        + (1.0 - u) * v * c[3][0],
                    (1.0 - u) * (1.0 - v) * c[0][1]
                        + u * (1.0 - v) * c[1][1]
                        + u * v * c[2][1]
                        + (1.0 - u) * v * c[3][1],
                ];
                assert!(
                    (x[0] - b[0]).abs() < 1e-12 && (x[1] - b[1]).abs() < 1e-12,
                    "{x:?} {b:?}"
                );
            }
        }
    }

    #[test]
    fn the_cubic_triangle_centre_reproduces_a_quadratic_map() {
        // x = ξ + 0.3 ξη, y = η + 0.2 ξ²: quadratic, so the cubic must hit it at (1/3, 1/3)
        let map = |xi: f64, eta: f64| [xi + 0.3 * xi * eta, eta + 0.2 * xi * xi];
        let refs = reference::reference_nodes(CellType::new(Shape::Tri, 3)).unwrap();
        let pts: Vec<[f64; 2]> = refs.iter().map(|r| map(r[0], r[1])).collect();
        let mut out = Vec::new();
        cell_nodes(3, &pts[..3], &pts[3..9], &Interiors::new(3), &mut out);
        let want = map(1.0 / 3.0, 1.0 / 3.0);
        assert!((out[9][0] - want[0]).abs() < 1e-14 && (out[9][1] - want[1]).abs() < 1e-14);
    }
}
