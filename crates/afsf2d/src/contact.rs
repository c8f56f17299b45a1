//! The contact test of two front edges: whether they meet other than at a node they share.
//! The step verification (`grow`) and the whole-state check (`sanity`) both use it.

use geom_predicates::vector::dot;
use geom_predicates::{orient2d, segments_meet};

use crate::geom::P2;

/// True when front edges `x` and `y` (node pairs) meet other than at a node they share:
/// edges with no common node must not meet at all, edges with one common node may touch
/// only there (not overlap along a line), and two edges on the same two nodes always meet.
pub(crate) fn front_edges_meet(pos: &[P2], x: [u32; 2], y: [u32; 2]) -> bool {
    let shared = x.iter().filter(|n| **n == y[0] || **n == y[1]).count();
    let (pa, pb, pc, pd) = (
        pos[x[0] as usize],
        pos[x[1] as usize],
        pos[y[0] as usize],
        pos[y[1] as usize],
    );
    match shared {
        0 => segments_meet(pa, pb, pc, pd),
        1 => {
            // consecutive edges: they may only meet at the shared node
            let (s, ox, oy) = if x[0] == y[0] {
                (pa, pb, pd)
            } else if x[0] == y[1] {
                (pa, pb, pc)
            } else if x[1] == y[0] {
                (pb, pa, pd)
            } else {
                (pb, pa, pc)
            };
            orient2d(s, ox, oy) == 0.0
                && dot([ox[0] - s[0], ox[1] - s[1]], [oy[0] - s[0], oy[1] - s[1]]) > 0.0
        }
        _ => true,
    }
}
