//! Recovery by re-tetrahedralising a cavity, a generalised flip that needs no sequence of
//! small flips to exist. A missing edge `a b`: the tets its segment passes through are replaced
//! by the cone from `a` (or `b`) over the cavity's faces away from it, when `a` sees them all.
//! A missing facet (edges present): the tets with an edge crossing it form a cavity that the
//! facet cuts in two (each such tet meets the facet's plane only inside the facet, since the
//! facet's edges are edges of the mesh); each half is the cone from a point that sees all of its
//! faces, the facet included — a vertex of that half if one does, else a Steiner point strictly
//! inside the half's kernel, which is off every input facet. A cavity is only replaced when the
//! new tets are positive, close up exactly on its boundary and keep every kept face and edge.

use crate::flip::edge_key;
use crate::mesh::{FACE, GHOST, Mesh, face_key, face_of};
use crate::quality::{cross, dot, sub};
use crate::recover::Recovery;
use geom_predicates::orient3d;
use std::collections::HashSet;

/// A cavity's boundary face: the tet inside and its face index.
type Face = (u32, usize);

impl Mesh {
    /// Replaces `old` by `new` when the new tets are positive and their faces are the old
    /// boundary's, once each, plus inner faces paired; None (nothing changed) otherwise.
    pub fn replace_checked(&mut self, old: &[u32], new: &[[u32; 4]]) -> Option<Vec<u32>> {
        if !new.iter().all(|&v| self.positive(v)) {
            return None;
        }
        // the old boundary faces as seen from inside the cavity: each must be a new tet's face
        // once, in the same orientation; every other new face must meet its twin exactly once
        let mut open: HashSet<[u32; 3], crate::insert::BuildFx> = HashSet::default();
        for &t in old {
            for i in 0..4 {
                if !old.contains(&self.neighbour(t, i)) {
                    open.insert(oriented(face_of(self.tets[t as usize], i)));
                }
            }
        }
        let mut inner: HashSet<[u32; 3], crate::insert::BuildFx> = HashSet::default();
        for &v in new {
            for i in 0..4 {
                let f = oriented(face_of(v, i));
                if !open.remove(&f)
                    && !inner.remove(&oriented([f[0], f[2], f[1]]))
                    && !inner.insert(f)
                {
                    return None;
                }
            }
        }
        if !open.is_empty() || !inner.is_empty() {
            return None;
        }
        Some(self.replace(old, new))
    }
}

/// A face's corners rotated so that the smallest comes first (orientation kept).
fn oriented(f: [u32; 3]) -> [u32; 3] {
    let k = (0..3).min_by_key(|&k| f[k]).unwrap_or(0);
    [f[k], f[(k + 1) % 3], f[(k + 2) % 3]]
}

/// A region being re-tetrahedralised: its tets and its boundary faces seen from inside.
#[derive(Clone, Default)]
struct Region {
    tets: Vec<u32>,
    faces: Vec<Face>,
}

/// How many tets a region may take in by growing.
const GROWTH: usize = 48;

