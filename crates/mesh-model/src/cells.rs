//! A compact store of mixed cells: one flat node array with offsets, so that a mesh of
//! 100k mixed cells is three allocations, not 100k.

use serde::{Deserialize, Serialize};

use crate::cell::{CellType, Shape};

/// Mixed cells of any type, nodes stored flat (compressed-row layout).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cells {
    types: Vec<CellType>,
    offsets: Vec<u32>,
    nodes: Vec<u32>,
}

/// One cell borrowed from a [`Cells`] store.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CellRef<'a> {
    /// The cell's type.
    pub ty: CellType,
    /// Its node indices, in Gmsh order.
    pub nodes: &'a [u32],
}

impl<'a> CellRef<'a> {
    /// The corner nodes (the linear cell underneath).
    pub fn corners(&self) -> &'a [u32] {
        &self.nodes[..self.ty.shape.corners()]
    }
}

impl Default for Cells {
    fn default() -> Self {
        Cells::new()
    }
}

impl Cells {
    /// An empty store.
    pub fn new() -> Self {
        Cells {
            types: Vec::new(),
            offsets: vec![0],
            nodes: Vec::new(),
        }
    }

    /// An empty store with room for `cells` cells of `nodes_per_cell` nodes.
    pub fn with_capacity(cells: usize, nodes_per_cell: usize) -> Self {
        Cells::with_capacity_for(cells, cells * nodes_per_cell)
    }

    /// An empty store with room for `cells` cells of `nodes` nodes in all (no more: a store
    /// of mixed cells filled to the byte).
    pub fn with_capacity_for(cells: usize, nodes: usize) -> Self {
        let mut offsets = Vec::with_capacity(cells + 1);
        offsets.push(0);
        Cells {
            types: Vec::with_capacity(cells),
            offsets,
            nodes: Vec::with_capacity(nodes),
        }
    }

    /// The store of cells of `types`, the nodes of cell `i` at `nodes[offsets[i]..offsets[i +
    /// 1]]`: the parts of a store filled other than by [`Cells::push`] (by several threads at
    /// once, each into its own range).
    ///
    /// # Panics
    /// If `offsets` does not start at 0, step by each type's node count and end at
    /// `nodes.len()`: that is a bug in the caller, not bad input.
    pub fn from_parts(types: Vec<CellType>, offsets: Vec<u32>, nodes: Vec<u32>) -> Self {
        assert_eq!(
            offsets.len(),
            types.len() + 1,
            "one offset per cell, and one more"
        );
        assert_eq!(offsets[0], 0, "the first cell's nodes start at 0");
        assert_eq!(
            offsets[types.len()] as usize,
            nodes.len(),
            "the last offset is the node count"
        );
        for (i, ty) in types.iter().enumerate() {
            assert_eq!(
                (offsets[i + 1] - offsets[i]) as usize,
                ty.node_count(),
                "cell {i} ({ty:?}) has the nodes of its type"
            );
        }
        Cells {
            types,
            offsets,
            nodes,
        }
    }

    /// Appends a cell and returns its index.
    ///
    /// # Panics
    /// If `nodes.len()` is not the node count of `ty`: that is a bug in the caller, not bad input.
    pub fn push(&mut self, ty: CellType, nodes: &[u32]) -> usize {
        assert_eq!(
            nodes.len(),
            ty.node_count(),
            "cell {ty:?} needs {} nodes",
            ty.node_count()
        );
        self.types.push(ty);
        self.nodes.extend_from_slice(nodes);
        self.offsets.push(self.nodes.len() as u32);
        self.types.len() - 1
    }

