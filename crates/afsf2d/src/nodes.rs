//! The per-node data of the growing mesh in one store (struct of arrays): every node is
//! added by [`NodeStore::push_node`] (or a layer step's at once, [`NodeStore::push_layer`])
//! and removed by [`NodeStore::truncate`], so the arrays always have one entry per node.
//!
//! Nodes are kept in creation order: the boundary nodes first, then layer after layer, then
//! the nodes the hole filling adds. A node's parents are older than the node.

use geom_predicates::vector::dist;
use mesh_model::NONE;
use rayon::prelude::*;

use crate::geom::P2;

/// Nodes from which [`NodeStore::neighbour_shares`] splits its range between threads (and the
/// layer step finds them beside the choice of the problem's nodes).
pub(crate) const PARALLEL_SHARES_MIN: usize = 4096;

/// One new node (see the fields of [`NodeStore`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct NewNode {
    pub pos: P2,
    pub layer: u32,
    pub parent: u32,
    pub ideal: f64,
    pub share: f64,
    pub offset: f64,
}

impl NewNode {
    /// A node with no parent on layer 0 (a boundary node or a node of the hole filling).
    pub(crate) fn unlayered(pos: P2) -> Self {
        NewNode {
            pos,
            layer: 0,
            parent: NONE,
            ideal: 0.0,
            share: 1.0,
            offset: 0.0,
        }
    }
}

/// The per-node arrays, one entry per node.
#[derive(Debug, Clone, Default)]
pub(crate) struct NodeStore {
    pub pos: Vec<P2>,
    pub layer: Vec<u32>,
    /// The node it was extruded from (NONE on the boundary and in the filled region).
    pub parent: Vec<u32>,
    /// The parent of the second child merged into this node when it differs from the first
    /// parent, else NONE.
    pub parent2: Vec<u32>,
    /// Neighbours on the node's own layer (front order), NONE at a step or a layer's end.
    pub left: Vec<u32>,
    pub right: Vec<u32>,
    /// Ideal length of the extrusion edge ending at the node.
    pub ideal: Vec<f64>,
    /// C_aniso of the parent in that extrusion spring.
    pub share: Vec<f64>,
    /// Fan offset of the node's ideal direction from its parent's bisector (radians).
    pub offset: Vec<f64>,
    /// False once the node has been merged into another.
    pub alive: Vec<bool>,
}

impl NodeStore {
    /// The store of the boundary nodes.
    pub(crate) fn boundary(points: Vec<P2>) -> Self {
        let mut s = NodeStore::default();
        for p in points {
            s.push_node(NewNode::unlayered(p));
        }
        s
    }

    /// Number of nodes.
    pub(crate) fn len(&self) -> usize {
        self.pos.len()
    }

    /// Adds a node (alive, with no layer neighbours and no second parent); returns its index.
    pub(crate) fn push_node(&mut self, n: NewNode) -> u32 {
        let g = self.pos.len() as u32;
        self.pos.push(n.pos);
        self.layer.push(n.layer);
        self.parent.push(n.parent);
        self.parent2.push(NONE);
        self.left.push(NONE);
        self.right.push(NONE);
        self.ideal.push(n.ideal);
        self.share.push(n.share);
        self.offset.push(n.offset);
        self.alive.push(true);
        g
    }

    /// Pushes the children of one loop's layer step at once, array by array (the store of
    /// a [`NodeStore::push_node`] each): their positions, ideal lengths and fan offsets, and
    /// their `parents` (one each, in order), all on `layer` with the parent's `share`.
    pub(crate) fn push_layer(
        &mut self,
        layer: u32,
        share: f64,
        (pos, ideal, offset): (&[P2], &[f64], &[f64]),
        parents: impl Iterator<Item = u32>,
    ) {
        let n = pos.len();
        debug_assert!(ideal.len() == n && offset.len() == n);
        self.pos.extend_from_slice(pos);
        self.layer.extend(std::iter::repeat_n(layer, n));
        self.parent.extend(parents);
        debug_assert_eq!(self.parent.len(), self.pos.len());
        for list in [&mut self.parent2, &mut self.left, &mut self.right] {
            list.extend(std::iter::repeat_n(NONE, n));
        }
        self.ideal.extend_from_slice(ideal);
        self.share.extend(std::iter::repeat_n(share, n));
        self.offset.extend_from_slice(offset);
        self.alive.extend(std::iter::repeat_n(true, n));
    }

