//! The edge table of a mesh made in two goes: the table of its first cells ([`PartEdges`]),
//! built while the rest of the mesh is still being made (the layered part of a linear mesh,
//! beside the fill), then finished into the whole mesh's table once the mesh is done — some
//! of those first cells taken out, more cells after them — by [`finish`]. The finished table
//! is the table built on the whole mesh, entry for entry (`mesh_model::topology::
//! edge_table_2d`); only its cost after the mesh is done changes: the new cells' edge uses
//! sorted and merged in, against every cell's.
//!
//! It does not build the table of the part (`table`), nor decide which cells are the part.

use mesh_model::topology::EdgeTable2d;
use mesh_model::{Cells, NONE};
use rayon::prelude::*;

use crate::table::{Record, uses_of};

/// The edge table of the first cells of a mesh not yet finished: the curving finishes it
/// for the whole mesh ([`crate::curve_mesh_owned_with`]) instead of building the whole
/// mesh's table.
#[derive(Debug, Clone)]
pub struct PartEdges {
    table: EdgeTable2d,
    /// Whether no edge of the part has more than two uses: else a cell taken out may
    /// uncover a use the table does not keep, and the whole table is built instead.
    manifold: bool,
}

impl PartEdges {
    /// The table of `cells`, whose nodes are all below `nodes`, built on every thread of
    /// the pool.
    pub fn new(cells: &Cells, nodes: usize) -> Self {
        let (table, manifold) = crate::table::build(cells, nodes);
        PartEdges { table, manifold }
    }

    /// How many cells the part has.
    pub fn cells(&self) -> usize {
        self.table.2.len()
    }
}

/// The part's cells that the mesh left out, and the cells it added after the others.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Changes<'a> {
    /// The positions, among the part's cells, of those the mesh does not have (increasing).
    pub removed: &'a [u32],
    /// The mesh's cells (the part's without `removed`, in order, then the new ones).
    pub cells: &'a Cells,
}

/// The edge table of the mesh `changes.cells`: `part`'s table, the cells `removed` taken out
/// of it and the new cells' edges added. `None` when it cannot be told from the part (an
/// edge of it with more than two uses, `changes` that do not fit the part, or sampled cells
/// whose edges are not the mesh's: a table of other cells): the caller builds the whole
/// table.
pub(crate) fn finish(part: PartEdges, changes: Changes<'_>) -> Option<EdgeTable2d> {
    let Changes { removed, cells } = changes;
    let (ends, cells_of, of_cell) = part.table;
    let fits = removed.windows(2).all(|w| w[0] < w[1])
        && removed.last().is_none_or(|&r| (r as usize) < of_cell.len())
        && of_cell.len() - removed.len() <= cells.len();
    if !part.manifold || !fits || !samples_agree(&ends, &of_cell, changes) {
        return None;
    }
    let kept = of_cell.len() - removed.len();
    let added = added_uses(cells, kept);
    // each key of the new cells' uses: a part edge, or the next new edge
    // (the keys increase: each is looked for from where the last one was)
    let (mut groups, mut reused, mut new_keys) = (Vec::new(), Vec::new(), Vec::new());
    let mut from = 0;
    for (k, r) in added.iter().enumerate() {
        if k > 0 && added[k - 1].0 == r.0 {
            continue;
        }
        from = first_not_below(&ends, from, &r.0);
        groups.push(if ends.get(from) == Some(&r.0) {
            reused.push(from as u32);
            Edge::Part(from as u32)
        } else {
            new_keys.push(r.0);
            Edge::New(new_keys.len() as u32 - 1)
        });
    }
    let dropped = dropped_edges(&of_cell, &cells_of, removed, &reused);
    let Merged {
        ends,
        mut cells_of,
        old_to_new,
        new_ids,
    } = merge(&ends, &new_keys, &dropped, |e| {
        if removed.is_empty() {
            return cells_of[e];
        }
        // each cell's number once the removed ones are out (NONE: removed); what is left
        // keeps its order, the lower cell first
        let [a, b] = cells_of[e].map(|c| renumbered(c, removed));
        if a == NONE { [b, NONE] } else { [a, b] }
    });
    // the part's cells' edges renumbered in place, the removed cells taken out
    let mut of_cell_out = of_cell;
    of_cell_out.par_iter_mut().for_each(|slots| {
        for e in slots.iter_mut().filter(|e| **e != NONE) {
            *e = old_to_new[*e as usize];
        }
    });
    let removed_at: Vec<usize> = removed.iter().map(|&r| r as usize).collect();
    mesh_model::cells::remove_sorted(&mut of_cell_out, &removed_at);
    of_cell_out.resize(cells.len(), [NONE; 4]);
    // the new cells' uses, in the table's order (every new cell after every kept one)
    let mut group = 0;
    for (k, &(key, cell, local)) in added.iter().enumerate() {
        if k > 0 && added[k - 1].0 != key {
            group += 1;
        }
        let id = match groups[group] {
            Edge::Part(e) => old_to_new[e as usize],
            Edge::New(n) => new_ids[n as usize],
        };
        if let Some(slot) = cells_of[id as usize].iter_mut().find(|c| **c == NONE) {
            *slot = cell;
        }
        of_cell_out[cell as usize][usize::from(local)] = id;
    }
    Some((ends, cells_of, of_cell_out))
}

