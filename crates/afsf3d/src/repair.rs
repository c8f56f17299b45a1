//! A local repair of a checked layer for the cut (issue 13, table 7): where no cone cut of a
//! cell (any apex, any diagonals of its quadrilaterals away from it — every cut
//! `topo-cut`'s refining can choose for the cell alone) keeps its tetrahedra under a
//! dihedral angle limit, the cell's children are moved, one at a time, by a small compass
//! search (across and along their extrusion edge, the step halving from a quarter of the
//! edge), to lower the worst best cut of the cells around them; a move is kept only when
//! every cell around the child still passes its check and its extrusion edge stays within
//! the larger of 30° and its deviation before the move from its ideal direction. Where
//! the new front then intersects itself, every move is undone.
//!
//! Such cells are flat under a front facet whose largest angle is near 180° (a "cap": one
//! node close to the opposite edge): every tetrahedron on that facet has a dihedral angle
//! near 180° at the edge through the cap's node, whatever the apex.

use geom_predicates::vector::{cross3, dist, dot, sub};
use geom_surface::{Facet, first_self_intersection, unit};
use mesh_model::{NONE, is_positive_tet};
use mesh_model::measure3d::tet_dihedral_angles_deg;
use rayon::prelude::*;

use crate::check::layer_cell_ok;
use crate::layer::Layer;

/// The quality given to a cut with an inverted or flat tetrahedron.
const INVERTED: f64 = 360.0;

/// The largest dihedral angle of the tetrahedron `o a b c` (positive orientation), or
/// [`INVERTED`].
fn tet_quality(o: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    if !is_positive_tet(o, a, b, c) {
        return INVERTED;
    }
    tet_dihedral_angles_deg([o, a, b, c])
        .into_iter()
        .fold(0.0, f64::max)
}

/// The best cone cut of the cell with the outward faces `faces` (nodes at `pos`): the
/// smallest, over every apex and every choice of diagonals of the quadrilaterals without
/// it, of the largest dihedral angle of the cut's tetrahedra ([`INVERTED`] for an inverted
/// one). Stops at the first cut at or under `enough`.
pub(crate) fn best_cone_cut(faces: &[Vec<u32>], pos: impl Fn(u32) -> [f64; 3], enough: f64) -> f64 {
    let mut nodes: Vec<u32> = faces.iter().flatten().copied().collect();
    nodes.sort_unstable();
    nodes.dedup();
    let mut best = INVERTED;
    for &apex in &nodes {
        let x = pos(apex);
        let far: Vec<&Vec<u32>> = faces.iter().filter(|k| !k.contains(&apex)).collect();
        // each face alone: its triangle's tetrahedron, or each diagonal's two
        let mut fixed = 0.0f64;
        let mut quads: Vec<[f64; 2]> = Vec::new();
        for k in far {
            let p = |j: usize| pos(k[j % k.len()]);
            if k.len() == 3 {
                fixed = fixed.max(tet_quality(p(0), p(2), p(1), x));
            } else {
                let split = |s: usize| {
                    tet_quality(p(s), p(s + 2), p(s + 1), x).max(tet_quality(p(s), p(s + 3), p(s + 2), x))
                };
                quads.push([split(0), split(1)]);
            }
            if fixed >= best {
                break;
            }
        }
        // the diagonals of different faces are independent: the best of each
        let worst = quads
            .iter()
            .map(|q| q[0].min(q[1]))
            .fold(fixed, f64::max);
        best = best.min(worst);
        if best <= enough {
            break;
        }
    }
    best
}

/// The worst best cone cut ([`best_cone_cut`]) of the cells of `layer` over `facets`
/// (front nodes `front`).
fn cell_cut(front: &[[f64; 3]], layer: &Layer, facet: &Facet, enough: f64) -> f64 {
    let n = front.len() as u32;
    let pos = |v: u32| {
        if v < n {
            front[v as usize]
        } else {
            layer.children[(v - n) as usize]
        }
    };
    best_cone_cut(&layer.cell_faces(facet), pos, enough)
}

/// The dihedral angle (degrees) over which a cell's best cone cut is repaired: `topo-cut`
/// refines every cell over 150°.
pub(crate) const CUT_LIMIT: f64 = 150.0;

/// What a repair did.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub(crate) struct Repair {
    /// Cells whose best cut was over the limit before, and after.
    pub bad_before: usize,
    pub bad_after: usize,
    /// Children moved.
    pub moved: usize,
}

