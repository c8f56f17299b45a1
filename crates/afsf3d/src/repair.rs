//! A local repair of a checked layer for the cut (issue 13, table 7): where no cone cut of
//! a cell over a front triangle (any apex, any diagonals of its quadrilaterals away from it
//! — every cut `topo-cut`'s refining can choose for the cell alone) keeps its tetrahedra
//! under a dihedral angle limit, the cell's children are moved, one at a time, by a small compass
//! search (across and along their extrusion edge, the step halving from a quarter of the
//! edge), to lower the worst best cut of the cells around them; a move is kept only when
//! every cell around the child still passes its check, its extrusion edge keeps its length
//! within 25 % and stays within the larger of 20° and its deviation before the move from
//! its ideal direction, and the smallest corner scaled Jacobian of the unmerged cells around
//! it stays at least 0.5 (or its value before, if lower). Where the new front then
//! intersects itself, every move is undone.
//! Cells whose best cut is under the limit are left to the bit, so a layer without such a
//! cell (the sphere, the cube) is unchanged.
//!
//! Such cells are flat under a front facet whose largest angle is near 180° (a "cap": one
//! node close to the opposite edge): every tetrahedron on that facet has a dihedral angle
//! near 180° at the edge through the cap's node, whatever the apex.

use geom_predicates::vector::{cross3, dist, dot, sub};
use geom_surface::{Facet, first_self_intersection, unit};
use mesh_model::is_positive_tet;
use mesh_model::measure3d::tet_max_dihedral_deg_of;
use rayon::prelude::*;

use crate::check::{cell_node, cell_sj, layer_cell_ok};
use crate::children::Layer;
use crate::compass::compass_search;

/// The quality given to a cut with an inverted or flat tetrahedron.
const INVERTED: f64 = 360.0;

/// The largest dihedral angle of the tetrahedron `o a b c` (positive orientation), or
/// [`INVERTED`].
fn tet_quality(o: [f64; 3], a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> f64 {
    if !is_positive_tet(o, a, b, c) {
        return INVERTED;
    }
    tet_max_dihedral_deg_of([o, a, b, c])
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
                    tet_quality(p(s), p(s + 2), p(s + 1), x).max(tet_quality(
                        p(s),
                        p(s + 3),
                        p(s + 2),
                        x,
                    ))
                };
                quads.push([split(0), split(1)]);
            }
            if fixed >= best {
                break;
            }
        }
        // the diagonals of different faces are independent: the best of each
        let worst = quads.iter().map(|q| q[0].min(q[1])).fold(fixed, f64::max);
        best = best.min(worst);
        if best <= enough {
            break;
        }
    }
    best
}

/// The best cone cut ([`best_cone_cut`]) of the cell of `layer` over `facet` (front nodes
/// `front`).
pub(crate) fn cell_cut(front: &[[f64; 3]], layer: &Layer, facet: &Facet, enough: f64) -> f64 {
    best_cone_cut(
        &layer.cell_faces(facet),
        |v| cell_node(front, layer, v),
        enough,
    )
}

/// The smallest edge-normalised corner scaled Jacobian of the cells of `layer` over
/// `around` that keep every top node (`mesh_model::measure3d::corner_determinants`; 1
/// without such cells).
fn min_corner_sj(front: &[[f64; 3]], facets: &[Facet], around: &[u32], layer: &Layer) -> f64 {
    let mut worst = 1.0f64;
    for &f in around {
        let facet = &facets[f as usize];
        if !layer.is_plain(facet) {
            continue;
        }
        worst = worst.min(cell_sj(front, facet, |v| {
            layer.children[layer.child[v as usize] as usize]
        }));
    }
    worst
}

/// A move may lower the smallest corner scaled Jacobian of the cells around a child to
/// this, or to its value before the move if that is lower: the prisms' and hexahedra's bar
/// (issue 13).
const SJ_FLOOR: f64 = 0.5;

/// The dihedral angle (degrees) over which a cell's best cone cut is repaired: under
/// `topo-cut`'s 150° target, so that its conforming cut (one diagonal per quadrilateral for
/// both cells) keeps a margin to 160° (with 150° the wing's case 3 kept one tetrahedron of
/// 161.5° whose cell alone cuts at 144.8°).
pub(crate) const CUT_LIMIT: f64 = 140.0;

/// How far (degrees) a moved child's extrusion edge may lean off its ideal direction (or
/// off as far as it already did): table 6's third bin. With 30° one of the wing's cases lost
/// layers further up.
const MAX_DEVIATION_DEG: f64 = 20.0;

/// How much a moved child's extrusion edge may be shorter or longer than before, relative.
const LENGTH_BAND: f64 = 0.25;

