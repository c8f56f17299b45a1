//! Boundary recovery: every input facet made a face of the tetrahedralisation without splitting
//! it. Missing edges first, then missing facets, each by flips that remove what crosses them
//! (2-3 flips of crossed faces, edge removals of crossed edges, preferring the flip that makes
//! the missing piece; an edge crossed by one edge alone — a planar quadrilateral's other
//! diagonal — by removing that edge with its ring triangulated through the missing one); when
//! no flip helps, Steiner points are inserted off the surface, never splitting it: off the
//! facet's centroid on the fill's side or behind it (inside the body, where a point is dropped
//! with the body's tets), no further than halfway to the nearest other point, and as a last
//! resort over the crossings of a missing edge. The insertions are constrained Bowyer–Watson:
//! recovered facets are never crossed and recovered edges never removed. Recovered facets and
//! input edges are kept from then on.

use crate::build::collinear;
use crate::flip::{EdgeSet, Kept, edge_key};
use crate::insert::{BuildFx, FaceSet, Located, Scratch};
use crate::mesh::{GHOST, Mesh, face_key, face_of};
use crate::quality::{cross, shape, sub};
use geom_predicates::{SegmentMeet, orient3d, segment_meet, segment_meets_triangle};
use std::collections::HashSet;

/// Where recovery's Steiner points go, in turn: off the facet's centroid along its normal, in
/// multiples of its size (each no further than halfway to the nearest other point); positive
/// into the fill, negative behind the facet (inside the body, whose tets are dropped, so a
/// point there is free: it breaks up flat configurations of the body's own points — an
/// extruded surface's rectangles — that block the flips).
const STEINER_OFFSETS: [f64; 10] = [0.3, -0.3, 0.15, -0.15, 0.6, -0.6, 0.08, -0.08, 1.0, -1.0];

/// The most Steiner points a facet's recovery puts over its missing edges' crossings.
const MAX_CROSSING_POINTS: usize = 16;

/// What recovery works with: the mesh, the kept faces and edges, a tet per vertex.
pub(crate) struct Recovery<'m> {
    pub mesh: &'m mut Mesh,
    pub faces: FaceSet,
    pub edges: EdgeSet,
    /// A tet holding each vertex, refreshed when stale.
    vt: Vec<u32>,
    /// Per tet slot: the last search that saw it.
    mark: Vec<u32>,
    round: u32,
    /// Points added off the surfaces.
    pub steiner: usize,
    /// The cap on the mesh's points.
    pub max_points: usize,
    scratch: Scratch,
}

/// What crosses a missing edge or facet.
#[derive(Default, Debug)]
struct Crossings {
    /// Faces crossed in their interior, as (tet, face index).
    faces: Vec<(u32, usize)>,
    /// Edges crossed, with a tet holding each.
    edges: Vec<(u32, u32, u32)>,
    /// A vertex on the missing piece (recovery impossible without splitting it).
    vertex: Option<u32>,
    /// The missing piece when it is an edge.
    segment: Option<[u32; 2]>,
}

impl<'m> Recovery<'m> {
    /// Recovery over `mesh`, with `max_points` the cap on its points.
    pub fn new(mesh: &'m mut Mesh, max_points: usize) -> Self {
        Self {
            mesh,
            faces: FaceSet::default(),
            edges: EdgeSet::default(),
            vt: Vec::new(),
            mark: Vec::new(),
            round: 0,
            steiner: 0,
            max_points,
            scratch: Scratch::default(),
        }
    }

    /// A live tet holding `v`.
    fn tet_of(&mut self, v: u32) -> u32 {
        let cached = self.vt.get(v as usize).copied().unwrap_or(GHOST);
        if cached != GHOST
            && !self.mesh.is_dead(cached)
            && self.mesh.tets[cached as usize].contains(&v)
        {
            return cached;
        }
        // rare: the first call, or a vertex missed by `note_tets`
        self.vt = vec![GHOST; self.mesh.points.len()];
        for t in 0..self.mesh.tets.len() as u32 {
            if !self.mesh.is_dead(t) {
                self.note_tet(t);
            }
        }
        self.vt[v as usize]
    }

