//! Point location and Bowyer–Watson insertion. The walk goes from the last tet towards the
//! point through any face that sees the point on its far side (faces tried from a random one,
//! which keeps it from cycling); the cavity is every tet whose circumsphere strictly contains
//! the point, found breadth first from the tet that holds it, then made star-shaped: grown in
//! a Delaunay tetrahedralisation, shrunk when constraint faces bound it (they are never
//! crossed); it is replaced by the tets joining its boundary faces to the point.

use crate::mesh::{GHOST, Mesh, face_key, face_of};
use geom_predicates::orient3d;
use geom_predicates::vector::dist;
use std::collections::HashSet;

/// Faces that insertion must keep (sorted corner triples).
pub(crate) type FaceSet = HashSet<[u32; 3], BuildFx>;

/// Edges that flips (and recovery's insertions) must keep (sorted pairs).
pub(crate) type EdgeSet = HashSet<[u32; 2], BuildFx>;

/// A sorted edge.
#[inline]
pub(crate) fn edge_key(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

/// A small, fast hasher for integer keys (Fx, as in rustc): no denial-of-service concern here.
#[derive(Default, Clone, Copy)]
pub(crate) struct BuildFx;

/// The Fx hasher's state.
#[derive(Default)]
pub(crate) struct Fx(u64);

impl std::hash::Hasher for Fx {
    #[inline]
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.write_u64(u64::from(b));
        }
    }
    #[inline]
    fn write_u32(&mut self, i: u32) {
        self.write_u64(u64::from(i));
    }
    #[inline]
    fn write_u64(&mut self, i: u64) {
        self.0 = (self.0.rotate_left(5) ^ i).wrapping_mul(0x517c_c1b7_2722_0a95);
    }
    #[inline]
    fn write_usize(&mut self, i: usize) {
        self.write_u64(i as u64);
    }
    #[inline]
    fn finish(&self) -> u64 {
        self.0
    }
}

impl std::hash::BuildHasher for BuildFx {
    type Hasher = Fx;
    fn build_hasher(&self) -> Fx {
        Fx(0)
    }
}

/// Where a point is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Located {
    /// In this real tet (closed), or beyond the hull face of this ghost tet.
    Tet(u32),
    /// On this existing vertex.
    Vertex(u32),
}

/// How near (times the shortest edge of the tet holding it) a new point may come to a corner
/// of that tet: nearer, it is not inserted.
pub(crate) const NEAR_VERTEX: f64 = 1e-6;

/// Reusable buffers of the insertion.
#[derive(Default)]
pub(crate) struct Scratch {
    /// Per tet slot: the round it was last put in the cavity.
    mark: Vec<u32>,
    /// Tets kept out of this insertion's cavity (rare: constrained insertion only).
    excluded: Vec<u32>,
    round: u32,
    cavity: Vec<u32>,
    stack: Vec<u32>,
    boundary: Vec<(u32, usize)>,
    new: Vec<(u32, usize)>,
    edges: Vec<(u64, u32)>,
}

impl Scratch {
    /// The tets of the last cavity found.
    pub fn cavity_tets(&self) -> &[u32] {
        &self.cavity
    }

    /// The corners of the tets that would replace the last cavity found for point `v`.
    pub fn new_tets<'a>(&'a self, mesh: &'a Mesh, v: u32) -> impl Iterator<Item = [u32; 4]> + 'a {
        self.boundary.iter().map(move |&(t, i)| {
            let mut c = mesh.tets[t as usize];
            c[i] = v;
            c
        })
    }

    fn grow_marks(&mut self, n: usize) {
        if self.mark.len() < n {
            self.mark.resize(n, 0);
        }
    }
}

impl Mesh {
    /// Finds the tet holding `p` by a visibility walk from the hint.
    pub fn locate(&mut self, p: [f64; 3]) -> Located {
        let mut t = self.hint;
        if t as usize >= self.tets.len() || self.is_dead(t) {
            t = (0..self.tets.len() as u32)
                .find(|&t| !self.is_dead(t))
                .expect("a live tet");
        }
        if let Some(g) = self.tets[t as usize].iter().position(|&v| v == GHOST) {
            t = self.neighbour(t, g);
        }
        let cap = 4 * self.tets.len() + 64;
        for _ in 0..cap {
            if self.is_ghost(t) {
                return Located::Tet(t);
            }
            let r = self.random() as usize;
            let next = (0..4)
                .map(|k| (r + k) & 3)
                .find(|&i| self.orient_face(t, i, p) < 0.0);
            match next {
                Some(i) => t = self.neighbour(t, i),
                None => return self.at_tet(t, p),
            }
        }
        self.locate_by_scan(p)
    }

