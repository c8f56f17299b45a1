//! Fans at sharp convex edges (the 3D form of `afsf2d`'s fan at a sharp corner, dissertation
//! §3.2): along a wing's sharp trailing edge one column per wall node must point along the
//! bisector of the upper and lower surfaces, nearly along both, so the first cells on either
//! side taper to nothing at the edge and every cut of them has tetrahedra near 180°. Instead,
//! each node of a chain of sharp edges grows `K + 1` columns: copy 0 along the normal of one
//! side, copy `K` along the other's, the ones between turned evenly around the edge.
//!
//! The fan is made on the wall before the first layer, by topology alone: each fanned node
//! becomes `K + 1` nodes at its place (copy 0 is the node itself; the facets on the other
//! side of its chain use copy `K`), and each edge of a chain is opened into `K` zero-area
//! facets (quadrilaterals between copies `j` and `j + 1` of its two ends; triangles where one
//! end is not fanned). The fanned wall is a closed manifold by its indices, so the first
//! layer is grown over it as over any front — one child per node — except that the copies'
//! children stand at their fan directions (not balanced), the cells over the zero-area facets
//! are the fan's prisms lying on their side (checked strictly convex, their copies
//! identified), and the zero-area facets have no bottom face. From the second layer on the
//! fan is ordinary front: thin quadrilaterals around the edge.
//!
//! A node is fanned when exactly two of its edges are sharp: convex, their facets' normals
//! more than [`crate::LayerParams::fan_threshold_deg`] apart. The end of a chain (a node with
//! one sharp edge, the corner where a trailing edge meets a wing's flat tip) counts its rim
//! edge as a second one (`rim_edges`: its convex edge that turns most, over 45°, whose far end
//! lies on the rim), so its fan turns from one side over the tip to the other, the rim edge
//! opened like a chain's; a chain's end without such a rim and a node where three or more
//! sharp edges meet keep one column, the fan's last facets before it triangles.

use std::collections::HashMap;

use geom_surface::{Facet, Surface, angle_between, fan_normal, unit};
use mesh_model::NONE;

use crate::children::FanTopo;
use crate::front::Topo;

/// A wall with its fans (see the module's doc).
#[derive(Debug, Clone)]
pub(crate) struct Fanned {
    /// The surface's nodes, then the copies; its facets (the corners on the far side of a chain
    /// renumbered to the last copy), then the fans' zero-area facets, with their patches.
    pub wall: Surface,
    /// For each node of `wall`, the surface node at its place (itself for the surface's), and
    /// the edges from a chain's unfanned end to its fanned neighbour's copies.
    pub fan: FanTopo,
    /// For each node of `wall`: `Some` its first layer's direction when it is a fanned node or
    /// one of its copies, else `None`.
    pub dir: Vec<Option<[f64; 3]>>,
    /// For each facet of `wall`, the surface facet whose pipe its cells join (itself for the
    /// surface's; a fan facet joins the facet on the side of its chain edge's copy 0).
    pub pipe: Vec<u32>,
    /// The number of surface facets: the facets after them are the fans'.
    pub real_facets: usize,
}

impl Fanned {
    /// The wall without fans.
    fn plain(surface: &Surface) -> Fanned {
        let n = surface.nodes.len();
        Fanned {
            wall: surface.clone(),
            fan: FanTopo {
                origin: (0..n as u32).collect(),
                apex_edges: Vec::new(),
            },
            dir: vec![None; n],
            pipe: (0..surface.facets.len() as u32).collect(),
            real_facets: surface.facets.len(),
        }
    }

    /// The number of fanned surface nodes.
    pub fn fanned_nodes(&self) -> usize {
        (0..self.dir.len())
            .filter(|&v| self.fan.origin[v] as usize == v && self.dir[v].is_some())
            .count()
    }

    /// Whether wall node `v` is a fanned node or one of its copies.
    pub fn is_fanned(&self, v: usize) -> bool {
        self.dir[v].is_some()
    }
}

