//! Broad phase over axis-aligned boxes by sort and sweep: sort the boxes on their low x, then
//! sweep each box against the following ones until their low x passes its high x, testing the
//! other axes. Unlike fixed-radius neighbour queries it works for boxes of very different
//! sizes; O(n log n + pairs in x) — quadratic only when most boxes overlap in x.

/// A closed axis-aligned box.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Aabb<const D: usize> {
    /// The lowest corner.
    pub lo: [f64; D],
    /// The highest corner.
    pub hi: [f64; D],
}

impl<const D: usize> Aabb<D> {
    /// The box of segment `a b` grown by `inflate` on every side.
    #[inline]
    pub fn of_segment(a: [f64; D], b: [f64; D], inflate: f64) -> Self {
        Aabb {
            lo: std::array::from_fn(|k| a[k].min(b[k]) - inflate),
            hi: std::array::from_fn(|k| a[k].max(b[k]) + inflate),
        }
    }

    /// The box of some points (`None` when there are none).
    pub fn of_points<P: Copy + Into<[f64; D]>>(points: &[P]) -> Option<Self> {
        let first: [f64; D] = (*points.first()?).into();
        let mut b = Aabb {
            lo: first,
            hi: first,
        };
        for &p in &points[1..] {
            let p: [f64; D] = p.into();
            b.lo = std::array::from_fn(|k| b.lo[k].min(p[k]));
            b.hi = std::array::from_fn(|k| b.hi[k].max(p[k]));
        }
        Some(b)
    }

    /// Whether the two closed boxes share a point.
    #[inline]
    pub fn overlaps(&self, other: &Self) -> bool {
        (0..D).all(|k| other.lo[k] <= self.hi[k] && other.hi[k] >= self.lo[k])
    }
}

/// Calls `visit(i, j)` for every pair of boxes that overlap (closed: touching counts), each pair
/// once, until `visit` returns `Some`; returns that value. The order is that of the sweep: `i`
/// runs over the boxes by increasing low x (ties in input order),
/// `j` over the boxes after `i` in that order; so `i < j` in input order is not guaranteed.
pub fn find_overlapping_pair<const D: usize, T>(
    boxes: &[Aabb<D>],
    mut visit: impl FnMut(usize, usize) -> Option<T>,
) -> Option<T> {
    let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
    // stable: ties keep the input order, and boxes listed along a curve come in a few
    // monotone runs in x, which the stable sort merges in nearly linear time
    order.sort_by(|&a, &b| boxes[a as usize].lo[0].total_cmp(&boxes[b as usize].lo[0]));
    // the boxes in sweep order, so that the scan reads memory in order
    let sorted: Vec<Aabb<D>> = order.iter().map(|&i| boxes[i as usize]).collect();
    for (k, (&i, bi)) in order.iter().zip(&sorted).enumerate() {
        for (&j, bj) in order[k + 1..].iter().zip(&sorted[k + 1..]) {
            if bj.lo[0] > bi.hi[0] {
                break;
            }
            let overlap = (1..D).all(|a| bj.lo[a] <= bi.hi[a] && bj.hi[a] >= bi.lo[a]);
            // (no let-chain: the workspace's rust-version is 1.85)
            let found = if overlap {
                visit(i as usize, j as usize)
            } else {
                None
            };
            if found.is_some() {
                return found;
            }
        }
    }
    None
}

/// Calls `visit(i, j)` for every pair of overlapping boxes, in the order of
/// [`find_overlapping_pair`].
#[inline]
pub fn for_each_overlapping_pair<const D: usize>(
    boxes: &[Aabb<D>],
    mut visit: impl FnMut(usize, usize),
) {
    find_overlapping_pair::<D, ()>(boxes, |i, j| {
        visit(i, j);
        None
    });
}

/// Every pair of overlapping boxes as `(i, j)` with `i < j`, sorted.
pub fn overlapping_pairs<const D: usize>(boxes: &[Aabb<D>]) -> Vec<(usize, usize)> {
    let mut pairs = Vec::new();
    for_each_overlapping_pair(boxes, |i, j| pairs.push((i.min(j), i.max(j))));
    pairs.sort_unstable();
    pairs
}