    /// Keeps the first `n` nodes.
    pub(crate) fn truncate(&mut self, n: usize) {
        self.pos.truncate(n);
        self.layer.truncate(n);
        self.parent.truncate(n);
        self.parent2.truncate(n);
        self.left.truncate(n);
        self.right.truncate(n);
        self.ideal.truncate(n);
        self.share.truncate(n);
        self.offset.truncate(n);
        self.alive.truncate(n);
    }

    /// Both parents of node `g`.
    pub(crate) fn parents(&self, g: usize) -> [u32; 2] {
        [self.parent[g], self.parent2[g]]
    }

    /// The left share of the neighbour spring of each node of `range` (its place in the
    /// range): the share of |AK| + |KB| that |AK| should take for node K (parent P, layer
    /// neighbours A and B) is the share of the parents' spacing |A'P| / (|A'P| + |PB'|), so
    /// that a wall's graded spacing carries up the layers; ½ where a neighbour shares K's
    /// parent (fan children) or has none. Clamped to [0.2, 0.8]. NaN for a node without a
    /// neighbour spring (dead, or a neighbour or the parent missing). Made on every thread
    /// for a large range.
    pub(crate) fn neighbour_shares(&self, range: std::ops::Range<usize>) -> Vec<f64> {
        let share = |g: usize| {
            let (a, b, p) = (self.left[g], self.right[g], self.parent[g]);
            let n = self.len() as u32;
            // (a dead node's neighbours may be gone: it has no spring)
            if !self.alive[g] || a >= n || b >= n || p >= n {
                return f64::NAN;
            }
            let (pa, pb) = (self.parent[a as usize], self.parent[b as usize]);
            if pa == NONE || pb == NONE || pa == p || pb == p {
                return 0.5;
            }
            let pp = self.pos[p as usize];
            let (la, lb) = (
                dist(self.pos[pa as usize], pp),
                dist(pp, self.pos[pb as usize]),
            );
            if la + lb <= 0.0 {
                return 0.5;
            }
            (la / (la + lb)).clamp(0.2, 0.8)
        };
        if range.len() >= PARALLEL_SHARES_MIN {
            range
                .into_par_iter()
                .with_min_len(1024)
                .map(share)
                .collect()
        } else {
            range.map(share).collect()
        }
    }

    /// The first inconsistency of the store: arrays of different lengths, a parent that is
    /// not an older node, a layer neighbour out of range.
    pub(crate) fn check(&self) -> Result<(), String> {
        let n = self.len();
        let lengths = [
            self.layer.len(),
            self.parent.len(),
            self.parent2.len(),
            self.left.len(),
            self.right.len(),
            self.ideal.len(),
            self.share.len(),
            self.offset.len(),
            self.alive.len(),
        ];
        if let Some(l) = lengths.iter().find(|&&l| l != n) {
            return Err(format!(
                "node store: an array has {l} entries for {n} nodes"
            ));
        }
        for g in 0..n {
            for p in self.parents(g) {
                if p != NONE && p as usize >= g {
                    return Err(format!("node {g}: parent {p} is not an older node"));
                }
            }
            for o in [self.left[g], self.right[g]] {
                if o != NONE && o as usize >= n {
                    return Err(format!("node {g}: layer neighbour {o} out of range"));
                }
            }
        }
        Ok(())
    }
}
