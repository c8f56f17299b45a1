//! The four measures a move is judged by, cell by cell against the unmoved mesh of the same
//! order: **lin**, the corner scaled Jacobian of the cell's straight corners (skew); **sj**,
//! the scaled Jacobian of the curved cell, least over its nodes (the Jacobian's variation and
//! the curving); **sicn**, its signed inverse condition number, least over its nodes (both);
//! **edge**, its shortest corner-to-corner edge (collapse, which angles do not see). Each is
//! reported as its worst ratio after / before, with the cell and where it is.
//!
//! sj and sicn are taken at the cell's own Lagrange nodes (sampled, not certified: the
//! certification of every cell is the report's `quality`), triangles measured through the
//! map of the reference triangle onto an equilateral one, so that an equilateral or square
//! straight cell scores 1. `tests/movement/measures.py` takes the same four ratios with Gmsh's
//! own minSJ and minSICN.

use std::collections::HashMap;

use jacobian_check::{matrix_from_gradients, reference_nodes, shape_gradients};
use mesh_model::{CellType, Mesh, Shape};
use rayon::prelude::*;
use serde::Serialize;

/// What the measures are.
pub const MEASURES_OF: &str = "per cell, after / before, the worst over the cells: lin, the \
    corner scaled Jacobian of the straight corners; sj, the scaled Jacobian of the curved cell, \
    least over its Lagrange nodes; sicn, its signed inverse condition number, least over its \
    Lagrange nodes; edge, the shortest corner-to-corner edge (sj and sicn sampled, not \
    certified; triangles measured against an equilateral one)";

/// The worst ratio of one measure and where it is.
#[derive(Debug, Clone, Copy, Serialize)]
pub struct Worst {
    /// Least over the cells of the measure after / before.
    pub ratio: f64,
    /// The cell (0-based).
    pub cell: usize,
    /// Its centroid after the move.
    pub at: [f64; 2],
}

/// The four measures of a move.
#[derive(Debug, Clone, Serialize)]
pub struct Measures {
    /// Corner scaled Jacobian of the straight corners.
    pub lin: Worst,
    /// Scaled Jacobian of the curved cell.
    pub sj: Worst,
    /// Signed inverse condition number of the curved cell.
    pub sicn: Worst,
    /// Shortest corner-to-corner edge.
    pub edge: Worst,
    /// What they are.
    pub of: &'static str,
}

/// Each cell's four measures (lin, sj, sicn, edge) in the unmoved mesh: the side of
/// [`measures`] that every step of a sequence shares.
#[derive(Debug, Clone)]
pub struct Baseline {
    mesh: Mesh,
    cells: Vec<[f64; 4]>,
}

impl Baseline {
    /// The measures of every cell of `mesh` (the unmoved mesh at the moved one's order).
    pub fn of(mesh: Mesh) -> Baseline {
        let tables = gradient_tables(&mesh);
        let cells = (0..mesh.cells.len())
            .into_par_iter()
            .with_min_len(256)
            .map(|i| cell_measures(&mesh, i, &tables))
            .collect();
        Baseline { mesh, cells }
    }
}

/// The measures of `after` (the moved mesh) against `before` (the unmoved one, same cells);
/// `None` when the meshes do not have the same cells.
pub fn measures(before: &Baseline, after: &Mesh) -> Option<Measures> {
    let mesh = &before.mesh;
    if mesh.cells.len() != after.cells.len() || mesh.order != after.order {
        return None;
    }
    let tables = gradient_tables(after);
    let ratios: Vec<[f64; 4]> = (0..after.cells.len())
        .into_par_iter()
        .with_min_len(256)
        .map(|i| {
            let (b, a) = (before.cells[i], cell_measures(after, i, &tables));
            [0, 1, 2, 3].map(|m| a[m] / b[m])
        })
        .collect();
    let worst = |m: usize| {
        let (cell, ratio) = ratios
            .iter()
            .enumerate()
            .map(|(i, r)| (i, r[m]))
            .filter(|(_, r)| !r.is_nan())
            .min_by(|x, y| x.1.total_cmp(&y.1))
            .unwrap_or((0, f64::NAN));
        Worst {
            ratio,
            cell,
            at: centroid(after, cell),
        }
    };
    Some(Measures {
        lin: worst(0),
        sj: worst(1),
        sicn: worst(2),
        edge: worst(3),
        of: MEASURES_OF,
    })
}

/// The shape functions' reference gradients at each Lagrange node of a cell type (one row
/// per node, one entry per shape function).
type GradientTable = Vec<Vec<[f64; 3]>>;

/// The gradient table of every cell type of `mesh`, evaluated once: a cell's Jacobian at its
/// nodes is then a sum over its nodes (evaluating the basis per cell was a tenth of a move).
fn gradient_tables(mesh: &Mesh) -> HashMap<CellType, Option<GradientTable>> {
    let mut tables = HashMap::new();
    for &ty in mesh.cells.types() {
        tables.entry(ty).or_insert_with(|| {
            reference_nodes(ty)
                .ok()?
                .into_iter()
                .map(|xi| shape_gradients(ty, xi).ok())
                .collect::<Option<GradientTable>>()
        });
    }
    tables
}

