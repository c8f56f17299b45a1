//! One layer's children over a front: the front with its ideal steps and balanced children
//! ([`Ideal`]), and the layer they make ([`Layer`]: each front node's child, the children's
//! parents, the new front's facets, the faces of each cell). A front node whose column has
//! stopped keeps itself as its child (`kept`): the cells beside it lose that corner's side
//! edge (a prism becomes a pyramid or a tetrahedron), and a facet whose nodes all stopped has
//! no cell and stays on the front. A leaf: the checks, the repair, the upright places, the
//! merging, the squeeze and the stopping all work on these.

use geom_surface::Facet;
use mesh_model::NONE;

/// A front with its ideal steps and its balanced children.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Ideal<'a> {
    /// The front's nodes.
    pub nodes: &'a [[f64; 3]],
    /// Each node's ideal direction and length.
    pub dir: &'a [[f64; 3]],
    pub len: &'a [f64],
    /// Each node's child after the balance.
    pub balanced: &'a [[f64; 3]],
    /// The nodes whose columns have stopped: their child is the node itself (empty: none).
    pub stopped: &'a [bool],
    /// The wall's fans, in the first layer (`fan`).
    pub fan: Option<&'a FanTopo>,
}

/// What the first layer's cells need of the wall's fans (`fan`): which front nodes share a
/// place, and the edges from a chain's unfanned end to the copies of its fanned neighbour.
#[derive(Debug, Clone, Default, PartialEq)]
pub(crate) struct FanTopo {
    /// For each front node, the node whose place it shares (itself but for a fan's copies).
    pub origin: Vec<u32>,
    /// Each edge (its two front nodes, lower first) from a chain's unfanned end `q` to a copy
    /// of its fanned neighbour `p`, with `q`, sorted: the fan's cells over the edge `p q`
    /// are tetrahedra from `p` to `q`'s one child, and the two cells either side of the
    /// fan meet on the triangle `p q q'` (see [`Layer::cell_faces`]).
    pub apex_edges: Vec<([u32; 2], u32)>,
}

impl FanTopo {
    /// The chain's unfanned end on the edge `a b`, if it is one of [`FanTopo::apex_edges`].
    pub fn apex(&self, a: u32, b: u32) -> Option<u32> {
        let key = [a.min(b), a.max(b)];
        self.apex_edges
            .binary_search_by(|(e, _)| e.cmp(&key))
            .ok()
            .map(|i| self.apex_edges[i].1)
    }
}

impl Ideal<'_> {
    /// Whether front node `i`'s column has stopped.
    pub(crate) fn is_stopped(&self, i: usize) -> bool {
        self.stopped.get(i).copied().unwrap_or(false)
    }

    /// The child of front nodes `a` and `b` merged: over the middle of their edge by the
    /// mean of their ideal lengths, along the mean of their ideal directions. (Not the
    /// middle of their two children: children merge where the front shrinks, and there
    /// the balance drives them towards each other along the front, so their middle can lie
    /// almost on the front.)
    pub(crate) fn merged_child(&self, a: usize, b: usize) -> [f64; 3] {
        let (p, q) = (self.nodes[a], self.nodes[b]);
        let dir = geom_surface::unit(std::array::from_fn(|d| self.dir[a][d] + self.dir[b][d]));
        let len = (self.len[a] + self.len[b]) / 2.0;
        std::array::from_fn(|d| (p[d] + q[d]) / 2.0 + len * dir[d])
    }
}

/// One grown layer over a front: the children (some merged) and the new front.
#[derive(Debug, Clone)]
pub(crate) struct Layer {
    /// For each front node, its child (an index into `children`).
    pub child: Vec<u32>,
    /// The children's positions.
    pub children: Vec<[f64; 3]>,
    /// For each child, the front nodes it grew from (the second [`NONE`] unless merged).
    pub parents: Vec<[u32; 2]>,
    /// For each child, whether it is its parent itself (a stopped column; never merged).
    pub kept: Vec<bool>,
    /// The new front's facets, over the children (a facet whose top collapsed to an edge
    /// is left out).
    pub top: Vec<Facet>,
    /// For each new facet, the front facet below it (its cell).
    pub top_of: Vec<u32>,
    /// The front facets whose cells fail their check, when checked since the children last
    /// moved.
    pub failing: Option<Vec<usize>>,
    /// The wall's fans, in the first layer (`fan`).
    pub fan: Option<FanTopo>,
}