    /// `Vertex` when `p` is a corner of real tet `t`, else `Tet(t)`.
    fn at_tet(&self, t: u32, p: [f64; 3]) -> Located {
        match self.tets[t as usize].iter().find(|&&v| self.p(v) == p) {
            Some(&v) => Located::Vertex(v),
            None => Located::Tet(t),
        }
    }

    /// Whether `p` lies within [`NEAR_VERTEX`] times the shortest edge of real tet `t` of one of
    /// its corners: a point inserted there would make tetrahedra flat to within rounding yet
    /// positive by the exact predicates (a refinement point 1e-16 from another in the extruded
    /// 30P30N's fill).
    pub fn near_vertex(&self, t: u32, p: [f64; 3]) -> bool {
        let k = self.tets[t as usize];
        if k.contains(&GHOST) {
            return false;
        }
        let x = k.map(|v| self.p(v));
        // (the pairs by hand: `cavity`'s edge list would make insert → cavity → flip → insert)
        let shortest = (0..4)
            .flat_map(|i| (i + 1..4).map(move |j| (i, j)))
            .map(|(i, j)| dist(x[i], x[j]))
            .fold(f64::INFINITY, f64::min);
        x.iter().any(|&c| dist(c, p) <= NEAR_VERTEX * shortest)
    }

    /// The walk's fallback (it never needed so far): every tet tried.
    fn locate_by_scan(&self, p: [f64; 3]) -> Located {
        for t in self.real_tets() {
            if (0..4).all(|i| self.orient_face(t, i, p) >= 0.0) {
                return self.at_tet(t, p);
            }
        }
        let ghost = (0..self.tets.len() as u32)
            .find(|&t| !self.is_dead(t) && self.is_ghost(t) && self.conflicts(t, p))
            .expect("a point outside every real tet sees a hull face");
        Located::Tet(ghost)
    }

    /// Inserts point `v` (already in `points`), starting from tet `start` that holds it
    /// (`locate`); the cavity never crosses a face of `keep`. Returns false, changing nothing,
    /// when no star-shaped cavity around the point exists within the constraints; else the
    /// new tets are in `new`.
    pub fn insert(
        &mut self,
        v: u32,
        start: u32,
        keep: Option<&FaceSet>,
        s: &mut Scratch,
        new: &mut Vec<u32>,
    ) -> bool {
        self.insert_keeping(v, start, keep, None, s, new)
    }

    /// [`Mesh::insert`], the cavity also leaving every edge of `keep_edges` in place (each on
    /// its boundary, so the new tets keep it): recovery's Steiner points must not undo the
    /// edges it has made.
    pub fn insert_keeping(
        &mut self,
        v: u32,
        start: u32,
        keep: Option<&FaceSet>,
        keep_edges: Option<&EdgeSet>,
        s: &mut Scratch,
        new: &mut Vec<u32>,
    ) -> bool {
        if !self.star_cavity(v, start, keep, keep_edges, s) {
            return false;
        }
        self.retriangulate(v, s, new);
        true
    }

    /// Finds the cavity that inserting point `v` would replace (in `s`, see
    /// [`Scratch::cavity_tets`] and [`Scratch::new_tets`]), without changing the mesh; false
    /// when no star-shaped cavity exists within the constraints. [`Mesh::commit_cavity`]
    /// then makes it.
    pub fn star_cavity(
        &self,
        v: u32,
        start: u32,
        keep: Option<&FaceSet>,
        keep_edges: Option<&EdgeSet>,
        s: &mut Scratch,
    ) -> bool {
        let p = self.p(v);
        s.grow_marks(self.tets.len());
        s.excluded.clear();
        loop {
            self.find_cavity(p, start, keep, s);
            let hidden = self.first_hidden_face(p, s).map(|(t, _)| t);
            let Some(t) = hidden.or_else(|| keep_edges.and_then(|e| self.lost_edge_tet(e, s)))
            else {
                return true;
            };
            if keep.is_none() {
                // Delaunay: the tets beyond join the cavity (p is on their spheres)
                return self.grow_until_visible(p, s);
            }
            // constrained: the cavity may not grow across a kept face, so it shrinks
            if t == start {
                return false;
            }
            s.excluded.push(t);
        }
    }

    /// Replaces the cavity [`Mesh::star_cavity`] found for `v` by the tets joining its
    /// boundary faces to `v`; the new tets in `new`.
    pub fn commit_cavity(&mut self, v: u32, s: &mut Scratch, new: &mut Vec<u32>) {
        self.retriangulate(v, s, new);
    }

