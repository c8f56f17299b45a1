//! Columns that stop (issue 47): where a column cannot take its next layer — a cell stays
//! inverted, or the new front crosses itself or another body's front, after the shrinks and
//! the unmerging of `grow`'s `settle_layer` — the front nodes of the failing cells keep
//! themselves as their children (`children`'s `kept`), so the cells beside them close the step
//! down to the stopped column with pyramids and tetrahedra, and the layer is checked again;
//! the rest keep growing. A stopped column never grows again.
//!
//! Around stopped columns the step down is made gradual: a front node may rise at most
//! [`STOP_SLOPE`] × its distance along the front from a stopped node above that node's
//! thickness ([`rises`]), so its layer is lower there; a node left less than [`MIN_RISE`] of
//! the layer's height stops too (why: [`StopWhy::Transition`]).

use std::cmp::Ordering;
use std::collections::BinaryHeap;

use geom_predicates::vector::dist;

use crate::StopWhy;
use crate::check::CROSSING;
use crate::front::Topo;

/// The steepest step (rise over distance along the front) between a stopped column and the
/// columns around it: 1, a 45° slope.
pub(crate) const STOP_SLOPE: f64 = 1.0;

/// A node whose layer [`rises`] would cut below this fraction of the layer's height stops
/// instead: thinner cells would only be slivers.
pub(crate) const MIN_RISE: f64 = 0.25;

/// A node and a distance (its allowed thickness here, its distance along the front in
/// `proximity`), for a heap that pops the smallest first.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Reach(pub(crate) f64, pub(crate) u32);

impl Eq for Reach {}

impl Ord for Reach {
    fn cmp(&self, other: &Self) -> Ordering {
        other.0.total_cmp(&self.0).then(other.1.cmp(&self.1))
    }
}

impl PartialOrd for Reach {
    fn partial_cmp(&self, other: &Self) -> Option<Ordering> {
        Some(self.cmp(other))
    }
}

/// How high each front node (positions `x`, edges `topo`) may rise in a layer of `height`:
/// `height`, or less near stopped nodes — at most `thick[s] + STOP_SLOPE × d(s, v) −
/// thick[v]` for every stopped node `s` (`d` the shortest path along the front's edges,
/// `thick` each node's thickness so far); 0 for a stopped node. Without stopped nodes every
/// node rises `height`.
pub(crate) fn rises(
    topo: &Topo,
    x: &[[f64; 3]],
    thick: &[f64],
    stopped: &[bool],
    height: f64,
) -> Vec<f64> {
    let n = x.len();
    if !stopped.iter().any(|&s| s) {
        return vec![height; n];
    }
    // the front's edges by node (CSR)
    let mut start = vec![0u32; n + 1];
    for e in &topo.edges {
        start[e.nodes[0] as usize + 1] += 1;
        start[e.nodes[1] as usize + 1] += 1;
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut next = vec![0u32; start[n] as usize];
    for e in &topo.edges {
        let [a, b] = e.nodes;
        next[fill[a as usize] as usize] = b;
        fill[a as usize] += 1;
        next[fill[b as usize] as usize] = a;
        fill[b as usize] += 1;
    }
    // the least allowed thickness, from every stopped node at once (Dijkstra); no node
    // beyond the thickest one plus a layer is limited
    let cutoff = thick.iter().copied().fold(0.0, f64::max) + height;
    let mut allowed = vec![f64::INFINITY; n];
    let mut heap = BinaryHeap::new();
    for v in (0..n).filter(|&v| stopped[v]) {
        allowed[v] = thick[v];
        heap.push(Reach(thick[v], v as u32));
    }
    while let Some(Reach(a, v)) = heap.pop() {
        let v = v as usize;
        if a > allowed[v] || a >= cutoff {
            continue;
        }
        for &w in &next[start[v] as usize..start[v + 1] as usize] {
            let w = w as usize;
            let b = a + STOP_SLOPE * dist(x[v], x[w]);
            if b < allowed[w] {
                allowed[w] = b;
                heap.push(Reach(b, w as u32));
            }
        }
    }
    (0..n)
        .map(|v| {
            if stopped[v] {
                0.0
            } else {
                (allowed[v] - thick[v]).clamp(0.0, height)
            }
        })
        .collect()
}

/// Why the nodes of a layer's failing cells stop, from what failed.
pub(crate) fn why_failed(what: &str) -> StopWhy {
    if what == CROSSING {
        StopWhy::FrontsCross
    } else {
        StopWhy::InvertedCell
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use geom_surface::Facet;

    /// A strip of unit squares along x (nodes 2i at y = 0, 2i + 1 at y = 1).
    fn strip(squares: u32) -> (Vec<[f64; 3]>, Topo) {
        let x: Vec<[f64; 3]> = (0..=squares)
            .flat_map(|i| [[i as f64, 0.0, 0.0], [i as f64, 1.0, 0.0]])
            .collect();
        let facets: Vec<Facet> = (0..squares)
            .map(|i| Facet::quad(2 * i, 2 * i + 2, 2 * i + 3, 2 * i + 1))
            .collect();
        (x, Topo::from_facets(&facets))
    }

    #[test]
    fn the_rise_grows_with_the_distance_from_a_stopped_column() {
        let (x, topo) = strip(5);
        let n = x.len();
        let thick = vec![1.0; n];
        let none = vec![false; n];
        assert_eq!(rises(&topo, &x, &thick, &none, 0.3), vec![0.3; n]);
        // node 0 stopped, as thick as the others: each node may rise its distance from it
        let mut stopped = none.clone();
        stopped[0] = true;
        let r = rises(&topo, &x, &thick, &stopped, 2.5);
        assert_eq!(r[0], 0.0);
        assert_eq!(r[1], 1.0); // one edge away
        assert_eq!(r[2], 1.0);
        assert!((r[3] - 2.0).abs() < 1e-12, "{}", r[3]); // two edges (no diagonals)
        assert_eq!(r[8], 2.5); // capped by the layer's height
        // a stopped node lower than the others holds them back further
        let mut low = thick.clone();
        low[0] = 0.5;
        let r = rises(&topo, &x, &low, &stopped, 2.5);
        assert_eq!(r[1], 0.5);
    }
}
