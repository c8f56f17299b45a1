//! Merges where the front is squeezed (issue 13, the step's concave edges): once the layers
//! are as thick as the wall's spacing, the offset of a concave edge swallows a band on both
//! sides, and with one child per node the cells next to it are squeezed — their corners
//! flatten while their edges stay long next to the extrusion length, so Coe_shrink (which
//! compares the children's edge with the extrusion length) does not fire. Here a cell whose
//! smallest edge-normalised corner scaled Jacobian (with the balanced children, no merges)
//! falls below [`crate::LayerParams::squeeze`] merges the children of one of its edges: the
//! edge whose children came closest relative to their parents (the direction in which the
//! front shrinks most), if they came closer than their parents. The worst cells choose
//! first, each front node in one merge per layer; the merges then go through the same
//! placement and checks as Coe_shrink's (`layer::merged_layer`), so the cells stay the raw
//! merged cells `topo-cut` cuts, and a merge is kept only if it helps: every unmerged cell
//! around the merged child ends above the cell that asked for it. The layer loop applies the
//! rule from the first layer whose top is half the wall's mean edge off the wall.
//!
//! Off by default: on the step it lifts the grown cells' worst corner (0.087 → 0.333) but
//! merging children several layer heights apart tilts their extrusion edges (table 6) and
//! the tets cut of the merged cells passes 160° (`docs/3d.md`).

use geom_predicates::vector::dist;
use geom_surface::Facet;

use crate::check::cell_sj;
use crate::children::{Ideal, Layer};
use crate::front::Topo;
use crate::layer::{best_free_edge, merged_layer};

/// A squeezed cell merges the children of an edge only where they came closer than this
/// fraction of their parents' distance: where the front shrinks.
const SHRUNK: f64 = 1.0;

/// Adds to `merges` (node-disjoint pairs of front nodes joined by a front edge) the merges
/// of squeezed cells: for each front facet whose cell's smallest corner scaled Jacobian is
/// below `floor` (worst first), the edge of that facet whose children are closest relative
/// to the edge between their parents, when that ratio is below [`SHRUNK`] and neither node merges
/// yet. Returns the added pairs, each with the corner scaled Jacobian of the cell that chose
/// it.
fn add_squeezed(
    topo: &Topo,
    front: &Ideal<'_>,
    facets: &[Facet],
    floor: f64,
    merges: &mut Vec<[u32; 2]>,
) -> Vec<(f64, [u32; 2])> {
    let mut squeezed: Vec<(f64, usize)> = facets
        .iter()
        .enumerate()
        .map(|(f, facet)| {
            (
                cell_sj(front.nodes, facet, |v| front.balanced[v as usize]),
                f,
            )
        })
        .filter(|s| s.0 < floor)
        .collect();
    if squeezed.is_empty() {
        return Vec::new();
    }
    squeezed.sort_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)));
    // a stopped node merges with none
    let mut used: Vec<bool> = (0..front.nodes.len())
        .map(|i| front.is_stopped(i))
        .collect();
    for &[a, b] in merges.iter() {
        used[a as usize] = true;
        used[b as usize] = true;
    }
    let mut added = Vec::new();
    for (q, f) in squeezed {
        let closest = best_free_edge(topo, f, &used, |x, y| {
            dist(front.balanced[x], front.balanced[y]) / dist(front.nodes[x], front.nodes[y])
        });
        if let Some((_, [a, b])) = closest.filter(|c| c.0 < SHRUNK) {
            used[a as usize] = true;
            used[b as usize] = true;
            merges.push([a, b]);
            added.push((q, [a, b]));
        }
    }
    added
}