impl Recovery<'_> {
    /// Makes edge `a b` by a cone from `a` (or `b`) over the tets its segment passes through
    /// (`cavity`), grown across the faces the apex does not see. True when done.
    pub(crate) fn edge_by_cone(&mut self, a: u32, b: u32, cavity: &[u32]) -> bool {
        for apex in [a, b] {
            let mut region = Region {
                tets: cavity.to_vec(),
                faces: self.boundary(cavity),
            };
            for _ in 0..GROWTH {
                let hidden = self.hidden(&region.faces, &[], self.mesh.p(apex), apex);
                if hidden.is_empty() {
                    let new = self.cone(&region.faces, apex);
                    if self.try_replace(&region.tets, &new) {
                        return true;
                    }
                    break;
                }
                if !hidden.iter().any(|&f| self.grow(&mut region, None, f)) {
                    break;
                }
            }
        }
        false
    }

    /// Makes facet `f` by two cones over the tets its crossing edges' rings fill (`cavity`),
    /// one on each side, each half grown when no apex sees it. True when done.
    pub(crate) fn facet_by_cavity(&mut self, f: [u32; 3], cavity: &[u32]) -> bool {
        let [pa, pb, pc] = f.map(|w| self.mesh.p(w));
        let mut halves = [Region::default(), Region::default()];
        for (t, i) in self.boundary(cavity) {
            let g = face_of(self.mesh.tets[t as usize], i);
            let s = g
                .iter()
                .map(|&w| orient3d(pa, pb, pc, self.mesh.p(w)))
                .find(|&s| s != 0.0);
            match s {
                Some(s) => halves[usize::from(s < 0.0)].faces.push((t, i)),
                None => return false,
            }
        }
        halves[0].tets = cavity.to_vec();
        // the facet as seen from each half: positive towards it
        let facet = [[f[0], f[1], f[2]], [f[1], f[0], f[2]]];
        let first_new = self.mesh.points.len();
        let mut apexes = [GHOST; 2];
        for h in 0..2 {
            let (mine, theirs) = if h == 0 {
                let (x, y) = halves.split_at_mut(1);
                (&mut x[0], &y[0])
            } else {
                let (x, y) = halves.split_at_mut(1);
                (&mut y[0], &x[0])
            };
            match self.half_apex(mine, theirs, facet[h]) {
                Some(w) => apexes[h] = w,
                None => break,
            }
        }
        let mut old = halves[0].tets.clone();
        old.extend_from_slice(&halves[1].tets);
        let mut new = Vec::new();
        for h in 0..2 {
            if apexes[h] == GHOST {
                self.mesh.points.truncate(first_new);
                return false;
            }
            new.extend(self.cone(&halves[h].faces, apexes[h]));
            let [x, y, z] = facet[h];
            new.push([x, y, z, apexes[h]]);
        }
        if self.try_replace(&old, &new) {
            self.steiner += self.mesh.points.len() - first_new;
            true
        } else {
            self.mesh.points.truncate(first_new);
            false
        }
    }

    /// An apex for a half: one of its vertices that sees all its faces (`facet` included),
    /// the half grown across hidden faces for a few rounds, else a new point in its kernel.
    fn half_apex(&mut self, half: &mut Region, other: &Region, facet: [u32; 3]) -> Option<u32> {
        let back = [facet[0], facet[2], facet[1]];
        for round in 0..GROWTH {
            let mut vertices: Vec<u32> = half
                .faces
                .iter()
                .flat_map(|&(t, i)| face_of(self.mesh.tets[t as usize], i))
                .filter(|w| !facet.contains(w))
                .collect();
            vertices.sort_unstable();
            vertices.dedup();
            let mut best: Option<Vec<Face>> = None;
            for &w in &vertices {
                let hidden = self.hidden(&half.faces, &[back], self.mesh.p(w), w);
                if hidden.is_empty() {
                    return Some(w);
                }
                if best.as_ref().is_none_or(|b| hidden.len() < b.len()) {
                    best = Some(hidden);
                }
            }
            let grown = round < 6
                && best
                    .is_some_and(|hidden| hidden.iter().any(|&f| self.grow(half, Some(other), f)));
            if !grown {
                break;
            }
        }
        self.kernel_apex(&half.faces, back)
    }

    /// A new point (pushed onto the mesh's points) strictly inside the region bounded by
    /// `faces` and `back` (a face oriented with the inside negative).
    fn kernel_apex(&mut self, faces: &[Face], back: [u32; 3]) -> Option<u32> {
        if self.mesh.points.len() >= self.max_points {
            return None;
        }
        let mut planes: Vec<[u32; 3]> = faces
            .iter()
            .map(|&(t, i)| {
                let g = face_of(self.mesh.tets[t as usize], i);
                [g[0], g[2], g[1]]
            })
            .collect();
        planes.push(back);
        let q = kernel_point(self.mesh, &planes)?;
        let inside = planes
            .iter()
            .all(|g| orient3d(self.mesh.p(g[0]), self.mesh.p(g[1]), self.mesh.p(g[2]), q) < 0.0);
        if !inside {
            return None;
        }
        self.mesh.points.push(q);
        Some((self.mesh.points.len() - 1) as u32)
    }

    /// The faces (not holding `apex`) that point `p` does not see strictly from inside, and
    /// whether any of `extra` (inside negative) hides it (then every face is returned).
    fn hidden(&self, faces: &[Face], extra: &[[u32; 3]], p: [f64; 3], apex: u32) -> Vec<Face> {
        let m = &self.mesh;
        if extra
            .iter()
            .any(|g| orient3d(m.p(g[0]), m.p(g[1]), m.p(g[2]), p) >= 0.0)
        {
            return faces.to_vec();
        }
        faces
            .iter()
            .copied()
            .filter(|&(t, i)| {
                let g = face_of(m.tets[t as usize], i);
                !g.contains(&apex) && m.orient_face(t, i, p) <= 0.0
            })
            .collect()
    }

    /// Takes the tet across boundary face `f` into the region (not across a kept face, nor
    /// into a ghost tet or one of `other`'s). True when grown.
    fn grow(&self, region: &mut Region, other: Option<&Region>, f: Face) -> bool {
        let (t, i) = f;
        let g = face_of(self.mesh.tets[t as usize], i);
        let n = self.mesh.neighbour(t, i);
        let taken = |r: &Region| r.tets.contains(&n);
        if g.contains(&GHOST)
            || self.faces.contains(&face_key(g))
            || self.mesh.is_ghost(n)
            || taken(region)
            || other.is_some_and(taken)
        {
            return false;
        }
        region.tets.push(n);
        for j in 0..4 {
            let m = self.mesh.neighbour(n, j);
            // a face shared with the region itself becomes inner: dropped from both sides
            match region
                .faces
                .iter()
                .position(|&(u, k)| u == m && self.mesh.neighbour(u, k) == n)
            {
                Some(p) => {
                    region.faces.swap_remove(p);
                }
                None => region.faces.push((n, j)),
            }
        }
        true
    }

    /// The tets joining each face to `apex` (faces holding it skipped).
    fn cone(&self, faces: &[Face], apex: u32) -> Vec<[u32; 4]> {
        faces
            .iter()
            .filter(|&&(t, i)| !face_of(self.mesh.tets[t as usize], i).contains(&apex))
            .map(|&(t, i)| {
                let mut v = self.mesh.tets[t as usize];
                v[i] = apex;
                v
            })
            .collect()
    }
    /// The cavity's boundary faces.
    fn boundary(&self, cavity: &[u32]) -> Vec<Face> {
        let mut out = Vec::new();
        for &t in cavity {
            for i in 0..4 {
                if !cavity.contains(&self.mesh.neighbour(t, i)) {
                    out.push((t, i));
                }
            }
        }
        out
    }

    /// Replaces `old` by `new` if valid and every kept face and edge of `old` survives.
    fn try_replace(&mut self, old: &[u32], new: &[[u32; 4]]) -> bool {
        if new.iter().any(|v| v.contains(&GHOST)) {
            return false;
        }
        let mut new_faces = Vec::new();
        let mut new_edges = Vec::new();
        for v in new {
            for i in 0..4 {
                new_faces.push(face_key(face_of(*v, i)));
            }
            for (k, m) in EDGES {
                new_edges.push(edge_key(v[k], v[m]));
            }
        }
        for &t in old {
            let v = self.mesh.tets[t as usize];
            // a vertex inside the cavity would be dropped by the cones
            if v.iter().any(|w| !new.iter().any(|n| n.contains(w))) {
                return false;
            }
            let lost_face = FACE.iter().any(|f| {
                let key = face_key(f.map(|k| v[k]));
                self.faces.contains(&key) && !new_faces.contains(&key)
            });
            let lost_edge = EDGES.iter().any(|&(k, m)| {
                let key = edge_key(v[k], v[m]);
                self.edges.contains(&key) && !new_edges.contains(&key)
            });
            if lost_face || lost_edge {
                return false;
            }
        }
        match self.mesh.replace_checked(old, new) {
            Some(made) => {
                self.note_tets(&made);
                true
            }
            None => false,
        }
    }
}

