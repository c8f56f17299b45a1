//! The smoothing of a fill's added (Steiner) nodes: Gauss–Seidel sweeps in node order, each
//! node moved toward the centroid of its triangles' other corners when that lowers the
//! largest angle of its triangles. It owns the sweeps' order and their tables; the flips,
//! the triangulation and the peeling are the parent module's.
//!
//! The sweeps run level by level. A node's level is one more than the highest level of the
//! added nodes below it (in number) that share a triangle with it, so two nodes of one level
//! share no triangle, and when a level is run every neighbour of its nodes stands where the
//! sweep in node order would have it: the lower ones already moved in this sweep (a lower
//! level), the higher ones not yet (a higher level). A large level is run on every thread;
//! the moves are those of the sweep in node order, whatever the threads (on one thread, or
//! in a small fill, the nodes are simply tried in node order). What the nodes of
//! one level write (their positions, their triangles' figures, their own records) no other
//! node of that level reads, so the shared tables are relaxed atomics: plain loads and
//! stores, ordered from level to level by rayon's joins.

use std::sync::atomic::{AtomicU8, AtomicU64, Ordering::Relaxed};

use geom_predicates::orient2d;
use rayon::prelude::*;

use crate::geom::P2;
use crate::quality::AngleLimit;

/// Sweeps of the Steiner-node smoothing.
pub(super) const SMOOTHING_SWEEPS: usize = 6;

/// The nodes of a level from which it is run on every thread: below, the fork costs more
/// than the half it saves (a node's try is some 0.4 µs).
const PARALLEL_LEVEL_MIN: usize = 256;

/// Moves each added node (the local nodes from `front` on) toward the centroid of its
/// triangles' other corners when that lowers the largest angle of its triangles (and keeps
/// them positive): the refinement leaves obtuse triangles where it may not split a front
/// edge, and these moves mend most of them. Front nodes never move.
pub(super) fn smooth_steiner(tris: &[[u32; 3]], pts: &mut [P2], front: usize) {
    smooth_steiner_from(tris, pts, front, PARALLEL_LEVEL_MIN);
}

/// [`smooth_steiner`], levels of at least `parallel_min` nodes run on every thread (with
/// fewer added nodes than that, or one thread, the nodes are tried in node order: the same
/// moves).
fn smooth_steiner_from(tris: &[[u32; 3]], pts: &mut [P2], front: usize, parallel_min: usize) {
    let added = pts.len() - front;
    if added == 0 {
        return;
    }
    let smoother = Smoother::new(tris, front, added);
    let levels =
        (rayon::current_num_threads() > 1 && added >= parallel_min).then(|| smoother.levels());
    let state = State::new(pts, added, tris.len());
    for sweep in 0..SMOOTHING_SWEEPS {
        // the time of a node's try in this sweep: its place in the sweeps in node order
        let base = (sweep * added) as u64;
        let try_node = |&s: &u32| smoother.try_node(s as usize, base, &state);
        match &levels {
            None => (0..added as u32).for_each(|s| try_node(&s)),
            Some(levels) => {
                for level in levels.iter() {
                    if level.len() >= parallel_min {
                        level.par_iter().with_min_len(32).for_each(try_node);
                    } else {
                        level.iter().for_each(try_node);
                    }
                }
            }
        }
    }
    state.write_back(pts, front);
}

/// The smoothing's tables: the fill triangles (in local numbers: the front nodes first,
/// added node `s` is `front + s`) of each added node.
pub(super) struct Smoother {
    front: usize,
    /// `incident[start[s]..start[s + 1]]`: the triangles of added node `s`, increasing, each
    /// with its corners (the triangles do not change here: a copy beside the node reads
    /// faster than the triangle list).
    start: Vec<u32>,
    incident: Vec<Incident>,
}

/// The added nodes by level: `nodes[start[l]..start[l + 1]]` are level `l`'s.
struct Levels {
    start: Vec<u32>,
    nodes: Vec<u32>,
}

