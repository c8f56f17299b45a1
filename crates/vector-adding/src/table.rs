//! The unique edges of a linear 2D mesh built on every thread: the same three arrays as
//! `mesh_model::topology::edge_table_2d` (each edge's ends, its first two cells, each cell's
//! edges), to the last entry, whatever the number of threads.
//!
//! The nodes are cut into as many ranges as there are threads; each range gathers, in two
//! passes over the cells (a count, then a scatter straight from the cells; only the chunks of
//! cells whose nodes meet its range), the edges whose lower node it holds, sorted by their
//! lower node and then in full within each node's few edges. The ranges are in node order, so
//! their edges one after the other are the edges of the whole mesh in sorted order; each range
//! then numbers its own edges from where the ranges before it end, and writes them into its
//! own part of the final arrays.

use std::sync::atomic::{AtomicU32, Ordering};

use mesh_model::topology::EdgeTable2d;
use mesh_model::{Cells, NONE};
use rayon::prelude::*;

/// One edge use: the edge's ends (lower node first), the cell and its local edge.
pub(crate) type Record = ([u32; 2], u32, u8);

/// A range's part of the final arrays: its edges' ends and first two cells.
type Part<'a> = (&'a mut [[u32; 2]], &'a mut [[u32; 2]]);

/// The edge table of `cells`, whose nodes are all below `nodes`: as
/// `mesh_model::topology::edge_table_2d`, built on every thread of the pool.
pub(crate) fn edge_table_2d(cells: &Cells, nodes: usize) -> EdgeTable2d {
    build(cells, nodes).0
}

/// [`edge_table_2d`], and whether no edge has more than two uses.
pub(crate) fn build(cells: &Cells, nodes: usize) -> (EdgeTable2d, bool) {
    let parts = rayon::current_num_threads().clamp(1, 64);
    let range = |t: usize| (nodes * t / parts) as u32..(nodes * (t + 1) / parts) as u32;
    // (one range reads every cell: it needs no spans)
    let spans = if parts > 1 {
        chunk_spans(cells)
    } else {
        Vec::new()
    };
    let sorted: Vec<Vec<Record>> = (0..parts)
        .into_par_iter()
        .map(|t| records_from(cells, &spans, range(t)))
        .collect();
    let unique: Vec<usize> = sorted.par_iter().map(|r| count_unique(r)).collect();
    let first: Vec<usize> = unique
        .iter()
        .scan(0, |sum, &u| {
            let at = *sum;
            *sum += u;
            Some(at)
        })
        .collect();
    let of_cell: Vec<[AtomicU32; 4]> = (0..cells.len())
        .into_par_iter()
        .map(|_| [const { AtomicU32::new(NONE) }; 4])
        .collect();
    // each range writes its edges into its own part of the final arrays
    let total = unique.iter().sum();
    let (mut ends, mut cells_of) = (vec![[0; 2]; total], vec![[NONE; 2]; total]);
    let mut parts_of: Vec<Part<'_>> = Vec::with_capacity(parts);
    let (mut ends_left, mut cells_left) = (&mut ends[..], &mut cells_of[..]);
    for &u in &unique {
        let (e, rest_e) = std::mem::take(&mut ends_left).split_at_mut(u);
        let (c, rest_c) = std::mem::take(&mut cells_left).split_at_mut(u);
        parts_of.push((e, c));
        (ends_left, cells_left) = (rest_e, rest_c);
    }
    let manifold = sorted
        .into_par_iter()
        .zip(parts_of)
        .zip(first)
        .map(|((records, (ends, cells_of)), first)| {
            number(&records, first, ends, cells_of, &of_cell)
        })
        .reduce(|| true, |a, b| a && b);
    let of_cell = of_cell
        .into_iter()
        .map(|slots| slots.map(AtomicU32::into_inner))
        .collect();
    ((ends, cells_of, of_cell), manifold)
}

/// Cells per chunk of [`chunk_spans`].
const SPAN_CHUNK: usize = 4096;

/// The lowest and the highest corner of the cells of each chunk of [`SPAN_CHUNK`] cells, on
/// every thread: a range's passes skip the chunks with none of its nodes. The cells of a
/// layered mesh come nearly in the order of their nodes, so each range reads little more than
/// its share of the cells (every range read every cell twice before).
fn chunk_spans(cells: &Cells) -> Vec<[u32; 2]> {
    (0..cells.len().div_ceil(SPAN_CHUNK))
        .into_par_iter()
        .map(|k| {
            let mut span = [u32::MAX, 0];
            for i in k * SPAN_CHUNK..((k + 1) * SPAN_CHUNK).min(cells.len()) {
                for &v in cells.get(i).corners() {
                    span = [span[0].min(v), span[1].max(v)];
                }
            }
            span
        })
        .collect()
}