/// The cyclic sequence `k` without a node repeated next to itself.
pub(crate) fn dedup_cyclic(k: impl IntoIterator<Item = u32>) -> Vec<u32> {
    let mut out: Vec<u32> = Vec::with_capacity(4);
    for v in k {
        if out.last() != Some(&v) {
            out.push(v);
        }
    }
    while out.len() > 1 && out.first() == out.last() {
        out.pop();
    }
    out
}

impl Layer {
    /// The layer of the balanced children `balanced` (one per front node) over the front
    /// (`front`, `facets`), with the children of each pair in `merges` (front nodes joined by
    /// a front edge, each node in one pair at most) merged into one over the middle of their
    /// edge (see [`merged_child`](Ideal::merged_child)); a stopped node's child is the node
    /// itself, and a pair with a stopped node does not merge. Without merges each front node's
    /// child keeps its index.
    pub fn new(front: &Ideal<'_>, facets: &[Facet], merges: &[[u32; 2]]) -> Layer {
        let balanced = front.balanced;
        let n = balanced.len();
        let mut partner = vec![NONE; n];
        for &[a, b] in merges {
            if !front.is_stopped(a as usize) && !front.is_stopped(b as usize) {
                partner[a as usize] = b;
                partner[b as usize] = a;
            }
        }
        let merges = partner.iter().any(|&p| p != NONE);
        let mut child = vec![NONE; n];
        let mut children = Vec::with_capacity(n);
        let mut parents = Vec::with_capacity(n);
        let mut kept = Vec::with_capacity(n);
        for i in 0..n {
            if child[i] != NONE {
                continue;
            }
            let c = children.len() as u32;
            child[i] = c;
            let j = partner[i];
            let stopped = front.is_stopped(i);
            kept.push(stopped);
            if stopped {
                children.push(front.nodes[i]);
                parents.push([i as u32, NONE]);
            } else if j == NONE {
                children.push(balanced[i]);
                parents.push([i as u32, NONE]);
            } else {
                child[j as usize] = c;
                let (p, q) = (balanced[i], balanced[j as usize]);
                children.push(std::array::from_fn(|d| (p[d] + q[d]) / 2.0));
                parents.push([i as u32, j]);
            }
        }
        let mut top = Vec::with_capacity(facets.len());
        let mut top_of = Vec::with_capacity(facets.len());
        if !merges {
            // every child keeps its parent's index: the front's facets over the children
            top.extend_from_slice(facets);
            top_of.extend(0..facets.len() as u32);
        } else {
            for (f, facet) in facets.iter().enumerate() {
                let t = dedup_cyclic(facet.nodes().iter().map(|&v| child[v as usize]));
                if t.len() < 3 {
                    continue;
                }
                // (a node repeated apart from itself is caught by `tangled_children`)
                let fourth = t.get(3).copied().unwrap_or(geom_surface::NO_NODE);
                top.push(Facet([t[0], t[1], t[2], fourth]));
                top_of.push(f as u32);
            }
        }
        Layer {
            child,
            children,
            parents,
            top,
            top_of,
            kept,
            failing: None,
            fan: front.fan.cloned(),
        }
    }

    /// The front node whose place front node `v` shares (`v` itself but for a fan's copies).
    pub fn origin(&self, v: u32) -> u32 {
        self.fan
            .as_ref()
            .and_then(|f| f.origin.get(v as usize).copied())
            .unwrap_or(v)
    }

    /// Whether `facet` is one of the wall's zero-area fan facets (two of its corners share a
    /// place): its cell is a prism of the fan lying on its side, or a tetrahedron next to a
    /// chain's end, with no bottom.
    pub fn is_fan(&self, facet: &Facet) -> bool {
        if self.fan.is_none() {
            return false;
        }
        let k = facet.nodes();
        (0..k.len()).any(|i| self.origin(k[i]) == self.origin(k[(i + 1) % k.len()]))
    }

