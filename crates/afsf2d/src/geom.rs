//! Planar names used across afsf2d: a point is `[f64; 2]` and a box is 2D. The predicates
//! themselves (exact orientation, segment crossing and distance, projection, sort-and-sweep)
//! and the polygon area are the shared ones of `geom-predicates`; [`par_overlapping`] runs
//! the same sort-and-sweep on every thread, for the tests whose result is a set;
//! [`par_overlapping_strips_in`] finds the same pairs by a sweep within horizontal strips, for
//! sets of boxes where many share a range of x without meeting (the fronts of a far-field
//! circle).

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

/// Strip entries per box at most before [`par_overlapping_strips_in`] falls back to the sweep
/// (boxes much taller than the typical one, crossing many strips each).
const STRIP_ENTRIES_PER_BOX: usize = 8;

/// Boxes from which [`Strips::rebuild`] runs on two threads.
const PARALLEL_STRIP_BOXES: usize = 4096;

/// [`par_overlapping_strips_in`] with strips of its own.
#[cfg(test)]
pub(crate) fn par_overlapping_strips<T: Send>(
    boxes: &[Aabb],
    visit: impl Fn(usize, usize, &mut Vec<T>) + Sync,
) -> Vec<T> {
    par_overlapping_strips_in(&mut Strips::default(), boxes, visit)
}

/// The pairs of [`par_overlapping`], each visited as `visit(i, j, out)` with the same `i` and
/// `j` (`i` the first of the two in the sweep's order: by low x, ties by index), found by a
/// sweep within horizontal strips: each box is listed in every strip (of the median box's
/// larger side) it crosses, and a pair is visited in the first strip both cross. Where many
/// boxes share a range of x far apart in y (the fronts of a far-field circle: the whole sweep
/// met the far side of the circle), a strip holds only the near ones. The findings come back
/// in strip order (deterministic, whatever the number of threads), not in the sweep's: for
/// set results only. Falls back to [`par_overlapping`] when a coordinate is not finite or
/// the boxes are too unequal in height.
///
/// The strips are built in `strips`, whose memory a caller that runs this again and again
/// keeps (the layer steps' closing and front tests: at 1M cells fresh buffers each step were
/// a third of the run's page faults).
pub(crate) fn par_overlapping_strips_in<T: Send>(
    strips: &mut Strips,
    boxes: &[Aabb],
    visit: impl Fn(usize, usize, &mut Vec<T>) + Sync,
) -> Vec<T> {
    if !strips.rebuild(boxes) {
        return par_overlapping(boxes, visit);
    }
    let strips = &*strips;
    // tasks of about SWEEP_CHUNK entries, whole strips each
    let (mut tasks, mut first) = (vec![0usize], 0usize);
    for row in 0..strips.rows() {
        if (strips.start[row + 1] - strips.start[first]) as usize >= SWEEP_CHUNK {
            first = row + 1;
            tasks.push(first);
        }
    }
    if first != strips.rows() {
        tasks.push(strips.rows());
    }
    let found: Vec<Vec<T>> = tasks
        .par_windows(2)
        .map(|rows| {
            let mut out = Vec::new();
            for row in rows[0]..rows[1] {
                strips.sweep(row, boxes, &visit, &mut out);
            }
            out
        })
        .collect();
    found.into_iter().flatten().collect()
}

/// Boxes by horizontal strip: `entries[start[r]..start[r + 1]]` are the boxes crossing strip
/// `r`, in the sweep's order (low x, ties by index). Built again in place for each set of
/// boxes ([`Strips::rebuild`]).
#[derive(Default)]
pub(crate) struct Strips {
    start: Vec<u32>,
    entries: Vec<Entry>,
    /// Where the next entry of each strip goes, while building.
    fill: Vec<u32>,
    /// The first and last strip of each box, while building.
    spans: Vec<[u32; 2]>,
}

/// A box listed in a strip: its low and high x, index and first strip.
#[derive(Clone, Copy, Default)]
struct Entry {
    lo: f64,
    hi: f64,
    index: u32,
    first: u32,
}

/// The boxes' range of y, `None` when a coordinate is not finite; on `two` threads.
fn range_of_y(boxes: &[Aabb], two: bool) -> Option<(f64, f64)> {
    let of_box = |b: &Aabb| {
        let finite = b.lo.iter().chain(&b.hi).all(|v| v.is_finite());
        (finite, b.lo[1], b.hi[1])
    };
    let both = |a: (bool, f64, f64), b: (bool, f64, f64)| (a.0 && b.0, a.1.min(b.1), a.2.max(b.2));
    let none = (true, f64::INFINITY, f64::NEG_INFINITY);
    let (finite, y0, y1) = if two {
        boxes.par_iter().map(of_box).reduce(|| none, both)
    } else {
        boxes.iter().map(of_box).fold(none, both)
    };
    finite.then_some((y0, y1))
}

