//! The record of every decision the curving took — how each edge got its high-order nodes and
//! how each quadrilateral was cut — so that a moved mesh of the same topology can be curved
//! the same way ([`crate::curve_mesh_keeping`]) and differentiated ([`crate::tangent`]).
//!
//! With the decisions fixed, the curving is a linear homogeneous map of the linear nodes and
//! of the boundary's high-order nodes: a carried edge is its chord plus a fraction of the
//! deviation of its source edge from that edge's chord; a diagonal is its chord or a point
//! of its quadrilateral's map; interior nodes follow from the edges.

use std::collections::BTreeMap;
use std::ops::Index;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

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

/// The rule of every edge of a mesh, `Straight` unless set otherwise. Most edges are
/// straight (at 1M cells, 99 % of them), so only the others are stored, by edge index: the
/// record of a curving is small next to the mesh. Serialised as the list of every edge's rule
/// in edge order (as a `Vec<EdgeRule>` is, so files written before read the same).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct EdgeRules {
    /// How many edges there are.
    len: usize,
    /// The rule of every edge that is not straight, by edge index.
    other: BTreeMap<u32, EdgeRule>,
}

/// What [`EdgeRules`] answers for an edge it does not store.
static STRAIGHT: EdgeRule = EdgeRule::Straight;

impl EdgeRules {
    /// `len` straight edges.
    pub fn straight(len: usize) -> Self {
        EdgeRules {
            len,
            other: BTreeMap::new(),
        }
    }

    /// Number of edges.
    pub fn len(&self) -> usize {
        self.len
    }

    /// Whether there is no edge.
    pub fn is_empty(&self) -> bool {
        self.len == 0
    }

    /// Sets the rule of edge `e`.
    ///
    /// # Panics
    /// If `e` is not an edge (`e ≥ len`).
    pub fn set(&mut self, e: usize, rule: EdgeRule) {
        assert!(e < self.len, "edge {e} of {} edges", self.len);
        if rule == EdgeRule::Straight {
            self.other.remove(&(e as u32));
        } else {
            self.other.insert(e as u32, rule);
        }
    }

    /// Adds an edge with `rule` after the others.
    pub fn push(&mut self, rule: EdgeRule) {
        self.len += 1;
        self.set(self.len - 1, rule);
    }

    /// Keeps the first `len` edges.
    pub fn truncate(&mut self, len: usize) {
        if len < self.len {
            self.other.split_off(&(len as u32));
            self.len = len;
        }
    }

    /// Every edge's rule, in edge order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = EdgeRule> + '_ {
        let mut other = self.other.iter().peekable();
        (0..self.len).map(move |e| match other.next_if(|&(&o, _)| o as usize == e) {
            Some((_, rule)) => *rule,
            None => EdgeRule::Straight,
        })
    }

    /// The edges that are not straight, in edge order, with their rules.
    pub fn not_straight(&self) -> impl Iterator<Item = (usize, &EdgeRule)> + '_ {
        self.other.iter().map(|(&e, rule)| (e as usize, rule))
    }
}

impl Index<usize> for EdgeRules {
    type Output = EdgeRule;

    /// The rule of edge `e`; panics if `e` is not an edge.
    fn index(&self, e: usize) -> &EdgeRule {
        assert!(e < self.len, "edge {e} of {} edges", self.len);
        self.other.get(&(e as u32)).unwrap_or(&STRAIGHT)
    }
}

impl FromIterator<EdgeRule> for EdgeRules {
    fn from_iter<I: IntoIterator<Item = EdgeRule>>(rules: I) -> Self {
        let mut out = EdgeRules::default();
        for rule in rules {
            out.push(rule);
        }
        out
    }
}

impl From<Vec<EdgeRule>> for EdgeRules {
    fn from(rules: Vec<EdgeRule>) -> Self {
        rules.into_iter().collect()
    }
}

impl Serialize for EdgeRules {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.collect_seq(self.iter())
    }
}

impl<'de> Deserialize<'de> for EdgeRules {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        Vec::<EdgeRule>::deserialize(d).map(EdgeRules::from)
    }
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
    pub rules: EdgeRules,
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

#[cfg(test)]
mod tests {
    use super::*;

    fn carried(source: u32, fraction: f64) -> EdgeRule {
        EdgeRule::Carried(Carry {
            source,
            source_from: 0,
            from: 1,
            reversed: source > 1,
            fraction,
        })
    }

    #[test]
    fn sparse_rules_read_as_the_dense_list() {
        let dense = vec![
            EdgeRule::Straight,
            EdgeRule::OnCurve,
            carried(1, 0.5),
            EdgeRule::Straight,
            EdgeRule::Straight,
            carried(2, 1.0),
        ];
        let mut rules = EdgeRules::from(dense.clone());
        assert_eq!(rules.len(), 6);
        assert_eq!(rules.iter().collect::<Vec<_>>(), dense);
        for (e, rule) in dense.iter().enumerate() {
            assert_eq!(&rules[e], rule);
        }
        assert_eq!(rules.not_straight().count(), 3);
        // setting an edge straight forgets it: equal to a record that never had it
        rules.set(2, EdgeRule::Straight);
        let mut again = dense.clone();
        again[2] = EdgeRule::Straight;
        assert_eq!(rules, EdgeRules::from(again));
        rules.truncate(2);
        assert_eq!(rules.iter().collect::<Vec<_>>(), &dense[..2]);
        rules.push(EdgeRule::Straight);
        assert_eq!(rules.len(), 3);
        assert_eq!(rules[2], EdgeRule::Straight);
    }

    #[test]
    fn sparse_rules_serialise_as_a_dense_list() {
        let dense = vec![EdgeRule::OnCurve, EdgeRule::Straight, carried(0, 0.25)];
        let rules = EdgeRules::from(dense.clone());
        let json = serde_json::to_string(&rules).unwrap();
        assert_eq!(json, serde_json::to_string(&dense).unwrap());
        let back: EdgeRules = serde_json::from_str(&json).unwrap();
        assert_eq!(back, rules);
    }

    #[test]
    #[should_panic(expected = "edge 3 of 3 edges")]
    fn an_edge_past_the_end_is_refused() {
        let mut rules = EdgeRules::straight(3);
        rules.set(3, EdgeRule::OnCurve);
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