/// The first place at or after `from` in `sorted` whose entry is not below `key` (the
/// length when there is none), found by steps doubling from `from`, then halving: a few
/// reads when it is near, as the next of many increasing keys is.
fn first_not_below<T: Ord>(sorted: &[T], from: usize, key: &T) -> usize {
    let (mut lo, mut step) = (from, 1);
    // `sorted[..lo]` is below `key`; find an end not below it
    let mut hi = from;
    while hi < sorted.len() && sorted[hi] < *key {
        lo = hi + 1;
        hi += step;
        step *= 2;
    }
    let hi = hi.min(sorted.len());
    lo + sorted[lo..hi].partition_point(|e| e < key)
}

/// Cells of the part compared with the mesh's by [`samples_agree`].
const SAMPLES: usize = 256;

/// Whether some [`SAMPLES`] kept cells of the part, spread through it, have in the part's
/// table the edges the mesh's cells at their new places have: a table of other cells (not
/// this mesh's first ones) is told apart at little cost, and built again.
fn samples_agree(ends: &[[u32; 2]], of_cell: &[[u32; 4]], changes: Changes<'_>) -> bool {
    let Changes { removed, cells } = changes;
    let kept = of_cell.len() - removed.len();
    let step = (kept / SAMPLES).max(1);
    let (mut c, mut gone) = (0usize, 0usize);
    for at in (0..kept).step_by(step) {
        // the part's cell that is the mesh's cell `at`
        while c - gone < at || removed.get(gone) == Some(&(c as u32)) {
            if removed.get(gone) == Some(&(c as u32)) {
                gone += 1;
            }
            c += 1;
        }
        let mut want = uses_of(cells, at).map(|(key, _, _)| Some(key));
        for &e in &of_cell[c] {
            let have = (e != NONE).then(|| ends.get(e as usize).copied()).flatten();
            if want.next().flatten() != have {
                return false;
            }
        }
    }
    true
}

/// Part cell `c`'s number once the cells at `removed` (increasing) are out of the part,
/// NONE when it is one of them (or is NONE).
#[inline]
fn renumbered(c: u32, removed: &[u32]) -> u32 {
    // (a handful of removed cells, as a fill's peeling leaves: a scan beats a search)
    let below = if removed.len() <= 16 {
        removed.iter().take_while(|&&r| r < c).count()
    } else {
        removed.partition_point(|&r| r < c)
    };
    if c == NONE || removed.get(below) == Some(&c) {
        NONE
    } else {
        c - below as u32
    }
}

/// Where the edge of a new cell's use is: a part edge (its number in the part's table), or
/// a new edge (its place among the new edges).
#[derive(Clone, Copy)]
enum Edge {
    Part(u32),
    New(u32),
}

/// The edge uses of the cells from `first` on, sorted (on every thread).
fn added_uses(cells: &Cells, first: usize) -> Vec<Record> {
    let mut added: Vec<Record> = Vec::with_capacity(4 * (cells.len() - first));
    added.par_extend(
        (first..cells.len())
            .into_par_iter()
            .flat_map_iter(|i| uses_of(cells, i)),
    );
    added.par_sort_unstable();
    added
}

/// The part's edges that no cell has once the `removed` cells are out and that no new cell
/// uses (`reused`: the part's edges a new cell uses, sorted), increasing.
fn dropped_edges(
    of_cell: &[[u32; 4]],
    cells_of: &[[u32; 2]],
    removed: &[u32],
    reused: &[u32],
) -> Vec<u32> {
    let mut touched: Vec<u32> = removed
        .iter()
        .flat_map(|&r| of_cell[r as usize])
        .filter(|&e| e != NONE)
        .collect();
    touched.sort_unstable();
    touched.dedup();
    touched.retain(|&e| {
        let left = cells_of[e as usize]
            .iter()
            .any(|&c| c != NONE && removed.binary_search(&c).is_err());
        !left && reused.binary_search(&e).is_err()
    });
    touched
}

