//! Planar names used across afsf2d: a point is `[f64; 2]` and a box is 2D. The predicates
//! themselves (exact orientation, segment crossing and distance, projection, sort-and-sweep)
//! and the polygon area are the shared ones of `geom-predicates`; [`par_overlapping`] runs
//! the same sort-and-sweep on every thread, for the tests whose result is a set;
//! [`par_overlapping_grid`] finds the same pairs through a uniform grid, for sets of boxes
//! where many boxes share a range of x without meeting (the fronts of a far-field circle).

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

/// Grid cells per box at most: a grid finer than this costs more to fill than it saves.
const GRID_CELLS_PER_BOX: usize = 2;

/// Grid entries per box at most before [`par_overlapping_grid`] falls back to the sweep
/// (boxes much larger than the typical one, covering many cells each).
const GRID_ENTRIES_PER_BOX: usize = 12;

/// The pairs of [`par_overlapping`], each visited as `visit(i, j, out)` with the same `i` and
/// `j` (`i` the first of the two in the sweep's order: by low x, ties by index), found through
/// a uniform grid instead of the sweep: each box is listed in every grid cell it covers and a
/// pair is visited in the first cell both cover. The findings come back in grid order
/// (deterministic, whatever the number of threads), not in the sweep's: for set results
/// only. Falls back to [`par_overlapping`] when a coordinate is not finite or the boxes are
/// too unequal for one cell size.
pub(crate) fn par_overlapping_grid<T: Send>(
    boxes: &[Aabb],
    visit: impl Fn(usize, usize, &mut Vec<T>) + Sync,
) -> Vec<T> {
    let Some(grid) = Grid::new(boxes) else {
        return par_overlapping(boxes, visit);
    };
    let rows_per_task = (SWEEP_CHUNK / grid.nx.max(1)).max(1);
    let found: Vec<Vec<T>> = (0..grid.ny.div_ceil(rows_per_task))
        .into_par_iter()
        .map(|task| {
            let mut out = Vec::new();
            let rows = task * rows_per_task..((task + 1) * rows_per_task).min(grid.ny);
            for cell in rows.start * grid.nx..rows.end * grid.nx {
                grid.pairs_in(cell, boxes, &visit, &mut out);
            }
            out
        })
        .collect();
    found.into_iter().flatten().collect()
}

/// Whether box `i` comes before box `j` in the sweep's order (low x, ties by index).
#[inline]
fn sweeps_first(boxes: &[Aabb], i: usize, j: usize) -> bool {
    boxes[i].lo[0].total_cmp(&boxes[j].lo[0]).then(i.cmp(&j)) == std::cmp::Ordering::Less
}

/// A uniform grid over boxes: `entries[start[c]..start[c + 1]]` are the boxes covering cell
/// `c` (row-major, `nx` cells a row), by increasing index.
struct Grid {
    nx: usize,
    ny: usize,
    start: Vec<u32>,
    entries: Vec<Entry>,
}

/// A box listed in a grid cell, with the first cell it covers.
#[derive(Clone, Copy, Default)]
struct Entry {
    index: u32,
    first: [u32; 2],
}

impl Grid {
    /// The grid of `boxes`, its cell the median of their larger sides (at most
    /// [`GRID_CELLS_PER_BOX`] cells a box); `None` when a coordinate is not finite, there are
    /// fewer than two boxes or more than [`GRID_ENTRIES_PER_BOX`] entries a box.
    fn new(boxes: &[Aabb]) -> Option<Self> {
        let n = boxes.len();
        let finite = |b: &Aabb| b.lo.iter().chain(&b.hi).all(|v| v.is_finite());
        if n < 2 || n >= u32::MAX as usize || !boxes.iter().all(finite) {
            return None;
        }
        let mut lo = boxes[0].lo;
        let mut hi = boxes[0].hi;
        for b in boxes {
            for k in 0..2 {
                lo[k] = lo[k].min(b.lo[k]);
                hi[k] = hi[k].max(b.hi[k]);
            }
        }
        // the median larger side of (at most) 1024 boxes spread through the list
        let samples = n.min(1024);
        let mut sides: Vec<f64> = (0..samples)
            .map(|k| {
                let b = &boxes[k * n / samples];
                (b.hi[0] - b.lo[0]).max(b.hi[1] - b.lo[1])
            })
            .collect();
        let mid = samples / 2;
        let (_, &mut median, _) = sides.select_nth_unstable_by(mid, f64::total_cmp);
        let (w, h) = (hi[0] - lo[0], hi[1] - lo[1]);
        let most = (GRID_CELLS_PER_BOX * n) as f64;
        let mut side = median.max(f64::MIN_POSITIVE);
        if (w / side + 1.0) * (h / side + 1.0) > most {
            side = side.max(((w * h) / most).sqrt()).max(w.max(h) / most);
        }
        let nx = ((w / side) as usize + 1).min(n * GRID_CELLS_PER_BOX);
        let ny = ((h / side) as usize + 1).min(n * GRID_CELLS_PER_BOX);
        let at = |v: f64, k: usize, cells: usize| (((v - lo[k]) / side) as usize).min(cells - 1);
        let span = |b: &Aabb| {
            (
                [at(b.lo[0], 0, nx), at(b.lo[1], 1, ny)],
                [at(b.hi[0], 0, nx), at(b.hi[1], 1, ny)],
            )
        };
        let mut start = vec![0u32; nx * ny + 1];
        let mut total = 0usize;
        for b in boxes {
            let (a, z) = span(b);
            total += (z[0] - a[0] + 1) * (z[1] - a[1] + 1);
            if total > GRID_ENTRIES_PER_BOX * n {
                return None;
            }
            for y in a[1]..=z[1] {
                for x in a[0]..=z[0] {
                    start[y * nx + x + 1] += 1;
                }
            }
        }
        for c in 0..nx * ny {
            start[c + 1] += start[c];
        }
        let mut fill = start.clone();
        let mut entries = vec![Entry::default(); total];
        for (i, b) in boxes.iter().enumerate() {
            let (a, z) = span(b);
            let entry = Entry {
                index: i as u32,
                first: [a[0] as u32, a[1] as u32],
            };
            for y in a[1]..=z[1] {
                for x in a[0]..=z[0] {
                    let c = y * nx + x;
                    entries[fill[c] as usize] = entry;
                    fill[c] += 1;
                }
            }
        }
        Some(Grid {
            nx,
            ny,
            start,
            entries,
        })
    }