impl Strips {
    /// The strips of `boxes`, or `None` where [`Strips::rebuild`] says false.
    #[cfg(test)]
    fn new(boxes: &[Aabb]) -> Option<Self> {
        let mut strips = Strips::default();
        strips.rebuild(boxes).then_some(strips)
    }

    /// Makes these the strips of `boxes`, their memory reused: strips as tall as the median
    /// larger side of the boxes (of 1024 spread through the list; at most as many strips as
    /// boxes); false when a coordinate is not finite, there are fewer than two boxes, or more
    /// than [`STRIP_ENTRIES_PER_BOX`] entries a box. From [`PARALLEL_STRIP_BOXES`] boxes on,
    /// the strips are counted and filled on two threads, each for a range of strips (the
    /// same entries in the same places).
    fn rebuild(&mut self, boxes: &[Aabb]) -> bool {
        let n = boxes.len();
        if n < 2 || n >= u32::MAX as usize {
            return false;
        }
        let two = n >= PARALLEL_STRIP_BOXES && rayon::current_num_threads() > 1;
        let Some((y0, y1)) = range_of_y(boxes, two) else {
            return false;
        };
        let samples = n.min(1024);
        let mut sides: Vec<f64> = (0..samples)
            .map(|k| {
                let b = &boxes[k * n / samples];
                (b.hi[0] - b.lo[0]).max(b.hi[1] - b.lo[1])
            })
            .collect();
        let (_, &mut median, _) = sides.select_nth_unstable_by(samples / 2, f64::total_cmp);
        let side = median.max((y1 - y0) / n as f64).max(f64::MIN_POSITIVE);
        let rows = (((y1 - y0) / side) as usize + 1).min(n);
        let at = |y: f64| (((y - y0) / side) as usize).min(rows - 1) as u32;
        // the first and last strip of each box
        let span = |b: &Aabb| [at(b.lo[1]), at(b.hi[1])];
        let spans = &mut self.spans;
        if two {
            boxes.par_iter().map(span).collect_into_vec(spans);
        } else {
            spans.clear();
            spans.extend(boxes.iter().map(span));
        }
        let total: usize = spans.iter().map(|s| (s[1] - s[0]) as usize + 1).sum();
        if total > STRIP_ENTRIES_PER_BOX * n {
            return false;
        }
        self.fill_strips(boxes, rows, total, two);
        // each strip in the sweep's order (the entries of a strip come by increasing index:
        // a stable sort on low x)
        self.sort_rows();
        true
    }

    /// [`Strips::rebuild`]'s counting sort of the boxes' entries (`total` of them, the boxes'
    /// spans made) into `rows` strips, each box's entries by increasing index; on `two`
    /// threads, each for a range of strips.
    fn fill_strips(&mut self, boxes: &[Aabb], rows: usize, total: usize, two: bool) {
        let spans = &self.spans[..];
        let start = &mut self.start;
        start.clear();
        start.resize(rows + 1, 0);
        // `start[r + 1]`: the entries of strip r, for the strips from `first` on
        let count = |first: usize, counts: &mut [u32]| {
            let end = first + counts.len();
            for s in spans {
                for r in (s[0] as usize).max(first)..(s[1] as usize + 1).min(end) {
                    counts[r - first] += 1;
                }
            }
        };
        if two {
            let (low, high) = start[1..].split_at_mut(rows / 2);
            rayon::join(|| count(0, low), || count(rows / 2, high));
        } else {
            count(0, &mut start[1..]);
        }
        for r in 0..rows {
            start[r + 1] += start[r];
        }
        let entries = &mut self.entries;
        entries.clear();
        entries.resize(total, Entry::default());
        let fill = &mut self.fill;
        fill.clone_from(start);
        // the entries of the strips from `first` on, which start at entry `base`
        let scatter = |first: usize, base: u32, fill: &mut [u32], out: &mut [Entry]| {
            let end = first + fill.len();
            for (i, (s, b)) in spans.iter().zip(boxes).enumerate() {
                for r in (s[0] as usize).max(first)..(s[1] as usize + 1).min(end) {
                    let slot = &mut fill[r - first];
                    out[(*slot - base) as usize] = Entry {
                        lo: b.lo[0],
                        hi: b.hi[0],
                        index: i as u32,
                        first: s[0],
                    };
                    *slot += 1;
                }
            }
        };
        if two {
            // two ranges of strips with about as many entries each
            let mid = start
                .partition_point(|&e| (e as usize) < total / 2)
                .min(rows);
            let (fill_low, fill_high) = fill[..rows].split_at_mut(mid);
            let (low, high) = entries.split_at_mut(start[mid] as usize);
            let base = start[mid];
            rayon::join(
                || scatter(0, 0, fill_low, low),
                || scatter(mid, base, fill_high, high),
            );
        } else {
            scatter(0, 0, &mut fill[..rows], entries);
        }
    }

    fn rows(&self) -> usize {
        self.start.len() - 1
    }

