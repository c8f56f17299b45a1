//! Where a merged child stands when its first place leans it (issue 13, table 6): a child
//! merged from the children of front nodes `a` and `b` grows from both, so its two extrusion
//! edges lean off their parents' normals; over the middle of the two parents they lean by
//! only atan(D / 2h) (D the parents' distance, h the step), but the first place
//! `layer::place_merged` chooses (most often the middle of the two balanced children) leans
//! by 30°–45° where the balance drove the children along the front. Where it leans over
//! table 6's 30°, places between it and two upright ones (over the parents' middle at the
//! mean ideal step, and at the first place's own height) are tried; among those leaning less
//! where as many cells around the child pass their check, every merged cell and every cell
//! valid without merges among them, and where every cell around keeps a cone cut
//! ([`best_cone_cut`](crate::repair::best_cone_cut), the cut `topo-cut` can choose for a cell alone) under the repair's
//! [`CUT_LIMIT`] (140°), the one leaning least (any within 30° alike) with the best such
//! cut is kept. The bound keeps the cut (table 7): upright places chosen on their lean alone
//! pushed the wing's tetrahedra to 164.6°, and a bound relative to the first place's cut
//! (when that was over 140°) left cells the repair no longer mends (an upright child may
//! only lean 20° there). Children leaning 30° or less are left to the bit.

use geom_predicates::vector::sub;
use geom_surface::{Facet, unit};
use mesh_model::measure3d::angle_deg;

use crate::children::{Ideal, Layer};
use crate::repair::{CUT_LIMIT, cell_cut};

/// Table 6's last bin: a merged child leaning this much or less off its parents' normals
/// stays where it is.
const MAX_TILT_DEG: f64 = 30.0;

/// The fractions of the way from the first place to each upright one tried.
const BLENDS: [f64; 4] = [0.25, 0.5, 0.75, 1.0];

/// How far (degrees) a child at `p` merged from front nodes `a` and `b` leans: the larger
/// angle between its extrusion edge from each parent and that parent's normal.
pub(crate) fn tilt_deg(
    nodes: &[[f64; 3]],
    normals: &[[f64; 3]],
    [a, b]: [usize; 2],
    p: [f64; 3],
) -> f64 {
    angle_deg(sub(p, nodes[a]), normals[a]).max(angle_deg(sub(p, nodes[b]), normals[b]))
}

/// The worst best cone cut ([`best_cone_cut`](crate::repair::best_cone_cut)) of the cells of `layer` over `around`.
fn worst_cut(nodes: &[[f64; 3]], facets: &[Facet], around: &[u32], layer: &Layer) -> f64 {
    around
        .iter()
        .map(|&f| cell_cut(nodes, layer, &facets[f as usize], 0.0))
        .fold(0.0, f64::max)
}

/// The places tried for the child merged from `a` and `b` first placed at `first`: blends
/// from it to the ideal merged place and to the place over the parents' middle at its own
/// height along their mean normal.
fn candidates(
    front: &Ideal<'_>,
    normals: &[[f64; 3]],
    [a, b]: [usize; 2],
    first: [f64; 3],
) -> Vec<[f64; 3]> {
    let (p, q) = (front.nodes[a], front.nodes[b]);
    let mid: [f64; 3] = std::array::from_fn(|d| (p[d] + q[d]) / 2.0);
    let n = unit(std::array::from_fn(|d| normals[a][d] + normals[b][d]));
    let h = geom_predicates::vector::dot(sub(first, mid), n);
    let mut targets = vec![front.merged_child(a, b)];
    if h > 0.0 {
        targets.push(std::array::from_fn(|d| mid[d] + h * n[d]));
    }
    targets
        .iter()
        .flat_map(|t| {
            BLENDS
                .iter()
                .map(move |&s| std::array::from_fn(|d| first[d] + s * (t[d] - first[d])))
        })
        .collect()
}

/// The front facets whose cells hold a merged child.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Around<'a> {
    /// The front's facets.
    pub facets: &'a [Facet],
    /// The facets (indices into `facets`) whose cells hold the child.
    pub cells: &'a [u32],
}