/// lin, sj, sicn and edge of cell `i` of `mesh`.
fn cell_measures(
    mesh: &Mesh,
    i: usize,
    tables: &HashMap<CellType, Option<GradientTable>>,
) -> [f64; 4] {
    let c = mesh.cells.get(i);
    let corners: Vec<[f64; 2]> = c.corners().iter().map(|&k| mesh.xy(k)).collect();
    let nodes: Vec<[f64; 2]> = c.nodes.iter().map(|&k| mesh.xy(k)).collect();
    let lin = mesh_move::scaled_jacobian(&corners);
    let n = corners.len();
    let edge = (0..n)
        .map(|j| {
            let (p, q) = (corners[j], corners[(j + 1) % n]);
            (p[0] - q[0]).hypot(p[1] - q[1])
        })
        .fold(f64::INFINITY, f64::min);
    let (mut sj, mut sicn) = (f64::INFINITY, f64::INFINITY);
    let Some(Some(table)) = tables.get(&c.ty) else {
        return [lin, f64::NAN, f64::NAN, edge];
    };
    if nodes.iter().any(|p| !p[0].is_finite() || !p[1].is_finite()) {
        return [lin, f64::NAN, f64::NAN, edge];
    }
    for grads in table {
        let j = matrix_from_gradients(&nodes, grads);
        let m = if c.ty.shape == Shape::Tri {
            equilateral(j)
        } else {
            j
        };
        let (c1, c2) = ([m[0][0], m[1][0]], [m[0][1], m[1][1]]);
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        let (l1, l2) = (c1[0].hypot(c1[1]), c2[0].hypot(c2[1]));
        sj = sj.min(det / (l1 * l2));
        sicn = sicn.min(2.0 * det / (l1 * l1 + l2 * l2));
    }
    [lin, sj, sicn, edge]
}

/// `J W⁻¹`, with `W` the map of the reference right triangle onto the equilateral triangle
/// of unit side: an equilateral cell's becomes a scaled rotation.
fn equilateral(j: [[f64; 2]; 2]) -> [[f64; 2]; 2] {
    // W = [[1, 1/2], [0, √3/2]], W⁻¹ = [[1, −1/√3], [0, 2/√3]]
    let s = 3f64.sqrt();
    [0, 1].map(|r| [j[r][0], -j[r][0] / s + 2.0 * j[r][1] / s])
}

/// The mean of a cell's corners.
fn centroid(mesh: &Mesh, cell: usize) -> [f64; 2] {
    let k = mesh.cells.get(cell).corners();
    let sum = k.iter().fold([0.0, 0.0], |s, &v| {
        let x = mesh.xy(v);
        [s[0] + x[0], s[1] + x[1]]
    });
    [sum[0] / k.len() as f64, sum[1] / k.len() as f64]
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::{CellType, Dim};

    fn one(shape: Shape, corners: &[[f64; 2]]) -> Mesh {
        let mut mesh = Mesh::new(Dim::Two, 1);
        for p in corners {
            mesh.nodes.push([p[0], p[1], 0.0]);
        }
        let k: Vec<u32> = (0..corners.len() as u32).collect();
        mesh.cells.push(CellType::new(shape, 1), &k);
        mesh
    }

    #[test]
    fn square_and_equilateral_cells_score_one_and_a_stretch_is_seen_by_sicn_only() {
        let square = one(
            Shape::Quad,
            &[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]],
        );
        let [lin, sj, sicn, _] = cell_measures(&square, 0, &gradient_tables(&square));
        assert!((lin - 1.0).abs() < 1e-12 && (sj - 1.0).abs() < 1e-12);
        assert!((sicn - 1.0).abs() < 1e-12);
        let h = 3f64.sqrt() / 2.0;
        let tri = one(Shape::Tri, &[[0.0, 0.0], [1.0, 0.0], [0.5, h]]);
        let [_, sj, sicn, edge] = cell_measures(&tri, 0, &gradient_tables(&tri));
        assert!(
            (sj - 1.0).abs() < 1e-12 && (sicn - 1.0).abs() < 1e-12,
            "{sj} {sicn}"
        );
        assert!((edge - 1.0).abs() < 1e-12);
        // the square stretched twice as long: angles and the shortest edge unchanged
        let long = one(
            Shape::Quad,
            &[[0.0, 0.0], [2.0, 0.0], [2.0, 1.0], [0.0, 1.0]],
        );
        let m = measures(&Baseline::of(square.clone()), &long).unwrap();
        assert!((m.lin.ratio - 1.0).abs() < 1e-12 && (m.edge.ratio - 1.0).abs() < 1e-12);
        assert!((m.sicn.ratio - 0.8).abs() < 1e-12, "{:?}", m.sicn);
        // turned inside out: negative
        let flipped = one(
            Shape::Quad,
            &[[0.0, 0.0], [0.0, 1.0], [1.0, 1.0], [1.0, 0.0]],
        );
        assert!(
            measures(&Baseline::of(square.clone()), &flipped)
                .unwrap()
                .sj
                .ratio
                < 0.0
        );
    }
}
