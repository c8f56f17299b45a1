//! Neighbour merging (Coe_shrink, dissertation §5.2.1 step 7 and §5.2.3): which children of
//! front edges merge, the layer they make (a [`Layer`], whose children, parents and new
//! front's facets the `children` module builds), and the checks a merge must pass (the new
//! front stays a closed manifold, every merged cell strictly convex: `check`'s
//! `strictly_convex`).

use geom_predicates::vector::dist;
use geom_surface::Facet;
use mesh_model::NONE;

use crate::check::layer_cell_ok;
use crate::children::{Ideal, Layer};
use crate::front::Topo;
use crate::upright::{Around, upright_place};

/// The pairs of front nodes whose children merge (Coe_shrink): the children of a front edge
/// closer than `coe` times the mean of the two nodes' ideal extrusion lengths `len`, the
/// shortest (relative to that length) first, each node in one pair at most, none with a
/// `stopped` node (empty: none stopped).
///
/// With `rows` (a ratio, [`LayerParams::merge_rows`](crate::LayerParams::merge_rows)), each
/// pair taken is carried across the front's quads: the opposite side of each quad on a taken
/// edge merges too where its ratio is below `rows` and both its nodes are free, and so on
/// along the row of quads. Taken edge by edge, a row of thin quads (the quad wing's trailing
/// edge, 0.00084 × 0.05) pairs its nodes one way at one span station and the other way at
/// the next, and the quad between them keeps one merged side: a triangle of 1° whose prism
/// has a corner scaled Jacobian of 0.016 (`docs/3d.md`). Carried along the row, both sides
/// of each quad merge and it leaves the front as an edge.
pub(crate) fn choose_merges(
    topo: &Topo,
    children: &[[f64; 3]],
    len: &[f64],
    coe: f64,
    rows: Option<f64>,
    stopped: &[bool],
) -> Vec<[u32; 2]> {
    let ratio = |[a, b]: [u32; 2]| {
        let (a, b) = (a as usize, b as usize);
        dist(children[a], children[b]) / ((len[a] + len[b]) / 2.0)
    };
    let mut short: Vec<(f64, u32)> = topo
        .edges
        .iter()
        .enumerate()
        .filter_map(|(i, e)| {
            let r = ratio(e.nodes);
            (r < coe).then_some((r, i as u32))
        })
        .collect();
    short.sort_by(|x, y| {
        let key = |e: u32| topo.edges[e as usize].nodes;
        x.0.total_cmp(&y.0).then(key(x.1).cmp(&key(y.1)))
    });
    // the edges by their sorted nodes, to find a quad's opposite side
    let mut by_nodes: Vec<([u32; 2], u32)> = Vec::new();
    if rows.is_some() {
        by_nodes = topo
            .edges
            .iter()
            .enumerate()
            .map(|(i, e)| {
                let [a, b] = e.nodes;
                ([a.min(b), a.max(b)], i as u32)
            })
            .collect();
        by_nodes.sort_unstable();
    }
    let mut used = free(children.len(), stopped);
    let mut merges = Vec::new();
    let mut stack = Vec::new();
    for (_, e) in short {
        let [a, b] = topo.edges[e as usize].nodes;
        if used[a as usize] || used[b as usize] {
            continue;
        }
        used[a as usize] = true;
        used[b as usize] = true;
        merges.push([a, b]);
        let Some(limit) = rows else { continue };
        stack.push(e);
        while let Some(e) = stack.pop() {
            for [p, q] in topo.edges[e as usize].far {
                // a triangle's far side is its opposite node, twice
                if p == q || used[p as usize] || used[q as usize] || ratio([p, q]) >= limit {
                    continue;
                }
                let Ok(i) = by_nodes.binary_search_by(|x| x.0.cmp(&[p.min(q), p.max(q)])) else {
                    continue;
                };
                used[p as usize] = true;
                used[q as usize] = true;
                merges.push(topo.edges[by_nodes[i].1 as usize].nodes);
                stack.push(by_nodes[i].1);
            }
        }
    }
    merges
}

/// For each of `n` front nodes, whether it is taken for merging already: the `stopped` ones
/// (empty: none).
fn free(n: usize, stopped: &[bool]) -> Vec<bool> {
    (0..n)
        .map(|i| stopped.get(i).copied().unwrap_or(false))
        .collect()
}