    /// The side faces of the cell over the front edge `a → b` (of its facet, counter-clockwise
    /// seen from the fluid), its children `up`: the quadrilateral `a b b' a'` without the
    /// repeated nodes of merged or kept children, or of a fan's copies. On an edge from a
    /// chain's unfanned end `q` to a copy of its fanned neighbour `p` the quadrilateral is
    /// split on its diagonal `p q'`: the triangle without `q` faces the fan's tetrahedron,
    /// the triangle `p q q'` (the second face, only for a cell that is not the fan's) the
    /// cell on the other side of the fan.
    pub fn side_faces(&self, a: u32, b: u32, up: impl Fn(u32) -> u32) -> [Vec<u32>; 2] {
        let (oa, ob) = (self.origin(a), self.origin(b));
        let quad = [oa, ob, up(b), up(a)];
        let apex = self.fan.as_ref().and_then(|f| f.apex(a, b));
        let Some(q) = apex else {
            return [dedup_cyclic(quad), Vec::new()];
        };
        // (the wall's `q` left out, not its child: a stopped `q` is its own child)
        let (toward, pinch) = if q == b {
            ([oa, up(b), up(a)], [oa, ob, up(b)])
        } else {
            ([ob, up(b), up(a)], [oa, ob, up(a)])
        };
        let pinch = dedup_cyclic(pinch);
        let pinch = if pinch.len() == 3 { pinch } else { Vec::new() };
        let toward = dedup_cyclic(toward);
        [toward, pinch]
    }

    /// Whether the cell over `facet` has fewer distinct top nodes than bottom nodes.
    pub fn is_merged(&self, facet: &Facet) -> bool {
        let k = facet.nodes();
        (0..k.len()).any(|i| self.child[k[i] as usize] == self.child[k[(i + 1) % k.len()] as usize])
    }

    /// Whether front node `v`'s child is `v` itself (its column stopped).
    pub fn is_kept(&self, v: u32) -> bool {
        self.kept[self.child[v as usize] as usize]
    }

    /// Whether the cell over `facet` is a plain prism or hexahedron: no children merged, none
    /// kept.
    pub fn is_plain(&self, facet: &Facet) -> bool {
        !self.is_merged(facet) && !facet.nodes().iter().any(|&v| self.is_kept(v))
    }

    /// Whether every node of `facet` stopped: it has no cell and stays on the front.
    pub fn is_bare(&self, facet: &Facet) -> bool {
        facet.nodes().iter().all(|&v| self.is_kept(v))
    }

    /// The unmerged layer of `children` over the front `front`, `facets` (for tests).
    #[cfg(test)]
    pub fn unmerged(front: &[[f64; 3]], facets: &[Facet], children: &[[f64; 3]]) -> Layer {
        let ideal = Ideal {
            nodes: front,
            dir: &[],
            len: &[],
            balanced: children,
            stopped: &[],
            fan: None,
        };
        Layer::new(&ideal, facets, &[])
    }

    /// The front facets (cells) around each child, each once.
    pub fn cells_around(&self, facets: &[Facet]) -> Vec<Vec<u32>> {
        let mut around: Vec<Vec<u32>> = vec![Vec::new(); self.children.len()];
        for (f, facet) in facets.iter().enumerate() {
            for &v in facet.nodes() {
                let c = self.child[v as usize] as usize;
                if around[c].last() != Some(&(f as u32)) {
                    around[c].push(f as u32);
                }
            }
        }
        around
    }

    /// The sum over child `c`'s parents (one, or two when merged) of their vectors in
    /// `per_node` (one per front node): a merged child's direction or normal, unnormalised.
    pub fn parents_sum(&self, c: usize, per_node: &[[f64; 3]]) -> [f64; 3] {
        self.parents[c]
            .iter()
            .filter(|&&v| v != NONE)
            .fold([0.0; 3], |s, &v| {
                std::array::from_fn(|d| s[d] + per_node[v as usize][d])
            })
    }

    /// The point child `c` shrinks towards: its parent, or the midpoint of its two parents.
    pub fn base(&self, front: &[[f64; 3]], c: usize) -> [f64; 3] {
        match self.parents[c] {
            [p, NONE] => front[p as usize],
            [p, q] => {
                let (p, q) = (front[p as usize], front[q as usize]);
                std::array::from_fn(|d| (p[d] + q[d]) / 2.0)
            }
        }
    }

