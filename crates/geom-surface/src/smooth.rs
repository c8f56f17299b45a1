//! A smooth surface rebuilt from a surface's facets: the true shape of a wall known only by
//! its triangles (an STL or `.msh` surface), where the P2 wall nodes go.
//!
//! Feature edges are the edges whose two facets' normals differ by more than a threshold
//! angle (default [`DEFAULT_FEATURE_ANGLE_DEG`], 30°), and every edge not in exactly two
//! facets running opposite ways (an open rim, a non-manifold edge): they stay sharp. A node
//! with no feature edge is smooth; one with two, through which the feature line turns by no
//! more than the threshold, is on a crease; any other node with feature edges is a corner.
//! Normals are per (facet, corner): the angle-weighted normals of the facets around the node
//! that can be reached without crossing a feature edge (one smooth sector), so a crease node
//! has one normal per side, each made square to the crease's tangent.
//!
//! Each triangle (each quad split along `0–2`) becomes a PN triangle (Vlachos, Peters, Boyd &
//! Mitchell 2001): a cubic Bézier triangle through its corners. On a smooth edge the control
//! point near a corner is the chord's third projected onto that corner's tangent plane; on a
//! feature edge it is a third of the chord along the crease's tangent (the circle through the
//! crease node and its two feature neighbours), or along the chord at a corner, so the curve
//! is straight there. Either way an edge's curve depends only on its two end positions and
//! what both facets share (the sector normals of a smooth edge, the tangents of a feature
//! edge): the two facets of an edge agree along it. A flat region stays flat and straight
//! feature lines stay straight, so a cube is its facets. The patches are made when asked for
//! (ten control points of a triangle), not stored.

use std::collections::HashMap;

use crate::{Facet, Surface, angle_between, cross, dot, fan_normal, norm, sub, unit};

/// The default feature angle: adjacent facets whose normals differ by more than this
/// (degrees) meet at a sharp edge.
pub const DEFAULT_FEATURE_ANGLE_DEG: f64 = 30.0;

/// How a node sits on the feature lines.
#[derive(Debug, Clone, Copy, PartialEq)]
enum NodeKind {
    /// No feature edge.
    Smooth,
    /// On one feature line, which passes through with this unit tangent.
    Crease([f64; 3]),
    /// Any other node with a feature edge: feature edges leave it straight.
    Corner,
}

/// A smooth, G1 away from feature edges, surface through a [`Surface`]'s nodes (module docs).
#[derive(Debug, Clone)]
pub struct SmoothSurface {
    nodes: Vec<[f64; 3]>,
    facets: Vec<Facet>,
    /// Per facet, bit `i`: its edge `i` (corner `i` to corner `i + 1`) is a feature edge.
    feature: Vec<u8>,
    /// The unit normal of each (facet, corner): index `4·facet + corner`.
    normals: Vec<[f64; 3]>,
    kinds: Vec<NodeKind>,
    feature_edges: usize,
}

/// A cubic Bézier triangle, its control points in the order `b300, b030, b003` (the
/// corners), `b210, b120, b021, b012, b102, b201` (two per edge), `b111`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PnTriangle {
    /// The ten control points.
    pub control: [[f64; 3]; 10],
}

/// The exponents of each control point's barycentric monomial, in [`PnTriangle`] order.
const EXPONENTS: [[i32; 3]; 10] = [
    [3, 0, 0],
    [0, 3, 0],
    [0, 0, 3],
    [2, 1, 0],
    [1, 2, 0],
    [0, 2, 1],
    [0, 1, 2],
    [1, 0, 2],
    [2, 0, 1],
    [1, 1, 1],
];

/// The multinomial coefficient 3! / (i! j! k!) of each control point.
const MULTINOMIAL: [f64; 10] = [1.0, 1.0, 1.0, 3.0, 3.0, 3.0, 3.0, 3.0, 3.0, 6.0];

impl PnTriangle {
    /// The point at barycentric coordinates `b` (weights of the corners, summing to 1).
    pub fn point(&self, b: [f64; 3]) -> [f64; 3] {
        let mut p = [0.0; 3];
        for (c, (e, m)) in self.control.iter().zip(EXPONENTS.iter().zip(MULTINOMIAL)) {
            let w = m * b[0].powi(e[0]) * b[1].powi(e[1]) * b[2].powi(e[2]);
            (0..3).for_each(|d| p[d] += w * c[d]);
        }
        p
    }

