//! The checks of a new layer (positive corner tetrahedra of every cell, strictly convex
//! merged cells, no self-intersection of the new front) and the shrinking of the children
//! where they fail.

use geom_surface::{Facet, self_intersections};
use mesh_model::is_positive_tet;
use mesh_model::measure3d::corner_determinants;
use rayon::prelude::*;

use crate::children::Layer;
use crate::front::turn_off;
use crate::{GrowError, GrowStats};

/// Whether every corner tetrahedron of a cell with the `m` bottom corners `bottom(i)`
/// (counter-clockwise seen from the fluid) and their children `top(i)` is positive: at each
/// bottom corner the corner, its next and previous neighbours and the child; at each top
/// corner the child, its previous and next neighbours and the parent.
fn corners_ok(
    bottom: impl Fn(usize) -> [f64; 3],
    top: impl Fn(usize) -> [f64; 3],
    m: usize,
) -> bool {
    (0..m).all(|i| {
        let (p, a, c) = ((i + m - 1) % m, i, (i + 1) % m);
        is_positive_tet(bottom(a), bottom(c), bottom(p), top(a))
            && is_positive_tet(top(a), top(p), top(c), bottom(a))
    })
}

/// The position of node `v` of [`Layer::cell_faces`]: front node `v`, or child `v - n` of
/// `layer` (`n` front nodes).
pub(crate) fn cell_node(front: &[[f64; 3]], layer: &Layer, v: u32) -> [f64; 3] {
    let n = front.len() as u32;
    if v < n {
        front[v as usize]
    } else {
        layer.children[(v - n) as usize]
    }
}

/// The edge-normalised corner scaled Jacobians of the prism or hexahedron over the front
/// facet `facet` (nodes `nodes`) whose node `v` has the child `top(v)`, bottom corners first.
pub(crate) fn cell_corners(
    nodes: &[[f64; 3]],
    facet: &Facet,
    top: impl Fn(u32) -> [f64; 3],
) -> Vec<f64> {
    let k = facet.nodes();
    let p: Vec<[f64; 3]> = k
        .iter()
        .map(|&v| nodes[v as usize])
        .chain(k.iter().map(|&v| top(v)))
        .collect();
    corner_determinants(&p, true)
}

/// The smallest of [`cell_corners`].
pub(crate) fn cell_sj(nodes: &[[f64; 3]], facet: &Facet, top: impl Fn(u32) -> [f64; 3]) -> f64 {
    cell_corners(nodes, facet, top)
        .into_iter()
        .fold(f64::INFINITY, f64::min)
}

/// Whether the cell with the outward faces `faces` (nodes at `pos`) is strictly convex:
/// every node of the cell off a face lies strictly inside of the triangle at every corner of
/// that face, so every cone from a node over the faces without it — every cut of
/// `topo-cut` — is positive.
pub(crate) fn strictly_convex(faces: &[Vec<u32>], pos: impl Fn(u32) -> [f64; 3]) -> bool {
    let mut all: Vec<u32> = faces.iter().flatten().copied().collect();
    all.sort_unstable();
    all.dedup();
    cones_ok(faces, pos, &all)
}

/// Whether every cone from a node of `apexes` over the faces of the cell (outward `faces`,
/// nodes at `pos`) without it is positive whatever the diagonals of its quadrilaterals: each
/// apex lies strictly inside the triangle at every corner of every face without it.
pub(crate) fn cones_ok(faces: &[Vec<u32>], pos: impl Fn(u32) -> [f64; 3], apexes: &[u32]) -> bool {
    faces.iter().all(|k| {
        let m = k.len();
        (0..m).all(|i| {
            let (p, c, q) = (pos(k[(i + m - 1) % m]), pos(k[i]), pos(k[(i + 1) % m]));
            apexes
                .iter()
                .filter(|v| !k.contains(v))
                .all(|&v| is_positive_tet(c, p, q, pos(v)))
        })
    })
}

/// Whether the cell of `layer` over the front facet `facet` is valid: [`corners_ok`] when its
/// top keeps every node, strictly convex (every cut of `topo-cut` positive) when children
/// of it merged; where some of its nodes stopped, every cone from a stopped node positive
/// ([`cones_ok`]: `topo-cut` sweeps a stopped node first, so one of them is the cell's apex
/// and splits its quadrilaterals). Stopping makes the cell thin by its top and bottom sharing
/// nodes, and a warped bottom quadrilateral then folds some other cone however high the
/// children rise: the stopped node's cones depend on the children's directions only. A facet
/// whose nodes all stopped has no cell.
pub(crate) fn layer_cell_ok(front: &[[f64; 3]], layer: &Layer, facet: &Facet) -> bool {
    let k = facet.nodes();
    if layer.is_bare(facet) {
        return true;
    }
    if layer.is_fan(facet) {
        // a fan's prism on its side (`fan`): its copies one node each
        return strictly_convex(&layer.cell_faces(facet), |v| cell_node(front, layer, v));
    }
    let kept: Vec<u32> = k.iter().copied().filter(|&v| layer.is_kept(v)).collect();
    if !kept.is_empty() {
        cones_ok(
            &layer.cell_faces(facet),
            |v| cell_node(front, layer, v),
            &kept,
        )
    } else if layer.is_merged(facet) {
        strictly_convex(&layer.cell_faces(facet), |v| cell_node(front, layer, v))
    } else {
        let up = |i: usize| layer.children[layer.child[k[i] as usize] as usize];
        corners_ok(|i| front[k[i] as usize], up, k.len())
    }
}

