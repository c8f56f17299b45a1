//! Flips: a face removed (2-3: two tets sharing a face become three around the edge joining
//! their apexes) and an edge removed (n tets around it become 2n-4, its ring triangulated by
//! a fan; 3-2 and 4-4 are the cases n = 3 and 4). A flip is made only when every new tet is
//! strictly positive — with the new tets oriented as one chain with the old boundary, that
//! makes them tile exactly the old tets' union — and never removes a kept face or edge.

use crate::insert::FaceSet;
pub(crate) use crate::insert::{EdgeSet, edge_key};
use crate::mesh::{GHOST, Mesh, face_key, face_of};
use geom_predicates::orient3d;

/// The constraints flips respect.
pub(crate) struct Kept<'a> {
    /// Faces never flipped away.
    pub faces: &'a FaceSet,
    /// Edges never flipped away.
    pub edges: &'a EdgeSet,
}

impl Mesh {
    /// Whether the tet with corners `v` is strictly positive.
    pub fn positive(&self, v: [u32; 4]) -> bool {
        !v.contains(&GHOST)
            && orient3d(self.p(v[0]), self.p(v[1]), self.p(v[2]), self.p(v[3])) > 0.0
    }

    /// Replaces the tets `old` by `new` (corners), which must tile the same union: the faces
    /// on the union's boundary keep their outer neighbours, the others are paired among the
    /// new tets. Returns the new tets.
    pub fn replace(&mut self, old: &[u32], new: &[[u32; 4]]) -> Vec<u32> {
        let mut outer: Vec<([u32; 3], u32)> = Vec::new();
        for &t in old {
            for i in 0..4 {
                if !old.contains(&self.neighbour(t, i)) {
                    outer.push((
                        face_key(face_of(self.tets[t as usize], i)),
                        self.adj[t as usize][i],
                    ));
                }
            }
        }
        for &t in old {
            self.kill(t);
        }
        let mut inner: Vec<([u32; 3], u32)> = Vec::new();
        let mut made = Vec::with_capacity(new.len());
        for &v in new {
            let t = self.alloc(v);
            made.push(t);
            for k in 0..4 {
                let key = face_key(face_of(v, k));
                match outer.iter().position(|o| o.0 == key) {
                    Some(j) => {
                        let code = outer.swap_remove(j).1;
                        self.link(t, k, code >> 2, (code & 3) as usize);
                    }
                    None => inner.push((key, t * 4 + k as u32)),
                }
            }
        }
        debug_assert!(
            outer.is_empty(),
            "the new tets leave an old boundary face open"
        );
        inner.sort_unstable();
        for pair in inner.chunks_exact(2) {
            debug_assert_eq!(
                pair[0].0, pair[1].0,
                "the new tets' inner faces do not pair"
            );
            let (a, b) = (pair[0].1, pair[1].1);
            self.link(a >> 2, (a & 3) as usize, b >> 2, (b & 3) as usize);
        }
        self.hint = made[0];
        made
    }

    /// The 2-3 flip of face `i` of `t`: the two old tets and the three new, if the face may go
    /// and every new tet is positive.
    pub fn flip23(&self, t: u32, i: usize, kept: &Kept) -> Option<([u32; 2], [[u32; 4]; 3])> {
        let v = self.tets[t as usize];
        let u = self.neighbour(t, i);
        let f = face_of(v, i);
        if v.contains(&GHOST) || self.is_ghost(u) || kept.faces.contains(&face_key(f)) {
            return None;
        }
        let code = self.adj[t as usize][i];
        let b = self.tets[u as usize][(code & 3) as usize];
        // each new tet: t with one corner of the shared face replaced by u's apex, which keeps
        // the chain's orientation
        let mut new = [[0u32; 4]; 3];
        for (n, s) in (0..4).filter(|&s| s != i).enumerate() {
            let mut w = v;
            w[s] = b;
            if !self.positive(w) {
                return None;
            }
            new[n] = w;
        }
        Some(([t, u], new))
    }

    /// The tets around edge `a b` in order and the ring of their other corners (tet `k` holds
    /// ring corners `k` and `k + 1`), starting from tet `t`, which holds the edge.
    pub fn ring(&self, t: u32, a: u32, b: u32) -> (Vec<u32>, Vec<u32>) {
        let v = self.tets[t as usize];
        let others: Vec<usize> = (0..4).filter(|&k| v[k] != a && v[k] != b).collect();
        if others.len() != 2 {
            return (Vec::new(), Vec::new());
        }
        let mut tets = vec![t];
        let mut ring = vec![v[others[0]], v[others[1]]];
        // tet k and k + 1 share the face (a, b, ring k + 1): leave across from ring corner k
        let (mut cur, mut leave) = (t, others[0]);
        loop {
            let code = self.adj[cur as usize][leave];
            let next = code >> 2;
            if next == t || tets.len() > 64 {
                ring.pop();
                break;
            }
            let came = (code & 3) as usize;
            let w = self.tets[next as usize];
            tets.push(next);
            ring.push(w[came]);
            leave = (0..4)
                .find(|&m| m != came && w[m] != a && w[m] != b)
                .expect("a tet around the edge holds it");
            cur = next;
        }
        (tets, ring)
    }