/// The edge of front facet `f` with neither node `used` and the smallest `ratio` of its two
/// nodes, with that ratio (ties to the smaller pair).
pub(crate) fn best_free_edge(
    topo: &Topo,
    f: usize,
    used: &[bool],
    ratio: impl Fn(usize, usize) -> f64,
) -> Option<(f64, [u32; 2])> {
    topo.facet_edges[f]
        .iter()
        .filter(|&&e| e != u32::MAX)
        .map(|&e| topo.edges[e as usize].nodes)
        .filter(|e| !used[e[0] as usize] && !used[e[1] as usize])
        .map(|[a, b]| (ratio(a as usize, b as usize), [a, b]))
        .min_by(|x, y| x.0.total_cmp(&y.0).then(x.1.cmp(&y.1)))
}

/// Adds to `merges` (the pairs of [`choose_merges`]) the second trigger of §5.2.1: for each
/// cell over `bad` (front facets whose cells fail their check), the children of its
/// shortest edge relative to the mean ideal extrusion length, when that is below
/// `ratio` and neither node merges yet nor is `stopped` (empty: none).
pub(crate) fn add_twisted(
    topo: &Topo,
    children: &[[f64; 3]],
    len: &[f64],
    (bad, stopped): (&[usize], &[bool]),
    ratio: f64,
    merges: &mut Vec<[u32; 2]>,
) {
    let mut used = free(children.len(), stopped);
    for &[a, b] in merges.iter() {
        used[a as usize] = true;
        used[b as usize] = true;
    }
    for &f in bad {
        let shortest = best_free_edge(topo, f, &used, |x, y| {
            dist(children[x], children[y]) / ((len[x] + len[y]) / 2.0)
        });
        if let Some((_, [a, b])) = shortest.filter(|s| s.0 < ratio) {
            used[a as usize] = true;
            used[b as usize] = true;
            merges.push([a, b]);
        }
    }
}

/// The merged children that break the new front's topology: on a new facet that repeats a
/// node or another facet, or at an end of a new front edge not in exactly two facets
/// running opposite ways.
pub(crate) fn tangled_children(layer: &Layer) -> Vec<u32> {
    let merged = |c: &u32| layer.parents[*c as usize][1] != NONE;
    let mut bad: Vec<u32> = Vec::new();
    let mut keys: Vec<([u32; 4], u32)> = Vec::with_capacity(layer.top.len());
    for (t, f) in layer.top.iter().enumerate() {
        let mut key = f.0;
        key.sort_unstable();
        if key
            .windows(2)
            .any(|w| w[0] == w[1] && w[0] != geom_surface::NO_NODE)
        {
            bad.extend(f.nodes().iter().filter(|c| merged(c)));
        }
        keys.push((key, t as u32));
    }
    keys.sort_unstable();
    for w in keys.windows(2).filter(|w| w[0].0 == w[1].0) {
        bad.extend(
            layer.top[w[0].1 as usize]
                .nodes()
                .iter()
                .filter(|c| merged(c)),
        );
    }
    // (low, high, forward)
    let mut sides: Vec<(u32, u32, bool)> = Vec::new();
    for f in &layer.top {
        let k = f.nodes();
        for i in 0..k.len() {
            let (a, b) = (k[i], k[(i + 1) % k.len()]);
            sides.push((a.min(b), a.max(b), a < b));
        }
    }
    sides.sort_unstable();
    for group in sides.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
        if group.len() != 2 || group[0].2 == group[1].2 {
            bad.extend([group[0].0, group[0].1].iter().filter(|c| merged(c)));
        }
    }
    bad.sort_unstable();
    bad.dedup();
    bad
}