/// The six edges of a tet, as corner pairs.
pub(crate) const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];

/// A point strictly on the negative side of every face (its kernel's interior), searched by
/// ascent on the smallest distance to the faces' planes from the centroid of the corners.
fn kernel_point(mesh: &Mesh, faces: &[[u32; 3]]) -> Option<[f64; 3]> {
    // unit inward normals and offsets: inside where dot(n, p) > d
    let planes: Vec<([f64; 3], f64)> = faces
        .iter()
        .filter_map(|g| {
            let [a, b, c] = g.map(|w| mesh.p(w));
            // orient3d(a, b, c, p) < 0 inside: the inward normal is (b - a) × (c - a)
            let n = cross(sub(a, b), sub(a, c));
            let len = dot(n, n).sqrt();
            (len > 0.0).then(|| {
                let n = n.map(|x| x / len);
                (n, dot(n, a))
            })
        })
        .collect();
    let mut p = [0.0; 3];
    let corners: Vec<[f64; 3]> = faces.iter().flatten().map(|&w| mesh.p(w)).collect();
    for q in &corners {
        for k in 0..3 {
            p[k] += q[k] / corners.len() as f64;
        }
    }
    let size = corners
        .iter()
        .map(|&q| dot(sub(p, q), sub(p, q)).sqrt())
        .fold(0.0, f64::max);
    let depth = |p: [f64; 3]| {
        planes
            .iter()
            .map(|(n, d)| dot(*n, p) - d)
            .fold(f64::INFINITY, f64::min)
    };
    let mut step = 0.25 * size;
    let mut best = depth(p);
    for _ in 0..400 {
        if best > 1e-9 * size && step < 1e-3 * size {
            break;
        }
        // move along the sum of the normals of the nearly worst planes
        let mut dir = [0.0; 3];
        for (n, d) in &planes {
            if dot(*n, p) - d <= best + 0.05 * step {
                for k in 0..3 {
                    dir[k] += n[k];
                }
            }
        }
        let len = dot(dir, dir).sqrt();
        if len == 0.0 {
            break;
        }
        let q = [0, 1, 2].map(|k| p[k] + step * dir[k] / len);
        let dq = depth(q);
        if dq > best {
            (p, best) = (q, dq);
        } else {
            step *= 0.5;
        }
    }
    (best > 1e-12 * size).then_some(p)
}