/// A better place for merged child `c` of `layer` (parents `a`, `b`, placed first where
/// `ok` of the cells `around` pass; `fits` tells for the layer as it stands whether
/// every cell that must pass does, and how many pass), or `None` to keep the first place
/// (see the module's doc). Leaves `layer.children[c]` at the first place.
pub(crate) fn upright_place(
    front: &Ideal<'_>,
    normals: &[[f64; 3]],
    around: Around<'_>,
    c: usize,
    ok: usize,
    fits: impl Fn(&Layer) -> (bool, usize),
    layer: &mut Layer,
) -> Option<[f64; 3]> {
    let parents = layer.parents[c].map(|v| v as usize);
    let first = layer.children[c];
    let tilt = tilt_deg(front.nodes, normals, parents, first);
    if tilt <= MAX_TILT_DEG {
        return None;
    }
    // (the tilt above table 6's bin, the worst best cut, the place)
    let mut best: Option<(f64, f64, [f64; 3])> = None;
    for p in candidates(front, normals, parents, first) {
        let t = tilt_deg(front.nodes, normals, parents, p);
        if t >= tilt {
            continue;
        }
        layer.children[c] = p;
        let (needed, passing) = fits(layer);
        if !needed || passing < ok {
            continue;
        }
        let cut = worst_cut(front.nodes, around.facets, around.cells, layer);
        if cut > CUT_LIMIT {
            continue;
        }
        let key = (t.max(MAX_TILT_DEG), cut);
        if best.is_none_or(|b| key < (b.0, b.1)) {
            best = Some((key.0, key.1, p));
        }
    }
    layer.children[c] = first;
    best.map(|b| b.2)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::layer_cell_ok;
    use crate::layer::merged_layer;

    /// A flat front of six triangles around the short edge 0-1 (0.2 long), grown by 0.25
    /// along z, the children of 0 and 1 driven 0.2 across it along the front by the balance.
    fn drifted() -> (Vec<[f64; 3]>, Vec<Facet>, Vec<[f64; 3]>) {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [0.2, 0.0, 0.0],
            [0.1, 0.8, 0.0],
            [0.1, -0.8, 0.0],
            [-0.8, 0.0, 0.0],
            [1.0, 0.0, 0.0],
        ];
        let facets = vec![
            Facet::tri(0, 1, 2),
            Facet::tri(1, 0, 3),
            Facet::tri(0, 2, 4),
            Facet::tri(0, 4, 3),
            Facet::tri(1, 5, 2),
            Facet::tri(1, 3, 5),
        ];
        let balanced = nodes
            .iter()
            .enumerate()
            .map(|(i, p)| {
                let drift = if i < 2 { 0.2 } else { 0.0 };
                [p[0], p[1] + drift, 0.25]
            })
            .collect();
        (nodes, facets, balanced)
    }

    #[test]
    fn a_merged_child_tilted_over_30_degrees_stands_upright_when_its_cells_cut_as_well() {
        let (nodes, facets, balanced) = drifted();
        let ideal = Ideal {
            nodes: &nodes,
            dir: &[[0.0, 0.0, 1.0]; 6],
            len: &[0.25; 6],
            balanced: &balanced,
            stopped: &[],
            fan: None,
        };
        let normals = geom_surface::node_normals(&nodes, &facets);
        let around: Vec<u32> = (0..6).collect();
        // the first place, the middle of the two balanced children, leans by 41.8°
        let mut first = Layer::new(&ideal, &facets, &[[0, 1]]);
        assert_eq!(first.parents[0], [0, 1]);
        let tilt = tilt_deg(&nodes, &normals, [0, 1], first.children[0]);
        assert!(tilt > 41.0, "{tilt}");
        assert!(facets.iter().all(|f| layer_cell_ok(&nodes, &first, f)));
        let first_cut = worst_cut(&nodes, &facets, &around, &first);

        let layer = merged_layer(&ideal, &facets, vec![[0, 1]]);
        assert_eq!(layer.parents[0], [0, 1]);
        let tilt = tilt_deg(&nodes, &normals, [0, 1], layer.children[0]);
        assert!(tilt <= MAX_TILT_DEG, "{tilt}");
        assert!(facets.iter().all(|f| layer_cell_ok(&nodes, &layer, f)));
        let cut = worst_cut(&nodes, &facets, &around, &layer);
        assert!(cut <= CUT_LIMIT, "{cut} {first_cut}");
        // a child within 30° stays where it was placed
        first.children = layer.children.clone();
        let fits = |_: &Layer| (true, 6);
        let cells = Around {
            facets: &facets,
            cells: &around,
        };
        let again = upright_place(&ideal, &normals, cells, 0, 6, fits, &mut first);
        assert_eq!(again, None);
    }
}