/// Repairs `layer` (checked, over the front `front` with `facets`; `dir` each front node's
/// ideal direction) where a cell's best cone cut is over `limit` degrees (see the module's
/// doc). The layer stays checked: every move keeps the cells around the child valid, and
/// all moves are undone if the new front intersects itself.
pub(crate) fn repair_layer(
    front: &[[f64; 3]],
    facets: &[Facet],
    dir: &[[f64; 3]],
    layer: &mut Layer,
    limit: f64,
) -> Repair {
    let bad: Vec<usize> = (0..facets.len())
        .into_par_iter()
        .filter(|&f| cell_cut(front, layer, &facets[f], limit) > limit)
        .collect();
    let mut out = Repair {
        bad_before: bad.len(),
        bad_after: bad.len(),
        moved: 0,
    };
    if bad.is_empty() {
        return out;
    }
    // the cells around each child
    let mut around: Vec<Vec<u32>> = vec![Vec::new(); layer.children.len()];
    for (f, facet) in facets.iter().enumerate() {
        for &v in facet.nodes() {
            let c = layer.child[v as usize] as usize;
            if around[c].last() != Some(&(f as u32)) {
                around[c].push(f as u32);
            }
        }
    }
    let mut todo: Vec<u32> = bad
        .iter()
        .flat_map(|&f| facets[f].nodes().iter().map(|&v| layer.child[v as usize]))
        .collect();
    todo.sort_unstable();
    todo.dedup();
    let saved = layer.children.clone();
    for &c in &todo {
        let c = c as usize;
        let ideal = unit(layer.parents[c].iter().filter(|&&v| v != NONE).fold(
            [0.0; 3],
            |s, &v| std::array::from_fn(|d| s[d] + dir[v as usize][d]),
        ));
        if improve_child(front, facets, &around[c], ideal, c, layer, limit) {
            out.moved += 1;
        }
    }
    if out.moved > 0 && first_self_intersection(&layer.children, &layer.top).is_some() {
        layer.children = saved;
        out.moved = 0;
        return out;
    }
    out.bad_after = bad
        .iter()
        .filter(|&&f| cell_cut(front, layer, &facets[f], limit) > limit)
        .count();
    out
}

/// The compass search of one child `c` (ideal direction `ideal`: its parent's, or the mean
/// of its two parents' when merged) over the cells `around` it: returns whether it moved.
fn improve_child(
    front: &[[f64; 3]],
    facets: &[Facet],
    around: &[u32],
    ideal: [f64; 3],
    c: usize,
    layer: &mut Layer,
    limit: f64,
) -> bool {
    let base = layer.base(front, c);
    let start = layer.children[c];
    let edge = sub(start, base);
    let h = dist(start, base);
    if h <= 0.0 {
        return false;
    }
    let max_dev = angle(edge, ideal).max(30f64.to_radians());
    let e = unit(edge);
    let t1 = unit(cross3(e, if e[0].abs() < 0.9 { [1.0, 0.0, 0.0] } else { [0.0, 1.0, 0.0] }));
    let t2 = cross3(e, t1);
    let moves = [t1, t2, e].map(|t| t.map(|x| x * h));
    // (worst best cut around, sum of them): lexicographic
    let score = |layer: &Layer| {
        let mut worst = 0.0f64;
        let mut sum = 0.0;
        for &f in around {
            let facet = &facets[f as usize];
            if !layer_cell_ok(front, layer, facet) {
                return (INVERTED, f64::INFINITY);
            }
            let q = cell_cut(front, layer, facet, 0.0);
            worst = worst.max(q);
            sum += q;
        }
        (worst, sum)
    };
    let first = score(layer);
    if first.0 <= limit {
        return false;
    }
    let mut best = first;
    let mut step = 0.25;
    for _ in 0..6 {
        let mut improved = true;
        let mut rounds = 0;
        while improved && rounds < 8 {
            improved = false;
            rounds += 1;
            for m in &moves {
                for sign in [1.0, -1.0] {
                    let x = layer.children[c];
                    let y: [f64; 3] = std::array::from_fn(|d| x[d] + sign * step * m[d]);
                    let length = dist(y, base);
                    if angle(sub(y, base), ideal) > max_dev || length < 0.5 * h || length > 1.5 * h {
                        continue;
                    }
                    layer.children[c] = y;
                    let s = score(layer);
                    if s.0 < best.0 - 1e-9 || (s.0 <= best.0 && s.1 < best.1 - 1e-9) {
                        best = s;
                        improved = true;
                    } else {
                        layer.children[c] = x;
                    }
                }
            }
        }
        step /= 2.0;
    }
    if best.0 < first.0 {
        true
    } else {
        layer.children[c] = start;
        false
    }
}

/// The angle between `a` and `b`, in radians.
fn angle(a: [f64; 3], b: [f64; 3]) -> f64 {
    let c = dot(a, b) / (dot(a, a) * dot(b, b)).sqrt();
    c.clamp(-1.0, 1.0).acos()
}