    /// Keeps only the cells for which `keep(index, cell)` is true, in order (in place: the
    /// kept cells move down over the others).
    pub fn retain(&mut self, mut keep: impl FnMut(usize, CellRef<'_>) -> bool) {
        let (mut cells, mut nodes) = (0, 0);
        for i in 0..self.len() {
            if !keep(i, self.get(i)) {
                continue;
            }
            let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
            self.nodes.copy_within(a..b, nodes);
            self.types[cells] = self.types[i];
            nodes += b - a;
            cells += 1;
            self.offsets[cells] = nodes as u32;
        }
        self.types.truncate(cells);
        self.offsets.truncate(cells + 1);
        self.nodes.truncate(nodes);
    }

    /// Removes the cells at the increasing indices `at`, in place: the cells after the first
    /// of them move down, run by run (the cells between two removed ones in one move), the
    /// others are not touched.
    ///
    /// # Panics
    /// If `at` is not increasing or names a cell past the end: a bug in the caller.
    pub fn remove_sorted(&mut self, at: &[usize]) {
        let runs = kept_runs(at, self.len(), "cells");
        let Some(&first) = at.first() else {
            return;
        };
        let (mut cells, mut nodes) = (first, self.offsets[first] as usize);
        for run in runs {
            let (a, b) = (
                self.offsets[run.start] as usize,
                self.offsets[run.end] as usize,
            );
            self.nodes.copy_within(a..b, nodes);
            self.types.copy_within(run.clone(), cells);
            // (each offset is read before the one written over it: cells < run.start)
            let shift = (a - nodes) as u32;
            for i in run.clone() {
                self.offsets[cells + 1 + i - run.start] = self.offsets[i + 1] - shift;
            }
            nodes += b - a;
            cells += run.len();
        }
        self.types.truncate(cells);
        self.offsets.truncate(cells + 1);
        self.nodes.truncate(nodes);
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.types.len()
    }

    /// True when there is no cell.
    pub fn is_empty(&self) -> bool {
        self.types.is_empty()
    }

    /// Cell `i`.
    pub fn get(&self, i: usize) -> CellRef<'_> {
        let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
        CellRef {
            ty: self.types[i],
            nodes: &self.nodes[a..b],
        }
    }

    /// Mutable node indices of cell `i` (to renumber or to add high-order nodes in place).
    pub fn nodes_mut(&mut self, i: usize) -> &mut [u32] {
        let (a, b) = (self.offsets[i] as usize, self.offsets[i + 1] as usize);
        &mut self.nodes[a..b]
    }

    /// All cells in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = CellRef<'_>> + Clone + '_ {
        (0..self.len()).map(move |i| self.get(i))
    }

    /// The shape and the corner nodes of every cell, in order: the input of the
    /// [`crate::topology`] builders.
    pub fn shapes_and_corners(
        &self,
    ) -> impl ExactSizeIterator<Item = (Shape, &[u32])> + Clone + '_ {
        self.iter().map(|c| (c.ty.shape, c.corners()))
    }

    /// The types of all cells, in order.
    pub fn types(&self) -> &[CellType] {
        &self.types
    }

    /// All node indices of all cells, flat.
    pub fn flat_nodes(&self) -> &[u32] {
        &self.nodes
    }

    /// How many cells of each shape there are.
    pub fn count(&self, shape: Shape) -> usize {
        self.types.iter().filter(|t| t.shape == shape).count()
    }
}

/// Removes the entries of `list` at the increasing positions `at`, in place, the others kept
/// in their order, run by run (what [`Cells::remove_sorted`] does to cells, for a per-cell
/// array).
///
/// # Panics
/// If `at` is not increasing or names an entry past the end: a bug in the caller.
pub fn remove_sorted<T: Copy>(list: &mut Vec<T>, at: &[usize]) {
    let runs = kept_runs(at, list.len(), "entries");
    let Some(&first) = at.first() else {
        return;
    };
    let mut kept = first;
    for run in runs {
        list.copy_within(run.clone(), kept);
        kept += run.len();
    }
    list.truncate(kept);
}

