//! The checks a surface must pass before it is meshed, each failure a one-line error naming
//! the first bad node, facet, edge or body (`bodies`: the bodies of a surface of several
//! must each face out and lie side by side, none inside another).

use geom_predicates::{Aabb, orient3d, overlapping_pairs, segment_meets_triangle, triangles_meet};

use rayon::prelude::*;

use crate::{Facet, Surface, cross, dot, norm, sub};

mod bodies;

/// What is wrong with a surface (the first problem found).
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SurfaceError {
    /// No facets.
    #[error("the surface has no facets")]
    Empty,
    /// A node coordinate is NaN or infinite.
    #[error("surface node {node} has a non-finite coordinate")]
    NonFinite {
        /// Node index.
        node: usize,
    },
    /// A facet names a node that does not exist, or a node twice, or a patch that does not
    /// exist.
    #[error("facet {facet} names a missing node or patch, or a node twice")]
    BadFacet {
        /// Facet index.
        facet: usize,
    },
    /// A facet (or a triangle of a quad) has no area.
    #[error("facet {facet} is degenerate (no area)")]
    Degenerate {
        /// Facet index.
        facet: usize,
    },
    /// An edge is in one facet only: the surface has a hole.
    #[error("the surface is not closed: edge {edge:?} of facet {facet} is in no other facet")]
    Open {
        /// The edge's nodes, increasing.
        edge: [u32; 2],
        /// A facet with it.
        facet: usize,
    },
    /// An edge is in more than two facets.
    #[error("the surface is not manifold: edge {edge:?} (facet {facet}) is in {count} facets")]
    NonManifold {
        /// The edge's nodes, increasing.
        edge: [u32; 2],
        /// A facet with it.
        facet: usize,
        /// In how many facets.
        count: usize,
    },
    /// Two facets run along their shared edge in the same direction.
    #[error(
        "the surface is inconsistently oriented: facets {facet} and {other} run along edge {edge:?} the same way"
    )]
    Misoriented {
        /// The edge's nodes, increasing.
        edge: [u32; 2],
        /// One facet.
        facet: usize,
        /// The other.
        other: usize,
    },
    /// The enclosed volume is not positive: the facets face into the body.
    #[error(
        "the surface is inverted: it encloses a volume of {volume:e} (facets must be counter-clockwise seen from the fluid)"
    )]
    Inverted {
        /// The signed enclosed volume.
        volume: f64,
    },
    /// One body (connected component) of several encloses a volume that is not positive:
    /// its facets face into it. Bodies are numbered from 1 in the order of their first facet.
    #[error(
        "the surface's body {body} (group {group:?}, facet {facet}) is inverted: it encloses a volume of {volume:e} (facets must be counter-clockwise seen from the fluid)"
    )]
    InvertedBody {
        /// The body's number, from 1.
        body: usize,
        /// Its first facet.
        facet: usize,
        /// That facet's patch.
        group: String,
        /// The signed volume it encloses.
        volume: f64,
    },
    /// A body lies inside another: the layers would grow inside a solid.
    #[error(
        "the surface's body {body} (group {group:?}, facet {facet}) lies inside body {outer} (group {outer_group:?}, facet {outer_facet}): bodies must lie side by side"
    )]
    NestedBody {
        /// The inner body's number, from 1.
        body: usize,
        /// Its first facet.
        facet: usize,
        /// That facet's patch.
        group: String,
        /// The outer body's number.
        outer: usize,
        /// Its first facet.
        outer_facet: usize,
        /// That facet's patch.
        outer_group: String,
    },
    /// Two facets cross or touch away from their shared nodes.
    #[error("the surface intersects itself: facets {facet} and {other} meet")]
    SelfIntersecting {
        /// One facet.
        facet: usize,
        /// The other.
        other: usize,
    },
}

