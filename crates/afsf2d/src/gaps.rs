//! Narrow gaps between boundary loops: where two loops come nearer to each other than a
//! fraction of their node spacing, every cell across the gap has a corner near 180° unless
//! the nodes of the two sides face each other. A boundary facet AB of length s facing another
//! loop at distance w < s/3 can only be the side of a usable triangle whose third corner is a
//! node of the other side (no node inside so thin a channel helps, and layers grown in it keep
//! the same tangential spacing); when no such node gives a triangle with all angles below the
//! bound, the gap cannot be meshed with these boundary nodes and the mesher says so, naming
//! the gap, instead of returning slivers.
//!
//! It owns this test only; the boundary spacing is `boundary1d`'s.

use geom_predicates::vector::dist;
use geom_predicates::{closest_on_segment, for_each_overlapping_pair, orient2d};

use crate::geom::{Aabb, P2};

/// A gap between two loops that the boundary nodes cannot resolve.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct NarrowGap {
    /// The loop of the facet that has no usable triangle across the gap.
    pub loop_a: usize,
    /// The loop it faces.
    pub loop_b: usize,
    /// Distance between the two loops there.
    pub width: f64,
    /// A point in the gap.
    pub at: [f64; 2],
    /// The length of the facet (boundary node spacing there).
    pub spacing: f64,
    /// The smallest largest angle of a triangle on that facet with a corner across the gap.
    pub best_angle_deg: f64,
}

/// A facet is in a narrow gap when another loop is nearer than this fraction of its length.
const NARROW: f64 = 1.0 / 3.0;

/// The narrowest gap (loops `a` ≠ `b`) where a facet has no triangle across the gap with all
/// angles below `max_angle_deg`, or None. `loops[i]` are the loop's points in order with the
/// domain on the left.
pub(crate) fn unresolved_gap(loops: &[Vec<P2>], max_angle_deg: f64) -> Option<NarrowGap> {
    let mut facets: Vec<(usize, P2, P2)> = Vec::new();
    for (li, l) in loops.iter().enumerate() {
        let n = l.len();
        facets.extend((0..n).map(|i| (li, l[i], l[(i + 1) % n])));
    }
    let boxes: Vec<Aabb> = facets
        .iter()
        .map(|&(_, a, b)| Aabb::of_segment(a, b, NARROW * dist(a, b)))
        .collect();
    // per facet: nearest other-loop facet distance, its loop, and candidate third corners
    let mut near: Vec<(f64, usize, Vec<P2>)> =
        vec![(f64::INFINITY, usize::MAX, Vec::new()); facets.len()];
    for_each_overlapping_pair(&boxes, |x, y| {
        let (fx, fy) = (facets[x], facets[y]);
        if fx.0 == fy.0 {
            return;
        }
        for (i, o) in [(x, fy), (y, fx)] {
            let (a, b) = (facets[i].1, facets[i].2);
            let s = dist(a, b);
            let Some(d) = distance_in_front(a, b, o.1, o.2) else {
                continue;
            };
            if d >= NARROW * s {
                continue;
            }
            let entry = &mut near[i];
            if d < entry.0 {
                entry.0 = d;
                entry.1 = o.0;
            }
            entry.2.push(o.1);
            entry.2.push(o.2);
        }
    });
    let mut worst: Option<NarrowGap> = None;
    for (i, (w, other, corners)) in near.iter().enumerate() {
        if corners.is_empty() {
            continue;
        }
        let (li, a, b) = facets[i];
        let best = corners
            .iter()
            .filter(|&&c| orient2d(a, b, c) > 0.0)
            .map(|&c| crate::quality::max_triangle_angle_deg(a, b, c))
            .fold(180.0f64, f64::min);
        if best < max_angle_deg {
            continue;
        }
        if worst.is_some_and(|g| g.width <= *w) {
            continue;
        }
        let s = dist(a, b);
        let mid = [0.5 * (a[0] + b[0]), 0.5 * (a[1] + b[1])];
        // a point in the gap: halfway from the facet's middle toward the other side
        let foot = corners
            .chunks(2)
            .map(|c| closest_on_segment(mid, c[0], c[1]))
            .min_by(|p, q| dist(mid, *p).total_cmp(&dist(mid, *q)))
            .unwrap_or(mid);
        worst = Some(NarrowGap {
            loop_a: li,
            loop_b: *other,
            width: *w,
            at: [0.5 * (mid[0] + foot[0]), 0.5 * (mid[1] + foot[1])],
            spacing: s,
            best_angle_deg: best,
        });
    }
    worst
}

/// The least distance from facet AB to the part of segment CD that lies in front of it (on
/// its left, between the normals at A and B), or None when no part of CD is there: a loop
/// beside the facet (at the mouth of a gap) leaves the room in front of it open.
fn distance_in_front(a: P2, b: P2, c: P2, d: P2) -> Option<f64> {
    let ab = [b[0] - a[0], b[1] - a[1]];
    let s = (ab[0] * ab[0] + ab[1] * ab[1]).sqrt();
    if s == 0.0 {
        return None;
    }
    let local = |p: P2| {
        let v = [p[0] - a[0], p[1] - a[1]];
        (
            (v[0] * ab[0] + v[1] * ab[1]) / (s * s),
            (ab[0] * v[1] - ab[1] * v[0]) / s,
        )
    };
    let ((tc, uc), (td, ud)) = (local(c), local(d));
    // clip CD to 0 <= t <= 1
    let (mut lo, mut hi) = (0.0f64, 1.0f64);
    if tc == td {
        if !(0.0..=1.0).contains(&tc) {
            return None;
        }
    } else {
        let (k0, k1) = ((0.0 - tc) / (td - tc), (1.0 - tc) / (td - tc));
        lo = lo.max(k0.min(k1));
        hi = hi.min(k0.max(k1));
        if lo > hi {
            return None;
        }
    }
    let u = |k: f64| uc + k * (ud - uc);
    let m = u(lo).min(u(hi));
    (m > 0.0).then_some(m)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn strip(y: f64, xs: &[f64], up: bool) -> Vec<P2> {
        // a thin box whose long side at height y carries the nodes xs, domain on the left
        let mut p: Vec<P2> = xs.iter().map(|&x| [x, y]).collect();
        let h = if up { -1.0 } else { 1.0 };
        p.push([xs[xs.len() - 1], y + h]);
        p.push([xs[0], y + h]);
        if !up {
            p.reverse();
        }
        p
    }

    #[test]
    fn facing_nodes_pass_and_offset_nodes_are_named() {
        let xs = [0.0, 1.0, 2.0, 3.0];
        // lower body (domain above its top side), upper body 1e-3 above, nodes facing
        let lower = strip(0.0, &xs, true);
        let upper = strip(1e-3, &xs, false);
        assert!(unresolved_gap(&[lower.clone(), upper], 135.0).is_none());
        // the lower facet from 1 to 2 has no node across the gap near either end
        let shifted = [0.0, 0.5, 2.5, 3.0];
        let upper = strip(1e-3, &shifted, false);
        let g = unresolved_gap(&[lower, upper], 135.0).expect("a gap");
        assert!((g.width - 1e-3).abs() < 1e-12, "{g:?}");
        assert!(g.best_angle_deg > 170.0, "{g:?}");
        assert!((g.at[1] - 5e-4).abs() < 1e-9, "{g:?}");
    }
}
