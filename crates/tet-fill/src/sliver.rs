//! Sliver removal (after Klingner–Shewchuk, "Aggressive tetrahedral mesh improvement"): the
//! inside tets whose largest dihedral angle exceeds the target are visited worst first and
//! improved by whatever lowers the worst angle of the tets it touches — an edge removal
//! (3-2, 4-4 and larger rings) or a 2-3 flip, never across an input facet or edge; then by
//! moving one of the fill's own points (never an input point) to lower its star's worst angle,
//! a pattern search that only accepts improvements and keeps every tet positive; and where a
//! sliver still survives, a point inserted near it (constrained Bowyer–Watson, then the
//! neighbourhood improved again), kept only when every tet it makes is better than the worst
//! of the sliver and the tets it replaces: in a narrow gap between fronts an insertion that
//! moves a sliver beside its own point starts a cascade of slivers among the fill's points.
//! A flat tet (over 179°: four front points on two parallel front edges across a gap, the
//! span stations of extruded bodies facing each other) is flipped only into other flat tets
//! and its faces' offsets leave the gap, so points close to its own plane are tried last.

use crate::FillOptions;
use crate::cavity::EDGES;
use crate::flip::{EdgeSet, Kept, edge_key};
use crate::insert::{FaceSet, Located, Scratch};
use crate::mesh::{GHOST, Mesh};
use crate::quality::{circumcentre, cross, dihedral_rank, dist, dot, rank_of_deg, sub};
use crate::region::Side;

/// A tet with a dihedral angle over this (degrees) is flat: its corners lie in one plane up
/// to rounding.
const FLAT_DEG: f64 = 179.0;

/// The offsets (× the longest edge) from a flat tet's centroid along the normal of its
/// largest face where [`Improver::insert_near`] tries a point last.
const FLAT_OFFSETS: [f64; 3] = [0.2, 0.1, 0.05];

/// What improvement works with.
struct Improver<'a> {
    mesh: &'a mut Mesh,
    side: &'a mut Vec<Side>,
    faces: &'a FaceSet,
    edges: EdgeSet,
    /// Points from this index on may move.
    first_free: usize,
    scratch: Scratch,
}

/// Improves the worst dihedral angles of the inside tets; the number of points added.
pub(crate) fn improve(
    mesh: &mut Mesh,
    side: &mut Vec<Side>,
    faces: &FaceSet,
    first_free: usize,
    options: &FillOptions,
    encroached: &dyn Fn([f64; 3]) -> bool,
) -> usize {
    let mut edges = EdgeSet::default();
    for f in faces {
        for k in 0..3 {
            edges.insert(edge_key(f[k], f[(k + 1) % 3]));
        }
    }
    let mut imp = Improver {
        mesh,
        side,
        faces,
        edges,
        first_free,
        scratch: Scratch::default(),
    };
    // angles compared as ranks (minus their cosines): no `acos`
    let target = rank_of_deg(options.max_dihedral_deg);
    let mut added = 0;
    for pass in 0..8 {
        let bad = imp.bad_tets(target);
        if bad.is_empty() {
            break;
        }
        for t in bad {
            if !imp.is_bad(t, target) {
                continue;
            }
            let fixed = imp.try_flips(t) || imp.try_smooth(t);
            // the last passes insert a point where flips and smoothing did not help
            let room = imp.mesh.points.len() < options.max_points;
            if !fixed
                && room
                && pass >= 2
                && imp.is_bad(t, target)
                && imp.insert_near(t, encroached)
            {
                added += 1;
            }
        }
    }
    added
}