/// For each edge of `topo` (over `surface`), how far (radians) its two facets' normals turn
/// when it is convex, 0 when it is not: an edge is sharp when it turns by more than
/// [`crate::LayerParams::fan_threshold_deg`], a rim's when by more than [`RIM_TURN`].
fn convex_turns(surface: &Surface, topo: &Topo) -> Vec<f64> {
    let normals: Vec<[f64; 3]> = surface
        .facets
        .iter()
        .map(|f| unit(fan_normal(&surface.nodes, f.nodes())))
        .collect();
    topo.edges
        .iter()
        .map(|e| {
            let [nf, ng] = e.facets.map(|f| normals[f as usize]);
            // convex: the far side of the second facet lies below the first's plane
            let a = surface.nodes[e.nodes[0] as usize];
            let far = surface.nodes[e.far[1][0] as usize];
            let below =
                geom_predicates::vector::dot(nf, geom_predicates::vector::sub(far, a)) < 0.0;
            if below { angle_between(nf, ng) } else { 0.0 }
        })
        .collect()
}

/// The facets around each node (CSR: `start[v]..start[v + 1]` into `list`).
fn facets_around(surface: &Surface) -> (Vec<usize>, Vec<u32>) {
    let n = surface.nodes.len();
    let mut start = vec![0usize; n + 1];
    for f in &surface.facets {
        f.nodes().iter().for_each(|&v| start[v as usize + 1] += 1);
    }
    for v in 0..n {
        start[v + 1] += start[v];
    }
    let mut next = start.clone();
    let mut list = vec![0u32; start[n]];
    for (i, f) in surface.facets.iter().enumerate() {
        for &v in f.nodes() {
            list[next[v as usize]] = i as u32;
            next[v as usize] += 1;
        }
    }
    (start, list)
}

/// The facets around `v` split by its two sharp edges: `side[i]` is 0 or 1 for the facet
/// `around[i]` (joined across `v`'s other edges to its side), the facet `first` on side 0.
/// `None` if the two sharp edges do not split the facets around `v` in two.
fn split_sides(
    surface: &Surface,
    v: u32,
    around: &[u32],
    sharp_at: &[[u32; 2]],
    first: u32,
) -> Option<Vec<u8>> {
    // two facets around v are joined when they share an edge (v, w) that is not sharp
    let other_ends = |f: u32| {
        let k = surface.facets[f as usize].nodes();
        let i = k.iter().position(|&x| x == v).unwrap_or(0);
        [k[(i + 1) % k.len()], k[(i + k.len() - 1) % k.len()]]
    };
    let is_sharp = |w: u32| sharp_at.iter().any(|e| e.contains(&w));
    let mut side = vec![u8::MAX; around.len()];
    let start = around.iter().position(|&f| f == first)?;
    for (seed, label) in [(Some(start), 0u8), (None, 1u8)] {
        let seed = seed.or_else(|| side.iter().position(|&s| s == u8::MAX))?;
        side[seed] = label;
        let mut stack = vec![seed];
        while let Some(i) = stack.pop() {
            for w in other_ends(around[i]).into_iter().filter(|&w| !is_sharp(w)) {
                for (j, &g) in around.iter().enumerate() {
                    if side[j] == u8::MAX && other_ends(g).contains(&w) {
                        side[j] = label;
                        stack.push(j);
                    }
                }
            }
        }
    }
    side.iter().all(|&s| s != u8::MAX).then_some(side)
}

/// The angle-weighted unit normal at corner `v` of the facets `facets` of `surface`.
fn side_normal(surface: &Surface, v: u32, facets: impl Iterator<Item = u32>) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for f in facets {
        let k = surface.facets[f as usize].nodes();
        let i = k.iter().position(|&x| x == v).unwrap_or(0);
        let x = |j: usize| surface.nodes[k[(i + j) % k.len()] as usize];
        let a = geom_predicates::vector::sub(x(k.len() - 1), x(0));
        let b = geom_predicates::vector::sub(x(1), x(0));
        let w = angle_between(a, b);
        let nrm = unit(fan_normal(&surface.nodes, k));
        (0..3).for_each(|d| sum[d] += w * nrm[d]);
    }
    unit(sum)
}