impl Levels {
    /// Each level's nodes, level after level.
    fn iter(&self) -> impl Iterator<Item = &[u32]> + '_ {
        self.start
            .windows(2)
            .map(|w| &self.nodes[w[0] as usize..w[1] as usize])
    }
}

/// A triangle of an added node: its index and its corners.
#[derive(Clone, Copy, Default)]
struct Incident {
    t: u32,
    tri: [u32; 3],
}

/// What the sweeps change, shared by the threads of a level: every local node's position
/// (as bits), the largest angle of each triangle where its corners are (infinite when it is
/// not positive; [`UNKNOWN`] when not measured since one of them moved), and each added
/// node's records: the time of its last move (0: none), the time it was last tried and left
/// where it was (0: not since it last moved), and the position among its triangles of the
/// one that then kept it there. A time is a try's place in the sweeps in node order, so
/// "moved since it was left" reads as it did with a count of moves.
struct State {
    pts: Vec<[AtomicU64; 2]>,
    figure: Vec<AtomicU64>,
    moved: Vec<AtomicU64>,
    settled: Vec<AtomicU64>,
    failed: Vec<AtomicU8>,
}

/// A triangle's figure not measured since one of its corners moved (a NaN no measure gives:
/// a NaN figure is kept as the plain NaN, which every use of it reads alike).
const UNKNOWN: u64 = u64::MAX;

impl State {
    fn new(pts: &[P2], added: usize, triangles: usize) -> Self {
        let zeros = |n: usize| (0..n).map(|_| AtomicU64::new(0)).collect::<Vec<_>>();
        State {
            pts: pts
                .iter()
                .map(|p| p.map(|x| AtomicU64::new(x.to_bits())))
                .collect(),
            figure: (0..triangles).map(|_| AtomicU64::new(UNKNOWN)).collect(),
            moved: zeros(added),
            settled: zeros(added),
            failed: (0..added).map(|_| AtomicU8::new(0)).collect(),
        }
    }

    fn at(&self, v: u32) -> P2 {
        self.pts[v as usize]
            .each_ref()
            .map(|x| f64::from_bits(x.load(Relaxed)))
    }

    fn set(&self, v: usize, p: P2) {
        for (x, c) in self.pts[v].iter().zip(p) {
            x.store(c.to_bits(), Relaxed);
        }
    }

    /// The added nodes' positions back into `pts`.
    fn write_back(&self, pts: &mut [P2], front: usize) {
        for (p, v) in pts[front..].iter_mut().zip(front..) {
            *p = self.at(v as u32);
        }
    }
}

impl Smoother {
    pub(super) fn new(tris: &[[u32; 3]], front: usize, added: usize) -> Self {
        let mut start = vec![0u32; added + 1];
        for tri in tris {
            for &g in tri {
                if g as usize >= front {
                    start[g as usize - front + 1] += 1;
                }
            }
        }
        for s in 0..added {
            start[s + 1] += start[s];
        }
        let mut next = start.clone();
        let mut incident = vec![Incident::default(); start[added] as usize];
        for (t, &tri) in tris.iter().enumerate() {
            for &g in &tri {
                if g as usize >= front {
                    let slot = &mut next[g as usize - front];
                    incident[*slot as usize] = Incident { t: t as u32, tri };
                    *slot += 1;
                }
            }
        }
        Smoother {
            front,
            start,
            incident,
        }
    }

    /// The triangles of added node `s`.
    fn of(&self, s: usize) -> &[Incident] {
        &self.incident[self.start[s] as usize..self.start[s + 1] as usize]
    }