/// Places every merged child of `layer` where the merged cells around it are strictly
/// convex and the most cells around it pass their check ([`layer_cell_ok`]), trying the
/// middle of the two balanced children, either balanced child, and the ideal merged place
/// ([`Ideal::merged_child`]), the first of the best. Returns the merged children placed
/// nowhere.
fn place_merged(
    front: &Ideal<'_>,
    normals: &[[f64; 3]],
    facets: &[Facet],
    unmerged_ok: &[bool],
    layer: &mut Layer,
) -> Vec<u32> {
    let mut around: Vec<Vec<u32>> = vec![Vec::new(); layer.children.len()];
    for (f, facet) in facets.iter().enumerate() {
        for &v in facet.nodes() {
            let c = layer.child[v as usize] as usize;
            if layer.parents[c][1] != NONE && around[c].last() != Some(&(f as u32)) {
                around[c].push(f as u32);
            }
        }
    }
    let mut bad = Vec::new();
    for (c, around) in around.iter().enumerate() {
        let [a, b] = layer.parents[c].map(|v| v as usize);
        if b == NONE as usize {
            continue;
        }
        let tries = [
            layer.children[c],
            front.balanced[a],
            front.balanced[b],
            front.merged_child(a, b),
        ];
        // (cells around it that pass, whether every merged one and every one that passed
        // without merges does)
        let fits = |layer: &Layer| {
            let mut ok = 0;
            let mut needed_ok = true;
            for &f in around {
                let facet = &facets[f as usize];
                let pass = layer_cell_ok(front.nodes, layer, facet);
                ok += usize::from(pass);
                let needed = !layer.is_plain(facet) || unmerged_ok[f as usize];
                needed_ok &= pass || !needed;
            }
            (needed_ok, ok)
        };
        let mut best: Option<(usize, [f64; 3])> = None;
        for p in tries {
            layer.children[c] = p;
            let (merged_ok, ok) = fits(layer);
            if merged_ok && best.is_none_or(|b| ok > b.0) {
                best = Some((ok, p));
            }
        }
        match best {
            Some((ok, p)) => {
                layer.children[c] = p;
                let cells = Around {
                    facets,
                    cells: around,
                };
                if let Some(q) = upright_place(front, normals, cells, c, ok, fits, layer) {
                    layer.children[c] = q;
                }
            }
            None => bad.push(c as u32),
        }
    }
    bad
}