/// The unit vector a fraction `t` of the way from `a` to `b` on their great circle.
fn slerp(a: [f64; 3], b: [f64; 3], t: f64) -> [f64; 3] {
    let omega = angle_between(a, b);
    if omega < 1e-12 {
        return a;
    }
    let (wa, wb) = (
        ((1.0 - t) * omega).sin() / omega.sin(),
        (t * omega).sin() / omega.sin(),
    );
    unit(std::array::from_fn(|d| wa * a[d] + wb * b[d]))
}

/// What one fanned node keeps: its two sides' facets and normals, its pieces.
struct Node {
    /// The facets on side 1 (their corner at the node becomes copy `K`).
    far_side: Vec<u32>,
    normals: [[f64; 3]; 2],
    pieces: usize,
}

/// The wall `surface` (checked; its edges `topo`) with fans at its chains of sharp convex
/// edges: those whose facets' normals turn by more than `threshold_deg`, each fan in pieces
/// of at most `max_angle_deg`. The surface nodes flagged in `skip` are not fanned (their
/// chains are grown without fans).
pub(crate) fn fan_wall(
    surface: &Surface,
    topo: &Topo,
    (threshold_deg, max_angle_deg): (f64, f64),
    skip: &[bool],
) -> Fanned {
    if threshold_deg <= 0.0 {
        return Fanned::plain(surface);
    }
    let turns = convex_turns(surface, topo);
    let threshold = threshold_deg.to_radians();
    let mut sharp: Vec<bool> = turns.iter().map(|&t| t > threshold).collect();
    let n = surface.nodes.len();
    let at = |sharp: &[bool]| {
        let mut sharp_at: Vec<Vec<u32>> = vec![Vec::new(); n];
        for (e, edge) in topo.edges.iter().enumerate().filter(|(e, _)| sharp[*e]) {
            for v in edge.nodes {
                sharp_at[v as usize].push(e as u32);
            }
        }
        sharp_at
    };
    for e in rim_edges(topo, &turns, &at(&sharp), skip) {
        sharp[e as usize] = true;
    }
    let sharp_at = at(&sharp);
    let candidate = |v: usize| sharp_at[v].len() == 2 && !skip.get(v).copied().unwrap_or(false);
    let (mut nodes, components) = chains(surface, topo, &sharp_at, candidate);
    if nodes.is_empty() {
        return Fanned::plain(surface);
    }
    // one number of pieces per chain: the most its widest turn needs
    let max_angle = max_angle_deg.to_radians();
    for chain in &components {
        let widest = chain
            .iter()
            .filter_map(|v| nodes.get(v))
            .map(|x| angle_between(x.normals[0], x.normals[1]))
            .fold(0.0, f64::max);
        let pieces = ((widest / max_angle).ceil() as usize).max(1);
        for v in chain {
            if let Some(x) = nodes.get_mut(v) {
                x.pieces = pieces;
            }
        }
    }
    build(surface, topo, &sharp, &nodes)
}

/// The least turn (radians) of a rim edge that a chain's end fans across: a flat tip's
/// edge turns by 90°.
const RIM_TURN: f64 = std::f64::consts::FRAC_PI_4;