    /// Visits the overlapping pairs whose first common cell is `cell`.
    fn pairs_in<T>(
        &self,
        cell: usize,
        boxes: &[Aabb],
        visit: &impl Fn(usize, usize, &mut Vec<T>),
        out: &mut Vec<T>,
    ) {
        let here = [(cell % self.nx) as u32, (cell / self.nx) as u32];
        let list = &self.entries[self.start[cell] as usize..self.start[cell + 1] as usize];
        for (k, ea) in list.iter().enumerate() {
            let a = ea.index as usize;
            let ba = &boxes[a];
            for eb in &list[k + 1..] {
                // the first cell both cover: the larger of their first cells on each axis
                if ea.first[0].max(eb.first[0]) != here[0]
                    || ea.first[1].max(eb.first[1]) != here[1]
                {
                    continue;
                }
                let b = eb.index as usize;
                if !ba.overlaps(&boxes[b]) {
                    continue;
                }
                if sweeps_first(boxes, a, b) {
                    visit(a, b, out);
                } else {
                    visit(b, a, out);
                }
            }
        }
    }
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

    /// The grid finds exactly the sweep's pairs, each the same way round, for boxes of very
    /// different sizes (a ring of small boxes, some large ones, some equal low x), with one
    /// thread and with several.
    #[test]
    fn the_grid_finds_the_sweeps_pairs_the_same_way_round() {
        let mut rng = testkit::layered::Rng(7);
        let mut next = || rng.unit();
        let mut boxes: Vec<Aabb> = (0..5000)
            .map(|k| {
                let t = std::f64::consts::TAU * k as f64 / 5000.0;
                let (p, r) = ([20.0 * t.cos(), 20.0 * t.sin()], 0.08 * next());
                let q = [p[0] + r * (t + 1.0).cos(), p[1] + r * (t + 1.0).sin()];
                Aabb::of_segment(p, q, 0.02 * next())
            })
            .collect();
        for k in 0..300 {
            let x = if k % 5 == 0 {
                3.0
            } else {
                40.0 * next() - 20.0
            };
            let p = [x, 40.0 * next() - 20.0];
            let s = if k % 50 == 0 { 5.0 } else { 0.1 };
            boxes.push(Aabb::of_segment(
                p,
                [x + s * next(), p[1] + s * next()],
                0.0,
            ));
        }
        let mut expected = Vec::new();
        geom_predicates::for_each_overlapping_pair(&boxes, |i, j| expected.push((i, j)));
        expected.sort_unstable();
        assert!(expected.len() > 3000, "{} pairs", expected.len());
        assert!(Grid::new(&boxes).is_some(), "the grid, not the fallback");
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut found = pool.install(|| {
                par_overlapping_grid(&boxes, |i, j, out: &mut Vec<(usize, usize)>| {
                    out.push((i, j))
                })
            });
            found.sort_unstable();
            assert_eq!(found, expected, "{threads} threads");
        }
        // too few boxes, or a coordinate not finite: the sweep's pairs all the same
        assert!(Grid::new(&boxes[..1]).is_none());
        let mut odd = boxes[..100].to_vec();
        odd[3].hi[0] = f64::INFINITY;
        assert!(Grid::new(&odd).is_none());
    }
}