/// The facets whose cells fail [`layer_cell_ok`] (in parallel).
pub(crate) fn bad_cells(front: &[[f64; 3]], layer: &Layer, facets: &[Facet]) -> Vec<usize> {
    facets
        .par_iter()
        .enumerate()
        .filter(|(_, f)| !layer_cell_ok(front, layer, f))
        .map(|(i, _)| i)
        .collect()
}

/// What fails where a cell is inverted (or a merged or stopped cell not strictly convex).
pub(crate) const INVERTED: &str = "an inverted cell";

/// What fails where the new front meets itself (two of its parts, or two bodies' fronts).
pub(crate) const CROSSING: &str = "the front intersects itself";

/// Where a layer stays invalid: the failing front facets and what fails.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Failed {
    pub bad: Vec<usize>,
    pub what: &'static str,
}

impl Failed {
    /// The growth's error for this failure in layer `layer` (the wall facet of each front
    /// facet in `pipes`).
    pub fn error(&self, pipes: &[u32], layer: usize) -> GrowError {
        GrowError::LayerFailed {
            layer,
            facet: pipes[self.bad[0]] as usize,
            what: self.what,
        }
    }
}

/// How many times the children of an inverted cell are moved halfway back before the layer
/// fails there (and those columns stop, `stop`): a cell halved again and again stays valid
/// only as a flat one, whose tetrahedra pass 170° (the swept wing and the capsule's fin of
/// `fixtures/surfaces`: 179.7° and 177.8° with 8 halvings, 174.8° and 168.4° with 1, the
/// coverage 0.964 and 0.991 either way; the built-in cases never need a second one).
pub(crate) const INVERTED_SHRINKS: usize = 1;

/// Checks `layer` over the front (nodes `front`, facets `facets`); while a cell is invalid
/// or the new front intersects itself, moves the children of the failing facets halfway
/// back to their parents (a merged child to the midpoint of its two). Fails after
/// `inverted` rounds where a cell is inverted (the growth: [`INVERTED_SHRINKS`]),
/// `crossing` where the front crosses itself (two fronts slowing down as they meet keep
/// good cells), with the facets that still fail.
pub(crate) fn shrink_until_valid(
    front: &[[f64; 3]],
    facets: &[Facet],
    layer: &mut Layer,
    (inverted, crossing): (usize, usize),
    stats: &mut GrowStats,
) -> Result<(), Failed> {
    let mut round = 0;
    loop {
        let mut bad = match layer.failing.take() {
            Some(bad) => bad,
            None => bad_cells(front, layer, facets),
        };
        let mut what = INVERTED;
        if bad.is_empty() {
            // every crossing pair at once: two fronts growing into each other meet over many
            let crossing = self_intersections(&layer.children, &layer.top);
            if crossing.is_empty() {
                return Ok(());
            }
            bad = crossing
                .iter()
                .flat_map(|&(f, g)| [layer.top_of[f] as usize, layer.top_of[g] as usize])
                .collect();
            bad.sort_unstable();
            bad.dedup();
            what = CROSSING;
        }
        let limit = if what == INVERTED { inverted } else { crossing };
        if round >= limit {
            return Err(Failed { bad, what });
        }
        round += 1;
        let mut moved = vec![false; layer.children.len()];
        for &f in &bad {
            for &v in facets[f].nodes() {
                moved[layer.child[v as usize] as usize] = true;
            }
        }
        for c in (0..moved.len()).filter(|&c| moved[c] && !layer.kept[c]) {
            let (base, x) = (layer.base(front, c), layer.children[c]);
            layer.children[c] = std::array::from_fn(|d| (base[d] + x[d]) / 2.0);
            stats.shrunk_nodes += 1;
        }
        stats.shrinks += 1;
    }
}

/// The smallest cosine between a turned step and the normal of each of its node's bottom
/// corner triangles that [`turned_steps`] aims for (or half the best there is, if lower).
const TURN_FLOOR: f64 = 0.2;

