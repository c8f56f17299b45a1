//! Broad phase over 2D boxes by a uniform grid: every box is listed in the grid cells it
//! covers (cells as large as the median box), and the boxes sharing a cell are tested pair
//! by pair, each pair only in the first cell both cover. Where many boxes share a range of
//! x but not of y (fronts running up and down, a circle's sides), the sort-and-sweep scans
//! them all; the grid does not. It visits exactly the pairs the sweep does, each named the
//! way the sweep names it, in another order; it falls back on the sweep when the grid would
//! not pay (few boxes, non-finite coordinates, boxes much larger than the median).

use crate::sweep::{Aabb, for_each_overlapping_pair};

/// Below this many boxes the sweep is used.
const FEW: usize = 64;
/// At most this many grid entries per box on average, else the sweep is used.
const MOST_ENTRIES_PER_BOX: usize = 8;

/// Calls `visit(i, j)` for every pair of overlapping boxes (closed: touching counts), each
/// pair once: the same pairs as [`for_each_overlapping_pair`], with `i` the box that comes
/// first by increasing low x (ties: lower index), as there; but in another order (by grid
/// cell), so only for callers whose outcome does not depend on the order of the pairs.
pub fn for_each_overlapping_pair_grid(boxes: &[Aabb<2>], mut visit: impl FnMut(usize, usize)) {
    let Some(grid) = Grid::new(boxes) else {
        return for_each_overlapping_pair(boxes, visit);
    };
    let mut entries: Vec<(u64, u32)> = Vec::with_capacity(2 * boxes.len());
    let mut spans = Vec::with_capacity(boxes.len());
    for (i, b) in boxes.iter().enumerate() {
        let span = grid.span(b);
        for y in span[1]..=span[3] {
            for x in span[0]..=span[2] {
                entries.push(((u64::from(y) << 32) | u64::from(x), i as u32));
            }
        }
        spans.push(span);
        if entries.len() > MOST_ENTRIES_PER_BOX * boxes.len() {
            return for_each_overlapping_pair(boxes, visit);
        }
    }
    entries.sort_unstable();
    let first_of = |i: usize| (boxes[i].lo[0], i);
    let mut start = 0;
    while start < entries.len() {
        let cell = entries[start].0;
        let end = start + entries[start..].partition_point(|e| e.0 == cell);
        let (cx, cy) = ((cell & 0xffff_ffff) as u32, (cell >> 32) as u32);
        for (k, &(_, a)) in entries[start..end].iter().enumerate() {
            let (a, sa) = (a as usize, spans[a as usize]);
            for &(_, b) in &entries[start + k + 1..end] {
                let (b, sb) = (b as usize, spans[b as usize]);
                // the first cell both cover: the pair is tested there only
                if sa[0].max(sb[0]) != cx || sa[1].max(sb[1]) != cy {
                    continue;
                }
                if !boxes[a].overlaps(&boxes[b]) {
                    continue;
                }
                let ((xa, _), (xb, _)) = (first_of(a), first_of(b));
                let a_first = match xa.total_cmp(&xb) {
                    std::cmp::Ordering::Less => true,
                    std::cmp::Ordering::Greater => false,
                    std::cmp::Ordering::Equal => a < b,
                };
                if a_first { visit(a, b) } else { visit(b, a) }
            }
        }
        start = end;
    }
}

/// The grid: its low corner, cell size and cell counts.
struct Grid {
    lo: [f64; 2],
    h: f64,
    n: [u32; 2],
}

impl Grid {
    /// The grid of cells the size of the median box's larger side, over all the boxes; None
    /// when the sweep should be used.
    fn new(boxes: &[Aabb<2>]) -> Option<Grid> {
        if boxes.len() < FEW || boxes.len() > u32::MAX as usize {
            return None;
        }
        let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
        for b in boxes {
            for k in 0..2 {
                if !(b.lo[k].is_finite() && b.hi[k].is_finite()) || b.lo[k] > b.hi[k] {
                    return None;
                }
                lo[k] = lo[k].min(b.lo[k]);
                hi[k] = hi[k].max(b.hi[k]);
            }
        }
        let mut sides: Vec<f64> = boxes
            .iter()
            .map(|b| (b.hi[0] - b.lo[0]).max(b.hi[1] - b.lo[1]))
            .collect();
        let mid = sides.len() / 2;
        let (_, &mut median, _) = sides.select_nth_unstable_by(mid, f64::total_cmp);
        let extent = (hi[0] - lo[0]).max(hi[1] - lo[1]);
        // no more cells than some boxes per cell on average would need
        let floor = extent / (4.0 * boxes.len() as f64).sqrt();
        let h = median.max(floor);
        if !(h > 0.0 && h.is_finite()) {
            return None;
        }
        let count = |k: usize| ((hi[k] - lo[k]) / h).floor() as u32 + 1;
        Some(Grid {
            lo,
            h,
            n: [count(0), count(1)],
        })
    }

