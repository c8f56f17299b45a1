//! Measures for comparing movers on the same motion: the scaled Jacobian of every linear
//! cell before and after, the worst-cell ratio, the inverted cells, and the drift of the
//! first layer (its height and the angle of its extrusion edges to the wall's normal).

use mesh_model::{Mesh, Role, Shape, is_positive_polygon};

use crate::MoveError;
use crate::boundary::check_linear_2d;

/// The scaled Jacobian of a linear cell given by its corners (counter-clockwise): the
/// smallest over the corners of `(e₁ × e₂) / (|e₁| |e₂|)`, `e₁`, `e₂` the edges leaving the
/// corner towards its next and previous neighbours. 1 for a square (and any rectangle); a
/// triangle's value is multiplied by 2/√3 so that an equilateral triangle gets 1. Negative
/// for an inverted corner, 0 for a degenerate one (a zero-length edge).
pub fn scaled_jacobian(corners: &[[f64; 2]]) -> f64 {
    let n = corners.len();
    let mut worst = f64::INFINITY;
    for i in 0..n {
        let (p, a, b) = (corners[i], corners[(i + 1) % n], corners[(i + n - 1) % n]);
        let e1 = [a[0] - p[0], a[1] - p[1]];
        let e2 = [b[0] - p[0], b[1] - p[1]];
        // one square root, not two `hypot`s: the measures evaluate this for every cell
        let norm = ((e1[0] * e1[0] + e1[1] * e1[1]) * (e2[0] * e2[0] + e2[1] * e2[1])).sqrt();
        let v = if norm > 0.0 {
            (e1[0] * e2[1] - e1[1] * e2[0]) / norm
        } else {
            0.0
        };
        worst = worst.min(v);
    }
    if n == 3 {
        worst * 2.0 / 3f64.sqrt()
    } else {
        worst
    }
}

fn corners(mesh: &Mesh, i: usize) -> Vec<[f64; 2]> {
    mesh.cells
        .get(i)
        .corners()
        .iter()
        .map(|&k| mesh.xy(k))
        .collect()
}

/// The scaled Jacobian of every cell of the linear 2D mesh `mesh` (from its corners).
pub fn cell_scaled_jacobians(mesh: &Mesh) -> Vec<f64> {
    (0..mesh.cells.len())
        .map(|i| scaled_jacobian(&corners(mesh, i)))
        .collect()
}

/// The cells of the linear 2D mesh `mesh` that are inverted or degenerate: some corner does
/// not turn left by the exact orientation predicate.
pub fn inverted_cells(mesh: &Mesh) -> usize {
    inverted_cells_at(mesh, |k| mesh.xy(k))
}

/// [`inverted_cells`] of `mesh` with its node `k` at `at(k)` (a mover's trial positions,
/// without a copy of the mesh).
pub(crate) fn inverted_cells_at(mesh: &Mesh, at: impl Fn(u32) -> [f64; 2]) -> usize {
    let mut corners = Vec::with_capacity(4);
    (0..mesh.cells.len())
        .filter(|&i| {
            corners.clear();
            corners.extend(mesh.cells.get(i).corners().iter().map(|&k| at(k)));
            !is_positive_polygon(&corners)
        })
        .count()
}

/// How the first layer (the cells that have a wall facet as an edge) changed.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct FirstLayerDrift {
    /// First-layer cells.
    pub cells: usize,
    /// Largest relative change of a first-layer cell's height (its area over its wall
    /// facet's length for a quad, twice that for a triangle): `|h_after / h_before − 1|`.
    pub height: f64,
    /// Largest change, degrees, of the angle between an extrusion edge of a first-layer quad
    /// (the two edges leaving the wall facet) and the wall facet's normal.
    pub angle_deg: f64,
}

/// A comparison of a moved mesh with the original one.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Comparison {
    /// Smallest scaled Jacobian before.
    pub min_before: f64,
    /// Smallest scaled Jacobian after.
    pub min_after: f64,
    /// The worst-cell ratio: min over cells of (scaled Jacobian after / before), over the
    /// cells valid before.
    pub worst_cell_ratio: f64,
    /// The cell where it is reached.
    pub worst_cell: usize,
    /// Cells inverted or degenerate after (exact orientation predicates on the corners).
    pub inverted_cells: usize,
    /// The first layer's drift; `None` when the mesh has no wall patch.
    pub first_layer: Option<FirstLayerDrift>,
}

/// `after` compared with `before`: same cells and facets, other node positions.
///
/// # Errors
/// [`MoveError::NotLinear2d`], [`MoveError::TopologyMismatch`].
pub fn compare(before: &Mesh, after: &Mesh) -> Result<Comparison, MoveError> {
    check_linear_2d(before)?;
    check_linear_2d(after)?;
    let mismatch = |what: &str| {
        Err(MoveError::TopologyMismatch {
            what: what.to_string(),
        })
    };
    if before.nodes.len() != after.nodes.len() {
        return mismatch("node counts");
    }
    if before.cells.flat_nodes() != after.cells.flat_nodes()
        || before.cells.types() != after.cells.types()
    {
        return mismatch("cells");
    }
    if before.boundary.flat_nodes() != after.boundary.flat_nodes()
        || before.boundary_patch != after.boundary_patch
    {
        return mismatch("boundary facets");
    }
    let (sb, sa) = (cell_scaled_jacobians(before), cell_scaled_jacobians(after));
    let mut worst = (f64::INFINITY, 0);
    for (i, (b, a)) in sb.iter().zip(&sa).enumerate() {
        if *b > 0.0 && a / b < worst.0 {
            worst = (a / b, i);
        }
    }
    let inverted = inverted_cells(after);
    let fold_min = |v: &[f64]| v.iter().copied().fold(f64::INFINITY, f64::min);
    Ok(Comparison {
        min_before: fold_min(&sb),
        min_after: fold_min(&sa),
        worst_cell_ratio: worst.0,
        worst_cell: worst.1,
        inverted_cells: inverted,
        first_layer: first_layer_drift(before, after),
    })
}