/// The merged edges: the part's (less the dropped ones) and the new ones, sorted, each
/// part edge's new number and each new edge's.
struct Merged {
    ends: Vec<[u32; 2]>,
    cells_of: Vec<[u32; 2]>,
    old_to_new: Vec<u32>,
    new_ids: Vec<u32>,
}

/// Part edges per task of [`merge`].
const MERGE_CHUNK: usize = 1 << 15;

/// The part's edges `ends` less `dropped` (both sorted) and the sorted `new_keys` merged in
/// key order, on every thread: each chunk of the part's edges, with the new keys that fall
/// in its range of keys, writes its own stretch of the output. A kept part edge `e` takes
/// the cells `cells(e)`; a new one none yet.
fn merge(
    ends: &[[u32; 2]],
    new_keys: &[[u32; 2]],
    dropped: &[u32],
    cells: impl Fn(usize) -> [u32; 2] + Sync,
) -> Merged {
    let chunks = ends.len().div_ceil(MERGE_CHUNK).max(1);
    // chunk k: part edges [k C, (k + 1) C), and the new keys below the next chunk's first
    // key (from the last chunk's on: all the rest)
    let part_range =
        |k: usize| (k * MERGE_CHUNK).min(ends.len())..((k + 1) * MERGE_CHUNK).min(ends.len());
    let key_cut = |k: usize| {
        if k == 0 {
            0
        } else if k >= chunks {
            new_keys.len()
        } else {
            new_keys.partition_point(|n| *n < ends[k * MERGE_CHUNK])
        }
    };
    let sizes: Vec<(usize, usize)> = (0..chunks)
        .map(|k| {
            let r = part_range(k);
            let gone = dropped.partition_point(|&d| (d as usize) < r.end)
                - dropped.partition_point(|&d| (d as usize) < r.start);
            (r.len() - gone, key_cut(k + 1) - key_cut(k))
        })
        .collect();
    let total: usize = sizes.iter().map(|s| s.0 + s.1).sum();
    // (zeroed, so that their pages are first touched by the chunks, each on its thread;
    // every entry is written below)
    let mut out_ends = vec![[0u32; 2]; total];
    let mut out_cells = vec![[0u32; 2]; total];
    let mut old_to_new = vec![0u32; ends.len()];
    let mut new_ids = vec![0u32; new_keys.len()];
    // each chunk's stretch of every output array
    let mut stretches = Vec::with_capacity(chunks);
    let (mut e_left, mut c_left) = (&mut out_ends[..], &mut out_cells[..]);
    let (mut o_left, mut n_left) = (&mut old_to_new[..], &mut new_ids[..]);
    let mut at = 0;
    for (k, &(p, n)) in sizes.iter().enumerate() {
        let (e, rest_e) = std::mem::take(&mut e_left).split_at_mut(p + n);
        let (c, rest_c) = std::mem::take(&mut c_left).split_at_mut(p + n);
        let (o, rest_o) = std::mem::take(&mut o_left).split_at_mut(part_range(k).len());
        let (m, rest_n) = std::mem::take(&mut n_left).split_at_mut(n);
        stretches.push((k, at, e, c, o, m));
        (e_left, c_left, o_left, n_left) = (rest_e, rest_c, rest_o, rest_n);
        at += p + n;
    }
    stretches
        .into_par_iter()
        .for_each(|(k, at, e_out, c_out, o_out, n_out)| {
            let part = part_range(k);
            let news = &new_keys[key_cut(k)..key_cut(k + 1)];
            let (mut i, mut j, mut w) = (part.start, 0, 0);
            let mut gone = dropped.partition_point(|&d| (d as usize) < part.start);
            while i < part.end || j < news.len() {
                let take_new = i == part.end || (j < news.len() && news[j] < ends[i]);
                if take_new {
                    e_out[w] = news[j];
                    c_out[w] = [NONE; 2];
                    n_out[j] = (at + w) as u32;
                    j += 1;
                    w += 1;
                } else {
                    if dropped.get(gone) == Some(&(i as u32)) {
                        o_out[i - part.start] = NONE;
                        gone += 1;
                    } else {
                        e_out[w] = ends[i];
                        c_out[w] = cells(i);
                        o_out[i - part.start] = (at + w) as u32;
                        w += 1;
                    }
                    i += 1;
                }
            }
        });
    Merged {
        ends: out_ends,
        cells_of: out_cells,
        old_to_new,
        new_ids,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use mesh_model::topology::edge_table_2d;
    use proptest::prelude::*;

    /// The built-in NACA0012 linear mesh's cells and nodes, and its layered cells' count.
    fn naca0012() -> (Cells, usize, usize) {
        let g = test_cases::grow(&test_cases::real_case("naca0012"));
        let layered = &g.output.layered;
        let mesh = &layered.mesh;
        (
            mesh.cells.clone(),
            mesh.nodes.len(),
            layered.layering.layered_cells,
        )
    }

    /// The cells `0..first` of `cells` less those at `removed`, then `more`.
    fn without_then(cells: &Cells, first: usize, removed: &[u32], more: &[usize]) -> Cells {
        let mut out = Cells::new();
        for i in (0..first).filter(|&i| removed.binary_search(&(i as u32)).is_err()) {
            let c = cells.get(i);
            out.push(c.ty, c.nodes);
        }
        for &i in more {
            let c = cells.get(i);
            out.push(c.ty, c.nodes);
        }
        out
    }

    /// The first `first` cells of `cells` alone.
    fn prefix(cells: &Cells, first: usize) -> Cells {
        without_then(cells, first, &[], &[])
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(24))]
        /// The part's table finished for the whole mesh is the whole mesh's table, entry for
        /// entry: the part being the layered cells or fewer, a few of its cells taken out,
        /// the fill's triangles after them, and the taken cells again at the end (their edges
        /// used once more) or not (some of their edges gone), the part built on 1 to 3
        /// threads.
        #[test]
        fn the_finished_table_is_the_whole_meshs(
            cut in 0.5f64..1.0,
            picks in proptest::collection::vec(0.0f64..1.0, 0..6),
            again in any::<bool>(),
            threads in 1usize..4,
        ) {
            let (cells, nodes, layered) = naca0012();
            let first = ((layered as f64 * cut) as usize).max(1);
            let mut removed: Vec<u32> =
                picks.iter().map(|p| (p * first as f64) as u32 % first as u32).collect();
            removed.sort_unstable();
            removed.dedup();
            let mut more: Vec<usize> = (first..cells.len()).collect();
            if again {
                more.extend(removed.iter().map(|&r| r as usize));
            }
            let whole = without_then(&cells, first, &removed, &more);
            let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().unwrap();
            let part = pool.install(|| PartEdges::new(&prefix(&cells, first), nodes));
            prop_assert_eq!(part.cells(), first);
            let changes = Changes { removed: &removed, cells: &whole };
            let finished = pool.install(|| finish(part, changes));
            let want = edge_table_2d(whole.shapes_and_corners());
            prop_assert!(finished == Some(want));
        }
    }

    proptest! {
        /// The doubling search finds what a binary search of the rest finds.
        #[test]
        fn the_doubling_search_is_a_search_of_the_rest(
            mut sorted in proptest::collection::vec(0u32..200, 0..120),
            from in 0usize..130,
            key in 0u32..210,
        ) {
            sorted.sort_unstable();
            let from = from.min(sorted.len());
            let want = from + sorted[from..].partition_point(|&e| e < key);
            prop_assert_eq!(first_not_below(&sorted, from, &key), want);
        }
    }

    /// A part with an edge of three uses, the table of other cells, or changes that do not
    /// fit the part, is not finished: the caller builds the whole table.
    #[test]
    fn a_part_it_cannot_tell_is_left_to_the_whole_build() {
        let (cells, nodes, layered) = naca0012();
        let mut odd = prefix(&cells, layered);
        let c = cells.get(0);
        odd.push(c.ty, c.nodes);
        let whole = without_then(
            &cells,
            layered,
            &[],
            &(layered..cells.len()).collect::<Vec<_>>(),
        );
        let three_uses = PartEdges::new(&odd, nodes);
        let changes = Changes {
            removed: &[],
            cells: &whole,
        };
        assert!(finish(three_uses, changes).is_none());
        let part = PartEdges::new(&prefix(&cells, layered), nodes);
        // the table of other cells: the mesh's layered cells one place on
        let other = without_then(&cells, 0, &[], &(1..=layered).collect::<Vec<_>>());
        let changes = Changes {
            removed: &[],
            cells: &whole,
        };
        assert!(finish(PartEdges::new(&other, nodes), changes).is_none());
        for removed in [&[3, 3][..], &[5, 2], &[layered as u32]] {
            let changes = Changes {
                removed,
                cells: &whole,
            };
            assert!(finish(part.clone(), changes).is_none(), "{removed:?}");
        }
        let fine = Changes {
            removed: &[],
            cells: &whole,
        };
        assert_eq!(
            finish(part, fine),
            Some(edge_table_2d(whole.shapes_and_corners()))
        );
    }
}
