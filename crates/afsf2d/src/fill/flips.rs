//! The largest-angle edge flips of a fill: sweeps over its edges in increasing order, each
//! flipping the diagonal of two triangles when the other diagonal lowers the larger of their
//! largest angles. It owns the sweeps, their table of edge owners and the rule that skips a
//! pair tried unchanged; the triangulation, the smoothing and the peeling are the parent
//! module's.
//!
//! Within a sweep a triangle flips at most once, and a pair is tried only while neither of
//! its triangles has flipped in the sweep. So every pair tried sees its two triangles as the
//! sweep found them, and whether it would flip depends on the sweep's start alone. Each sweep
//! therefore judges every pair first, blocks of nodes on every thread, and then walks the
//! judged pairs in edge order, flipping those that would flip when neither triangle has
//! flipped yet: the flips of the sweep made one edge after the other, whatever the threads.

use geom_predicates::orient2d;
use mesh_model::NONE;
use rayon::prelude::*;

use crate::geom::P2;

/// Sweeps of the largest-angle edge flips.
pub(super) const FLIP_SWEEPS: usize = 16;

/// Nodes per block of a sweep's judging (the blocks are judged in parallel): large enough
/// that a block's vectors are few, small enough that a fill's blocks even out on the threads.
const JUDGE_BLOCK: usize = 2048;

/// Flips the diagonal of two fill triangles that share an edge which is not a front edge,
/// whenever the other diagonal lowers the larger of their largest angles: the constrained
/// Delaunay triangulation maximises the smallest angle, which is not the figure a solver
/// needs, and next to long front edges it keeps flat triangles whose other diagonal is
/// fine. Both new triangles must be positive (the pair forms a convex quadrilateral).
/// `constraints`: the front edges, lower end first, sorted.
pub(super) fn flip_min_max_angle(tris: &mut [[u32; 3]], pts: &[P2], constraints: &[(u32, u32)]) {
    flip_in_blocks(tris, pts, constraints, JUDGE_BLOCK);
}

/// A triangle's largest angle in degrees, infinite when it is not positive.
fn worst(pts: &[P2], t: [u32; 3]) -> f64 {
    let (a, b, c) = (pts[t[0] as usize], pts[t[1] as usize], pts[t[2] as usize]);
    if orient2d(a, b, c) <= 0.0 {
        return f64::INFINITY;
    }
    crate::quality::max_triangle_angle_deg(a, b, c)
}

/// One pair of a sweep, judged on the triangles as the sweep found them: the edge's position
/// `3 t1 + c1` (triangle `t1`, its corner `c1` opposite the edge), the other triangle `t2`,
/// and the flip (an index into its block's flips) or [`NONE`] when the pair stays.
#[derive(Clone, Copy)]
struct Judged {
    at: u32,
    t2: u32,
    flip: u32,
}

/// A flip judged better: the two new triangles and their largest angles.
type Flip = ([u32; 3], [u32; 3], [f64; 2]);

/// What a sweep reads, as it found them.
struct Sweep<'a> {
    tris: &'a [[u32; 3]],
    pts: &'a [P2],
    constraints: &'a [(u32, u32)],
    figure: &'a [f64],
    owner: &'a Owners,
    /// The pairs tried in the last sweep and not flipped ([`flip_in_blocks`]'s `kept`).
    tried: &'a [u32],
    /// The triangles flipped in the last sweep.
    flipped_before: &'a [bool],
}