/// The balanced children `balanced` of the front (`front`, `facets`) with the steps turned
/// of the nodes of the failing facets `bad` whose bottom corner fails: a corner triangle
/// of the front at the node (the node, its next and previous neighbours on a facet) that
/// its step does not stand off. No shrinking mends such a corner (the check depends on the
/// step's direction only): a node on a ridge beside a pit the shrinks of earlier layers
/// left (the quad wing far out, `docs/3d.md`). The step keeps its length and turns towards
/// the direction standing most steeply off all the node's corner triangles
/// ([`max_min_direction`](crate::front::max_min_direction)), just far enough that it stands off each at a cosine of
/// [`TURN_FLOOR`] (or half the best, if lower). `None` if no node turns.
pub(crate) fn turned_steps(
    front: &[[f64; 3]],
    facets: &[Facet],
    balanced: &[[f64; 3]],
    bad: &[usize],
) -> Option<Vec<[f64; 3]>> {
    use geom_predicates::vector::{cross3, dist, dot, sub};
    let corner = |f: &Facet, i: usize| {
        let k = f.nodes();
        let m = k.len();
        let x = |j: usize| front[k[j % m] as usize];
        geom_surface::unit(cross3(sub(x(i + 1), x(i)), sub(x(i + m - 1), x(i))))
    };
    let step = |v: usize| geom_surface::unit(sub(balanced[v], front[v]));
    let mut failing: Vec<u32> = Vec::new();
    for &f in bad {
        let facet = &facets[f];
        for (i, &v) in facet.nodes().iter().enumerate() {
            // a stopped node has no step to turn; a fan's zero-area corner no normal
            let normal = corner(facet, i);
            if balanced[v as usize] == front[v as usize] || normal == [0.0; 3] {
                continue;
            }
            if dot(normal, step(v as usize)) <= 0.0 {
                failing.push(v);
            }
        }
    }
    failing.sort_unstable();
    failing.dedup();
    if failing.is_empty() {
        return None;
    }
    let mut normals: Vec<Vec<[f64; 3]>> = vec![Vec::new(); failing.len()];
    for facet in facets {
        for (i, v) in facet.nodes().iter().enumerate() {
            if let Ok(slot) = failing.binary_search(v) {
                let normal = corner(facet, i);
                if normal != [0.0; 3] {
                    normals[slot].push(normal);
                }
            }
        }
    }
    let mut out = balanced.to_vec();
    let mut turned = false;
    for (&v, n) in failing.iter().zip(&normals) {
        let v = v as usize;
        let (d, target) = turn_off(step(v), n, TURN_FLOOR, 0.5);
        if target <= 0.0 {
            continue;
        }
        let len = dist(balanced[v], front[v]);
        out[v] = std::array::from_fn(|k| front[v][k] + len * d[k]);
        turned = true;
    }
    turned.then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::children::Ideal;

    #[test]
    fn a_step_under_its_corner_triangle_is_turned_off_it_keeping_its_length() {
        // two unit squares side by side in z = 0 (facing +z); node 1's step lies below the
        // plane: no shrinking mends that corner
        let front = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.0, 0.0],
            [2.0, 1.0, 0.0],
        ];
        let facets = [Facet::quad(0, 1, 2, 3), Facet::quad(1, 4, 5, 2)];
        let mut balanced: Vec<[f64; 3]> = front.iter().map(|p| [p[0], p[1], 0.5]).collect();
        balanced[1] = [1.8, 0.0, -0.1];
        // valid after at most eight shrinks
        let ok = |children: &[[f64; 3]]| {
            let ideal = Ideal {
                nodes: &front,
                dir: &[],
                len: &[],
                balanced: children,
                stopped: &[],
                fan: None,
            };
            let mut layer = Layer::new(&ideal, &facets, &[]);
            let mut stats = GrowStats::default();
            shrink_until_valid(&front, &facets, &mut layer, (8, 8), &mut stats).is_ok()
        };
        assert!(!ok(&balanced));
        let turned = turned_steps(&front, &facets, &balanced, &[0, 1]).unwrap();
        assert!(ok(&turned));
        let step: [f64; 3] = std::array::from_fn(|d| turned[1][d] - front[1][d]);
        let len = |v: [f64; 3]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
        assert!((len(step) - (0.64f64 + 0.01).sqrt()).abs() < 1e-12);
        assert!(step[2] / len(step) >= TURN_FLOOR - 1e-9);
        // the other steps stay to the bit; nothing to turn without a failing corner
        assert!((0..6).filter(|&v| v != 1).all(|v| turned[v] == balanced[v]));
        assert_eq!(turned_steps(&front, &facets, &turned, &[0, 1]), None);
    }

    #[test]
    fn a_prism_over_a_counter_clockwise_triangle_is_valid_and_upside_down_is_not() {
        let bottom = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
        let up = bottom.map(|p| [p[0], p[1], 0.2]);
        let down = bottom.map(|p| [p[0], p[1], -0.2]);
        let f = Facet::tri(0, 1, 2);
        let ok = |top: &[[f64; 3]]| {
            let ideal = Ideal {
                nodes: &bottom,
                dir: &[],
                len: &[],
                balanced: top,
                stopped: &[],
                fan: None,
            };
            layer_cell_ok(&bottom, &Layer::new(&ideal, &[f], &[]), &f)
        };
        assert!(ok(&up));
        assert!(!ok(&down));
        // a child pushed across its neighbour's extrusion edge twists the cell
        let mut twisted = up;
        twisted[0] = [1.5, 0.8, 0.2];
        assert!(!ok(&twisted));
    }
}