    /// The outward faces of the cell over `facet`, nodes numbered front first (`0..n`),
    /// then the children (`n + c`): the bottom (turned towards the wall) when it keeps three
    /// places, the top when it keeps three nodes, then the sides along the bottom's edges (a
    /// triangle where the edge's two children merged, or its two nodes share a place). A
    /// fan's copies are numbered by their [`origin`](Layer::origin).
    pub fn cell_faces(&self, facet: &Facet) -> Vec<Vec<u32>> {
        let n = self.child.len() as u32;
        // a kept child is its front node itself
        let up = |v: u32| {
            if self.is_kept(v) {
                self.origin(v)
            } else {
                n + self.child[v as usize]
            }
        };
        let k = facet.nodes();
        let mut faces = Vec::with_capacity(k.len() + 2);
        let bottom = dedup_cyclic(k.iter().rev().map(|&v| self.origin(v)));
        if bottom.len() >= 3 {
            faces.push(bottom);
        }
        let top = dedup_cyclic(k.iter().map(|&v| up(v)));
        if top.len() >= 3 {
            faces.push(top);
        }
        let fan = self.is_fan(facet);
        for i in 0..k.len() {
            let (a, b) = (k[i], k[(i + 1) % k.len()]);
            let [side, pinch] = self.side_faces(a, b, up);
            if !fan && pinch.len() == 3 {
                faces.push(pinch);
            }
            // the side of two kept nodes is an edge: no face
            if side.len() >= 3 {
                faces.push(side);
            }
        }
        faces
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::check::layer_cell_ok;

    /// A unit square 0 1 2 3 (z = 0, facing +z) and a triangle 1 4 2 beside it, every child
    /// 0.5 above its node; the nodes of `stopped` keep themselves.
    fn layer(stopped: &[usize]) -> (Vec<[f64; 3]>, Vec<Facet>, Layer) {
        let nodes = vec![
            [0.0, 0.0, 0.0],
            [1.0, 0.0, 0.0],
            [1.0, 1.0, 0.0],
            [0.0, 1.0, 0.0],
            [2.0, 0.5, 0.0],
        ];
        let balanced: Vec<[f64; 3]> = nodes.iter().map(|p| [p[0], p[1], 0.5]).collect();
        let mut flags = vec![false; 5];
        stopped.iter().for_each(|&v| flags[v] = true);
        let facets = vec![Facet::quad(0, 1, 2, 3), Facet::tri(1, 4, 2)];
        let ideal = Ideal {
            nodes: &nodes,
            dir: &[[0.0, 0.0, 1.0]; 5],
            len: &[0.5; 5],
            balanced: &balanced,
            stopped: &flags,
            fan: None,
        };
        let layer = Layer::new(&ideal, &facets, &[[1, 2]]);
        (nodes, facets, layer)
    }

    #[test]
    fn a_stopped_node_keeps_itself_and_its_cells_lose_that_corners_side_edge() {
        // node 1 stopped: the merge of 1 and 2 is dropped, 1 is its own child
        let (nodes, facets, l) = layer(&[1]);
        assert!(l.is_kept(1) && !l.is_kept(2));
        assert_eq!(l.children[l.child[1] as usize], nodes[1]);
        assert!(l.parents.iter().all(|p| p[1] == NONE));
        // the quad's cell: 7 nodes, the sides at node 1 triangles; the triangle's a pyramid
        let sizes = |f: &Facet| {
            let mut s: Vec<usize> = l.cell_faces(f).iter().map(Vec::len).collect();
            s.sort_unstable();
            s
        };
        assert_eq!(sizes(&facets[0]), [3, 3, 4, 4, 4, 4]);
        assert_eq!(sizes(&facets[1]), [3, 3, 3, 3, 4]);
        assert!(facets.iter().all(|f| !l.is_plain(f) && !l.is_bare(f)));
        assert!(facets.iter().all(|f| layer_cell_ok(&nodes, &l, f)));
        // 1 and 2 stopped: the quad's cell a prism on its side, the triangle's a tetrahedron
        let (nodes, facets, l) = layer(&[1, 2]);
        let sizes = |f: &Facet| {
            let mut s: Vec<usize> = l.cell_faces(f).iter().map(Vec::len).collect();
            s.sort_unstable();
            s
        };
        assert_eq!(sizes(&facets[0]), [3, 3, 4, 4, 4]);
        assert_eq!(sizes(&facets[1]), [3, 3, 3, 3]);
        assert!(facets.iter().all(|f| layer_cell_ok(&nodes, &l, f)));
        // 1, 2 and 4 stopped: the triangle has no cell and stays on the front as it was
        let (_, facets, l) = layer(&[1, 2, 4]);
        assert!(l.is_bare(&facets[1]));
        assert_eq!(l.top[1], Facet::tri(l.child[1], l.child[4], l.child[2]));
    }

    #[test]
    fn a_child_leaning_over_a_stopped_node_is_refused() {
        let (nodes, facets, mut l) = layer(&[1]);
        // node 4's child pushed over node 1's column: the pyramid folds
        let c = l.child[4] as usize;
        l.children[c] = [0.8, 0.5, 0.5];
        assert!(!layer_cell_ok(&nodes, &l, &facets[1]));
    }
}
