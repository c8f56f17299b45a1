//! The front's fixed topology (its unique edges with their two facets) and each front node's
//! ideal step (direction and length).

use geom_surface::{Facet, Surface, fan_normal, unit};

/// One unique front edge.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Edge {
    /// Its nodes, in the direction of its first facet.
    pub nodes: [u32; 2],
    /// The far side of each of its facets (see [`far_side`]), first facet first.
    pub far: [[u32; 2]; 2],
}

/// The edges of a closed surface and, for each facet, the edge of each of its sides.
#[derive(Debug, Clone)]
pub(crate) struct Topo {
    pub edges: Vec<Edge>,
    /// For facet f and its side i (nodes i → i+1): the edge's index.
    pub facet_edges: Vec<[u32; 4]>,
}

/// The far side of facet `f` from its side `i`: the opposite node (twice) of a triangle, the
/// opposite side of a quad.
fn far_side(f: &Facet, i: usize) -> [u32; 2] {
    let k = f.nodes();
    if k.len() == 3 {
        [k[(i + 2) % 3]; 2]
    } else {
        [k[(i + 2) % 4], k[(i + 3) % 4]]
    }
}

impl Topo {
    /// The topology of a checked (closed, manifold) surface.
    pub fn new(surface: &Surface) -> Topo {
        Topo::from_facets(&surface.facets)
    }

    /// The topology of the facets of a closed, manifold surface.
    pub fn from_facets(facets: &[Facet]) -> Topo {
        // (low, high, facet, side)
        let mut sides: Vec<(u32, u32, u32, u8)> = Vec::new();
        for (f, facet) in facets.iter().enumerate() {
            let k = facet.nodes();
            for i in 0..k.len() {
                let (a, b) = (k[i], k[(i + 1) % k.len()]);
                sides.push((a.min(b), a.max(b), f as u32, i as u8));
            }
        }
        sides.sort_unstable();
        let mut edges = Vec::with_capacity(sides.len() / 2);
        let mut facet_edges = vec![[u32::MAX; 4]; facets.len()];
        for pair in sides.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let id = edges.len() as u32;
            let (f, i) = (pair[0].2 as usize, pair[0].3 as usize);
            let k = facets[f].nodes();
            let mut far = [[0; 2]; 2];
            for (slot, s) in pair.iter().take(2).enumerate() {
                far[slot] = far_side(&facets[s.2 as usize], s.3 as usize);
                facet_edges[s.2 as usize][s.3 as usize] = id;
            }
            edges.push(Edge {
                nodes: [k[i], k[(i + 1) % k.len()]],
                far,
            });
        }
        Topo { edges, facet_edges }
    }

    /// The longest front edge at each node.
    pub fn longest_edge(&self, x: &[[f64; 3]]) -> Vec<f64> {
        let mut l = vec![0.0f64; x.len()];
        for e in &self.edges {
            let [a, b] = e.nodes.map(|v| v as usize);
            let d = geom_predicates::vector::dist(x[a], x[b]);
            l[a] = l[a].max(d);
            l[b] = l[b].max(d);
        }
        l
    }
}

/// Each front node's ideal direction and ideal length.
///
/// The direction is the angle-weighted normal of the node's facets; near concave nodes (a
/// node whose neighbours lie on average above its tangent plane, and the nodes next to it)
/// it is then `smoothing` times replaced by the normalised sum of its own and its
/// neighbours' directions, which fans the directions out of concave edges so the front
/// spreads there instead of folding; elsewhere (convex edges and corners) it stays the
/// normal. The length is `height`, divided at a concave node by the smallest cosine between
/// its direction and its facets' normals (at most 2), so that the child stands `height` off
/// each facet there.
pub(crate) fn ideal_steps(
    front: &Surface,
    topo: &Topo,
    height: f64,
    smoothing: usize,
) -> (Vec<[f64; 3]>, Vec<f64>) {
    let mut dir = front.node_normals();
    let n = front.nodes.len();
    let mut rise = vec![0.0f64; n];
    for e in &topo.edges {
        let [a, b] = e.nodes.map(|v| v as usize);
        let d = geom_predicates::vector::sub(front.nodes[b], front.nodes[a]);
        rise[a] += geom_predicates::vector::dot(d, dir[a]);
        rise[b] -= geom_predicates::vector::dot(d, dir[b]);
    }
    let mut near = vec![false; n];
    for e in &topo.edges {
        let [a, b] = e.nodes.map(|v| v as usize);
        if rise[a] > 0.0 || rise[b] > 0.0 {
            near[a] = true;
            near[b] = true;
        }
    }
    for _ in 0..smoothing {
        let mut sum = dir.clone();
        for e in &topo.edges {
            let [a, b] = e.nodes.map(|v| v as usize);
            (0..3).for_each(|d| {
                sum[a][d] += dir[b][d];
                sum[b][d] += dir[a][d];
            });
        }
        for i in (0..n).filter(|&i| near[i]) {
            dir[i] = unit(sum[i]);
        }
    }
    let mut min_cos = vec![1.0f64; n];
    for f in &front.facets {
        let normal = unit(fan_normal(&front.nodes, f.nodes()));
        for &v in f.nodes() {
            let c = geom_predicates::vector::dot(normal, dir[v as usize]);
            min_cos[v as usize] = min_cos[v as usize].min(c);
        }
    }
    let len = (0..n)
        .map(|i| {
            if rise[i] > 0.0 {
                height / min_cos[i].max(0.5)
            } else {
                height
            }
        })
        .collect();
    (dir, len)
}