    /// The partial derivative of the homogeneous cubic along barycentric coordinate `k`.
    fn derivative(&self, b: [f64; 3], k: usize) -> [f64; 3] {
        let mut p = [0.0; 3];
        for (c, (e, m)) in self.control.iter().zip(EXPONENTS.iter().zip(MULTINOMIAL)) {
            if e[k] == 0 {
                continue;
            }
            let mut w = m * f64::from(e[k]);
            for (j, &ej) in e.iter().enumerate() {
                w *= b[j].powi(if j == k { ej - 1 } else { ej });
            }
            (0..3).for_each(|d| p[d] += w * c[d]);
        }
        p
    }

    /// The unit normal at barycentric coordinates `b`, on the side the corners turn
    /// counter-clockwise about (the facet's normal for a flat triangle).
    pub fn normal(&self, b: [f64; 3]) -> [f64; 3] {
        let [du, dv, dw] = [0, 1, 2].map(|k| self.derivative(b, k));
        unit(cross(sub(dv, du), sub(dw, du)))
    }
}

/// The facets of every edge, keyed by its sorted ends: (facet, the edge's index in it).
type EdgeMap = HashMap<(u32, u32), Vec<(u32, u8)>>;

fn edge_map(facets: &[Facet]) -> EdgeMap {
    let mut map: EdgeMap = HashMap::with_capacity(2 * facets.len());
    for (f, facet) in facets.iter().enumerate() {
        let k = facet.nodes();
        for i in 0..k.len() {
            let (a, b) = (k[i], k[(i + 1) % k.len()]);
            map.entry((a.min(b), a.max(b)))
                .or_default()
                .push((f as u32, i as u8));
        }
    }
    map
}

/// The first node of edge `i` of facet `f`.
fn edge_start(facets: &[Facet], f: u32, i: u8) -> u32 {
    facets[f as usize].nodes()[i as usize]
}

/// Slot `4·f + i` of the corner of facet `f` at node `v` (`None` if `v` is not in it).
fn slot(facets: &[Facet], f: u32, v: u32) -> Option<usize> {
    let k = facets[f as usize].nodes();
    k.iter().position(|&x| x == v).map(|i| 4 * f as usize + i)
}

/// The root of `x` in a union-find forest (halving the path).
fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

impl SmoothSurface {
    /// The smooth surface of `surface`'s facets, edges whose facets' normals differ by more
    /// than `feature_angle_deg` degrees kept sharp. Never fails: a surface that is not
    /// closed or not manifold has feature edges there, a degenerate facet a zero normal.
    pub fn new(surface: &Surface, feature_angle_deg: f64) -> SmoothSurface {
        let (nodes, facets) = (&surface.nodes, &surface.facets);
        let threshold = feature_angle_deg.to_radians();
        let facet_normals: Vec<[f64; 3]> = facets
            .iter()
            .map(|f| unit(fan_normal(nodes, f.nodes())))
            .collect();
        let edges = edge_map(facets);
        let mut feature = vec![0u8; facets.len()];
        let mut neighbours: Vec<Vec<u32>> = vec![Vec::new(); nodes.len()];
        let mut feature_edges = 0;
        // sectors: the (facet, corner) slots joined across smooth edges
        let mut parent: Vec<usize> = (0..4 * facets.len()).collect();
        for (&(a, b), sides) in &edges {
            let smooth = match sides[..] {
                [(f, i), (g, j)] => {
                    edge_start(facets, f, i) != edge_start(facets, g, j)
                        && angle_between(facet_normals[f as usize], facet_normals[g as usize])
                            <= threshold
                }
                _ => false,
            };
            if smooth {
                let (f, g) = (sides[0].0, sides[1].0);
                for v in [a, b] {
                    if let (Some(s), Some(t)) = (slot(facets, f, v), slot(facets, g, v)) {
                        let (rs, rt) = (find(&mut parent, s), find(&mut parent, t));
                        parent[rs.max(rt)] = rs.min(rt);
                    }
                }
            } else {
                feature_edges += 1;
                neighbours[a as usize].push(b);
                neighbours[b as usize].push(a);
                for &(f, i) in sides {
                    feature[f as usize] |= 1 << i;
                }
            }
        }
        // (sorted: the map's order is arbitrary)
        neighbours.iter_mut().for_each(|n| n.sort_unstable());
        let kinds = (0..nodes.len())
            .map(|v| node_kind(nodes, v, &neighbours[v], threshold))
            .collect();
        let mut smooth = SmoothSurface {
            nodes: nodes.clone(),
            facets: facets.clone(),
            feature,
            normals: Vec::new(),
            kinds,
            feature_edges,
        };
        smooth.normals = smooth.sector_normals(&facet_normals, &mut parent);
        smooth
    }