impl Sweep<'_> {
    /// The pairs of the edges `(a, b)`, `a < b`, whose first node `a` is in `nodes`, in
    /// increasing order, with the flips judged better.
    fn judge(&self, nodes: std::ops::Range<usize>) -> (Vec<Judged>, Vec<Flip>) {
        let (mut pairs, mut flips) = (Vec::new(), Vec::new());
        let first = self
            .constraints
            .partition_point(|e| (e.0 as usize) < nodes.start);
        let mut constraint = self.constraints[first..].iter().peekable();
        for a in nodes {
            for ((a, b), (t1, c1)) in self.owner.leaving(a) {
                let at = (3 * t1 + c1) as u32;
                while constraint.next_if(|&&e| e < (a, b)).is_some() {}
                // a pair tried in the last sweep, neither triangle flipped since: `t2` still
                // owns (b, a) when every directed edge has one owner; it would not flip
                let t2 = self.tried[at as usize];
                if self.owner.unique
                    && t2 != NONE
                    && !self.flipped_before[t1]
                    && !self.flipped_before[t2 as usize]
                {
                    pairs.push(Judged { at, t2, flip: NONE });
                    continue;
                }
                if constraint.peek() == Some(&&(a, b)) {
                    continue;
                }
                let Some((t2, c2)) = self.owner.get((b, a)) else {
                    continue;
                };
                let (c, d) = (self.tris[t1][c1], self.tris[t2][c2]);
                // t1 = (a, b, c), t2 = (b, a, d), both counter-clockwise
                let before = self.figure[t1].max(self.figure[t2]);
                let (n1, n2) = ([c, a, d], [d, b, c]);
                // the second triangle is measured only when the first leaves the flip possible
                let w1 = worst(self.pts, n1);
                let w2 = if w1 >= before - 1e-6 {
                    f64::INFINITY
                } else {
                    worst(self.pts, n2)
                };
                let flip = if w1.max(w2) < before - 1e-6 {
                    flips.push((n1, n2, [w1, w2]));
                    (flips.len() - 1) as u32
                } else {
                    NONE
                };
                pairs.push(Judged {
                    at,
                    t2: t2 as u32,
                    flip,
                });
            }
        }
        (pairs, flips)
    }
}

/// [`flip_min_max_angle`], each sweep judged in blocks of `block` nodes.
fn flip_in_blocks(tris: &mut [[u32; 3]], pts: &[P2], constraints: &[(u32, u32)], block: usize) {
    // each triangle's figure, kept up to date through the flips (the nodes do not move here)
    let mut figure: Vec<f64> = tris.par_iter().map(|&t| worst(pts, t)).collect();
    // `kept[3 t + c]`: the other triangle of the edge opposite corner `c` of `t` when that pair
    // was tried in the last sweep and not flipped; a pair tried again unchanged (neither
    // triangle flipped since) would again not flip, so it is skipped
    let mut kept = vec![NONE; 3 * tris.len()];
    let mut flipped = vec![false; tris.len()];
    let n = pts.len();
    for _ in 0..FLIP_SWEEPS {
        let owner = Owners::new(tris, n);
        let flipped_before = std::mem::replace(&mut flipped, vec![false; tris.len()]);
        let tried = std::mem::replace(&mut kept, vec![NONE; 3 * tris.len()]);
        let sweep = Sweep {
            tris,
            pts,
            constraints,
            figure: &figure,
            owner: &owner,
            tried: &tried,
            flipped_before: &flipped_before,
        };
        // in a fixed order: the same input makes the same mesh
        let judged: Vec<(Vec<Judged>, Vec<Flip>)> = (0..n.div_ceil(block))
            .into_par_iter()
            .map(|k| sweep.judge(k * block..((k + 1) * block).min(n)))
            .collect();
        let mut flips = 0;
        for (pairs, better) in &judged {
            for &Judged { at, t2, flip } in pairs {
                let (t1, t2) = (at as usize / 3, t2 as usize);
                if flipped[t1] || flipped[t2] {
                    continue;
                }
                if flip == NONE {
                    kept[at as usize] = t2 as u32;
                    continue;
                }
                let (n1, n2, w) = better[flip as usize];
                tris[t1] = n1;
                tris[t2] = n2;
                figure[t1] = w[0];
                figure[t2] = w[1];
                flipped[t1] = true;
                flipped[t2] = true;
                flips += 1;
            }
        }
        if flips == 0 {
            break;
        }
    }
}

/// The triangle and the opposite corner of each directed edge (`tri[i] -> tri[i+1]`,
/// opposite corner `i+2`), by first node and then second node (the order of a sort by edge):
/// a directed edge met twice keeps its last triangle. Built by a counting sort on the first
/// node, each node's few edges then sorted by their second node and position.
struct Owners {
    /// `edges[start[a]..start[a + 1]]`: the edges leaving node `a`, as (second node, position
    /// `3 t + i` of the edge in the triangles), increasing.
    start: Vec<u32>,
    edges: Vec<(u32, u32)>,
    /// Whether no directed edge was met twice.
    unique: bool,
}

