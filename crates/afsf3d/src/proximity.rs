//! Fronts that stop before they meet (issue 46, item 3): before a layer grows, a column whose
//! front node faces another part of the front — another body's, or its own body's across a
//! gap or cavity — nearer than [`crate::LayerParams::stop_gap`] × the layer's height stops, so
//! the fronts keep a gap a volume fill can mesh instead of growing until they cross.
//!
//! Candidates come from a k-d tree of the front's nodes (`geom_predicates::PointTree`). Two
//! nodes face each other when each lies ahead of the other's direction (within 60° of it for
//! the node that stops, in its half-space for the other). Nodes of one front near each other
//! along it (the two sides of a concave edge, whose layers merge) are told apart from nodes
//! across a gap by their distance along the front: a pair is across a gap when the front's
//! edges join them by no path shorter than [`DETOUR`] × their distance.

use std::collections::{BinaryHeap, HashMap};

use geom_predicates::PointTree;
use geom_predicates::vector::{dist, dot, sub};

use crate::front::Topo;
use crate::stop::Reach;

/// A pair of front nodes is across a gap when the front joins them by no path shorter than
/// this × their distance (the two sides of a 90° concave edge: at most √2).
pub(crate) const DETOUR: f64 = 3.0;

/// The cosine of the widest angle between a node's direction and the way to a node across a
/// gap that stops it: 60°.
const AHEAD_COS: f64 = 0.5;

/// Which front nodes (positions `x`, edges `topo`, directions `dir`) face another part of the
/// front nearer than `reach`; nodes already `stopped` are not asked (but stop others).
/// `spacing`: a node's reach is at least this × the mean length of its front edges, so the gap
/// kept is no thinner than a fraction of the front's spacing there (a fill's cells across it
/// then stay thicker than the curving's bulge of their faces).
pub(crate) fn facing_fronts(
    topo: &Topo,
    x: &[[f64; 3]],
    dir: &[[f64; 3]],
    stopped: &[bool],
    (reach, spacing): (f64, f64),
) -> Vec<bool> {
    let n = x.len();
    let mut near = vec![false; n];
    if reach <= 0.0 || n == 0 {
        return near;
    }
    let tree = PointTree::new(x);
    let adjacency = adjacency(topo, x, n);
    for v in 0..n {
        if stopped[v] {
            continue;
        }
        let mean_edge =
            adjacency[v].iter().map(|e| e.1).sum::<f64>() / adjacency[v].len().max(1) as f64;
        let reach = reach.max(spacing * mean_edge);
        let facing: Vec<usize> = tree
            .within(x[v], reach)
            .into_iter()
            .filter(|&(u, d)| u != v && d > 0.0 && faces(x, dir, v, u, d))
            .map(|(u, _)| u)
            .collect();
        if facing.is_empty() {
            continue;
        }
        // the front's own distances from v, as far as DETOUR × the farthest candidate needs
        let limit = DETOUR * reach;
        let along = front_distances(&adjacency, v, limit);
        near[v] = facing.iter().any(|&u| {
            let d = dist(x[v], x[u]);
            along.get(&(u as u32)).is_none_or(|&a| a > DETOUR * d)
        });
    }
    near
}

/// Whether `u` (at distance `d` from `v`) lies ahead of `v` within 60° of its direction, and
/// `v` ahead of `u` (in the half-space its direction points into).
fn faces(x: &[[f64; 3]], dir: &[[f64; 3]], v: usize, u: usize, d: f64) -> bool {
    let vu = sub(x[u], x[v]);
    dot(dir[v], vu) > AHEAD_COS * d && dot(dir[u], vu) < 0.0
}

/// Each node's neighbours along the front's edges with the edges' lengths.
fn adjacency(topo: &Topo, x: &[[f64; 3]], n: usize) -> Vec<Vec<(u32, f64)>> {
    let mut adj = vec![Vec::new(); n];
    for e in &topo.edges {
        let [a, b] = e.nodes;
        let l = dist(x[a as usize], x[b as usize]);
        adj[a as usize].push((b, l));
        adj[b as usize].push((a, l));
    }
    adj
}

/// The distances along the front's edges from `from` to every node within `limit` of it
/// (Dijkstra, stopped at `limit`).
fn front_distances(adj: &[Vec<(u32, f64)>], from: usize, limit: f64) -> HashMap<u32, f64> {
    let mut best: HashMap<u32, f64> = HashMap::new();
    let mut heap = BinaryHeap::new();
    best.insert(from as u32, 0.0);
    heap.push(Reach(0.0, from as u32));
    while let Some(Reach(d, v)) = heap.pop() {
        if best.get(&v).is_some_and(|&b| d > b) {
            continue;
        }
        for &(u, l) in &adj[v as usize] {
            let du = d + l;
            if du <= limit && best.get(&u).is_none_or(|&b| du < b) {
                best.insert(u, du);
                heap.push(Reach(du, u));
            }
        }
    }
    best
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom_surface::Surface;

    /// Two spheres 0.1 apart: the nodes facing across the gap stop, the rest do not; one
    /// sphere alone stops nothing.
    #[test]
    fn nodes_facing_across_a_gap_stop() {
        let mut a = Surface::sphere(0.5, 2);
        let b = Surface::sphere(0.5, 2);
        let n = a.nodes.len() as u32;
        for p in &mut a.nodes {
            p[0] -= 0.55;
        }
        a.nodes
            .extend(b.nodes.iter().map(|p| [p[0] + 0.55, p[1], p[2]]));
        a.facets.extend(
            b.facets
                .iter()
                .map(|f| geom_surface::Facet(f.0.map(|v| v.saturating_add(n)))),
        );
        a.facet_patch.extend(b.facet_patch.iter());
        let topo = Topo::new(&a);
        let normals = a.node_normals();
        let stopped = vec![false; a.nodes.len()];
        let near = facing_fronts(&topo, &a.nodes, &normals, &stopped, (0.2, 0.0));
        let count = near.iter().filter(|&&s| s).count();
        assert!(count >= 2, "{count}");
        for (v, &s) in near.iter().enumerate() {
            if s {
                // only nodes in the gap, facing the other sphere
                assert!(a.nodes[v][0].abs() < 0.2, "{:?}", a.nodes[v]);
            }
        }
        let one = Surface::sphere(0.5, 2);
        let near = facing_fronts(
            &Topo::new(&one),
            &one.nodes,
            &one.node_normals(),
            &vec![false; one.nodes.len()],
            (0.4, 0.0),
        );
        assert!(!near.contains(&true));
    }

    /// The step's concave edges: the floor's and the tower's nodes face each other across the
    /// edge, but the front joins them by a short path, so nothing stops.
    #[test]
    fn a_concave_edge_is_not_a_gap() {
        let s = Surface::step(1);
        let near = facing_fronts(
            &Topo::new(&s),
            &s.nodes,
            &s.node_normals(),
            &vec![false; s.nodes.len()],
            (0.3, 0.0),
        );
        assert!(!near.contains(&true));
    }
}