    /// Records `t` as a tet holding each of its corners.
    fn note_tet(&mut self, t: u32) {
        for &w in &self.mesh.tets[t as usize] {
            if w != GHOST {
                if self.vt.len() <= w as usize {
                    self.vt
                        .resize(self.mesh.points.len().max(w as usize + 1), GHOST);
                }
                self.vt[w as usize] = t;
            }
        }
    }

    /// Records new tets: every corner of a replaced tet is a corner of one of them.
    pub(crate) fn note_tets(&mut self, made: &[u32]) {
        for &t in made {
            self.note_tet(t);
        }
    }

    /// `mesh.replace`, keeping the tet of each vertex.
    fn swap_tets(&mut self, old: &[u32], new: &[[u32; 4]]) -> Vec<u32> {
        let made = self.mesh.replace(old, new);
        self.note_tets(&made);
        made
    }

    /// The tets holding `v`.
    fn star(&mut self, v: u32) -> Vec<u32> {
        self.star_until(v, |_| false).0
    }

    /// The tets holding `v`, breadth first from the one `tet_of` knows, until one satisfies
    /// `stop` (then also returned).
    fn star_until(&mut self, v: u32, stop: impl Fn(&[u32; 4]) -> bool) -> (Vec<u32>, Option<u32>) {
        let t0 = self.tet_of(v);
        // a round number per search marks the tets seen, so no set is needed
        self.round = self.round.wrapping_add(1);
        if self.round == 0 {
            self.mark.fill(0);
            self.round = 1;
        }
        if self.mark.len() < self.mesh.tets.len() {
            self.mark.resize(self.mesh.tets.len(), 0);
        }
        let mut star = vec![t0];
        self.mark[t0 as usize] = self.round;
        let mut k = 0;
        while k < star.len() {
            let t = star[k];
            k += 1;
            if stop(&self.mesh.tets[t as usize]) {
                return (star, Some(t));
            }
            for i in 0..4 {
                if self.mesh.tets[t as usize][i] != v {
                    let n = self.mesh.neighbour(t, i);
                    if self.mark[n as usize] != self.round {
                        self.mark[n as usize] = self.round;
                        star.push(n);
                    }
                }
            }
        }
        (star, None)
    }

    /// A tet holding edge `a b` (the first in `star(a)`'s order).
    pub(crate) fn find_edge(&mut self, a: u32, b: u32) -> Option<u32> {
        // the star searched only as far as needed: most calls ask about present edges
        self.star_until(a, |v| v.contains(&b)).1
    }

    /// Whether `a b c` is a face.
    pub fn has_face(&mut self, f: [u32; 3]) -> bool {
        match self.find_edge(f[0], f[1]) {
            None => false,
            Some(t) => {
                let (tets, _) = self.mesh.ring(t, f[0], f[1]);
                tets.iter()
                    .any(|&t| self.mesh.tets[t as usize].contains(&f[2]))
            }
        }
    }

    /// The tets near the missing piece: the stars of its corners, grown across every face
    /// that `meets` says touches it.
    fn region(&mut self, corners: &[u32], meets: impl Fn(&Mesh, [u32; 3]) -> bool) -> Vec<u32> {
        let mut set: Vec<u32> = Vec::new();
        let mut seen: HashSet<u32, BuildFx> = HashSet::default();
        for &c in corners {
            for t in self.star(c) {
                if seen.insert(t) {
                    set.push(t);
                }
            }
        }
        let mut k = 0;
        while k < set.len() && set.len() < 4000 {
            let t = set[k];
            k += 1;
            for i in 0..4 {
                let f = face_of(self.mesh.tets[t as usize], i);
                let n = self.mesh.neighbour(t, i);
                if !f.contains(&GHOST) && !seen.contains(&n) && meets(self.mesh, f) {
                    seen.insert(n);
                    set.push(n);
                }
            }
        }
        set.retain(|&t| !self.mesh.is_ghost(t));
        set
    }

