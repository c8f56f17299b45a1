//! The active-set tables shared by the models and the solver: [`Influence`], which nodes'
//! forces depend on which, and [`Active`], the nodes one iteration updates.

/// Which nodes' forces depend on which, stored the way the active set needs it: for node
/// `j`, [`Influence::dependents`] lists the other nodes whose force depends on the position of
/// `j` (the nodes pushed by a spring that `j` belongs to). Built by [`Influence::from_pairs`]
/// or [`crate::springs::SpringSet2d::influence`].
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Influence {
    offsets: Vec<u32>,
    targets: Vec<u32>,
}

impl Influence {
    /// Builds the table for `n` nodes from (pushed node, node its force depends on) pairs;
    /// repeated pairs and pairs of a node with itself are dropped. Pairs naming a node
    /// `>= n` are ignored.
    pub fn from_pairs(n: usize, pairs: impl IntoIterator<Item = (u32, u32)>) -> Self {
        // counting sort into rows keyed by the node depended on, then each (short) row is
        // sorted and deduplicated in place
        let pairs: Vec<(u32, u32)> = pairs
            .into_iter()
            .filter(|&(a, b)| a != b && (a as usize) < n && (b as usize) < n)
            .collect();
        let mut start = vec![0u32; n + 1];
        for &(_, on) in &pairs {
            start[on as usize + 1] += 1;
        }
        for i in 0..n {
            start[i + 1] += start[i];
        }
        let mut fill = start.clone();
        let mut rows = vec![0u32; pairs.len()];
        for &(pushed, on) in &pairs {
            rows[fill[on as usize] as usize] = pushed;
            fill[on as usize] += 1;
        }
        let mut offsets = Vec::with_capacity(n + 1);
        offsets.push(0u32);
        let mut targets: Vec<u32> = Vec::with_capacity(rows.len());
        for i in 0..n {
            let row = &mut rows[start[i] as usize..start[i + 1] as usize];
            row.sort_unstable();
            let first = targets.len();
            for &t in row.iter() {
                if targets.len() == first || targets[targets.len() - 1] != t {
                    targets.push(t);
                }
            }
            offsets.push(targets.len() as u32);
        }
        Influence { offsets, targets }
    }

    /// The table of rows already sorted and free of repeats: row `j` is
    /// `targets[offsets[j]..offsets[j + 1]]`.
    pub(crate) fn from_rows(offsets: Vec<u32>, targets: Vec<u32>) -> Self {
        debug_assert!(
            offsets.first() == Some(&0) && offsets.last() == Some(&(targets.len() as u32))
        );
        Influence { offsets, targets }
    }

    /// Number of nodes the table covers.
    pub fn len(&self) -> usize {
        self.offsets.len().saturating_sub(1)
    }

    /// True when the table covers no node.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The nodes whose force depends on the position of `node`.
    pub fn dependents(&self, node: usize) -> &[u32] {
        &self.targets[self.offsets[node] as usize..self.offsets[node + 1] as usize]
    }
}

/// The nodes a [`crate::solve_active()`] iteration updates, as flags (one per node) and as a list.
#[derive(Debug, Clone, Copy)]
pub struct Active<'a> {
    /// `flags[i]`: node i is updated this iteration.
    pub flags: &'a [bool],
    /// The flagged nodes (each once, in no particular order).
    pub nodes: &'a [u32],
}