/// The edge uses of `cells` whose lower node is in `range`, sorted: counted by lower node,
/// scattered into their buckets in cell order, then each bucket sorted in full. `spans` are
/// the chunks' spans ([`chunk_spans`]), or empty to read every cell.
fn records_from(cells: &Cells, spans: &[[u32; 2]], range: std::ops::Range<u32>) -> Vec<Record> {
    let width = (range.end - range.start) as usize;
    let mut start = vec![0u32; width + 1];
    for_each_use(cells, spans, &range, |r| {
        start[(r.0[0] - range.start) as usize + 1] += 1
    });
    for v in 0..width {
        start[v + 1] += start[v];
    }
    let mut fill = start.clone();
    let mut records: Vec<Record> = vec![([0; 2], 0, 0); start[width] as usize];
    for_each_use(cells, spans, &range, |r| {
        let slot = &mut fill[(r.0[0] - range.start) as usize];
        records[*slot as usize] = r;
        *slot += 1;
    });
    for v in 0..width {
        records[start[v] as usize..start[v + 1] as usize].sort_unstable();
    }
    records
}

/// Calls `f` with every edge use of `cells` whose lower node is in `range`, in cell order,
/// reading only the chunks whose span (`spans`; empty: every cell) meets the range.
fn for_each_use(
    cells: &Cells,
    spans: &[[u32; 2]],
    range: &std::ops::Range<u32>,
    mut f: impl FnMut(Record),
) {
    let mut in_range = |i: usize| {
        uses_of(cells, i)
            .filter(|r| range.contains(&r.0[0]))
            .for_each(&mut f);
    };
    if spans.is_empty() {
        (0..cells.len()).for_each(&mut in_range);
        return;
    }
    for (k, span) in spans.iter().enumerate() {
        if span[0] < range.end && span[1] >= range.start {
            (k * SPAN_CHUNK..((k + 1) * SPAN_CHUNK).min(cells.len())).for_each(&mut in_range);
        }
    }
}

/// The edge uses of cell `i` of `cells`, in its local edges' order.
pub(crate) fn uses_of(cells: &Cells, i: usize) -> impl Iterator<Item = Record> + '_ {
    let c = cells.get(i);
    let nodes = c.corners();
    c.ty.shape.edges().iter().enumerate().map(move |(j, e)| {
        let (a, b) = (nodes[e[0]], nodes[e[1]]);
        ([a.min(b), a.max(b)], i as u32, j as u8)
    })
}

/// How many distinct edges the sorted `records` hold.
fn count_unique(records: &[Record]) -> usize {
    records.windows(2).filter(|w| w[0].0 != w[1].0).count() + usize::from(!records.is_empty())
}

/// The ends and first two cells of the edges of the sorted `records` into `ends` and
/// `cells_of` (as many as there are edges), the edges numbered from `first`; each use's edge
/// goes into `of_cell`. Returns whether no edge has more than two uses.
fn number(
    records: &[Record],
    first: usize,
    ends: &mut [[u32; 2]],
    cells_of: &mut [[u32; 2]],
    of_cell: &[[AtomicU32; 4]],
) -> bool {
    let mut manifold = true;
    let mut e: Option<usize> = None;
    for &(k, cell, local) in records {
        let at = match e {
            Some(at) if ends[at] == k => at,
            _ => {
                let at = e.map_or(0, |at| at + 1);
                ends[at] = k;
                at
            }
        };
        e = Some(at);
        match cells_of[at].iter_mut().find(|c| **c == NONE) {
            Some(slot) => *slot = cell,
            None => manifold = false,
        }
        of_cell[cell as usize][usize::from(local)].store((first + at) as u32, Ordering::Relaxed);
    }
    manifold
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The table is `mesh_model`'s, entry for entry, on a real layered mesh (quadrilaterals
    /// and triangles) with 1, 2 and 3 threads, its cells in their order (each range reads
    /// few chunks), reversed, and dealt out from both ends (each chunk spans every range).
    #[test]
    fn the_table_is_the_topology_one_whatever_the_threads() {
        let g = test_cases::grow(&test_cases::real_case("naca0012"));
        let mesh = &g.output.layered.mesh;
        let n = mesh.cells.len();
        assert!(n > 2 * SPAN_CHUNK, "{n} cells: several chunks");
        let reordered = |order: &mut dyn Iterator<Item = usize>| {
            let mut cells = Cells::new();
            for i in order {
                let c = mesh.cells.get(i);
                cells.push(c.ty, c.nodes);
            }
            cells
        };
        let mut dealt = (0..n).map(|k| if k % 2 == 0 { k / 2 } else { n - 1 - k / 2 });
        for cells in [
            mesh.cells.clone(),
            reordered(&mut (0..n).rev()),
            reordered(&mut dealt),
        ] {
            let want = mesh_model::topology::edge_table_2d(cells.shapes_and_corners());
            for threads in [1, 2, 3] {
                let pool = rayon::ThreadPoolBuilder::new()
                    .num_threads(threads)
                    .build()
                    .unwrap();
                let got = pool.install(|| edge_table_2d(&cells, mesh.nodes.len()));
                assert_eq!(got, want, "{threads} threads");
            }
        }
    }
}
