//! The record of every decision the curving took — how each edge got its high-order nodes and
//! how each quadrilateral was cut — so that a moved mesh of the same topology can be curved
//! the same way ([`crate::curve_mesh_keeping`]) and differentiated ([`crate::tangent`]).
//!
//! With the decisions fixed, the curving is a linear homogeneous map of the linear nodes and
//! of the boundary's high-order nodes: a carried edge is its chord plus a fraction of the
//! deviation of its source edge from that edge's chord; a diagonal is its chord or a point
//! of its quadrilateral's map; interior nodes follow from the edges.

use serde::{Deserialize, Serialize};

use crate::params::Strategy;

/// How one edge of the linear mesh got its high-order nodes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum EdgeRule {
    /// On its chord: never reached, or a pipe stopped below it.
    Straight,
    /// A boundary edge: its nodes lie on its loop's curve (given from outside).
    OnCurve,
    /// Its chord plus a fraction of another edge's deviation from its chord: the top of a
    /// pipe's cell (Vector-Adding) or an edge bent by the repair.
    Carried(Carry),
}

/// A carried edge: node `i` of the edge, listed from `from`, is the point at `(i + 1)/p` of
/// its chord plus `fraction` times the deviation of node `i` of edge `source` listed from
/// `source_from` (node `p − 2 − i` when `reversed`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Carry {
    /// The edge (topology index) whose deviation is laid on this one.
    pub source: u32,
    /// The end of `source` its deviation is listed from.
    pub source_from: u32,
    /// The end of this edge its nodes are listed from.
    pub from: u32,
    /// Whether the deviation is laid in reverse order.
    pub reversed: bool,
    /// The fraction of the deviation received (1, 0.5 or 0.25).
    pub fraction: f64,
}

/// The cut of one quadrilateral into two triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub struct Diagonal {
    /// The diagonal joins local corners `from` and `from + 2` (0 or 1).
    pub from: u8,
    /// Whether it follows the quadrilateral's map (else straight).
    pub curved: bool,
}

/// Every decision of one curving run, indexed by the linear mesh's edges in the order of
/// `mesh_model::topology::Edges` (sorted by their corner pairs) and by its cells.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Decisions {
    /// Order of the curved mesh.
    pub order: u8,
    /// Whether quadrilaterals were cut into triangles.
    pub triangles: bool,
    /// The vector strategy (it shapes curved diagonals).
    pub strategy: Strategy,
    /// Each edge's corner pair, lower node first, sorted.
    pub edges: Vec<[u32; 2]>,
    /// Each edge's rule.
    pub rules: Vec<EdgeRule>,
    /// Per cell, the cut of a quadrilateral (None for a triangle, and for every cell when
    /// not cutting).
    pub diagonals: Vec<Option<Diagonal>>,
}

impl Decisions {
    /// The topology index of the edge joining nodes `a` and `b`.
    pub fn edge(&self, a: u32, b: u32) -> Option<u32> {
        let key = [a.min(b), a.max(b)];
        self.edges.binary_search(&key).ok().map(|e| e as u32)
    }

    /// The rule of the edge joining nodes `a` and `b`.
    pub fn rule(&self, a: u32, b: u32) -> Option<&EdgeRule> {
        self.edge(a, b).map(|e| &self.rules[e as usize])
    }
}

/// One decision of a previous run that a re-curving changed.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum DecisionChange {
    /// An edge's rule changed (a stop moved, a fraction, a mend).
    Edge {
        /// The edge's corner nodes, lower first.
        corners: [u32; 2],
        /// The previous rule.
        old: EdgeRule,
        /// The rule now.
        new: EdgeRule,
    },
    /// A quadrilateral's cut changed.
    Diagonal {
        /// The linear cell.
        cell: u32,
        /// The previous cut.
        old: Diagonal,
        /// The cut now.
        new: Diagonal,
    },
}

/// The points of a carried edge: the point at `(i + 1)/p` from `xf` to `xt` plus `fraction`
/// times deviation `i` (`p − 2 − i` when `reversed`); `out` has `p − 1` slots.
pub(crate) fn lay(
    p: usize,
    xf: [f64; 2],
    xt: [f64; 2],
    dev: &[[f64; 2]],
    reversed: bool,
    fraction: f64,
    out: &mut [[f64; 2]],
) {
    let q = p - 1;
    for (i, o) in out.iter_mut().enumerate().take(q) {
        let d = if reversed { dev[q - 1 - i] } else { dev[i] };
        let l = crate::edges::lerp(xf, xt, (i + 1) as f64 / p as f64);
        *o = [l[0] + fraction * d[0], l[1] + fraction * d[1]];
    }
}