impl Surface {
    /// Checks that the surface can be meshed: finite nodes, valid facets, closed, manifold
    /// (each edge in exactly two facets), consistently oriented, positive enclosed volume
    /// (of each body, when there are several), not self-intersecting, no body inside another.
    /// Returns the first problem.
    pub fn check(&self) -> Result<(), SurfaceError> {
        if self.facets.is_empty() {
            return Err(SurfaceError::Empty);
        }
        if let Some(node) = self
            .nodes
            .iter()
            .position(|p| !p.iter().all(|x| x.is_finite()))
        {
            return Err(SurfaceError::NonFinite { node });
        }
        self.check_facets()?;
        self.check_edges()?;
        let volume = self.enclosed_volume();
        if volume.is_nan() || volume <= 0.0 {
            return Err(SurfaceError::Inverted { volume });
        }
        let bodies = bodies::bodies(self);
        if bodies.len() > 1 {
            for (i, b) in bodies.iter().enumerate() {
                let volume = bodies::volume(self, b);
                if volume.is_nan() || volume <= 0.0 {
                    let (body, facet, group) = self.body_at(i, b);
                    return Err(SurfaceError::InvertedBody {
                        body,
                        facet,
                        group,
                        volume,
                    });
                }
            }
        }
        if let Some((facet, other)) = first_self_intersection(&self.nodes, &self.facets) {
            return Err(SurfaceError::SelfIntersecting { facet, other });
        }
        // the bodies do not meet now, so one node of a body tells where all of it is
        let Some((i, j)) = bodies::first_nested(self, &bodies) else {
            return Ok(());
        };
        let (body, facet, group) = self.body_at(i, &bodies[i]);
        let (outer, outer_facet, outer_group) = self.body_at(j, &bodies[j]);
        Err(SurfaceError::NestedBody {
            body,
            facet,
            group,
            outer,
            outer_facet,
            outer_group,
        })
    }

    /// How errors name body `i`: its number from 1, its first facet, that facet's patch.
    fn body_at(&self, i: usize, body: &bodies::Body) -> (usize, usize, String) {
        let facet = body.facets[0] as usize;
        let group = self.patches[self.facet_patch[facet] as usize].name.clone();
        (i + 1, facet, group)
    }

    fn check_facets(&self) -> Result<(), SurfaceError> {
        let n = self.nodes.len() as u32;
        for (facet, f) in self.facets.iter().enumerate() {
            let k = f.nodes();
            let repeated = (0..k.len()).any(|i| k[i + 1..].contains(&k[i]));
            let patch_ok = self
                .facet_patch
                .get(facet)
                .is_some_and(|&p| (p as usize) < self.patches.len());
            if repeated || k.iter().any(|&v| v >= n) || !patch_ok {
                return Err(SurfaceError::BadFacet { facet });
            }
            let flat = f.triangles().any(|[a, b, c]| {
                let (a, b, c) = (
                    self.nodes[a as usize],
                    self.nodes[b as usize],
                    self.nodes[c as usize],
                );
                norm(cross(sub(b, a), sub(c, a))) == 0.0
            });
            if flat {
                return Err(SurfaceError::Degenerate { facet });
            }
        }
        Ok(())
    }

    fn check_edges(&self) -> Result<(), SurfaceError> {
        // (low node, high node, runs low → high, facet)
        let mut edges: Vec<(u32, u32, bool, u32)> = Vec::with_capacity(4 * self.facets.len());
        for (facet, f) in self.facets.iter().enumerate() {
            let k = f.nodes();
            for i in 0..k.len() {
                let (a, b) = (k[i], k[(i + 1) % k.len()]);
                edges.push((a.min(b), a.max(b), a < b, facet as u32));
            }
        }
        edges.sort_unstable_by_key(|e| (e.0, e.1, e.3));
        for group in edges.chunk_by(|x, y| (x.0, x.1) == (y.0, y.1)) {
            let (edge, facet) = ([group[0].0, group[0].1], group[0].3 as usize);
            match group.len() {
                1 => return Err(SurfaceError::Open { edge, facet }),
                2 if group[0].2 == group[1].2 => {
                    let other = group[1].3 as usize;
                    return Err(SurfaceError::Misoriented { edge, facet, other });
                }
                2 => {}
                count => return Err(SurfaceError::NonManifold { edge, facet, count }),
            }
        }
        Ok(())
    }
}