    /// The added nodes that share a triangle with `s` (some more than once), in local
    /// numbers.
    fn neighbours(&self, s: usize) -> impl Iterator<Item = usize> + '_ {
        let g = self.front + s;
        self.of(s)
            .iter()
            .flat_map(|i| i.tri)
            .map(|v| v as usize)
            .filter(move |&v| v >= self.front && v != g)
    }

    /// The added nodes by level (see the module's note), each level's in increasing order.
    fn levels(&self) -> Levels {
        let added = self.start.len() - 1;
        let mut level = vec![0u32; added];
        for s in 0..added {
            let g = self.front + s;
            level[s] = self
                .neighbours(s)
                .filter(|&v| v < g)
                .map(|v| level[v - self.front] + 1)
                .max()
                .unwrap_or(0);
        }
        // by a counting sort on the level
        let depth = level.iter().max().map_or(0, |&l| l as usize + 1);
        let mut start = vec![0u32; depth + 1];
        for &l in &level {
            start[l as usize + 1] += 1;
        }
        for l in 0..depth {
            start[l + 1] += start[l];
        }
        let mut next = start.clone();
        let mut nodes = vec![0u32; added];
        for (s, &l) in level.iter().enumerate() {
            nodes[next[l as usize] as usize] = s as u32;
            next[l as usize] += 1;
        }
        Levels { start, nodes }
    }

    /// Tries added node `s` in the sweep whose tries start after time `base`: skipped when
    /// it was left where it was and none of its neighbours moved since (it would stay
    /// again), else moved to the first of three points on the way to its centroid that
    /// lowers its triangles' largest angle, if any.
    fn try_node(&self, s: usize, base: u64, state: &State) {
        let now = base + s as u64 + 1;
        let settled = state.settled[s].load(Relaxed);
        if settled != 0 && self.still(s, state, settled) {
            return;
        }
        let Some(centroid) = self.centroid(s, state) else {
            return;
        };
        let old = state.at((self.front + s) as u32);
        let before = self.worst(s, state);
        // (its cosine once for the three tries)
        let limit = AngleLimit::new(before);
        state.settled[s].store(now, Relaxed);
        let mut failed = state.failed[s].load(Relaxed);
        for f in [1.0, 0.5, 0.25] {
            let p = [
                old[0] + f * (centroid[0] - old[0]),
                old[1] + f * (centroid[1] - old[1]),
            ];
            if self.improves(s, p, state, (before, &limit), &mut failed) {
                self.place(s, p, state);
                state.moved[s].store(now, Relaxed);
                state.settled[s].store(0, Relaxed);
                break;
            }
        }
        state.failed[s].store(failed, Relaxed);
    }

    /// Whether no neighbour of `s` moved since `s` was left (at time `settled`).
    fn still(&self, s: usize, state: &State, settled: u64) -> bool {
        self.neighbours(s)
            .all(|v| state.moved[v - self.front].load(Relaxed) < settled)
    }

    /// The centroid of the other corners of `s`'s triangles (none without triangles).
    fn centroid(&self, s: usize, state: &State) -> Option<P2> {
        let g = (self.front + s) as u32;
        let (mut sx, mut sy, mut k) = (0.0, 0.0, 0.0);
        for i in self.of(s) {
            for &v in &i.tri {
                if v != g {
                    let q = state.at(v);
                    sx += q[0];
                    sy += q[1];
                    k += 1.0;
                }
            }
        }
        (k != 0.0).then(|| [sx / k, sy / k])
    }

    /// The largest angle of node `s`'s triangles where they are (infinite when one is not
    /// positive), from the kept figures (measured and kept where unknown).
    fn worst(&self, s: usize, state: &State) -> f64 {
        let mut w = 0.0f64;
        for &Incident { t, tri } in self.of(s) {
            let kept = state.figure[t as usize].load(Relaxed);
            let f = if kept == UNKNOWN {
                let c = tri.map(|v| state.at(v));
                let f = if orient2d(c[0], c[1], c[2]) <= 0.0 {
                    f64::INFINITY
                } else {
                    crate::quality::max_triangle_angle_deg(c[0], c[1], c[2])
                };
                let f = if f.is_nan() { f64::NAN } else { f };
                state.figure[t as usize].store(f.to_bits(), Relaxed);
                f
            } else {
                f64::from_bits(kept)
            };
            if f == f64::INFINITY {
                return f64::INFINITY;
            }
            w = w.max(f);
        }
        w
    }

    /// Exactly "the largest angle of `s`'s triangles with `s` at `p` < before", the angles
    /// mostly compared by their cosines (`limit`: `before` and its cosine). The triangles
    /// are looked at from position `first` among them on (round), the one that last kept
    /// `s` where it was (and `first` becomes the one that does now): that one most likely
    /// fails again, and the answer, all of them passing, is the same in any order.
    fn improves(
        &self,
        s: usize,
        p: P2,
        state: &State,
        (before, limit): (f64, &AngleLimit),
        first: &mut u8,
    ) -> bool {
        let own = self.of(s);
        let start = if (*first as usize) < own.len() {
            *first as usize
        } else {
            0
        };
        let g = (self.front + s) as u32;
        let (head, tail) = own.split_at(start);
        for (j, i) in tail.iter().chain(head).enumerate() {
            let c = i.tri.map(|v| if v == g { p } else { state.at(v) });
            // (a NaN angle is passed over by the maximum in `worst`; corners of moderate
            // size have none)
            if orient2d(c[0], c[1], c[2]) <= 0.0
                || (!limit.triangle_below(c[0], c[1], c[2])
                    && (moderate(c)
                        || !crate::quality::max_triangle_angle_deg(c[0], c[1], c[2]).is_nan()))
            {
                *first = ((start + j) % own.len()).min(u8::MAX as usize) as u8;
                return false;
            }
        }
        0.0 < before
    }

    /// Moves `s` to `p`, forgetting its triangles' figures.
    fn place(&self, s: usize, p: P2, state: &State) {
        state.set(self.front + s, p);
        for i in self.of(s) {
            state.figure[i.t as usize].store(UNKNOWN, Relaxed);
        }
    }
}

