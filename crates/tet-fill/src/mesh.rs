//! The tetrahedralisation under construction: tets as four vertex indices, positively oriented
//! (`orient3d > 0`), with their face neighbours; the convex hull closed by ghost tets that share
//! one "vertex at infinity" ([`GHOST`]), so that every face has two tets and the walk and the
//! insertion need no special case at the hull. Dead tets' slots are reused.

use geom_predicates::{insphere, orient3d};

/// The vertex at infinity of the ghost tets (and the "no tet" marker of dead slots).
pub(crate) const GHOST: u32 = u32::MAX;

/// The corners of the face opposite corner `i`, ordered so that `orient3d(face, corner i) > 0`
/// for a positive tet: seen from corner `i`, the face turns clockwise.
pub(crate) const FACE: [[usize; 3]; 4] = [[1, 3, 2], [0, 2, 3], [0, 3, 1], [0, 1, 2]];

/// The tetrahedralisation: points, tets, neighbours.
pub(crate) struct Mesh {
    /// Every point, inserted or not.
    pub points: Vec<[f64; 3]>,
    /// Each tet's corners; a ghost tet has one corner [`GHOST`], a dead slot four.
    pub tets: Vec<[u32; 4]>,
    /// `adj[t][i]`: the tet across the face opposite corner `i`, times 4, plus that face's
    /// index in it.
    pub adj: Vec<[u32; 4]>,
    /// Dead slots, reused first.
    free: Vec<u32>,
    /// Where the next walk starts.
    pub hint: u32,
    /// The walk's random face order (xorshift state).
    pub rng: u64,
}

/// The point coordinates of a tet's face opposite `i` (real corners only).
#[inline]
pub(crate) fn face_of(t: [u32; 4], i: usize) -> [u32; 3] {
    FACE[i].map(|k| t[k])
}