    /// The cells `[x0, y0, x1, y1]` a box covers.
    fn span(&self, b: &Aabb<2>) -> [u32; 4] {
        let at = |v: f64, k: usize| (((v - self.lo[k]) / self.h).floor() as u32).min(self.n[k] - 1);
        [
            at(b.lo[0], 0),
            at(b.lo[1], 1),
            at(b.hi[0], 0),
            at(b.hi[1], 1),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    fn grid_pairs(boxes: &[Aabb<2>]) -> Vec<(usize, usize)> {
        let mut pairs = Vec::new();
        for_each_overlapping_pair_grid(boxes, |i, j| pairs.push((i, j)));
        pairs.sort_unstable();
        pairs
    }

    fn sweep_pairs(boxes: &[Aabb<2>]) -> Vec<(usize, usize)> {
        let mut pairs = Vec::new();
        for_each_overlapping_pair(boxes, |i, j| pairs.push((i, j)));
        pairs.sort_unstable();
        pairs
    }

    /// Segments along a circle and a smaller one inside, each box grown by a clearance of
    /// its own: the fronts of a mesh, boxes of many sizes, touching ones among them.
    fn fronts(n: usize, clearance: f64) -> Vec<Aabb<2>> {
        let mut boxes = Vec::new();
        for (r, m) in [(1.0, n), (0.3, n / 3)] {
            for i in 0..m {
                let a = std::f64::consts::TAU * i as f64 / m as f64;
                let b = std::f64::consts::TAU * (i + 1) as f64 / m as f64;
                let c = clearance * (1.0 + (i % 7) as f64);
                boxes.push(Aabb::of_segment(
                    [r * a.cos(), r * a.sin()],
                    [r * b.cos(), r * b.sin()],
                    c,
                ));
            }
        }
        boxes
    }

    #[test]
    fn the_pairs_are_those_of_the_sweep_named_alike() {
        for (n, c) in [(100, 0.0), (1000, 1e-3), (3000, 1e-2), (500, 0.2)] {
            let boxes = fronts(n, c);
            let pairs = grid_pairs(&boxes);
            assert!(!pairs.is_empty());
            assert_eq!(pairs, sweep_pairs(&boxes), "n {n} clearance {c}");
        }
    }

    #[test]
    fn equal_low_x_and_touching_boxes_are_named_as_the_sweep_names_them() {
        // a column of unit boxes, each touching the next; all share their low x
        let boxes: Vec<Aabb<2>> = (0..200)
            .rev()
            .map(|i| Aabb {
                lo: [0.0, f64::from(i)],
                hi: [1.0, f64::from(i + 1)],
            })
            .collect();
        assert_eq!(grid_pairs(&boxes).len(), 199);
        assert_eq!(grid_pairs(&boxes), sweep_pairs(&boxes));
    }

    #[test]
    fn a_non_finite_box_falls_back_on_the_sweep() {
        let mut boxes = fronts(200, 1e-3);
        boxes[3].hi[1] = f64::NAN;
        assert_eq!(grid_pairs(&boxes), sweep_pairs(&boxes));
    }

    proptest! {
        #[test]
        fn random_boxes_give_the_pairs_of_the_sweep(
            raw in prop::collection::vec((-10.0f64..10.0, -10.0f64..10.0, 0.0f64..1.5, 0.0f64..1.5), 0..400)
        ) {
            let boxes: Vec<Aabb<2>> = raw
                .iter()
                .map(|&(x, y, w, h)| Aabb { lo: [x, y], hi: [x + w, y + h] })
                .collect();
            prop_assert_eq!(grid_pairs(&boxes), sweep_pairs(&boxes));
        }
    }
}
