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
    /// Its two facets, the first running the edge's direction.
    pub facets: [u32; 2],
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
            let mut two = [pair[0].2; 2];
            for (slot, s) in pair.iter().take(2).enumerate() {
                far[slot] = far_side(&facets[s.2 as usize], s.3 as usize);
                two[slot] = s.2;
                facet_edges[s.2 as usize][s.3 as usize] = id;
            }
            edges.push(Edge {
                nodes: [k[i], k[(i + 1) % k.len()]],
                far,
                facets: two,
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
/// The direction is the angle-weighted normal of the node's facets (with `by_patch`, of each
/// patch's facets apart, the patches then weighted alike: [`patch_normals`]); near concave nodes (a
/// node whose neighbours lie on average above its tangent plane, and the nodes next to it)
/// it is then `smoothing` times replaced by the normalised sum of its own and its
/// neighbours' directions, which fans the directions out of concave edges so the front
/// spreads there instead of folding; elsewhere (convex edges and corners) it stays the
/// normal. Then a direction that stands off one of its facets at a cosine below `floor` is
/// turned towards the max-min direction ([`stand_off`]). The length is `height`, divided at a concave node by the smallest cosine between
/// its direction and its facets' normals (at most 2), so that the child stands `height` off
/// each facet there.
pub(crate) fn ideal_steps(
    front: &Surface,
    topo: &Topo,
    height: f64,
    smoothing: usize,
    floor: f64,
    (by_patch, coarse): (bool, &[bool]),
) -> (Vec<[f64; 3]>, Vec<f64>) {
    let mut dir = if by_patch {
        patch_normals(front)
    } else {
        front.node_normals()
    };
    let n = front.nodes.len();
    let mut rise = vec![0.0f64; n];
    for e in &topo.edges {
        let [a, b] = e.nodes.map(|v| v as usize);
        let d = geom_predicates::vector::sub(front.nodes[b], front.nodes[a]);
        rise[a] += geom_predicates::vector::dot(d, dir[a]);
        rise[b] -= geom_predicates::vector::dot(d, dir[b]);
    }
    // smoothed: nodes near concave ones, and those grown from a coarsely faceted wall curve
    let mut near: Vec<bool> = (0..n)
        .map(|v| coarse.get(v).copied().unwrap_or(false))
        .collect();
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
    if floor > 0.0 {
        stand_off(front, floor, &mut dir);
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

/// Off the wall's feature edges, a wall node with an edge whose facets' normals turn by more
/// than this (degrees) is on a coarsely faceted curve: the directions of its column are
/// smoothed whatever the front's shape round them. The normals of facets ten times a curve's radius (a swept
/// wing's leading edge, faceted by a CAD kernel's uniform triangles, turns by 20°–50° from
/// facet to facet) diverge and twist once the layers outgrow the radius, and the columns stop
/// there; smoothed, the swept wing keeps every column (`docs/3d.md`). Finer fronts (the
/// built-in wing, a sphere of 1 280 triangles: under 10°) and flat faces keep their normals.
pub(crate) const COARSE_TURN_DEG: f64 = 20.0;

/// A wall edge whose two facets' normals turn by more than this (degrees) is a feature edge
/// (a cube's edge, a wing tip's rim, a trailing edge): its nodes are not smoothed for
/// [`COARSE_TURN_DEG`] (the cube's edges keep columns normal to their faces). The wall's,
/// not the front's: on the front a cube's edge rounds into facets turning by 30°–45°, which
/// smoothed lean the step's columns at its tower until 36 of them stop (first height 3e-3).
pub(crate) const FEATURE_TURN_DEG: f64 = 60.0;

/// The wall nodes whose columns' directions are smoothed whatever the front's shape round
/// them: those with an edge turning by more than [`COARSE_TURN_DEG`] and none by more than
/// [`FEATURE_TURN_DEG`].
pub(crate) fn coarse_nodes(front: &Surface, topo: &Topo) -> Vec<bool> {
    let normals: Vec<[f64; 3]> = front
        .facets
        .iter()
        .map(|f| unit(fan_normal(&front.nodes, f.nodes())))
        .collect();
    // each node's largest edge turn
    let mut turn = vec![0.0f64; front.nodes.len()];
    for e in &topo.edges {
        let [f, g] = e.facets.map(|f| normals[f as usize]);
        let t = geom_surface::angle_between(f, g);
        for v in e.nodes {
            turn[v as usize] = turn[v as usize].max(t);
        }
    }
    let (coarse, feature) = (COARSE_TURN_DEG.to_radians(), FEATURE_TURN_DEG.to_radians());
    turn.into_iter()
        .map(|t| t > coarse && t <= feature)
        .collect()
}

/// Each node's normal: the sum over the patches of its facets of each patch's unit
/// angle-weighted normal at the node (each patch counted once, however its facets' angles at
/// the node change), normalised.
fn patch_normals(front: &Surface) -> Vec<[f64; 3]> {
    let patches = front.patches.len().max(1);
    let mut acc = vec![[0.0f64; 3]; front.nodes.len() * patches];
    for (f, facet) in front.facets.iter().enumerate() {
        let k = facet.nodes();
        let nrm = unit(fan_normal(&front.nodes, k));
        let patch = front.facet_patch.get(f).copied().unwrap_or(0) as usize;
        for i in 0..k.len() {
            let x = |j: usize| front.nodes[k[(i + j) % k.len()] as usize];
            let a = geom_predicates::vector::sub(x(k.len() - 1), x(0));
            let b = geom_predicates::vector::sub(x(1), x(0));
            let angle = geom_surface::angle_between(a, b);
            let slot = &mut acc[k[i] as usize * patches + patch];
            (0..3).for_each(|d| slot[d] += angle * nrm[d]);
        }
    }
    acc.chunks(patches)
        .map(|per| {
            let mut sum = [0.0; 3];
            for p in per {
                let u = unit(*p);
                (0..3).for_each(|d| sum[d] += u[d]);
            }
            unit(sum)
        })
        .collect()
}

/// Turns each node's direction `dir` that stands off one of its facets at a cosine below
/// `floor` towards the direction that stands most steeply off all of them
/// ([`max_min_direction`]), just far enough to reach `floor` (or all the way, where even
/// that direction does not). Elsewhere the direction is left as it is, to the bit.
///
/// At a saddle corner (the foot of a convex edge between two concave ones, as at the step's
/// tower) the angle-weighted normal leans towards the side with the most facet angle: it
/// stands off the tower's sides at a cosine of 1/√11 ≈ 0.30, the max-min direction at
/// 1/√3 ≈ 0.58 off all three planes.
fn stand_off(front: &Surface, floor: f64, dir: &mut [[f64; 3]]) {
    let mut normals: Vec<Vec<[f64; 3]>> = vec![Vec::new(); front.nodes.len()];
    for f in &front.facets {
        let normal = unit(fan_normal(&front.nodes, f.nodes()));
        for &v in f.nodes() {
            normals[v as usize].push(normal);
        }
    }
    for (d, n) in dir.iter_mut().zip(&normals) {
        if stand(*d, n) < floor {
            *d = turn_off(*d, n, floor, 1.0).0;
        }
    }
}

/// How steeply the unit vector `d` stands off the unit vectors `normals`: its smallest dot
/// product with them.
pub(crate) fn stand(d: [f64; 3], normals: &[[f64; 3]]) -> f64 {
    normals
        .iter()
        .map(|&n| geom_predicates::vector::dot(d, n))
        .fold(f64::INFINITY, f64::min)
}

/// The unit vector `d` turned towards the direction standing most steeply off all of
/// `normals` ([`max_min_direction`]), just far enough to stand off each at the target:
/// `floor`, or `share` of that best direction's stand where that is lower. Returns the
/// turned vector and the target; where the target is not positive no direction stands off
/// every normal, and the caller decides whether the turn is worth having.
pub(crate) fn turn_off(
    d: [f64; 3],
    normals: &[[f64; 3]],
    floor: f64,
    share: f64,
) -> ([f64; 3], f64) {
    let best = max_min_direction(normals, d);
    let target = floor.min(share * stand(best, normals));
    let turned = turn_towards(d, best, |d| stand(d, normals) >= target);
    (turned, target)
}

/// The unit blend of `d` and `best` nearest `d` (by bisection on the blend's weight) that
/// is `enough` (which `best` is).
fn turn_towards(d: [f64; 3], best: [f64; 3], enough: impl Fn([f64; 3]) -> bool) -> [f64; 3] {
    let at = |t: f64| unit(std::array::from_fn(|k| (1.0 - t) * d[k] + t * best[k]));
    let (mut lo, mut hi) = (0.0, 1.0);
    for _ in 0..30 {
        let mid = 0.5 * (lo + hi);
        if enough(at(mid)) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    at(hi)
}

/// The unit vector maximising the smallest dot product with the unit vectors `normals` (the
/// centre of their smallest enclosing spherical cap): the best of `start`, each normal, the
/// normalised sum of each pair and the vector at equal dot products with each triple.
pub(crate) fn max_min_direction(normals: &[[f64; 3]], start: [f64; 3]) -> [f64; 3] {
    use geom_predicates::vector::{cross3, dot};
    let worst = |d: [f64; 3]| stand(d, normals);
    let mut best = (worst(start), start);
    let mut consider = |d: [f64; 3]| {
        let d = unit(d);
        let w = worst(d);
        if w > best.0 + 1e-12 {
            best = (w, d);
        }
    };
    let m = normals.len();
    for i in 0..m {
        consider(normals[i]);
        for j in i + 1..m {
            let (a, b) = (normals[i], normals[j]);
            consider(std::array::from_fn(|d| a[d] + b[d]));
            for c in &normals[j + 1..] {
                let det = dot(a, cross3(b, *c));
                if det.abs() > 1e-9 {
                    let (x, y, z) = (cross3(b, *c), cross3(*c, a), cross3(a, b));
                    consider(std::array::from_fn(|d| (x[d] + y[d] + z[d]) / det));
                }
            }
        }
    }
    best.1
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn coarse_nodes_are_those_of_coarsely_faceted_curves_not_of_features_or_fine_fronts() {
        let coarse = |s: &Surface| coarse_nodes(s, &Topo::new(s));
        // an icosahedron's faces turn by 41.8° across each edge: every node on a coarse curve
        let ico = Surface::sphere(1.0, 0);
        assert!(coarse(&ico).iter().all(|&c| c));
        // a sphere of 1 280 triangles turns by under 10°, a cube's faces by 0° and its edges
        // by 90°: none
        assert!(!coarse(&Surface::sphere(1.0, 3)).contains(&true));
        assert!(!coarse(&Surface::cube(1.0, 4, false)).contains(&true));
        assert!(!coarse(&Surface::cube(1.0, 4, true)).contains(&true));
    }

    #[test]
    fn patch_normals_weigh_each_patch_alike_however_sheared_its_facets_are() {
        // node 0 on a rim: a cap patch below (z = 0, facing -z, a right angle at node 0) and
        // a side patch (y = 0, facing -y) whose quad is sheared to a 20° angle at node 0
        let t = 20f64.to_radians();
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [0.0, 1.0, 0.0],
            [t.cos(), 0.0, t.sin()],
            [1.0 + t.cos(), 0.0, t.sin()],
        ];
        let facets = vec![Facet::tri(0, 2, 1), Facet::quad(0, 1, 4, 3)];
        let mut surface = Surface::single_patch(nodes, facets, "cap");
        surface.patches.push(surface.patches[0].clone());
        surface.patches[1].name = "side".to_string();
        surface.facet_patch[1] = 1;
        let h = 0.5f64.sqrt();
        let d = patch_normals(&surface)[0];
        assert!((d[0]).abs() < 1e-12 && (d[1] + h).abs() < 1e-12 && (d[2] + h).abs() < 1e-12);
        // the plain angle weights lean to the cap: 90° against 20°
        let plain = surface.node_normals()[0];
        assert!(plain[2] < -0.9, "{plain:?}");
        // one patch: the plain angle-weighted normal
        let one = Surface::single_patch(surface.nodes.clone(), surface.facets.clone(), "wall");
        let (a, b) = (patch_normals(&one)[0], one.node_normals()[0]);
        assert!((0..3).all(|k| (a[k] - b[k]).abs() < 1e-12), "{a:?} {b:?}");
    }

    #[test]
    fn the_max_min_direction_of_a_saddle_corner_stands_equally_off_its_three_planes() {
        let (x, y, z) = ([1.0, 0.0, 0.0], [0.0, -1.0, 0.0], [0.0, 0.0, 1.0]);
        // the step's tower foot: three block-top facets, one on each tower side
        let start = unit([1.0, -1.0, 3.0]);
        let d = max_min_direction(&[z, z, z, x, y], start);
        let s = 1.0 / 3f64.sqrt();
        assert!(
            d.iter().zip([s, -s, s]).all(|(a, b)| (a - b).abs() < 1e-12),
            "{d:?}"
        );
        // two planes: the bisector; one: its normal
        let d = max_min_direction(&[x, z], [0.0, 0.0, 1.0]);
        let h = 0.5f64.sqrt();
        assert!(
            (d[0] - h).abs() < 1e-12 && (d[2] - h).abs() < 1e-12,
            "{d:?}"
        );
        assert_eq!(max_min_direction(&[z], z), z);
    }
}