/// The layer of the balanced children of `front` with `merges` (Coe_shrink's) and the merges
/// of squeezed cells ([`add_squeezed`]), placed and checked by [`merged_layer`]; a squeeze
/// merge is kept only if it helps: every unmerged cell around its merged child keeps a
/// corner scaled Jacobian above that of the cell that chose it (else it is dropped and the
/// layer rebuilt). Without squeezed cells the layer is [`merged_layer`]'s, to the bit.
/// Returns the layer and the merges it was built with.
pub(crate) fn squeezed_layer(
    topo: &Topo,
    front: &Ideal<'_>,
    facets: &[Facet],
    floor: f64,
    coe: Vec<[u32; 2]>,
) -> (Layer, Vec<[u32; 2]>) {
    let mut merges = coe.clone();
    let mut added = add_squeezed(topo, front, facets, floor, &mut merges);
    loop {
        let layer = merged_layer(front, facets, merges.clone());
        if added.is_empty() {
            return (layer, merges);
        }
        // the worst unmerged cell around each child
        let mut worst = vec![f64::INFINITY; layer.children.len()];
        for facet in facets.iter().filter(|f| layer.is_plain(f)) {
            let q = cell_sj(front.nodes, facet, |v| {
                layer.children[layer.child[v as usize] as usize]
            });
            for &v in facet.nodes() {
                let c = layer.child[v as usize] as usize;
                worst[c] = worst[c].min(q);
            }
        }
        let before = added.len();
        added.retain(|&(q, [a, b])| {
            let c = layer.child[a as usize];
            c != layer.child[b as usize] || worst[c as usize] > q
        });
        if added.len() == before {
            return (layer, merges);
        }
        merges = coe
            .iter()
            .copied()
            .chain(added.iter().map(|a| a.1))
            .collect();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Grown3d, LayerParams, grow_layers};
    use geom_surface::Surface;

    /// A block with a square tower on it (90° concave edges round the tower's foot), quads
    /// of 0.1: the proportions of the built-in step, 1 × 1 × 0.5 under 0.4 × 0.4 × 0.5.
    fn tower() -> Surface {
        Surface::voxels(
            [10, 10, 10],
            0.1,
            |[i, j, k]| k < 5 || ((3..7).contains(&i) && (3..7).contains(&j)),
            "tower",
        )
    }

    /// The smallest corner scaled Jacobian of the cells whose tops kept every node, over
    /// the layers `layers`, read off the wall facets' columns.
    fn min_sj(wall: &Surface, grown: &Grown3d, layers: std::ops::Range<usize>) -> f64 {
        let x = &grown.mesh.nodes;
        let at = |v: u32, l: usize| grown.columns[v as usize][l];
        layers
            .flat_map(|k| wall.facets.iter().map(move |f| (k, f)))
            .filter(|(k, f)| {
                let n = f.nodes();
                (0..n.len()).all(|i| at(n[i], k + 1) != at(n[(i + 1) % n.len()], k + 1))
            })
            .map(|(k, f)| {
                let low: Vec<[f64; 3]> = (0..wall.nodes.len() as u32)
                    .map(|v| x[at(v, k) as usize])
                    .collect();
                cell_sj(&low, f, |v| x[at(v, k + 1) as usize])
            })
            .fold(f64::INFINITY, f64::min)
    }

    #[test]
    fn squeezed_cells_at_concave_edges_merge_and_the_worst_corner_rises() {
        let wall = tower();
        let params = |squeeze| LayerParams {
            first_height: 2e-3,
            growth: 1.2,
            layers: 15,
            squeeze,
            ..LayerParams::default()
        };
        let plain = grow_layers(&wall, &params(0.0)).expect("grows");
        let squeezed = grow_layers(&wall, &params(0.5)).expect("grows");
        assert_eq!(plain.stats.merges, 0);
        assert!(squeezed.stats.merges > 0);
        // coverage: every column reaches the last layer, merged or not
        assert!(squeezed.columns.iter().all(|c| c.len() == 16));
        assert!(squeezed.mesh.validate().is_empty());
        let (before, after) = (
            min_sj(&wall, &plain, 10..15),
            min_sj(&wall, &squeezed, 10..15),
        );
        eprintln!("min corner scaled Jacobian, layers 10-14: {before:.3} -> {after:.3}");
        assert!(after > before + 0.1, "{before} -> {after}");
    }

    #[test]
    fn unsqueezed_layers_are_unchanged() {
        // the sphere's cells stay far above the floor: nothing merges, the layers are those
        // grown without the rule, to the bit
        let sphere = Surface::sphere(1.0, 2);
        let params = |squeeze| LayerParams {
            first_height: 0.02,
            growth: 1.2,
            layers: 12,
            squeeze,
            ..LayerParams::default()
        };
        let a = grow_layers(&sphere, &params(0.0)).expect("grows");
        let b = grow_layers(&sphere, &params(0.5)).expect("grows");
        assert_eq!(a.mesh.nodes, b.mesh.nodes);
        assert_eq!(b.stats.merges, 0);
    }
}