    /// What crosses segment `a b`.
    fn edge_crossings(&mut self, a: u32, b: u32) -> Crossings {
        let (pa, pb) = (self.mesh.p(a), self.mesh.p(b));
        let region = self.region(&[a, b], |m, f| {
            !f.contains(&a)
                && !f.contains(&b)
                && segment_meets_triangle(pa, pb, m.p(f[0]), m.p(f[1]), m.p(f[2]))
        });
        let mut c = Crossings {
            segment: Some([a, b]),
            ..Crossings::default()
        };
        for &t in &region {
            let v = self.mesh.tets[t as usize];
            for i in 0..4 {
                let f = face_of(v, i);
                if f.contains(&a) || f.contains(&b) {
                    continue;
                }
                let [x, y, z] = f.map(|w| self.mesh.p(w));
                let o = [
                    orient3d(pa, pb, x, y),
                    orient3d(pa, pb, y, z),
                    orient3d(pa, pb, z, x),
                ];
                let sides = (orient3d(x, y, z, pa), orient3d(x, y, z, pb));
                let inside = o.iter().all(|&s| s > 0.0) || o.iter().all(|&s| s < 0.0);
                if inside && sides.0 * sides.1 < 0.0 {
                    c.faces.push((t, i));
                }
            }
            for (k, m) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                let (x, y) = (v[k], v[m]);
                if [a, b].contains(&x) || [a, b].contains(&y) {
                    continue;
                }
                if segments_cross_3d(pa, pb, self.mesh.p(x), self.mesh.p(y)) {
                    c.edges.push((x.min(y), x.max(y), t));
                }
            }
            for &w in &v {
                if w != a && w != b && on_segment(pa, pb, self.mesh.p(w)) {
                    c.vertex = Some(w);
                }
            }
        }
        c.edges.sort_unstable_by_key(|e| (e.0, e.1));
        c.edges.dedup_by_key(|e| (e.0, e.1));
        c
    }

    /// What crosses triangle `f` (whose edges are all present).
    fn facet_crossings(&mut self, f: [u32; 3]) -> Crossings {
        let [pa, pb, pc] = f.map(|w| self.mesh.p(w));
        let region = self.region(&f, |m, g| {
            geom_predicates::triangles_meet(g.map(|w| m.p(w)), [pa, pb, pc])
        });
        let mut c = Crossings::default();
        for &t in &region {
            let v = self.mesh.tets[t as usize];
            for (k, m) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                let (x, y) = (v[k], v[m]);
                if f.contains(&x) || f.contains(&y) {
                    continue;
                }
                let (px, py) = (self.mesh.p(x), self.mesh.p(y));
                let (sx, sy) = (orient3d(pa, pb, pc, px), orient3d(pa, pb, pc, py));
                if sx * sy < 0.0 && segment_meets_triangle(px, py, pa, pb, pc) {
                    c.edges.push((x.min(y), x.max(y), t));
                }
            }
            for &w in &v {
                let pw = self.mesh.p(w);
                if !f.contains(&w)
                    && orient3d(pa, pb, pc, pw) == 0.0
                    && segment_meets_triangle(pw, pw, pa, pb, pc)
                {
                    c.vertex = Some(w);
                }
            }
        }
        c.edges.sort_unstable_by_key(|e| (e.0, e.1));
        c.edges.dedup_by_key(|e| (e.0, e.1));
        c
    }

    /// One flip that reduces the crossings that `cross` lists (None: the piece is there):
    /// 2-3 flips of crossed faces, removals of crossed edges and of the crossed faces' edges,
    /// each tried and undone unless the crossings drop. False when none helps.
    fn flip_once(
        &mut self,
        cross: &dyn Fn(&mut Self) -> Option<Crossings>,
        sideways: bool,
    ) -> bool {
        let Some(c) = cross(self) else {
            return true;
        };
        let count = c.faces.len() + c.edges.len();
        // an undone flip leaves the same tets in other slots: the candidates are listed anew,
        // in an order that does not depend on the slots
        for k in 0.. {
            let Some(c) = cross(self) else {
                return true;
            };
            let mut candidates = self.flip_candidates(&c);
            candidates.sort_by_cached_key(|(_, new)| {
                let mut key: Vec<[u32; 4]> = new
                    .iter()
                    .map(|t| {
                        let mut t = *t;
                        t.sort_unstable();
                        t
                    })
                    .collect();
                key.sort_unstable();
                key
            });
            if sideways {
                // a random flip that does not add crossings: a way out of a dead end
                if candidates.is_empty() || k >= 8 {
                    return false;
                }
                let pick = (self.mesh.random() % candidates.len() as u64) as usize;
                candidates.swap(0, pick);
            }
            let Some((old, new)) = candidates.into_iter().nth(if sideways { 0 } else { k }) else {
                return false;
            };
            let before: Vec<[u32; 4]> = old.iter().map(|&t| self.mesh.tets[t as usize]).collect();
            let made = self.swap_tets(&old, &new);
            match cross(self) {
                None => return true,
                Some(after)
                    if after.faces.len() + after.edges.len() < count + usize::from(sideways) =>
                {
                    return true;
                }
                _ => {}
            }
            self.swap_tets(&made, &before);
        }
        false
    }

    /// The flips that may remove crossings `c`: old tets and new corners.
    fn flip_candidates(&self, c: &Crossings) -> Vec<(Vec<u32>, Vec<[u32; 4]>)> {
        let mut candidates: Vec<(Vec<u32>, Vec<[u32; 4]>)> = Vec::new();
        let kept = Kept {
            faces: &self.faces,
            edges: &self.edges,
        };
        let score = |m: &Mesh, t: [u32; 4]| shape(t.map(|v| m.p(v)));
        let mut edges: Vec<(u32, u32, u32)> = c.edges.clone();
        for &(t, i) in &c.faces {
            if let Some((old, new)) = self.mesh.flip23(t, i, &kept) {
                candidates.push((old.to_vec(), new.to_vec()));
            }
            let f = face_of(self.mesh.tets[t as usize], i);
            for k in 0..3 {
                edges.push((f[k], f[(k + 1) % 3], t));
            }
        }
        for &(x, y, t) in &c.edges {
            // an edge crossing the missing one (a flat quadrilateral's other diagonal) is
            // removed with the missing one made across its ring
            if let Some(way) = c.segment.and_then(|ab| {
                self.mesh
                    .edge_removal_with(t, x, y, &kept, &score, Some(ab))
            }) {
                candidates.push(way);
            }
            let (tets, _) = self.mesh.ring(t, x, y);
            for u in tets {
                let v = self.mesh.tets[u as usize];
                for i in 0..4 {
                    if let Some((old, new)) = self.mesh.flip23(u, i, &kept) {
                        candidates.push((old.to_vec(), new.to_vec()));
                    }
                }
                for (k, m) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                    edges.push((v[k], v[m], u));
                }
            }
        }
        edges.sort_unstable_by_key(|e| (e.0.min(e.1), e.0.max(e.1)));
        edges.dedup_by_key(|e| (e.0.min(e.1), e.0.max(e.1)));
        for (x, y, t) in edges {
            if let Some(way) = self.mesh.edge_removal(t, x, y, &kept, &score) {
                candidates.push(way);
            }
        }
        candidates
    }

    /// The tets that the segment crossing `c` passes through: both sides of each crossed face
    /// and the rings of the crossed edges.
    fn edge_cavity(&self, c: &Crossings) -> Vec<u32> {
        let mut set = Vec::new();
        for &(t, i) in &c.faces {
            set.push(t);
            set.push(self.mesh.neighbour(t, i));
        }
        self.rings(&c.edges, set)
    }

    /// `set` with the tets around each edge added, deduplicated.
    fn rings(&self, edges: &[(u32, u32, u32)], mut set: Vec<u32>) -> Vec<u32> {
        for &(x, y, t) in edges {
            set.extend(self.mesh.ring(t, x, y).0);
        }
        set.sort_unstable();
        set.dedup();
        set
    }

    /// Makes edge `a b` by removing the one edge that crosses it when nothing else does (a flat
    /// quadrilateral whose other diagonal the Delaunay took: its ring holds `a` and `b`), the
    /// ring triangulated through `a b`. True when done.
    fn edge_by_removal(&mut self, a: u32, b: u32, c: &Crossings) -> bool {
        let [(x, y, t)] = c.edges[..] else {
            return false;
        };
        if !c.faces.is_empty() {
            return false;
        }
        let kept = Kept {
            faces: &self.faces,
            edges: &self.edges,
        };
        let score = |m: &Mesh, t: [u32; 4]| shape(t.map(|v| m.p(v)));
        match self
            .mesh
            .edge_removal_with(t, x, y, &kept, &score, Some([a, b]))
        {
            Some((old, new)) => {
                self.swap_tets(&old, &new);
                true
            }
            None => false,
        }
    }

    /// Recovers edge `a b` by flips. Err: why not.
    fn recover_edge_by_flips(&mut self, a: u32, b: u32) -> Result<(), String> {
        let cross = |r: &mut Self| {
            if r.find_edge(a, b).is_some() {
                None
            } else {
                Some(r.edge_crossings(a, b))
            }
        };
        for _ in 0..200 {
            let Some(c) = cross(self) else {
                self.edges.insert(edge_key(a, b));
                return Ok(());
            };
            if let Some(w) = c.vertex {
                return Err(format!("edge {a}-{b} passes through point {w}"));
            }
            if self.edge_by_removal(a, b, &c) {
                continue;
            }
            let cavity = self.edge_cavity(&c);
            if self.edge_by_cone(a, b, &cavity) {
                continue;
            }
            if !self.flip_once(&cross, false) && !self.flip_once(&cross, true) {
                return Err(format!(
                    "edge {a}-{b} is crossed by {} faces and {} edges that no flip removes",
                    c.faces.len(),
                    c.edges.len()
                ));
            }
        }
        Err(format!("edge {a}-{b}: flips do not converge"))
    }

    /// Recovers facet `f` (edges present) by flips. Err: why not.
    fn recover_facet_by_flips(&mut self, f: [u32; 3]) -> Result<(), String> {
        let cross = |r: &mut Self| {
            if r.has_face(f) {
                None
            } else {
                Some(r.facet_crossings(f))
            }
        };
        for _ in 0..200 {
            let Some(c) = cross(self) else {
                return Ok(());
            };
            if let Some(w) = c.vertex {
                return Err(format!("point {w} lies on the facet"));
            }
            let cavity = self.rings(&c.edges, Vec::new());
            if self.facet_by_cavity(f, &cavity) {
                continue;
            }
            if !self.flip_once(&cross, false) && !self.flip_once(&cross, true) {
                return Err(format!(
                    "crossed by {} edges that no flip removes",
                    c.edges.len()
                ));
            }
        }
        Err("flips do not converge".into())
    }

    /// Recovers the edges of facet `f` by cones and flips (no Steiner point); kept once there.
    pub fn recover_edges(&mut self, f: [u32; 3]) {
        for k in 0..3 {
            // a failure is retried with the facet, Steiner points allowed
            let _ = self.recover_edge_by_flips(f[k], f[(k + 1) % 3]);
        }
    }

    /// Recovers facet `f` (corners counter-clockwise seen from the fill): its edges, then
    /// itself, by flips and then with Steiner points off it, one more after each failed
    /// round: at the next place of [`STEINER_OFFSETS`] where one can be inserted, then over
    /// the middle crossing of a missing edge (nearer the facet: the last resort).
    pub fn recover_facet(&mut self, f: [u32; 3]) -> Result<(), String> {
        let mut next = 0;
        let mut over_crossings = 0;
        loop {
            let flipped = (|| {
                for k in 0..3 {
                    self.recover_edge_by_flips(f[k], f[(k + 1) % 3])?;
                }
                self.recover_facet_by_flips(f)
            })();
            let why = match flipped {
                Ok(()) => {
                    self.faces.insert(face_key(f));
                    return Ok(());
                }
                Err(why) => why,
            };
            // the next Steiner point that can be inserted, else this failure
            loop {
                if let Some(&off) = STEINER_OFFSETS.get(next) {
                    next += 1;
                    if self.add_steiner(f, off)? {
                        break;
                    }
                } else if over_crossings < MAX_CROSSING_POINTS
                    && self.add_steiner_over_crossing(f)?
                {
                    over_crossings += 1;
                    break;
                } else {
                    return Err(why);
                }
            }
        }
    }

    /// Inserts a point over the crossing nearest the middle of a missing edge of facet `f`
    /// (where the edge passes through a face), off the facet into the fill by half the
    /// distance from the crossing to that face's nearest corner. False when no edge is
    /// crossed by a face or the point could not be inserted.
    fn add_steiner_over_crossing(&mut self, f: [u32; 3]) -> Result<bool, String> {
        let Some(k) = (0..3).find(|&k| self.find_edge(f[k], f[(k + 1) % 3]).is_none()) else {
            return Ok(false);
        };
        let (a, b) = (f[k], f[(k + 1) % 3]);
        let c = self.edge_crossings(a, b);
        let (pa, pb) = (self.mesh.p(a), self.mesh.p(b));
        let mut best: Option<(f64, [f64; 3], f64)> = None;
        for &(t, i) in &c.faces {
            let g = face_of(self.mesh.tets[t as usize], i).map(|w| self.mesh.p(w));
            let (da, db) = (
                orient3d(g[0], g[1], g[2], pa),
                orient3d(g[0], g[1], g[2], pb),
            );
            let s = da / (da - db);
            let x = [0, 1, 2].map(|m| pa[m] + s * (pb[m] - pa[m]));
            let near = g
                .iter()
                .map(|q| norm(sub(*q, x)))
                .fold(f64::INFINITY, f64::min);
            if best.is_none_or(|(bs, _, _)| (s - 0.5).abs() < (bs - 0.5).abs()) {
                best = Some((s, x, near));
            }
        }
        let Some((_, x, near)) = best else {
            return Ok(false);
        };
        let [fa, fb, fc] = f.map(|w| self.mesh.p(w));
        // the normal of a counter-clockwise facet seen from the fill points into the fill
        let n = cross(sub(fa, fb), sub(fa, fc));
        let len = norm(n);
        self.insert_steiner([0, 1, 2].map(|m| x[m] + n[m] / len * 0.5 * near))
    }

    /// Inserts a point off facet `f`'s centroid along its normal, `off` times its size (the
    /// square root of twice its area) into the fill (behind it when negative), keeping the
    /// recovered facets and edges. False when it could not be inserted.
    fn add_steiner(&mut self, f: [u32; 3], off: f64) -> Result<bool, String> {
        let [a, b, c] = f.map(|w| self.mesh.p(w));
        // the normal of a counter-clockwise facet seen from the fill points into the fill
        let n = cross(sub(a, b), sub(a, c));
        let len = norm(n);
        let centroid = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0);
        // no further than halfway to the nearest point that is not the facet's (a front facing
        // it, or the body's other side)
        let off = (len.sqrt() * off.abs()).min(0.5 * self.clearance(f, centroid)) * off.signum();
        let q = [0, 1, 2].map(|k| centroid[k] + n[k] / len * off);
        self.insert_steiner(q)
    }

    /// Inserts Steiner point `q`, keeping the recovered facets and edges. False when it could
    /// not be inserted (outside the box, on a point, or no cavity within the constraints).
    fn insert_steiner(&mut self, q: [f64; 3]) -> Result<bool, String> {
        if self.mesh.points.len() >= self.max_points {
            return Err(format!("the cap of {} points is reached", self.max_points));
        }
        let Located::Tet(t) = self.mesh.locate(q) else {
            return Ok(false);
        };
        if self.mesh.is_ghost(t) || self.mesh.near_vertex(t, q) {
            return Ok(false);
        }
        self.mesh.points.push(q);
        let v = (self.mesh.points.len() - 1) as u32;
        let mut new = Vec::new();
        if self.mesh.insert_keeping(
            v,
            t,
            Some(&self.faces),
            Some(&self.edges),
            &mut self.scratch,
            &mut new,
        ) {
            self.steiner += 1;
            self.note_tets(&new);
            Ok(true)
        } else {
            self.mesh.points.pop();
            Ok(false)
        }
    }

    /// The distance from `p` to the nearest corner, other than `f`'s, of the tets around
    /// `f`'s corners.
    fn clearance(&mut self, f: [u32; 3], p: [f64; 3]) -> f64 {
        let mut nearest = f64::INFINITY;
        for &v in &f {
            for t in self.star(v) {
                for w in self.mesh.tets[t as usize] {
                    if w != GHOST && !f.contains(&w) {
                        nearest = nearest.min(norm(sub(self.mesh.p(w), p)));
                    }
                }
            }
        }
        nearest
    }

    /// Marks the input edges and facets already present as kept.
    pub fn keep_present(&mut self, facets: &[[u32; 3]]) {
        for &f in facets {
            for k in 0..3 {
                let (a, b) = (f[k], f[(k + 1) % 3]);
                if self.find_edge(a, b).is_some() {
                    self.edges.insert(edge_key(a, b));
                }
            }
            if self.has_face(f) {
                self.faces.insert(face_key(f));
            }
        }
    }
}

