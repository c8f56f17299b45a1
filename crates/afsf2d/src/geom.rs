//! Planar names used across afsf2d: a point is `[f64; 2]` and a box is 2D. The predicates
//! themselves (exact orientation, segment crossing and distance, projection, sort-and-sweep)
//! and the polygon area are the shared ones of `geom-predicates`; [`par_overlapping`] runs
//! the same sort-and-sweep on every thread, for the tests whose result is a set.

use rayon::prelude::*;

pub(crate) type P2 = [f64; 2];

/// An axis-aligned 2D box for the sort-and-sweep of `geom-predicates`.
pub(crate) type Aabb = geom_predicates::Aabb<2>;

/// Boxes of the sweep handed to one task: large enough that a task's work outweighs its
/// scheduling, small enough that both threads get many.
const SWEEP_CHUNK: usize = 2048;

/// The sort-and-sweep of `geom_predicates::for_each_overlapping_pair` on every thread:
/// `visit(i, j, out)` is called once for every overlapping pair (the same pairs, `i` before
/// `j` in the sweep order) and appends what it finds to `out`; the findings come back in the
/// sweep order, whatever the number of threads. The sort is stable, as the sequential one.
pub(crate) fn par_overlapping<T: Send>(
    boxes: &[Aabb],
    visit: impl Fn(usize, usize, &mut Vec<T>) + Sync,
) -> Vec<T> {
    if rayon::current_num_threads() == 1 {
        let mut out = Vec::new();
        geom_predicates::for_each_overlapping_pair(boxes, |i, j| visit(i, j, &mut out));
        return out;
    }
    let mut order: Vec<u32> = (0..boxes.len() as u32).collect();
    order.par_sort_by(|&a, &b| boxes[a as usize].lo[0].total_cmp(&boxes[b as usize].lo[0]));
    let sorted: Vec<Aabb> = order.par_iter().map(|&i| boxes[i as usize]).collect();
    let (order, sorted) = (&order, &sorted);
    let found: Vec<Vec<T>> = (0..sorted.len().div_ceil(SWEEP_CHUNK))
        .into_par_iter()
        .map(|chunk| {
            let mut out = Vec::new();
            let start = chunk * SWEEP_CHUNK;
            let end = (start + SWEEP_CHUNK).min(sorted.len());
            for k in start..end {
                let (i, bi) = (order[k] as usize, &sorted[k]);
                for (&j, bj) in order[k + 1..].iter().zip(&sorted[k + 1..]) {
                    if bj.lo[0] > bi.hi[0] {
                        break;
                    }
                    if bj.lo[1] <= bi.hi[1] && bj.hi[1] >= bi.lo[1] {
                        visit(i, j as usize, &mut out);
                    }
                }
            }
            out
        })
        .collect();
    found.into_iter().flatten().collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The parallel sweep finds the pairs of the sequential one, in its order, with one
    /// thread and with several.
    #[test]
    fn the_parallel_sweep_finds_the_sequential_pairs_in_order() {
        let mut rng = testkit::layered::Rng(99);
        let mut next = || rng.unit();
        // many boxes, some with equal low x (ties keep the input order)
        let boxes: Vec<Aabb> = (0..3 * SWEEP_CHUNK)
            .map(|i| {
                let x = if i % 7 == 0 { 0.5 } else { next() };
                let p = [x, next()];
                let q = [x + 0.01 * next(), p[1] + 0.01 * next()];
                Aabb::of_segment(p, q, 0.001)
            })
            .collect();
        let mut expected = Vec::new();
        geom_predicates::for_each_overlapping_pair(&boxes, |i, j| expected.push((i, j)));
        assert!(expected.len() > 1000);
        for threads in [1, 2, 3] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let found = pool.install(|| {
                par_overlapping(&boxes, |i, j, out: &mut Vec<(usize, usize)>| {
                    out.push((i, j))
                })
            });
            assert_eq!(found, expected, "{threads} threads");
        }
    }
}