/// The first pair of facets (by the sweep's order) that meet anywhere but at the nodes and
/// edges they share: quads are split into two triangles, candidate pairs come from a
/// sort-and-sweep over the triangles' boxes, and each pair is decided exactly
/// ([`triangles_meet`]; for triangles sharing one node, whether the edge opposite it in
/// either meets the other; for triangles sharing an edge, whether they fold onto each other
/// in one plane). Limit: two triangles sharing one node and crossing along a line from it
/// without either opposite edge meeting the other are not seen (the corner-tet checks of a
/// mesher see such folds).
pub fn first_self_intersection(nodes: &[[f64; 3]], facets: &[Facet]) -> Option<(usize, usize)> {
    let (tris, pairs) = candidate_pairs(nodes, facets);
    // the exact tests of the broad phase's pairs on all cores (the first in the sweep's
    // order wins, whatever the threads)
    pairs
        .par_iter()
        .map(|&(i, j)| (tris[i], tris[j]))
        .find_first(|&((fa, a), (fb, b))| fa != fb && triangles_cross(nodes, a, b))
        .map(|((fa, _), (fb, _))| (fa.min(fb) as usize, fa.max(fb) as usize))
}

/// Every pair of facets that meet anywhere but at the nodes and edges they share (the test
/// of [`first_self_intersection`]), each pair once, the lower facet first, sorted: where a
/// mesher must act on all of them at once (two fronts growing into each other meet over
/// many facets).
pub fn self_intersections(nodes: &[[f64; 3]], facets: &[Facet]) -> Vec<(usize, usize)> {
    let (tris, pairs) = candidate_pairs(nodes, facets);
    let mut out: Vec<(usize, usize)> = pairs
        .par_iter()
        .map(|&(i, j)| (tris[i], tris[j]))
        .filter(|&((fa, a), (fb, b))| fa != fb && triangles_cross(nodes, a, b))
        .map(|((fa, _), (fb, _))| (fa.min(fb) as usize, fa.max(fb) as usize))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// The facets' triangles (a quad split into two), each with its facet, and the pairs of
/// triangles whose boxes overlap (sort-and-sweep), in the sweep's order.
#[allow(clippy::type_complexity)]
fn candidate_pairs(
    nodes: &[[f64; 3]],
    facets: &[Facet],
) -> (Vec<(u32, [u32; 3])>, Vec<(usize, usize)>) {
    let tris: Vec<(u32, [u32; 3])> = facets
        .iter()
        .enumerate()
        .flat_map(|(f, facet)| facet.triangles().map(move |t| (f as u32, t)))
        .collect();
    let corners = |t: [u32; 3]| t.map(|v| nodes[v as usize]);
    let boxes: Vec<Aabb<3>> = tris
        .iter()
        .map(|&(_, t)| Aabb::of_points(&corners(t)).expect("three corners"))
        .collect();
    let pairs = overlapping_pairs(&boxes);
    (tris, pairs)
}

/// Whether triangles `a` and `b` (node indices) meet away from the nodes they share.
fn triangles_cross(nodes: &[[f64; 3]], a: [u32; 3], b: [u32; 3]) -> bool {
    let p = |v: u32| nodes[v as usize];
    let shared: Vec<u32> = a.iter().copied().filter(|v| b.contains(v)).collect();
    let opposite = |t: [u32; 3], v: u32| {
        let i = t.iter().position(|&x| x == v).expect("shared node");
        (t[(i + 1) % 3], t[(i + 2) % 3])
    };
    match shared.len() {
        0 => triangles_meet(a.map(p), b.map(p)),
        1 => {
            let v = shared[0];
            let ((a1, a2), (b1, b2)) = (opposite(a, v), opposite(b, v));
            segment_meets_triangle(p(a1), p(a2), p(b[0]), p(b[1]), p(b[2]))
                || segment_meets_triangle(p(b1), p(b2), p(a[0]), p(a[1]), p(a[2]))
        }
        2 => {
            let (v, w) = (shared[0], shared[1]);
            let x = a
                .iter()
                .copied()
                .find(|u| !shared.contains(u))
                .expect("third node");
            let y = b
                .iter()
                .copied()
                .find(|u| !shared.contains(u))
                .expect("third node");
            if orient3d(p(v), p(w), p(x), p(y)) != 0.0 {
                return false;
            }
            let e = sub(p(w), p(v));
            dot(cross(e, sub(p(x), p(v))), cross(e, sub(p(y), p(v)))) > 0.0
        }
        _ => true,
    }
}
