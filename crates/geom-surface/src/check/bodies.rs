//! The bodies of a surface that passed the other checks (closed, manifold, oriented, not
//! self-intersecting): its connected components (facets sharing a node), each enclosing a
//! positive volume and none inside another. Whether a body lies inside another is decided
//! by the winding number of one of its nodes about the other body (the sum of the solid
//! angles of that body's triangles over 4π, an integer for a closed surface and a point off
//! it: 0 outside); the surfaces do not meet, so one node tells for the whole body.

use crate::{Surface, cross, dot, facet_volume6, norm, sub};

/// One body: its facets, in increasing order.
pub(super) struct Body {
    pub facets: Vec<u32>,
}

/// The connected components of the facets (two facets in one when they share a node),
/// ordered by their first facet.
pub(super) fn bodies(s: &Surface) -> Vec<Body> {
    let mut parent: Vec<u32> = (0..s.nodes.len() as u32).collect();
    fn root(parent: &mut [u32], mut v: u32) -> u32 {
        while parent[v as usize] != v {
            let up = parent[parent[v as usize] as usize];
            parent[v as usize] = up; // path halving
            v = up;
        }
        v
    }
    for f in &s.facets {
        let k = f.nodes();
        for &v in &k[1..] {
            let (a, b) = (root(&mut parent, k[0]), root(&mut parent, v));
            parent[a.max(b) as usize] = a.min(b);
        }
    }
    let mut body_of_root = vec![u32::MAX; s.nodes.len()];
    let mut out: Vec<Body> = Vec::new();
    for (i, f) in s.facets.iter().enumerate() {
        let r = root(&mut parent, f.nodes()[0]) as usize;
        if body_of_root[r] == u32::MAX {
            body_of_root[r] = out.len() as u32;
            out.push(Body { facets: Vec::new() });
        }
        out[body_of_root[r] as usize].facets.push(i as u32);
    }
    out
}

/// The volume `body` encloses (divergence theorem, facets fanned from their centroid).
pub(super) fn volume(s: &Surface, body: &Body) -> f64 {
    let o = s.nodes[s.facets[body.facets[0] as usize].nodes()[0] as usize];
    body.facets
        .iter()
        .map(|&f| facet_volume6(&s.nodes, s.facets[f as usize].nodes(), o))
        .sum::<f64>()
        / 6.0
}

/// The bounding box of `body`'s nodes.
fn bounds(s: &Surface, body: &Body) -> ([f64; 3], [f64; 3]) {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for &f in &body.facets {
        for &v in s.facets[f as usize].nodes() {
            let p = s.nodes[v as usize];
            for d in 0..3 {
                lo[d] = lo[d].min(p[d]);
                hi[d] = hi[d].max(p[d]);
            }
        }
    }
    (lo, hi)
}

/// The winding number of `p` about the closed `body` (quads split into two triangles):
/// 1 inside a body facing out, 0 outside. `p` must not lie on the body.
pub(super) fn winding_number(s: &Surface, body: &Body, p: [f64; 3]) -> i64 {
    let mut sum = 0.0;
    for &f in &body.facets {
        for t in s.facets[f as usize].triangles() {
            let [a, b, c] = t.map(|v| sub(s.nodes[v as usize], p));
            // Van Oosterom and Strackee: tan(Ω/2) = det / denominator
            let (la, lb, lc) = (norm(a), norm(b), norm(c));
            let det = dot(a, cross(b, c));
            let den = la * lb * lc + dot(a, b) * lc + dot(a, c) * lb + dot(b, c) * la;
            sum += 2.0 * det.atan2(den);
        }
    }
    (sum / (4.0 * std::f64::consts::PI)).round() as i64
}

/// The first body (by its first facet) inside another, with that other: `(inner, outer)`.
pub(super) fn first_nested(s: &Surface, bodies: &[Body]) -> Option<(usize, usize)> {
    let boxes: Vec<_> = bodies.iter().map(|b| bounds(s, b)).collect();
    for (i, inner) in bodies.iter().enumerate() {
        let p = s.nodes[s.facets[inner.facets[0] as usize].nodes()[0] as usize];
        for (j, outer) in bodies.iter().enumerate() {
            let (lo, hi) = boxes[j];
            // a point out of the other's box is outside it; no sum needed
            let in_box = (0..3).all(|d| lo[d] <= p[d] && p[d] <= hi[d]);
            if i != j && in_box && winding_number(s, outer, p) != 0 {
                return Some((i, j));
            }
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(64))]

        /// The winding number about a sphere and a cube of quads is 1 inside and 0 outside,
        /// whatever the point.
        #[test]
        fn winding_numbers_tell_inside_from_outside(
            p in proptest::array::uniform3(-2.0f64..2.0),
        ) {
            let sphere = Surface::sphere(1.0, 2);
            let all = bodies(&sphere);
            prop_assert_eq!(all.len(), 1);
            let r = dot(p, p).sqrt();
            if (r - 1.0).abs() > 0.06 {
                let want = i64::from(r < 1.0);
                prop_assert_eq!(winding_number(&sphere, &all[0], p), want);
            }
            let cube = Surface::cube(2.0, 3, false).translated([-1.0; 3]);
            let all = bodies(&cube);
            let inside = p.iter().all(|x| x.abs() < 1.0);
            if p.iter().all(|x| (x.abs() - 1.0).abs() > 1e-9) {
                prop_assert_eq!(winding_number(&cube, &all[0], p), i64::from(inside));
            }
        }
    }

    impl Surface {
        fn translated(mut self, by: [f64; 3]) -> Surface {
            self.nodes
                .iter_mut()
                .for_each(|q| (0..3).for_each(|d| q[d] += by[d]));
            self
        }
    }
}