/// A face's corners sorted: the key of a face whatever tet it is seen from.
#[inline]
pub(crate) fn face_key(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

impl Mesh {
    /// An empty tetrahedralisation over `points`.
    pub fn new(points: Vec<[f64; 3]>) -> Self {
        Self {
            points,
            tets: Vec::new(),
            adj: Vec::new(),
            free: Vec::new(),
            hint: 0,
            rng: 0x9e37_79b9_7f4a_7c15,
        }
    }

    /// A random number for the walk's face order.
    #[inline]
    pub fn random(&mut self) -> u64 {
        self.rng ^= self.rng << 13;
        self.rng ^= self.rng >> 7;
        self.rng ^= self.rng << 17;
        self.rng
    }

    #[inline]
    pub fn p(&self, v: u32) -> [f64; 3] {
        self.points[v as usize]
    }

    /// Whether slot `t` holds no tet.
    #[inline]
    pub fn is_dead(&self, t: u32) -> bool {
        let v = self.tets[t as usize];
        v[0] == GHOST && v[1] == GHOST
    }

    /// Whether `t` is a ghost tet (one corner at infinity).
    #[inline]
    pub fn is_ghost(&self, t: u32) -> bool {
        self.tets[t as usize].contains(&GHOST)
    }

    /// The tet across face `i` of `t`.
    #[inline]
    pub fn neighbour(&self, t: u32, i: usize) -> u32 {
        self.adj[t as usize][i] >> 2
    }

    /// A new tet with corners `v` (neighbours unset).
    pub fn alloc(&mut self, v: [u32; 4]) -> u32 {
        if let Some(t) = self.free.pop() {
            self.tets[t as usize] = v;
            t
        } else {
            self.tets.push(v);
            self.adj.push([GHOST; 4]);
            (self.tets.len() - 1) as u32
        }
    }

    /// Frees slot `t`.
    pub fn kill(&mut self, t: u32) {
        self.tets[t as usize] = [GHOST; 4];
        self.free.push(t);
    }

    /// Links face `i` of `t` and face `j` of `u` as neighbours.
    #[inline]
    pub fn link(&mut self, t: u32, i: usize, u: u32, j: usize) {
        self.adj[t as usize][i] = u * 4 + j as u32;
        self.adj[u as usize][j] = t * 4 + i as u32;
    }

    /// `orient3d` of face `i` of `t` and point `p`: positive on `t`'s side. The face must be real.
    #[inline]
    pub fn orient_face(&self, t: u32, i: usize, p: [f64; 3]) -> f64 {
        let f = face_of(self.tets[t as usize], i);
        orient3d(self.p(f[0]), self.p(f[1]), self.p(f[2]), p)
    }

    /// Whether `p` is strictly inside the circumsphere of `t`; for a ghost tet, strictly beyond
    /// its hull face or in that face's plane strictly inside its circumcircle.
    pub fn conflicts(&self, t: u32, p: [f64; 3]) -> bool {
        let v = self.tets[t as usize];
        match v.iter().position(|&x| x == GHOST) {
            None => {
                crate::insphere::inside(self.p(v[0]), self.p(v[1]), self.p(v[2]), self.p(v[3]), p)
            }
            Some(g) => {
                let o = self.orient_face(t, g, p);
                if o != 0.0 {
                    return o > 0.0;
                }
                // in the hull face's plane: inside its circle is inside the sphere through it
                // and the real tet's far corner (any point off the plane would do)
                let code = self.adj[t as usize][g];
                let d = self.tets[(code >> 2) as usize][(code & 3) as usize];
                let f = face_of(v, g);
                insphere(self.p(f[1]), self.p(f[0]), self.p(f[2]), self.p(d), p) > 0.0
            }
        }
    }

    /// Links the faces through `apex` (at corner `slot` of each tet) among `new` tets, by the
    /// edge each such face has opposite the apex: every such face must meet exactly one other.
    /// `table` is scratch space: an open-addressing table of edges (cheaper than sorting them).
    pub fn link_around_apex(&mut self, new: &[(u32, usize)], table: &mut Vec<(u64, u32)>) {
        const EMPTY: u64 = u64::MAX;
        const PAIRED: u32 = u32::MAX;
        let bits = (6 * new.len()).next_power_of_two().trailing_zeros().max(4);
        let wrap = (1usize << bits) - 1;
        table.clear();
        table.resize(wrap + 1, (EMPTY, 0));
        for &(t, slot) in new {
            let v = self.tets[t as usize];
            for k in 0..4 {
                if k == slot {
                    continue;
                }
                let mut e = [0u32; 2];
                let mut n = 0;
                for (m, &x) in v.iter().enumerate() {
                    if m != slot && m != k {
                        e[n] = x;
                        n += 1;
                    }
                }
                // (an edge's smaller end is never the ghost: the key is never EMPTY)
                let key = (u64::from(e[0].min(e[1])) << 32) | u64::from(e[0].max(e[1]));
                let code = t * 4 + k as u32;
                let mut h = (key.wrapping_mul(0x9e37_79b9_7f4a_7c15) >> (64 - bits)) as usize;
                loop {
                    let entry = &mut table[h];
                    if entry.0 == EMPTY {
                        *entry = (key, code);
                        break;
                    }
                    if entry.0 == key {
                        let other = entry.1;
                        debug_assert_ne!(other, PAIRED, "an edge in three faces of the cavity");
                        entry.1 = PAIRED;
                        self.link(t, k, other >> 2, (other & 3) as usize);
                        break;
                    }
                    h = (h + 1) & wrap;
                }
            }
        }
        debug_assert!(
            table.iter().all(|e| e.0 == EMPTY || e.1 == PAIRED),
            "cavity boundary not a closed surface"
        );
    }

    /// Starts the tetrahedralisation with the positive tet on four non-coplanar points and
    /// the four ghost tets on its faces.
    pub fn start(&mut self, corners: [u32; 4]) {
        let [a, b, c, d] = corners;
        let v = if orient3d(self.p(a), self.p(b), self.p(c), self.p(d)) > 0.0 {
            [a, b, c, d]
        } else {
            [b, a, c, d]
        };
        let t = self.alloc(v);
        let mut ghosts = Vec::with_capacity(4);
        for i in 0..4 {
            // corner i at infinity and two others swapped: the hull face seen from outside
            let mut g = v;
            g[i] = GHOST;
            let (x, y) = match i {
                0 => (1, 2),
                _ => (0, if i == 1 { 2 } else { 1 }),
            };
            g.swap(x, y);
            let gt = self.alloc(g);
            self.link(t, i, gt, i);
            ghosts.push((gt, i));
        }
        let mut scratch = Vec::new();
        self.link_around_apex(&ghosts, &mut scratch);
        self.hint = t;
    }

    /// The live real tets.
    pub fn real_tets(&self) -> impl Iterator<Item = u32> + '_ {
        (0..self.tets.len() as u32).filter(|&t| !self.is_dead(t) && !self.is_ghost(t))
    }
}
