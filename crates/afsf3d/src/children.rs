//! One layer's children over a front: the front with its ideal steps and balanced children
//! ([`Ideal`]), and the layer they make ([`Layer`]: each front node's child, the children's
//! parents, the new front's facets, the faces of each cell). A leaf: the checks, the repair,
//! the upright places, the merging and the squeeze all work on these.

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
}

impl Ideal<'_> {
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
    /// The new front's facets, over the children (a facet whose top collapsed to an edge
    /// is left out).
    pub top: Vec<Facet>,
    /// For each new facet, the front facet below it (its cell).
    pub top_of: Vec<u32>,
    /// The front facets whose cells fail their check, when checked since the children last
    /// moved.
    pub failing: Option<Vec<usize>>,
}

/// The cyclic sequence `k` without a node repeated next to itself.
fn dedup_cyclic(k: impl IntoIterator<Item = u32>) -> Vec<u32> {
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
    /// edge (see [`merged_child`](Ideal::merged_child)). Without merges each front node's child keeps its index.
    pub fn new(front: &Ideal<'_>, facets: &[Facet], merges: &[[u32; 2]]) -> Layer {
        let balanced = front.balanced;
        let n = balanced.len();
        let mut partner = vec![NONE; n];
        for &[a, b] in merges {
            partner[a as usize] = b;
            partner[b as usize] = a;
        }
        let mut child = vec![NONE; n];
        let mut children = Vec::with_capacity(n);
        let mut parents = Vec::with_capacity(n);
        for i in 0..n {
            if child[i] != NONE {
                continue;
            }
            let c = children.len() as u32;
            child[i] = c;
            let j = partner[i];
            if j == NONE {
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
        if merges.is_empty() {
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
            failing: None,
        }
    }

    /// Whether the cell over `facet` has fewer distinct top nodes than bottom nodes.
    pub fn is_merged(&self, facet: &Facet) -> bool {
        let k = facet.nodes();
        (0..k.len()).any(|i| self.child[k[i] as usize] == self.child[k[(i + 1) % k.len()] as usize])
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
    /// then the children (`n + c`): the bottom (turned towards the wall), the top when it
    /// keeps three nodes, then the sides along the bottom's edges (a triangle where the
    /// edge's two children merged).
    pub fn cell_faces(&self, facet: &Facet) -> Vec<Vec<u32>> {
        let n = self.child.len() as u32;
        let up = |v: u32| n + self.child[v as usize];
        let k = facet.nodes();
        let mut faces = vec![k.iter().rev().copied().collect::<Vec<u32>>()];
        let top = dedup_cyclic(k.iter().map(|&v| up(v)));
        if top.len() >= 3 {
            faces.push(top);
        }
        for i in 0..k.len() {
            let (a, b) = (k[i], k[(i + 1) % k.len()]);
            faces.push(dedup_cyclic([a, b, up(b), up(a)]));
        }
        faces
    }
}