impl Improver<'_> {
    /// The worst dihedral angle of tet corners `v`, as its [`dihedral_rank`].
    fn worst(&self, v: [u32; 4]) -> f64 {
        dihedral_rank(v.map(|w| self.mesh.p(w)))
    }

    fn inside(&self, t: u32) -> bool {
        !self.mesh.is_dead(t) && self.side.get(t as usize) == Some(&Side::Inside)
    }

    fn is_bad(&self, t: u32, target: f64) -> bool {
        self.inside(t) && self.worst(self.mesh.tets[t as usize]) > target
    }

    /// The inside tets worse than `target` (a rank), worst first.
    fn bad_tets(&self, target: f64) -> Vec<u32> {
        let mut bad: Vec<(f64, u32)> = (0..self.mesh.tets.len() as u32)
            .filter(|&t| self.inside(t))
            .map(|t| (self.worst(self.mesh.tets[t as usize]), t))
            .filter(|&(w, _)| w > target)
            .collect();
        bad.sort_unstable_by(|a, b| b.0.total_cmp(&a.0));
        bad.into_iter().map(|(_, t)| t).collect()
    }

    /// Replaces `old` by `new` when the worst angle drops; true when done.
    fn accept(&mut self, old: &[u32], new: &[[u32; 4]]) -> bool {
        let before = old
            .iter()
            .map(|&t| self.worst(self.mesh.tets[t as usize]))
            .fold(f64::NEG_INFINITY, f64::max);
        let after = new
            .iter()
            .map(|&v| self.worst(v))
            .fold(f64::NEG_INFINITY, f64::max);
        if after >= before || !old.iter().all(|&t| self.inside(t)) {
            return false;
        }
        for t in self.mesh.replace(old, new) {
            self.mark_inside(t);
        }
        true
    }

    fn mark_inside(&mut self, t: u32) {
        if self.side.len() <= t as usize {
            self.side.resize(self.mesh.tets.len(), Side::Unknown);
        }
        self.side[t as usize] = Side::Inside;
    }

    /// The best edge removal or 2-3 flip around tet `t` that lowers the worst angle.
    fn try_flips(&mut self, t: u32) -> bool {
        let kept = Kept {
            faces: self.faces,
            edges: &self.edges,
        };
        let score = |m: &Mesh, v: [u32; 4]| -dihedral_rank(v.map(|w| m.p(w)));
        let v = self.mesh.tets[t as usize];
        let mut ways: Vec<(Vec<u32>, Vec<[u32; 4]>)> = Vec::new();
        for (k, m) in EDGES {
            if let Some(way) = self.mesh.edge_removal(t, v[k], v[m], &kept, &score) {
                ways.push(way);
            }
        }
        for i in 0..4 {
            if let Some((old, new)) = self.mesh.flip23(t, i, &kept) {
                ways.push((old.to_vec(), new.to_vec()));
            }
        }
        // the ways whose new tets are best first
        let mut ranked: Vec<(f64, usize)> = ways
            .iter()
            .enumerate()
            .map(|(k, (_, new))| {
                let worst = new.iter().map(|&v| self.worst(v));
                (worst.fold(f64::NEG_INFINITY, f64::max), k)
            })
            .collect();
        ranked.sort_unstable_by(|a, b| a.0.total_cmp(&b.0));
        ranked
            .into_iter()
            .any(|(_, k)| self.accept(&ways[k].0, &ways[k].1))
    }

    /// The tets holding `v`, from tet `t` that holds it.
    fn star(&self, t: u32, v: u32) -> Vec<u32> {
        let mut star = vec![t];
        let mut k = 0;
        while k < star.len() {
            let u = star[k];
            k += 1;
            for i in 0..4 {
                if self.mesh.tets[u as usize][i] != v {
                    let n = self.mesh.neighbour(u, i);
                    if !star.contains(&n) {
                        star.push(n);
                    }
                }
            }
        }
        star
    }

    /// Moves a free corner of `t` to lower its star's worst angle; true when it moved.
    fn try_smooth(&mut self, t: u32) -> bool {
        let corners = self.mesh.tets[t as usize];
        let mut moved = false;
        for v in corners {
            if (v as usize) < self.first_free || v == GHOST {
                continue;
            }
            let star = self.star(t, v);
            if star.iter().all(|&u| self.inside(u)) {
                moved |= self.smooth_point(v, &star);
            }
        }
        moved
    }

    /// The worst angle of `star` with `v` at `p` (infinite when a tet is not positive).
    fn star_worst(&mut self, v: u32, p: [f64; 3], star: &[u32]) -> f64 {
        let old = self.mesh.points[v as usize];
        self.mesh.points[v as usize] = p;
        let mut worst = f64::NEG_INFINITY;
        for &u in star {
            let c = self.mesh.tets[u as usize];
            if !self.mesh.positive(c) {
                worst = f64::INFINITY;
                break;
            }
            worst = worst.max(self.worst(c));
        }
        self.mesh.points[v as usize] = old;
        worst
    }

    /// Pattern search for `v`'s position over its star; keeps only improvements.
    fn smooth_point(&mut self, v: u32, star: &[u32]) -> bool {
        let start = self.mesh.p(v);
        let mut best = (self.star_worst(v, start, star), start);
        let initial = best.0;
        let mut step = star
            .iter()
            .flat_map(|&u| self.mesh.tets[u as usize])
            .filter(|&w| w != v)
            .map(|w| dist(self.mesh.p(w), start))
            .fold(f64::INFINITY, f64::min)
            * 0.25;
        for _ in 0..24 {
            let p = best.1;
            let mut improved = false;
            for k in 0..3 {
                for s in [-1.0, 1.0] {
                    let mut q = p;
                    q[k] += s * step;
                    let w = self.star_worst(v, q, star);
                    if w < best.0 {
                        best = (w, q);
                        improved = true;
                    }
                }
            }
            if !improved {
                step *= 0.5;
            }
        }
        if best.0 < initial {
            self.mesh.points[v as usize] = best.1;
            true
        } else {
            false
        }
    }

    /// Inserts a point where it takes sliver `t` into its cavity: its circumcentre when near
    /// and not encroaching a facet, else beyond one of its faces that are not facets (the
    /// first that falls in the region); true when the sliver is gone.
    fn insert_near(&mut self, t: u32, encroached: &dyn Fn([f64; 3]) -> bool) -> bool {
        let v = self.mesh.tets[t as usize];
        let p = v.map(|w| self.mesh.p(w));
        let (_, long) = crate::quality::edge_range(p);
        let mut candidates = Vec::new();
        candidates
            .extend(circumcentre(p).filter(|&c| dist(c, p[0]) < 2.0 * long && !encroached(c)));
        for i in 0..4 {
            let f = crate::mesh::face_of(v, i);
            if self.faces.contains(&crate::mesh::face_key(f)) {
                continue;
            }
            let [a, b, c] = f.map(|w| self.mesh.p(w));
            let n = cross(sub(a, b), sub(a, c));
            let len = dot(n, n).sqrt();
            // orient3d(face, corner i) > 0: corner i is on the side opposite the normal
            for d in [0.3, 0.6, 1.0] {
                let q = [0, 1, 2].map(|k| (a[k] + b[k] + c[k]) / 3.0 + d * long * n[k] / len);
                candidates.push(q);
            }
        }
        // last, a flat tet's own plane (`FLAT_DEG`): four points on two parallel front edges
        // (the spans of an extruded body facing each other across a gap) make a tet of no
        // volume, every flip of which is flat too, and whose faces' offsets above all leave
        // the gap; points close to its plane stay in it
        if self.worst(v) > rank_of_deg(FLAT_DEG) {
            let mid: [f64; 3] =
                std::array::from_fn(|k| (p[0][k] + p[1][k] + p[2][k] + p[3][k]) / 4.0);
            let n = (0..4)
                .map(|i| {
                    let [a, b, c] = crate::mesh::face_of(v, i).map(|w| self.mesh.p(w));
                    cross(sub(a, b), sub(a, c))
                })
                .fold([0.0; 3], |m, x| if dot(x, x) > dot(m, m) { x } else { m });
            let len = dot(n, n).sqrt();
            for d in FLAT_OFFSETS.iter().filter(|_| len > 0.0) {
                for sign in [1.0, -1.0] {
                    candidates.push(std::array::from_fn(|k| {
                        mid[k] + sign * d * long * n[k] / len
                    }));
                }
            }
        }
        // one point per sliver: a point that leaves it is not followed by more
        for q in candidates {
            if self.insert_at(t, q) {
                return self.mesh.is_dead(t);
            }
        }
        false
    }

    /// Inserts `q` (walking from `t`) if it falls inside the region and every tet it makes is
    /// better than the worst of sliver `t` and the tets it replaces (an insertion that only
    /// moves a sliver next to its own new point starts a cascade); true when inserted.
    fn insert_at(&mut self, t: u32, q: [f64; 3]) -> bool {
        self.mesh.hint = t;
        let Located::Tet(at) = self.mesh.locate(q) else {
            return false;
        };
        if !self.inside(at) || self.mesh.near_vertex(at, q) {
            return false;
        }
        self.mesh.points.push(q);
        let v = (self.mesh.points.len() - 1) as u32;
        if self
            .mesh
            .star_cavity(v, at, Some(self.faces), None, &mut self.scratch)
        {
            let before = self
                .scratch
                .cavity_tets()
                .iter()
                .map(|&c| self.worst(self.mesh.tets[c as usize]))
                .fold(self.worst(self.mesh.tets[t as usize]), f64::max);
            let after = self
                .scratch
                .new_tets(self.mesh, v)
                .map(|c| self.worst(c))
                .fold(f64::NEG_INFINITY, f64::max);
            if after < before {
                let mut new = Vec::new();
                self.mesh.commit_cavity(v, &mut self.scratch, &mut new);
                for &n in &new {
                    self.mark_inside(n);
                }
                return true;
            }
        }
        self.mesh.points.pop();
        false
    }
}