    /// The unit normal of every (facet, corner) slot: the angle-weighted facet normals over
    /// its sector (`parent`: the union-find forest of the sectors), made square to the
    /// crease's tangent at a crease node.
    fn sector_normals(&self, facet_normals: &[[f64; 3]], parent: &mut [usize]) -> Vec<[f64; 3]> {
        let mut sum = vec![[0.0; 3]; parent.len()];
        let mut root = vec![usize::MAX; parent.len()];
        for (f, facet) in self.facets.iter().enumerate() {
            let k = facet.nodes();
            for i in 0..k.len() {
                let p = self.nodes[k[i] as usize];
                let a = sub(self.nodes[k[(i + k.len() - 1) % k.len()] as usize], p);
                let b = sub(self.nodes[k[(i + 1) % k.len()] as usize], p);
                let angle = angle_between(a, b);
                let r = find(parent, 4 * f + i);
                root[4 * f + i] = r;
                (0..3).for_each(|d| sum[r][d] += angle * facet_normals[f][d]);
            }
        }
        let mut normals = vec![[0.0; 3]; parent.len()];
        for (f, facet) in self.facets.iter().enumerate() {
            for (i, &v) in facet.nodes().iter().enumerate() {
                let mut n = unit(sum[root[4 * f + i]]);
                if let NodeKind::Crease(t) = self.kinds[v as usize] {
                    let along = dot(n, t);
                    n = unit(std::array::from_fn(|d| n[d] - along * t[d]));
                }
                normals[4 * f + i] = n;
            }
        }
        normals
    }

    /// How many edges are kept sharp.
    pub fn feature_edge_count(&self) -> usize {
        self.feature_edges
    }

    /// Whether edge `i` of facet `f` (corner `i` to corner `i + 1`) is a feature edge.
    pub fn is_feature(&self, f: usize, i: usize) -> bool {
        self.feature[f] & (1 << i) != 0
    }

    /// The unit normal of facet `f` at its corner `i` (its smooth sector's normal there).
    pub fn normal(&self, f: usize, i: usize) -> [f64; 3] {
        self.normals[4 * f + i]
    }

    /// Whether node `v` is a corner of the feature lines (a node where feature edges meet
    /// other than along one crease): patches need not be G1 there.
    pub fn is_corner(&self, v: usize) -> bool {
        self.kinds[v] == NodeKind::Corner
    }

    /// How many patches facet `f` is made of: 1 for a triangle, 2 for a quad.
    pub fn patch_count(&self, f: usize) -> usize {
        self.facets[f].nodes().len() - 2
    }

    /// The corners of patch `s` of facet `f`, as corner indices of the facet: `[0, 1, 2]`,
    /// or for a quad `[0, 1, 2]` and `[0, 2, 3]`.
    pub fn patch_corners(s: usize) -> [usize; 3] {
        [0, s + 1, s + 2]
    }

    /// Patch `s` of facet `f` (see [`SmoothSurface::patch_corners`]).
    pub fn patch(&self, f: usize, s: usize) -> PnTriangle {
        let [i, j, k] = Self::patch_corners(s);
        let corner = |c: usize| self.nodes[self.facets[f].nodes()[c] as usize];
        let mut control = [[0.0; 3]; 10];
        control[0] = corner(i);
        control[1] = corner(j);
        control[2] = corner(k);
        control[3] = self.handle(f, i, j);
        control[4] = self.handle(f, j, i);
        control[5] = self.handle(f, j, k);
        control[6] = self.handle(f, k, j);
        control[7] = self.handle(f, k, i);
        control[8] = self.handle(f, i, k);
        // PN triangles' centre: E + (E − V) / 2, E the edge points' mean, V the corners'
        let (mut e, mut v) = ([0.0; 3], [0.0; 3]);
        for d in 0..3 {
            e[d] = control[3..9].iter().map(|c| c[d]).sum::<f64>() / 6.0;
            v[d] = control[..3].iter().map(|c| c[d]).sum::<f64>() / 3.0;
        }
        control[9] = std::array::from_fn(|d| e[d] + (e[d] - v[d]) / 2.0);
        PnTriangle { control }
    }