/// The length of `v`.
fn norm(v: [f64; 3]) -> f64 {
    (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt()
}

/// Whether point `p` lies on the closed segment `a b` (exact collinearity, then the box).
fn on_segment(a: [f64; 3], b: [f64; 3], p: [f64; 3]) -> bool {
    let (k, m) = drop_axis_of(a, b, p);
    let proj = |q: [f64; 3]| [q[k], q[m]];
    geom_predicates::orient2d(proj(a), proj(b), proj(p)) == 0.0
        && collinear(a, b, p)
        && (0..3).all(|i| p[i] >= a[i].min(b[i]) && p[i] <= a[i].max(b[i]))
}

/// The two axes to keep when projecting the plane through the points (the normal's largest
/// component dropped; any pair for a degenerate normal).
fn drop_axis_of(a: [f64; 3], b: [f64; 3], c: [f64; 3]) -> (usize, usize) {
    let n = cross(sub(a, b), sub(a, c));
    let big = (0..3)
        .max_by(|&i, &j| n[i].abs().total_cmp(&n[j].abs()))
        .unwrap_or(2);
    ((big + 1) % 3, (big + 2) % 3)
}

/// Whether segments `a b` and `x y` (no shared end) meet: coplanar and meeting in the
/// projection that keeps their plane's extent.
fn segments_cross_3d(a: [f64; 3], b: [f64; 3], x: [f64; 3], y: [f64; 3]) -> bool {
    if orient3d(a, b, x, y) != 0.0 {
        return false;
    }
    // a projection in which the four points' plane is not seen edge-on
    let (mut k, mut m) = drop_axis_of(a, b, x);
    if collinear(a, b, x) {
        (k, m) = drop_axis_of(a, b, y);
    }
    let proj = |q: [f64; 3]| [q[k], q[m]];
    if collinear(a, b, x) && collinear(a, b, y) {
        // all on one line: overlap means a vertex on the segment, found elsewhere
        return false;
    }
    segment_meet(proj(a), proj(b), proj(x), proj(y)) != SegmentMeet::Disjoint
}