/// Repairs `layer` (checked, over the front `front` with `facets`; `dir` each front node's
/// ideal direction) where a cell over a triangle has its best cone cut over `limit` degrees
/// (see the module's doc; cells over quadrilaterals are left alone: on the step, where every
/// cell is a hexahedron with 64 cone cuts and the cut already stays under 160°, moving
/// their children lowered the smallest corner scaled Jacobian from 0.087 to 0.047). The layer stays checked: every move keeps the cells around the child valid, and
/// all moves are undone if the new front intersects itself. Returns the children moved.
pub(crate) fn repair_layer(
    front: &[[f64; 3]],
    facets: &[Facet],
    dir: &[[f64; 3]],
    layer: &mut Layer,
    limit: f64,
) -> usize {
    let bad: Vec<usize> = (0..facets.len())
        .into_par_iter()
        .filter(|&f| {
            let facet = &facets[f];
            facet.nodes().len() == 3
                && !layer.is_bare(facet)
                && cell_cut(front, layer, facet, limit) > limit
        })
        .collect();
    if bad.is_empty() {
        return 0;
    }
    let around = layer.cells_around(facets);
    let mut todo: Vec<u32> = bad
        .iter()
        .flat_map(|&f| facets[f].nodes().iter().map(|&v| layer.child[v as usize]))
        .collect();
    todo.sort_unstable();
    todo.dedup();
    let saved = layer.children.clone();
    let mut moved = 0;
    for &c in &todo {
        let c = c as usize;
        let ideal = unit(layer.parents_sum(c, dir));
        if improve_child(front, facets, &around[c], ideal, c, layer, limit) {
            moved += 1;
        }
    }
    if moved > 0 && first_self_intersection(&layer.children, &layer.top).is_some() {
        layer.children = saved;
        return 0;
    }
    moved
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
    let max_dev = angle(edge, ideal).max(MAX_DEVIATION_DEG.to_radians());
    let e = unit(edge);
    let t1 = unit(cross3(
        e,
        if e[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        },
    ));
    let t2 = cross3(e, t1);
    let moves = [t1, t2, e].map(|t| t.map(|x| x * h));
    let sj_floor = min_corner_sj(front, facets, around, layer).min(SJ_FLOOR);
    // (worst best cut around, sum of them): lexicographic
    let score = |layer: &Layer| {
        if min_corner_sj(front, facets, around, layer) < sj_floor {
            return (INVERTED, f64::INFINITY);
        }
        let mut worst = 0.0f64;
        let mut sum = 0.0;
        for &f in around {
            let facet = &facets[f as usize];
            if layer.is_bare(facet) {
                continue;
            }
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
    compass_search(start, &moves, (6, 8), |y| {
        let length = dist(y, base);
        if angle(sub(y, base), ideal) > max_dev || (length - h).abs() > LENGTH_BAND * h {
            return false;
        }
        let x = layer.children[c];
        layer.children[c] = y;
        let s = score(layer);
        if s.0 < best.0 - 1e-9 || (s.0 <= best.0 && s.1 < best.1 - 1e-9) {
            best = s;
            true
        } else {
            layer.children[c] = x;
            false
        }
    });
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

#[cfg(test)]
mod tests {
    use super::*;

    /// A triangle of the front (and its neighbours: a fan of four around node 0) grown by
    /// 0.2 along z, its top a cap: the child of node 2 pushed across, next to the
    /// children of nodes 0 and 1.
    fn capped() -> (Vec<[f64; 3]>, Vec<Facet>, Vec<[f64; 3]>) {
        let front = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.5, 0.6, 0.0],
            [-0.5, 0.6, 0.0],
            [0.5, -0.6, 0.0],
        ];
        let facets = vec![
            Facet::tri(0, 1, 2),
            Facet::tri(0, 2, 3),
            Facet::tri(0, 4, 1),
        ];
        let mut children: Vec<[f64; 3]> = front.iter().map(|p| [p[0], p[1], 0.2]).collect();
        children[2] = [0.5, 0.01, 0.2];
        (front, facets, children)
    }

    #[test]
    fn a_capped_top_is_repaired_by_moving_its_child_and_the_layer_stays_checked() {
        let (front, facets, children) = capped();
        let mut layer = Layer::unmerged(&front, &facets, &children);
        // valid by the growth's checks, but no cut of the capped cell stays under 160°
        assert!(facets.iter().all(|f| layer_cell_ok(&front, &layer, f)));
        let capped = cell_cut(&front, &layer, &facets[0], 0.0);
        assert!(capped > 160.0, "{capped}");
        let dir = vec![[0.0, 0.0, 1.0]; front.len()];
        let moved = repair_layer(&front, &facets, &dir, &mut layer, CUT_LIMIT);
        assert!((1..=3).contains(&moved), "{moved}");
        let worst = facets
            .iter()
            .map(|f| cell_cut(&front, &layer, f, 0.0))
            .fold(0.0, f64::max);
        assert!(worst <= CUT_LIMIT, "{worst}");
        assert!(facets.iter().all(|f| layer_cell_ok(&front, &layer, f)));
        // only children of the capped cell moved
        assert_eq!(layer.children[3..], children[3..]);
        // a good layer is left to the bit
        let before = layer.children.clone();
        assert_eq!(
            repair_layer(&front, &facets, &dir, &mut layer, CUT_LIMIT),
            0
        );
        assert_eq!(layer.children, before);
    }

    #[test]
    fn the_best_cone_cut_of_a_right_prism_is_that_of_its_best_apex() {
        // a right prism over a right isosceles triangle, as high as its legs: the cut
        // through the right-angle corner
        let nodes: Vec<[f64; 3]> = (0..6)
            .map(|i| {
                let (x, y) = [(0.0, 0.0), (2.0, 0.0), (0.0, 2.0)][i % 3];
                [x, y, if i < 3 { 0.0 } else { 2.0 }]
            })
            .collect();
        let faces = vec![
            vec![0, 2, 1],
            vec![3, 4, 5],
            vec![0, 1, 4, 3],
            vec![1, 2, 5, 4],
            vec![2, 0, 3, 5],
        ];
        let best = best_cone_cut(&faces, |v| nodes[v as usize], 0.0);
        assert!((best - 90.0).abs() < 1e-9, "{best}");
        // turned inside out, every cut is inverted
        let inside_out: Vec<Vec<u32>> = faces
            .iter()
            .map(|k| k.iter().rev().copied().collect())
            .collect();
        assert_eq!(
            best_cone_cut(&inside_out, |v| nodes[v as usize], 0.0),
            INVERTED
        );
    }
}