/// For each end of a chain of sharp edges (a node with one sharp edge whose other end has
/// two: the corner where a trailing edge meets a flat tip), its convex edge that turns most
/// (the tip's rim), if it turns by more than [`RIM_TURN`]: fanned across it as across a
/// second sharp edge, the end's columns turn from one side over the tip to the other instead
/// of one column along the mean of all its facets' normals.
fn rim_edges(topo: &Topo, turns: &[f64], sharp_at: &[Vec<u32>], skip: &[bool]) -> Vec<u32> {
    let turning = |e: usize| turns[e] > RIM_TURN;
    // how many turning edges each node has
    let mut count = vec![0usize; sharp_at.len()];
    for (edge, _) in topo.edges.iter().zip(turns).filter(|(_, t)| **t > RIM_TURN) {
        edge.nodes.iter().for_each(|&w| count[w as usize] += 1);
    }
    let mut rims = Vec::new();
    for (v, edges) in sharp_at.iter().enumerate() {
        if edges.len() != 1 || skip.get(v).copied().unwrap_or(false) {
            continue;
        }
        let [a, b] = topo.edges[edges[0] as usize].nodes;
        let other = if a as usize == v { b } else { a };
        if sharp_at[other as usize].len() != 2 {
            continue;
        }
        // the rim's far end must lie on the rim (two turning edges), not at a corner of its
        // own: on a wedge whose end cap is one triangle the rim edge runs to the far corner,
        // where the fan's thin cells then fold
        let corner = |w: u32| w != v as u32 && count[w as usize] > 2;
        let best = topo
            .edges
            .iter()
            .enumerate()
            .filter(|(e, edge)| {
                turning(*e) && *e != edges[0] as usize && edge.nodes.contains(&(v as u32))
            })
            .filter(|(_, edge)| !edge.nodes.iter().any(|&w| corner(w)))
            .map(|(e, _)| (turns[e], e))
            .max_by(|x, y| x.0.total_cmp(&y.0).then(y.1.cmp(&x.1)));
        if let Some((_, e)) = best {
            rims.push(e as u32);
        }
    }
    rims
}

/// The fanned nodes (`candidate`: two sharp edges, not skipped) whose sharp edges split their
/// facets in two sides, each with its sides, and the chains of them (joined by sharp edges),
/// side 0 carried along each chain from node to node (the edge's facet on side 0 at one end
/// is on side 0 at the other). `sharp_at`: each node's sharp edges.
fn chains(
    surface: &Surface,
    topo: &Topo,
    sharp_at: &[Vec<u32>],
    candidate: impl Fn(usize) -> bool,
) -> (HashMap<u32, Node>, Vec<Vec<u32>>) {
    let n = surface.nodes.len();
    let (start, list) = facets_around(surface);
    // each chain of candidates, side 0 carried along it from node to node
    let mut nodes: HashMap<u32, Node> = HashMap::new();
    let mut component = vec![NONE; n];
    let mut components: Vec<Vec<u32>> = Vec::new();
    for seed in (0..n).filter(|&v| candidate(v)) {
        if component[seed] != NONE {
            continue;
        }
        let id = components.len() as u32;
        components.push(Vec::new());
        let first = topo.edges[sharp_at[seed][0] as usize].facets[0];
        let mut stack = vec![(seed as u32, first)];
        component[seed] = id;
        while let Some((v, first)) = stack.pop() {
            let around = &list[start[v as usize]..start[v as usize + 1]];
            let ends: Vec<[u32; 2]> = sharp_at[v as usize]
                .iter()
                .map(|&e| topo.edges[e as usize].nodes)
                .collect();
            let Some(side) = split_sides(surface, v, around, &ends, first) else {
                continue;
            };
            let on = |s: u8| {
                around
                    .iter()
                    .zip(&side)
                    .filter(move |(_, x)| **x == s)
                    .map(|(&f, _)| f)
            };
            let normals = [
                side_normal(surface, v, on(0)),
                side_normal(surface, v, on(1)),
            ];
            nodes.insert(
                v,
                Node {
                    far_side: on(1).collect(),
                    normals,
                    pieces: 0,
                },
            );
            components[id as usize].push(v);
            for &e in &sharp_at[v as usize] {
                let [a, b] = topo.edges[e as usize].nodes;
                let w = if a == v { b } else { a };
                if !candidate(w as usize) || component[w as usize] != NONE {
                    continue;
                }
                // the edge's facet on side 0 at v is on side 0 at w too
                let [f, g] = topo.edges[e as usize].facets;
                let near = if on(0).any(|x| x == f) { f } else { g };
                component[w as usize] = id;
                stack.push((w, near));
            }
        }
    }
    (nodes, components)
}