    /// Sorts every strip by low x, stably (ties keep the index order), on every thread.
    fn sort_rows(&mut self) {
        let mut rest: &mut [Entry] = &mut self.entries;
        let mut rows: Vec<&mut [Entry]> = Vec::with_capacity(self.start.len() - 1);
        for w in self.start.windows(2) {
            let (row, tail) = rest.split_at_mut((w[1] - w[0]) as usize);
            rows.push(row);
            rest = tail;
        }
        rows.par_iter_mut()
            .with_min_len(64)
            .for_each(|row| row.sort_by(|a, b| a.lo.total_cmp(&b.lo)));
    }

    /// Visits the overlapping pairs whose first common strip is `row`, by a sweep in x.
    fn sweep<T>(
        &self,
        row: usize,
        boxes: &[Aabb],
        visit: &impl Fn(usize, usize, &mut Vec<T>),
        out: &mut Vec<T>,
    ) {
        let list = &self.entries[self.start[row] as usize..self.start[row + 1] as usize];
        let row = row as u32;
        for (k, ea) in list.iter().enumerate() {
            let ba = &boxes[ea.index as usize];
            for eb in &list[k + 1..] {
                if eb.lo > ea.hi {
                    break;
                }
                // the first strip both cross: the later of their first strips
                if ea.first.max(eb.first) != row {
                    continue;
                }
                let bb = &boxes[eb.index as usize];
                if bb.lo[1] <= ba.hi[1] && bb.hi[1] >= ba.lo[1] {
                    visit(ea.index as usize, eb.index as usize, out);
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

    /// The strips built on two threads hold the entries of those built on one, in the same
    /// places: boxes spread over many strips, boxes in a single strip, and boxes of which
    /// most crowd into a few strips (the two threads' ranges then very unequal in strips).
    #[test]
    fn strips_built_on_two_threads_are_those_built_on_one() {
        let mut rng = testkit::layered::Rng(11);
        let mut next = || rng.unit();
        let n = 2 * PARALLEL_STRIP_BOXES;
        let spread: Vec<Aabb> = (0..n)
            .map(|_| {
                let p = [next(), next()];
                Aabb::of_segment(p, [p[0] + 0.01 * next(), p[1] + 0.01 * next()], 0.001)
            })
            .collect();
        let flat: Vec<Aabb> = (0..n)
            .map(|k| Aabb::of_segment([k as f64, 0.0], [k as f64 + 1.5, 0.0], 0.0))
            .collect();
        let crowded: Vec<Aabb> = (0..n)
            .map(|k| {
                let y = if k % 10 == 0 { 100.0 * next() } else { next() };
                Aabb::of_segment([next(), y], [next(), y + 0.5], 0.0)
            })
            .collect();
        let strips_of = |boxes: &[Aabb], threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut strips = Strips::default();
            assert!(pool.install(|| strips.rebuild(boxes)));
            let entries: Vec<(u64, u64, u32, u32)> = strips
                .entries
                .iter()
                .map(|e| (e.lo.to_bits(), e.hi.to_bits(), e.index, e.first))
                .collect();
            (strips.start, entries)
        };
        for (name, boxes) in [("spread", &spread), ("flat", &flat), ("crowded", &crowded)] {
            let one = strips_of(boxes, 1);
            assert!(one.0.len() > 1 && !one.1.is_empty(), "{name}");
            assert_eq!(strips_of(boxes, 2), one, "{name}");
        }
        assert_eq!(
            strips_of(&flat, 1).0.len(),
            2,
            "the flat boxes share one strip"
        );
    }

    /// The strips find exactly the sweep's pairs, each the same way round, for boxes of very
    /// different sizes (a ring of small boxes, some large ones, some equal low x), with one
    /// thread and with several.
    #[test]
    fn the_strips_find_the_sweeps_pairs_the_same_way_round() {
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
        assert!(
            Strips::new(&boxes).is_some(),
            "the strips, not the fallback"
        );
        for threads in [1, 2] {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut found = pool.install(|| {
                par_overlapping_strips(&boxes, |i, j, out: &mut Vec<(usize, usize)>| {
                    out.push((i, j))
                })
            });
            found.sort_unstable();
            assert_eq!(found, expected, "{threads} threads");
        }
        // strips kept from one set of boxes and built again for others (fewer, then more,
        // then after a fallback) find each set's own pairs
        let mut kept = Strips::default();
        let mut odd = boxes[..100].to_vec();
        odd[3].hi[0] = f64::INFINITY;
        for set in [&boxes[..], &boxes[1000..2500], &odd[..], &boxes[..]] {
            let mut expected = Vec::new();
            geom_predicates::for_each_overlapping_pair(set, |i, j| expected.push((i, j)));
            expected.sort_unstable();
            let mut found =
                par_overlapping_strips_in(&mut kept, set, |i, j, out: &mut Vec<(usize, usize)>| {
                    out.push((i, j))
                });
            found.sort_unstable();
            assert_eq!(found, expected, "{} boxes", set.len());
        }
        // too few boxes, or a coordinate not finite: the sweep's pairs all the same
        assert!(Strips::new(&boxes[..1]).is_none());
        assert!(Strips::new(&odd).is_none());
    }
}