/// The layer of the balanced children with as many of `merges` as keep the front's
/// topology ([`tangled_children`]) and can be placed ([`place_merged`]): the merges of bad
/// children are dropped until none is bad.
pub(crate) fn merged_layer(
    front: &Ideal<'_>,
    facets: &[Facet],
    mut merges: Vec<[u32; 2]>,
) -> Layer {
    let mut unmerged_ok: Vec<bool> = Vec::new();
    let mut normals: Vec<[f64; 3]> = Vec::new();
    loop {
        let mut layer = Layer::new(front, facets, &merges);
        if merges.is_empty() {
            return layer;
        }
        let mut bad = tangled_children(&layer);
        if bad.is_empty() {
            if unmerged_ok.is_empty() {
                let plain = Layer::new(front, facets, &[]);
                unmerged_ok = facets
                    .iter()
                    .map(|f| layer_cell_ok(front.nodes, &plain, f))
                    .collect();
                normals = geom_surface::node_normals(front.nodes, facets);
            }
            bad = place_merged(front, &normals, facets, &unmerged_ok, &mut layer);
            if bad.is_empty() {
                return layer;
            }
        }
        merges.retain(|&[a, _]| bad.binary_search(&layer.child[a as usize]).is_err());
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::strictly_convex;

    #[test]
    fn a_merged_edge_makes_its_quad_a_triangle_and_its_triangle_an_edge() {
        // a unit quad 0 1 2 3 and a triangle 1 4 2 on its edge 1-2, grown by 1 along z
        let nodes = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.5, 0.0],
        ];
        let balanced: Vec<[f64; 3]> = nodes.iter().map(|p| [p[0], p[1], 1.0]).collect();
        let facets = [Facet::quad(0, 1, 2, 3), Facet::tri(1, 4, 2)];
        let ideal = Ideal {
            nodes: &nodes,
            dir: &[[0.0, 0.0, 1.0]; 5],
            len: &[1.0; 5],
            balanced: &balanced,
            stopped: &[],
            fan: None,
        };
        let mut layer = Layer::new(&ideal, &facets, &[[1, 2]]);
        assert_eq!(layer.child, vec![0, 1, 1, 2, 3]);
        assert_eq!(layer.parents[1], [1, 2]);
        assert_eq!(layer.children[1], [1.0, 0.5, 1.0]);
        // the triangle's top collapsed to an edge and left the front
        assert_eq!(layer.top, vec![Facet::tri(0, 1, 2)]);
        assert_eq!(layer.top_of, vec![0]);
        assert!(facets.iter().all(|f| layer.is_merged(f)));
        // the cell under the triangle: its bottom and three sides, one a triangle
        let faces = layer.cell_faces(&facets[1]);
        assert_eq!(faces.len(), 4);
        assert_eq!(faces[3], vec![2, 1, 6]);
        let convex = |layer: &Layer, f: &Facet| {
            let pos = |v: u32| {
                if v < 5 {
                    nodes[v as usize]
                } else {
                    layer.children[v as usize - 5]
                }
            };
            strictly_convex(&layer.cell_faces(f), pos)
        };
        assert!(convex(&layer, &facets[0]));
        // the merged child pushed below the front folds the cells
        layer.children[1] = [1.0, 0.5, -0.5];
        assert!(!convex(&layer, &facets[0]));
    }

    /// A row of thin quads (three nodes across, 1 apart, four stations 10 apart) whose
    /// short sides' lengths alternate from station to station: taken edge by edge, the
    /// stations pair their nodes alternately one way and the other, so every quad keeps
    /// one merged side (a 6° triangle); carried along the row, each quad merges both sides
    /// or neither, the same pair at every station.
    #[test]
    fn merges_carried_along_a_row_of_thin_quads_pair_every_station_alike() {
        let middle = [0.99, 1.01, 0.995, 1.005];
        let nodes: Vec<[f64; 3]> = (0..4)
            .flat_map(|j| [0.0, middle[j], 2.0].map(|x| [x, 0.0, 10.0 * j as f64]))
            .collect();
        let facets: Vec<Facet> = (0..3u32)
            .flat_map(|j| (0..2u32).map(move |i| (j, i)))
            .map(|(j, i)| Facet::quad(3 * j + i, 3 * j + i + 1, 3 * j + i + 4, 3 * j + i + 3))
            .collect();
        let topo = Topo::from_facets(&facets);
        let len = vec![2.0; nodes.len()];
        let one_side_merged = |merges: &[[u32; 2]]| {
            let merged = |a: u32, b: u32| merges.iter().any(|m| m == &[a, b] || m == &[b, a]);
            facets.iter().any(|f| {
                let k = f.nodes();
                merged(k[0], k[1]) != merged(k[3], k[2])
            })
        };
        let plain = choose_merges(&topo, &nodes, &len, 0.65, None, &[]);
        assert_eq!(plain.len(), 4);
        assert!(one_side_merged(&plain), "{plain:?}");
        let rows = choose_merges(&topo, &nodes, &len, 0.65, Some(1.0), &[]);
        assert_eq!(rows.len(), 4);
        assert!(!one_side_merged(&rows), "{rows:?}");
        // the shortest pair (station 0, nodes 0-1) seeds the row
        assert!(rows.iter().all(|m| m[0] % 3 + m[1] % 3 == 1), "{rows:?}");
        // a row stops where the opposite side is not short enough
        let far = choose_merges(&topo, &nodes, &len, 0.65, Some(0.5), &[]);
        assert_eq!(far, plain);
    }

    #[test]
    fn a_merge_that_joins_two_facets_into_one_is_refused() {
        // a tetrahedron's surface: merging any edge leaves two triangles on the same nodes
        let nodes = [
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [0.0, 0.0, 1.0],
        ];
        let facets = [
            Facet::tri(0, 2, 1),
            Facet::tri(0, 1, 3),
            Facet::tri(1, 2, 3),
            Facet::tri(0, 3, 2),
        ];
        let ideal = Ideal {
            nodes: &nodes,
            dir: &[[0.0, 0.0, 1.0]; 4],
            len: &[1.0; 4],
            balanced: &nodes,
            stopped: &[],
            fan: None,
        };
        let layer = Layer::new(&ideal, &facets, &[[0, 1]]);
        assert_eq!(tangled_children(&layer), vec![0]);
        assert_eq!(
            merged_layer(&ideal, &facets, vec![[0, 1]]).children.len(),
            4
        );
    }
}