/// The first layer's drift from `before` to `after` (same topology); `None` without walls.
pub fn first_layer_drift(before: &Mesh, after: &Mesh) -> Option<FirstLayerDrift> {
    use std::collections::HashMap;
    let walls: Vec<[u32; 2]> = (0..before.boundary.len())
        .filter(|&f| before.patches[before.boundary_patch[f] as usize].role == Role::Wall)
        .map(|f| {
            let facet = before.boundary.get(f);
            let k = facet.corners();
            [k[0], k[1]]
        })
        .collect();
    if walls.is_empty() {
        return None;
    }
    // a wall facet a → b is the cell edge a → b (domain on the facet's left): the cells'
    // edges looked up among the wall facets (a map of every cell edge was most of the time)
    let wall_at: HashMap<[u32; 2], usize> =
        walls.iter().enumerate().map(|(f, &w)| (w, f)).collect();
    let mut facet_cell: Vec<Option<(usize, usize)>> = vec![None; walls.len()];
    for i in 0..before.cells.len() {
        let k = before.cells.get(i).corners();
        for j in 0..k.len() {
            if let Some(&f) = wall_at.get(&[k[j], k[(j + 1) % k.len()]]) {
                facet_cell[f] = Some((i, j));
            }
        }
    }
    let mut drift = FirstLayerDrift::default();
    for (w, at) in walls.iter().zip(&facet_cell) {
        let Some((cell, j)) = *at else {
            continue;
        };
        drift.cells += 1;
        let (hb, ha) = (height(before, cell, w), height(after, cell, w));
        drift.height = drift.height.max((ha / hb - 1.0).abs());
        let c = before.cells.get(cell);
        if c.ty.shape == Shape::Quad {
            let k = c.corners();
            // extrusion edges: b → k[j + 2] and a → k[j + 3]
            for (from, to) in [(w[1], k[(j + 2) % 4]), (w[0], k[(j + 3) % 4])] {
                let change = normal_angle(after, w, from, to) - normal_angle(before, w, from, to);
                let change = (change + std::f64::consts::PI).rem_euclid(std::f64::consts::TAU)
                    - std::f64::consts::PI;
                drift.angle_deg = drift.angle_deg.max(change.abs().to_degrees());
            }
        }
    }
    Some(drift)
}

/// A first-layer cell's height over its wall facet `w`: the mean distance of its other
/// corners from the facet's line (area over length would count a trapezoid at a convex
/// corner, whose top edge is longer, as higher when the wall stretches under it).
fn height(mesh: &Mesh, cell: usize, w: &[u32; 2]) -> f64 {
    let (a, b) = (mesh.xy(w[0]), mesh.xy(w[1]));
    let t = [b[0] - a[0], b[1] - a[1]];
    let len = (t[0] * t[0] + t[1] * t[1]).sqrt();
    let (mut sum, mut count) = (0.0, 0.0);
    for &k in mesh.cells.get(cell).corners() {
        if k != w[0] && k != w[1] {
            let p = mesh.xy(k);
            sum += (t[0] * (p[1] - a[1]) - t[1] * (p[0] - a[0])).abs() / len;
            count += 1.0;
        }
    }
    sum / count
}

/// Signed angle, radians, from the inward normal of wall facet `w` to edge `from → to`.
fn normal_angle(mesh: &Mesh, w: &[u32; 2], from: u32, to: u32) -> f64 {
    let (a, b) = (mesh.xy(w[0]), mesh.xy(w[1]));
    let n = [-(b[1] - a[1]), b[0] - a[0]]; // left of a → b: into the domain
    let (p, q) = (mesh.xy(from), mesh.xy(to));
    let e = [q[0] - p[0], q[1] - p[1]];
    (n[0] * e[1] - n[1] * e[0]).atan2(n[0] * e[0] + n[1] * e[1])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn squares_rectangles_and_equilateral_triangles_score_one_inverted_corners_below_zero() {
        let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
        assert_eq!(scaled_jacobian(&square), 1.0);
        let thin = [[0.0, 0.0], [1.0, 0.0], [1.0, 1e-6], [0.0, 1e-6]];
        assert_eq!(scaled_jacobian(&thin), 1.0);
        let h = 3f64.sqrt() / 2.0;
        let equilateral = [[0.0, 0.0], [1.0, 0.0], [0.5, h]];
        assert!((scaled_jacobian(&equilateral) - 1.0).abs() < 1e-15);
        let right = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]];
        // the 45° corners: sin 45° · 2/√3
        let want = (0.5f64).sqrt() * 2.0 / 3f64.sqrt();
        assert!((scaled_jacobian(&right) - want).abs() < 1e-15);
        let sheared = [[0.0, 0.0], [1.0, 0.0], [2.0, 1.0], [1.0, 1.0]];
        assert!((scaled_jacobian(&sheared) - 0.5f64.sqrt()).abs() < 1e-15);
        let dart = [[0.0, 0.0], [1.0, 0.0], [0.2, 0.2], [0.0, 1.0]];
        assert!(scaled_jacobian(&dart) < 0.0);
        let degenerate = [[0.0, 0.0], [0.0, 0.0], [1.0, 1.0]];
        assert_eq!(scaled_jacobian(&degenerate), 0.0);
    }
}