    /// The cavity: tets in conflict with `p` reached from `start` without crossing a kept face
    /// or entering an excluded tet; and its boundary faces.
    fn find_cavity(&self, p: [f64; 3], start: u32, keep: Option<&FaceSet>, s: &mut Scratch) {
        s.round = s.round.wrapping_add(1);
        if s.round == 0 {
            s.mark.fill(0);
            s.round = 1;
        }
        let round = s.round;
        s.cavity.clear();
        s.stack.clear();
        s.mark[start as usize] = round;
        s.cavity.push(start);
        s.stack.push(start);
        while let Some(t) = s.stack.pop() {
            for i in 0..4 {
                let n = self.neighbour(t, i);
                if s.mark[n as usize] == round
                    || (!s.excluded.is_empty() && s.excluded.contains(&n))
                {
                    continue;
                }
                // (the kept faces looked up only for conflicting tets: hashing costs more)
                let kept =
                    |k: &FaceSet, f: [u32; 3]| !f.contains(&GHOST) && k.contains(&face_key(f));
                if self.conflicts(n, p)
                    && !keep.is_some_and(|keep| kept(keep, face_of(self.tets[t as usize], i)))
                {
                    s.mark[n as usize] = round;
                    s.cavity.push(n);
                    s.stack.push(n);
                }
            }
        }
        self.refresh_boundary(s);
    }

    /// A cavity tet holding an edge of `keep` that the cavity would remove (on none of its
    /// boundary faces); not the cavity's first tet, unless only it holds the edge.
    fn lost_edge_tet(&self, keep: &EdgeSet, s: &Scratch) -> Option<u32> {
        let mut kept_edges = HashSet::<[u32; 2], BuildFx>::default();
        for &(t, i) in &s.boundary {
            let f = face_of(self.tets[t as usize], i);
            for k in 0..3 {
                kept_edges.insert(edge_key(f[k], f[(k + 1) % 3]));
            }
        }
        let mut lost: Option<[u32; 2]> = None;
        'tets: for &t in &s.cavity {
            let v = self.tets[t as usize];
            for (k, m) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                let e = edge_key(v[k], v[m]);
                if !e.contains(&GHOST) && keep.contains(&e) && !kept_edges.contains(&e) {
                    lost = Some(e);
                    break 'tets;
                }
            }
        }
        let e = lost?;
        let holds = |t: &&u32| {
            let v = self.tets[**t as usize];
            v.contains(&e[0]) && v.contains(&e[1])
        };
        let first = s.cavity[0];
        s.cavity
            .iter()
            .filter(holds)
            .find(|&&t| t != first)
            .or_else(|| s.cavity.iter().find(holds))
            .copied()
    }

    /// Recomputes the cavity's boundary faces from its tets.
    fn refresh_boundary(&self, s: &mut Scratch) {
        s.boundary.clear();
        for &t in &s.cavity {
            for i in 0..4 {
                if s.mark[self.neighbour(t, i) as usize] != s.round {
                    s.boundary.push((t, i));
                }
            }
        }
    }

    /// A boundary face (real, its new tet real) that does not see `p` strictly on its inner side.
    fn first_hidden_face(&self, p: [f64; 3], s: &Scratch) -> Option<(u32, usize)> {
        s.boundary.iter().copied().find(|&(t, i)| {
            let f = face_of(self.tets[t as usize], i);
            !f.contains(&GHOST) && orient3d(self.p(f[0]), self.p(f[1]), self.p(f[2]), p) <= 0.0
        })
    }

    /// Grows the cavity across hidden faces until every boundary face sees `p`.
    fn grow_until_visible(&self, p: [f64; 3], s: &mut Scratch) -> bool {
        for _ in 0..self.tets.len() {
            match self.first_hidden_face(p, s) {
                None => return true,
                Some((t, i)) => {
                    let n = self.neighbour(t, i);
                    s.mark[n as usize] = s.round;
                    s.cavity.push(n);
                    self.refresh_boundary(s);
                }
            }
        }
        false
    }

    /// Replaces the cavity by the tets joining its boundary faces to `v`.
    fn retriangulate(&mut self, v: u32, s: &mut Scratch, new: &mut Vec<u32>) {
        // read everything off the cavity before its slots are reused
        s.new.clear();
        let mut outer = Vec::with_capacity(s.boundary.len());
        for &(t, i) in &s.boundary {
            let mut c = self.tets[t as usize];
            c[i] = v;
            outer.push((c, i, self.adj[t as usize][i]));
        }
        for k in 0..s.cavity.len() {
            self.kill(s.cavity[k]);
        }
        new.clear();
        for (c, i, code) in outer {
            let t = self.alloc(c);
            self.link(t, i, code >> 2, (code & 3) as usize);
            s.new.push((t, i));
            new.push(t);
        }
        let pairs = std::mem::take(&mut s.new);
        self.link_around_apex(&pairs, &mut s.edges);
        s.new = pairs;
        self.hint = new[0];
        s.grow_marks(self.tets.len());
    }
}