/// Whether every coordinate of `c` is finite and below 1e150 in size: then the differences,
/// their squares and products and the sums of two of these are finite, and the largest
/// angle of the triangle (`atan2` of finite numbers) is not NaN.
fn moderate(c: [P2; 3]) -> bool {
    c.iter().flatten().all(|x| x.abs() < 1e150)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smoothing's test of a position gives the same answer from whichever triangle it
    /// starts, and when it refuses, it names a triangle that alone refuses: a fan of six
    /// triangles around one added node, moved over a grid of positions in and out of the fan,
    /// against limits from acute to flat.
    #[test]
    fn a_try_answers_the_same_from_any_first_triangle() {
        let mut pts: Vec<P2> = (0..6)
            .map(|i| {
                let a = std::f64::consts::TAU * i as f64 / 6.0;
                [a.cos() * (1.0 + 0.1 * i as f64), a.sin()]
            })
            .collect();
        pts.push([0.05, -0.02]);
        let tris: Vec<[u32; 3]> = (0..6).map(|i| [i, (i + 1) % 6, 6]).collect();
        let smoother = Smoother::new(&tris, 6, 1);
        let state = State::new(&pts, 1, tris.len());
        assert_eq!(smoother.of(0).len(), 6);
        let (mut refused, mut passed) = (0, 0);
        for before in [70.0, 95.0, 120.0, 150.0, 179.0] {
            let limit = AngleLimit::new(before);
            for i in -12..=12 {
                for j in -12..=12 {
                    let p = [0.1 * i as f64, 0.1 * j as f64];
                    let mut answers = Vec::new();
                    for first in 0..8u8 {
                        let mut at = first;
                        let ok = smoother.improves(0, p, &state, (before, &limit), &mut at);
                        if !ok {
                            // the named triangle refuses on its own
                            let alone = Smoother {
                                start: vec![0, 1],
                                incident: vec![smoother.of(0)[at as usize]],
                                ..Smoother::new(&tris, 6, 1)
                            };
                            let mut again = 0;
                            assert!(!alone.improves(0, p, &state, (before, &limit), &mut again));
                        }
                        answers.push(ok);
                    }
                    assert!(answers.windows(2).all(|w| w[0] == w[1]), "{p:?} {before}");
                    if answers[0] {
                        passed += 1;
                    } else {
                        refused += 1;
                    }
                }
            }
        }
        assert!(
            passed > 0 && refused > 0,
            "{passed} passed, {refused} refused"
        );
    }

    /// Nodes of one level share no triangle, and a node's lower neighbours are on lower
    /// levels: on a refined fill of many levels.
    #[test]
    fn a_level_holds_no_two_neighbours_and_follows_its_lower_ones() {
        let (tris, pts, front) = refined_annulus(3);
        let smoother = Smoother::new(&tris, front, pts.len() - front);
        let levels = smoother.levels();
        let depth = levels.iter().count();
        assert!(depth > 3, "{depth} levels");
        let mut level_of = vec![usize::MAX; pts.len() - front];
        for (l, nodes) in levels.iter().enumerate() {
            assert!(nodes.windows(2).all(|w| w[0] < w[1]));
            for &s in nodes {
                level_of[s as usize] = l;
            }
        }
        assert!(level_of.iter().all(|&l| l != usize::MAX), "every node");
        for s in 0..level_of.len() {
            for v in smoother.neighbours(s) {
                let v = v - front;
                assert_ne!(level_of[v], level_of[s]);
                if v < s {
                    assert!(level_of[v] < level_of[s]);
                }
            }
        }
    }

    /// The smoothing run level by level on up to three threads, every level forked, moves
    /// the nodes as the sweeps in node order do, to the last bit (those with the same
    /// tables, one node after the other).
    #[test]
    fn the_levels_on_any_threads_move_the_nodes_as_the_sweeps_in_order() {
        for case in 0..4 {
            let (tris, pts, front) = refined_annulus(case);
            let mut want = pts.clone();
            in_node_order(&tris, &mut want, front);
            assert_ne!(
                bits(&want),
                bits(&pts),
                "case {case}: the smoothing moves nodes"
            );
            for threads in 1..=3 {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let mut got = pts.clone();
                pool.install(|| smooth_steiner_from(&tris, &mut got, front, 1));
                assert_eq!(bits(&got), bits(&want), "case {case}, {threads} threads");
            }
        }
    }

    fn bits(p: &[P2]) -> Vec<[u64; 2]> {
        p.iter().map(|q| q.map(f64::to_bits)).collect()
    }

    /// The sweeps one node after the other in node order, with the tables of the levels.
    fn in_node_order(tris: &[[u32; 3]], pts: &mut [P2], front: usize) {
        let added = pts.len() - front;
        let smoother = Smoother::new(tris, front, added);
        let state = State::new(pts, added, tris.len());
        for sweep in 0..SMOOTHING_SWEEPS {
            for s in 0..added {
                smoother.try_node(s, (sweep * added) as u64, &state);
            }
        }
        state.write_back(pts, front);
    }

    /// A fill of a jittered annulus, refined (many added nodes on many levels), its nodes
    /// as the fill numbers them (the front first), and how many are front nodes.
    fn refined_annulus(case: u64) -> (Vec<[u32; 3]>, Vec<P2>, usize) {
        let mut rng = testkit::layered::Rng(40 + case);
        let (outer, inner) = (80 + 40 * case as usize, 50 + 20 * case as usize);
        let ring = super::super::tests::jittered_ring;
        let mut pos = ring(outer, 10.0, (0.2, 0.8), &mut rng);
        let mut hole = ring(inner, 3.0, (0.2, 0.8), &mut rng);
        hole.reverse(); // clockwise: the region on the left of its edges
        pos.extend(hole);
        let loop_edges = |from: usize, len: usize| {
            (0..len).map(move |i| ((from + i) as u32, (from + (i + 1) % len) as u32))
        };
        let directed: Vec<(u32, u32)> = loop_edges(0, outer)
            .chain(loop_edges(outer, inner))
            .collect();
        let (local, _) = super::super::triangulate(&directed, &[], &pos, 30.0).unwrap();
        let front = local.front.len();
        assert!(local.pts.len() > front + 200, "the refinement adds nodes");
        (local.tris, local.pts, front)
    }
}