    /// The control point next to corner `i` of facet `f` on the curve from corner `i` to
    /// corner `j`: it reads only the two ends, and the normal at `i` (smooth edge) or the
    /// crease's tangent at `i` (feature edge), which both facets of the edge share.
    fn handle(&self, f: usize, i: usize, j: usize) -> [f64; 3] {
        let k = self.facets[f].nodes();
        let (a, b) = (self.nodes[k[i] as usize], self.nodes[k[j] as usize]);
        let d = sub(b, a);
        let n = k.len();
        let on_feature = (j == (i + 1) % n && self.is_feature(f, i))
            || (i == (j + 1) % n && self.is_feature(f, j));
        let step = if on_feature {
            match self.kinds[k[i] as usize] {
                NodeKind::Crease(t) => {
                    let l = norm(d) * dot(t, d).signum();
                    t.map(|x| x * l)
                }
                _ => d,
            }
        } else {
            let normal = self.normal(f, i);
            let w = dot(d, normal);
            std::array::from_fn(|c| d[c] - w * normal[c])
        };
        std::array::from_fn(|c| a[c] + step[c] / 3.0)
    }

    /// The point of the smooth surface for `p`, a point on or near facet `f`: `p`'s
    /// barycentric coordinates in the flat patch triangle it is nearest inside (clamped to
    /// it), evaluated on the smooth patch. A facet's nodes and edges' points map onto its
    /// nodes and edges' curves.
    pub fn point(&self, p: [f64; 3], f: usize) -> [f64; 3] {
        let corners = self.facets[f].nodes();
        let mut best: Option<(f64, usize, [f64; 3])> = None;
        for s in 0..self.patch_count(f) {
            let t = Self::patch_corners(s).map(|c| self.nodes[corners[c] as usize]);
            let Some(b) = barycentric(p, t) else { continue };
            let least = b[0].min(b[1]).min(b[2]);
            if best.is_none_or(|(l, _, _)| least > l) {
                best = Some((least, s, b));
            }
        }
        let Some((_, s, b)) = best else { return p };
        let b = b.map(|x| x.max(0.0));
        let total = b[0] + b[1] + b[2];
        self.patch(f, s).point(b.map(|x| x / total))
    }
}

/// The kind of node `v` with feature neighbours `nbrs`: a crease when exactly two and the
/// line turns by at most `threshold` radians there, its tangent that of the circle through
/// the three nodes.
fn node_kind(nodes: &[[f64; 3]], v: usize, nbrs: &[u32], threshold: f64) -> NodeKind {
    match nbrs {
        [] => NodeKind::Smooth,
        &[u, w] => {
            let a = sub(nodes[v], nodes[u as usize]);
            let b = sub(nodes[w as usize], nodes[v]);
            if angle_between(a, b) > threshold {
                return NodeKind::Corner;
            }
            // the circle through u, v, w touches |b|² a + |a|² b at v
            let (aa, bb) = (dot(a, a), dot(b, b));
            NodeKind::Crease(unit(std::array::from_fn(|d| bb * a[d] + aa * b[d])))
        }
        _ => NodeKind::Corner,
    }
}

/// The barycentric coordinates of `p` projected onto the plane of triangle `t` (`None` for
/// a degenerate triangle).
fn barycentric(p: [f64; 3], t: [[f64; 3]; 3]) -> Option<[f64; 3]> {
    let n = cross(sub(t[1], t[0]), sub(t[2], t[0]));
    let nn = dot(n, n);
    if nn <= 0.0 || !nn.is_finite() {
        return None;
    }
    let u = dot(n, cross(sub(t[1], p), sub(t[2], p))) / nn;
    let v = dot(n, cross(sub(t[2], p), sub(t[0], p))) / nn;
    Some([u, v, 1.0 - u - v])
}