/// The run of entries kept after each of the positions `at` removed from `len` entries, in
/// order: what the removals move down, one run at a time.
///
/// # Panics
/// If `at` is not increasing or names a position past the end (`what`: what is removed).
fn kept_runs<'a>(
    at: &'a [usize],
    len: usize,
    what: &str,
) -> impl Iterator<Item = std::ops::Range<usize>> + 'a {
    assert!(
        at.windows(2).all(|w| w[0] < w[1]) && at.last().is_none_or(|&l| l < len),
        "{what} to remove: increasing, below {len}"
    );
    let next = move |k: usize| at.get(k + 1).copied().unwrap_or(len);
    at.iter()
        .enumerate()
        .map(move |(k, &gone)| gone + 1..next(k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mixed_cells_round_trip_through_the_flat_store() {
        let mut c = Cells::new();
        let t = c.push(CellType::new(Shape::Tri, 1), &[0, 1, 2]);
        let q = c.push(CellType::new(Shape::Quad, 2), &[0, 1, 2, 3, 4, 5, 6, 7, 8]);
        assert_eq!((t, q), (0, 1));
        assert_eq!(c.get(0).nodes, &[0, 1, 2]);
        assert_eq!(c.get(1).corners(), &[0, 1, 2, 3]);
        assert_eq!(c.count(Shape::Quad), 1);
        assert_eq!(c.iter().len(), 2);
        let d = Cells::default();
        assert!(d.is_empty());
    }

    #[test]
    fn retained_cells_are_those_pushed_alone() {
        let (tri, quad) = (CellType::new(Shape::Tri, 1), CellType::new(Shape::Quad, 3));
        let all: Vec<(CellType, Vec<u32>)> = (0..9u32)
            .map(|i| {
                let ty = if i % 3 == 1 { quad } else { tri };
                (
                    ty,
                    (0..ty.node_count() as u32).map(|k| 100 * i + k).collect(),
                )
            })
            .collect();
        for drop in [vec![], vec![0], vec![1, 2], vec![4, 8], (0..9).collect()] {
            let mut cells = Cells::new();
            for (ty, nodes) in &all {
                cells.push(*ty, nodes);
            }
            let mut seen = Vec::new();
            cells.retain(|i, c| {
                seen.push(i);
                assert_eq!(c.nodes, &all[i].1[..]);
                !drop.contains(&i)
            });
            assert_eq!(seen, (0..9).collect::<Vec<_>>());
            let mut kept = Cells::new();
            for (i, (ty, nodes)) in all.iter().enumerate() {
                if !drop.contains(&i) {
                    kept.push(*ty, nodes);
                }
            }
            assert_eq!(cells, kept, "dropping {drop:?}");
            let mut removed = Cells::new();
            for (ty, nodes) in &all {
                removed.push(*ty, nodes);
            }
            removed.remove_sorted(&drop);
            assert_eq!(removed, kept, "removing {drop:?}");
        }
    }

    proptest::proptest! {
        /// Cells and a per-cell list with some removed run by run are those kept one by one.
        #[test]
        fn removing_runs_keeps_the_others_in_order(
            sizes in proptest::collection::vec(0usize..3, 0..40),
            drop in proptest::collection::vec(proptest::prelude::any::<bool>(), 40),
        ) {
            let shapes = [(Shape::Tri, 1), (Shape::Quad, 1), (Shape::Quad, 3)];
            let mut cells = Cells::new();
            for (i, &k) in sizes.iter().enumerate() {
                let ty = CellType::new(shapes[k].0, shapes[k].1);
                let nodes: Vec<u32> = (0..ty.node_count() as u32).map(|n| 100 * i as u32 + n).collect();
                cells.push(ty, &nodes);
            }
            let at: Vec<usize> = (0..sizes.len()).filter(|&i| drop[i]).collect();
            let mut want = cells.clone();
            want.retain(|i, _| !drop[i]);
            let mut list: Vec<usize> = (0..sizes.len()).collect();
            let want_list: Vec<usize> = (0..sizes.len()).filter(|&i| !drop[i]).collect();
            cells.remove_sorted(&at);
            remove_sorted(&mut list, &at);
            proptest::prop_assert_eq!(cells, want);
            proptest::prop_assert_eq!(list, want_list);
        }
    }

    #[test]
    fn a_store_from_its_parts_is_the_pushed_one() {
        let (tri, quad) = (CellType::new(Shape::Tri, 1), CellType::new(Shape::Quad, 2));
        let mut pushed = Cells::new();
        pushed.push(tri, &[0, 1, 2]);
        pushed.push(quad, &[3, 4, 5, 6, 7, 8, 9, 10, 11]);
        let parts = Cells::from_parts(vec![tri, quad], vec![0, 3, 12], (0..12).collect());
        assert_eq!(parts, pushed);
    }

    #[test]
    #[should_panic(expected = "has the nodes of its type")]
    fn parts_that_give_a_cell_too_few_nodes_are_refused() {
        let tri = CellType::new(Shape::Tri, 1);
        Cells::from_parts(vec![tri, tri], vec![0, 2, 6], (0..6).collect());
    }
}