impl Owners {
    fn new(tris: &[[u32; 3]], n_nodes: usize) -> Self {
        Owners::in_blocks(tris, n_nodes, SORT_BLOCK)
    }

    /// [`Owners::new`], the runs sorted in blocks of `block` nodes.
    fn in_blocks(tris: &[[u32; 3]], n_nodes: usize, block: usize) -> Self {
        let mut start = vec![0u32; n_nodes + 1];
        for tri in tris {
            for &a in tri {
                start[a as usize + 1] += 1;
            }
        }
        for a in 0..n_nodes {
            start[a + 1] += start[a];
        }
        let mut next = start.clone();
        let mut edges = vec![(0u32, 0u32); 3 * tris.len()];
        for (t, tri) in tris.iter().enumerate() {
            for i in 0..3 {
                let slot = &mut next[tri[i] as usize];
                edges[*slot as usize] = (tri[(i + 1) % 3], (3 * t + i) as u32);
                *slot += 1;
            }
        }
        let unique = sort_runs(&mut edges, &start, block);
        if !unique {
            // among equal edges the last position is kept
            let mut kept = Vec::with_capacity(edges.len());
            let mut kept_start = vec![0u32; n_nodes + 1];
            for a in 0..n_nodes {
                let run = &edges[start[a] as usize..start[a + 1] as usize];
                for (k, e) in run.iter().enumerate() {
                    if run.get(k + 1).is_none_or(|f| f.0 != e.0) {
                        kept.push(*e);
                    }
                }
                kept_start[a + 1] = kept.len() as u32;
            }
            return Owners {
                start: kept_start,
                edges: kept,
                unique,
            };
        }
        Owners {
            start,
            edges,
            unique,
        }
    }

    /// The directed edges `(a, b)` leaving node `a` with `a < b`, increasing, each with its
    /// triangle and the triangle's corner opposite the edge.
    fn leaving(&self, a: usize) -> impl Iterator<Item = ((u32, u32), (usize, usize))> + '_ {
        self.edges[self.start[a] as usize..self.start[a + 1] as usize]
            .iter()
            .filter(move |e| e.0 > a as u32)
            .map(move |&(b, at)| ((a as u32, b), split(at)))
    }

    fn get(&self, (a, b): (u32, u32)) -> Option<(usize, usize)> {
        let a = a as usize;
        let run = &self.edges[self.start[a] as usize..self.start[a + 1] as usize];
        run.iter().find(|e| e.0 == b).map(|e| split(e.1))
    }
}

/// Nodes per block of [`sort_runs`] (the blocks sorted in parallel): some 20k edges.
const SORT_BLOCK: usize = 4096;

/// Sorts each node's run of edges `edges[start[a]..start[a + 1]]` by second node, stably
/// (the runs come in position order: among equal edges the positions stay increasing, the
/// order of a sort by (second node, position)), blocks of nodes on every thread. Returns
/// whether no run holds an edge twice. `block`: nodes per block.
fn sort_runs(edges: &mut [(u32, u32)], start: &[u32], block: usize) -> bool {
    let n_nodes = start.len() - 1;
    // each block of nodes with its stretch of the edges
    let mut blocks = Vec::with_capacity(n_nodes.div_ceil(block));
    let mut rest = edges;
    for a0 in (0..n_nodes).step_by(block) {
        let a1 = (a0 + block).min(n_nodes);
        let len = (start[a1] - start[a0]) as usize;
        let (block, after) = std::mem::take(&mut rest).split_at_mut(len);
        blocks.push((a0..a1, block));
        rest = after;
    }
    blocks
        .into_par_iter()
        .map(|(nodes, block)| {
            let base = start[nodes.start] as usize;
            let mut unique = true;
            for a in nodes {
                let run = &mut block[start[a] as usize - base..start[a + 1] as usize - base];
                // a run of a few edges: insertion by second node keeps equal ones in order
                for k in 1..run.len() {
                    let mut j = k;
                    while j > 0 && run[j - 1].0 > run[j].0 {
                        run.swap(j - 1, j);
                        j -= 1;
                    }
                }
                unique &= run.windows(2).all(|w| w[0].0 != w[1].0);
            }
            unique
        })
        .reduce(|| true, |a, b| a && b)
}