/// The fanned wall from the fanned nodes `nodes` (each with the facet on its side 0).
fn build(surface: &Surface, topo: &Topo, sharp: &[bool], nodes: &HashMap<u32, Node>) -> Fanned {
    let n = surface.nodes.len();
    let mut wall = surface.clone();
    let mut origin: Vec<u32> = (0..n as u32).collect();
    let mut dir: Vec<Option<[f64; 3]>> = vec![None; n];
    // copy j of each fanned node (copy 0 the node itself)
    let mut copies: HashMap<u32, Vec<u32>> = HashMap::new();
    let mut fanned: Vec<u32> = nodes.keys().copied().collect();
    fanned.sort_unstable();
    for &v in &fanned {
        let x = &nodes[&v];
        let mut list = vec![v];
        dir[v as usize] = Some(x.normals[0]);
        for j in 1..=x.pieces {
            list.push(wall.nodes.len() as u32);
            wall.nodes.push(surface.nodes[v as usize]);
            origin.push(v);
            let t = j as f64 / x.pieces as f64;
            dir.push(Some(slerp(x.normals[0], x.normals[1], t)));
        }
        for &f in &x.far_side {
            let facet = &mut wall.facets[f as usize];
            let m = facet.nodes().len();
            if let Some(i) = facet.0[..m].iter().position(|&c| c == v) {
                facet.0[i] = list[x.pieces];
            }
        }
        copies.insert(v, list);
    }
    let mut pipe: Vec<u32> = (0..surface.facets.len() as u32).collect();
    let mut apex_edges = Vec::new();
    for edge in topo
        .edges
        .iter()
        .zip(sharp)
        .filter(|(_, s)| **s)
        .map(|(e, _)| e)
    {
        let [p, q] = edge.nodes;
        let (cp, cq) = (copies.get(&p), copies.get(&q));
        let Some(pieces) = cp.or(cq).map(|c| c.len() - 1) else {
            continue;
        };
        if cp.is_some_and(|c| c.len() - 1 != pieces) || cq.is_some_and(|c| c.len() - 1 != pieces) {
            continue; // not expected: one number of pieces per chain
        }
        // the edge's facet on side 0 (copy 0) and the direction it runs the edge
        let fanned_end = if cp.is_some() { p } else { q };
        let far = &nodes[&fanned_end].far_side;
        let pair = edge.facets;
        let side0 = if far.contains(&pair[0]) {
            pair[1]
        } else {
            pair[0]
        };
        let forward = pair[0] == side0;
        let (p, q) = if forward { (p, q) } else { (q, p) };
        let copy = |v: u32, j: usize| copies.get(&v).map_or(v, |c| c[j]);
        if cp.is_none() || cq.is_none() {
            // the chain's end: the edges from it to its neighbour's copies
            let (end, other) = if cp.is_none() { (p, q) } else { (q, p) };
            for j in 0..=pieces {
                let c = copy(other, j);
                apex_edges.push(([c.min(end), c.max(end)], end));
            }
        }
        for j in 0..pieces {
            let k = crate::children::dedup_cyclic([
                copy(q, j),
                copy(p, j),
                copy(p, j + 1),
                copy(q, j + 1),
            ]);
            let fourth = k.get(3).copied().unwrap_or(geom_surface::NO_NODE);
            wall.facets.push(Facet([k[0], k[1], k[2], fourth]));
            wall.facet_patch.push(surface.facet_patch[side0 as usize]);
            pipe.push(side0);
        }
    }
    apex_edges.sort_unstable();
    Fanned {
        wall,
        fan: FanTopo { origin, apex_edges },
        dir,
        pipe,
        real_facets: surface.facets.len(),
    }
}
