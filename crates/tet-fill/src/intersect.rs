//! The input facets must meet only at their shared corners and edges: a facet crossing another
//! cannot be a face of a tetrahedralisation without splitting one of them, so such an input is
//! refused up front (a sweep over the facets' boxes, then exact triangle tests), naming both.

use crate::FillInput;
use crate::error::FillError;
use geom_predicates::{Aabb, find_overlapping_pair, segment_meets_triangle, triangles_meet};

/// Refuses facets that meet other than at shared corners or edges.
pub(crate) fn check_disjoint(input: &FillInput) -> Result<(), FillError> {
    let corners = |f: [u32; 3]| f.map(|v| input.points[v as usize]);
    let boxes: Vec<Aabb<3>> = input
        .facets
        .iter()
        .map(|&f| Aabb::of_points(&corners(f)).expect("three corners"))
        .collect();
    let hit = find_overlapping_pair(&boxes, |i, j| {
        meet(input, input.facets[i], input.facets[j]).then_some((i.min(j), i.max(j)))
    });
    match hit {
        None => Ok(()),
        Some((i, j)) => Err(FillError::Unrecoverable {
            facet: i,
            corners: Box::new(corners(input.facets[i])),
            why: format!(
                "it meets facet {j} {:?}: the input surfaces intersect",
                corners(input.facets[j])
            ),
            edge: None,
            missing_edges: Vec::new(),
        }),
    }
}

/// Whether facets `f` and `g` meet elsewhere than at what they share.
fn meet(input: &FillInput, f: [u32; 3], g: [u32; 3]) -> bool {
    let p = |v: u32| input.points[v as usize];
    let shared: Vec<u32> = f.iter().copied().filter(|v| g.contains(v)).collect();
    match shared.len() {
        0 => triangles_meet(f.map(p), g.map(p)),
        // one corner shared: the edge of each opposite it must miss the other
        1 => {
            let s = shared[0];
            let opposite = |t: [u32; 3]| {
                let k = t.iter().position(|&v| v == s).unwrap_or(0);
                (t[(k + 1) % 3], t[(k + 2) % 3])
            };
            let [ga, gb, gc] = g.map(p);
            let [fa, fb, fc] = f.map(p);
            let (x, y) = opposite(f);
            let (u, w) = opposite(g);
            segment_meets_triangle(p(x), p(y), ga, gb, gc)
                || segment_meets_triangle(p(u), p(w), fa, fb, fc)
        }
        // an edge shared: folded onto each other only when coplanar, left to recovery
        _ => false,
    }
}