    /// The best way to remove edge `a b` (held by tet `t`): the tets around it and the 2n-4
    /// that replace them, the ring triangulated (dynamic programming over its sub-polygons,
    /// n ≤ 10) so that every new tet is positive and the smallest `score` is largest.
    pub fn edge_removal(
        &self,
        t: u32,
        a: u32,
        b: u32,
        kept: &Kept,
        score: &dyn Fn(&Mesh, [u32; 4]) -> f64,
    ) -> Option<(Vec<u32>, Vec<[u32; 4]>)> {
        self.edge_removal_with(t, a, b, kept, score, None)
    }

    /// [`Mesh::edge_removal`], with the ring's triangulation made to hold `diagonal` (two ring
    /// corners that are not neighbours on the ring) when given: the edge a recovery wants,
    /// where the best triangulation of the whole ring may take another diagonal (a flat
    /// quadrilateral's two diagonals cross, so removing one need not make the other).
    pub fn edge_removal_with(
        &self,
        t: u32,
        a: u32,
        b: u32,
        kept: &Kept,
        score: &dyn Fn(&Mesh, [u32; 4]) -> f64,
        diagonal: Option<[u32; 2]>,
    ) -> Option<(Vec<u32>, Vec<[u32; 4]>)> {
        if kept.edges.contains(&edge_key(a, b)) {
            return None;
        }
        let (tets, ring) = self.ring(t, a, b);
        let n = ring.len();
        if !(3..=10).contains(&n) || tets.len() != n || tets.iter().any(|&t| self.is_ghost(t)) {
            return None;
        }
        if ring
            .iter()
            .any(|&r| kept.faces.contains(&face_key([a, b, r])))
        {
            return None;
        }
        // the ring's orientation about a → b fixes that of the new tets
        let sigma = orient3d(self.p(a), self.p(b), self.p(ring[0]), self.p(ring[1])) > 0.0;
        // the polygons to triangulate, each in the ring's order: the ring, or its two parts
        // either side of the diagonal
        let polygons: Vec<Vec<u32>> = match diagonal {
            None => vec![ring],
            Some([u, v]) => {
                let i = ring.iter().position(|&r| r == u)?;
                let j = ring.iter().position(|&r| r == v)?;
                let (i, j) = (i.min(j), i.max(j));
                if j - i < 2 || i + n - j < 2 {
                    return None;
                }
                let other: Vec<u32> = ring[j..].iter().chain(&ring[..=i]).copied().collect();
                vec![ring[i..=j].to_vec(), other]
            }
        };
        let mut new = Vec::with_capacity(2 * n - 4);
        for polygon in &polygons {
            new.extend(self.triangulate_ring(polygon, a, b, sigma, score)?);
        }
        Some((tets, new))
    }

    /// The tets over the best triangulation of `ring` (a polygon around edge `a b`, in the
    /// ring's order; `sigma` its orientation about a → b): two per triangle, one on each end
    /// of the edge, every one positive and the smallest `score` largest. None when no
    /// triangulation makes every tet positive.
    fn triangulate_ring(
        &self,
        ring: &[u32],
        a: u32,
        b: u32,
        sigma: bool,
        score: &dyn Fn(&Mesh, [u32; 4]) -> f64,
    ) -> Option<Vec<[u32; 4]>> {
        let n = ring.len();
        let pair = |i: usize, k: usize, j: usize| {
            let (x, y, z) = (ring[i], ring[k], ring[j]);
            if sigma {
                ([y, x, z, a], [x, y, z, b])
            } else {
                ([x, y, z, a], [y, x, z, b])
            }
        };
        let tri = |i: usize, k: usize, j: usize| {
            let (ta, tb) = pair(i, k, j);
            if self.positive(ta) && self.positive(tb) {
                score(self, ta).min(score(self, tb))
            } else {
                f64::NEG_INFINITY
            }
        };
        // best[i][j]: the best worst score triangulating ring i..=j; split[i][j] its apex
        let mut best = vec![vec![f64::INFINITY; n]; n];
        let mut split = vec![vec![0usize; n]; n];
        for len in 2..n {
            for i in 0..n - len {
                let j = i + len;
                best[i][j] = f64::NEG_INFINITY;
                for k in i + 1..j {
                    let v = tri(i, k, j).min(best[i][k]).min(best[k][j]);
                    if v > best[i][j] {
                        best[i][j] = v;
                        split[i][j] = k;
                    }
                }
            }
        }
        if best[0][n - 1] == f64::NEG_INFINITY {
            return None;
        }
        let mut new = Vec::with_capacity(2 * n - 4);
        let mut todo = vec![(0, n - 1)];
        while let Some((i, j)) = todo.pop() {
            if j - i < 2 {
                continue;
            }
            let k = split[i][j];
            let (ta, tb) = pair(i, k, j);
            new.push(ta);
            new.push(tb);
            todo.push((i, k));
            todo.push((k, j));
        }
        Some(new)
    }
}