/// The triangle of edge position `3 t + i` and its corner opposite the edge.
fn split(at: u32) -> (usize, usize) {
    (at as usize / 3, (at as usize % 3 + 2) % 3)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The edge owners by the counting sort on the first node are those of a stable sort by
    /// edge, where a directed edge met twice keeps its last triangle.
    #[test]
    fn the_edge_owners_are_those_of_a_stable_sort() {
        let mut rng = testkit::layered::Rng(5);
        let mut node = || rng.below(40) as u32;
        // random triangles over few nodes: many directed edges are met twice or more
        let tris: Vec<[u32; 3]> = (0..3000).map(|_| [node(), node(), node()]).collect();
        let mut owner: Vec<((u32, u32), (usize, usize))> = tris
            .iter()
            .enumerate()
            .flat_map(|(t, tri)| {
                (0..3).map(move |i| ((tri[i], tri[(i + 1) % 3]), (t, (i + 2) % 3)))
            })
            .collect();
        owner.sort_by_key(|&(k, _)| k);
        let mut kept: Vec<((u32, u32), (usize, usize))> = Vec::new();
        for o in owner {
            match kept.last_mut() {
                Some(last) if last.0 == o.0 => *last = o,
                _ => kept.push(o),
            }
        }
        for threads in 1..=3 {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            for block in [1, 7, SORT_BLOCK] {
                let owners = pool.install(|| Owners::in_blocks(&tris, 40, block));
                let listed: Vec<((u32, u32), (usize, usize))> =
                    (0..40).flat_map(|a| owners.leaving(a)).collect();
                let ascending: Vec<_> = kept.iter().copied().filter(|o| o.0.0 < o.0.1).collect();
                assert_eq!(listed, ascending, "{threads} threads, blocks of {block}");
            }
        }
        let owners = Owners::new(&tris, 40);
        assert!(!owners.unique);
        let listed: Vec<((u32, u32), (usize, usize))> = (0..40usize)
            .flat_map(|a| {
                let run = &owners.edges[owners.start[a] as usize..owners.start[a + 1] as usize];
                run.iter().map(move |&(b, at)| ((a as u32, b), split(at)))
            })
            .collect();
        assert_eq!(listed, kept);
        let ascending: Vec<_> = kept.iter().copied().filter(|o| o.0.0 < o.0.1).collect();
        assert_eq!(
            (0..40).flat_map(|a| owners.leaving(a)).collect::<Vec<_>>(),
            ascending
        );
        for &(edge, owner) in &kept {
            assert_eq!(owners.get(edge), Some(owner));
        }
        // a triangulation's edges are met once each
        let grid = [[0, 1, 2], [2, 1, 3]];
        assert!(Owners::new(&grid, 4).unique);
        assert_eq!(Owners::new(&grid, 4).get((2, 1)), Some((1, 2)));
    }

    /// The sweeps judged in blocks of any size, on one to three threads, make the flips of
    /// the sweeps made one edge after the other (the flips as specified: `naive_flips`) —
    /// on refined fills of annuli, where many pairs flip in the first sweep and a few later.
    #[test]
    fn the_flips_judged_in_blocks_are_the_flips_made_in_edge_order() {
        let mut rng = testkit::layered::Rng(39);
        for case in 0..3 {
            let (outer, inner) = (80 + 70 * case, 50 + 40 * case);
            let (fill, constraints) = super::super::tests::refined_annulus(outer, inner, &mut rng);
            let (tris, pts) = (fill.tris, fill.pts);
            let mut want = tris.clone();
            super::super::tests::naive_flips(&mut want, &|g| pts[g as usize], &constraints);
            assert_ne!(want, tris, "case {case}: some pairs flip");
            for threads in 1..=3 {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                for block in [1, 7, 64, JUDGE_BLOCK] {
                    let mut got = tris.clone();
                    pool.install(|| flip_in_blocks(&mut got, &pts, &constraints, block));
                    assert_eq!(
                        got, want,
                        "case {case}, {threads} threads, blocks of {block}"
                    );
                }
            }
        }
    }
}
