//! Closed surfaces of triangles and quads: the input of the 3D mesher (`afsf3d`).
//!
//! A [`Surface`] holds nodes, facets (triangles and quads, each counter-clockwise seen from
//! the fluid side, so that their normals point into the fluid), and per facet a patch with a
//! name and a role (wall or far field, [`mesh_model::Role`]). The built-in surfaces
//! ([`Surface::sphere`], [`Surface::cube`], [`Surface::step`]) and
//! [`Surface::from_triangles`] (for the STL reader of `mesh-io`) make one; [`Surface::check`]
//! tells whether it can be meshed: finite nodes, closed, manifold (every edge in two facets),
//! consistently oriented, enclosing a positive volume, and not self-intersecting (facet pairs
//! found by sort-and-sweep, decided by the exact triangle–triangle test of
//! `geom-predicates`); the first problem found is a one-line [`SurfaceError`].
//!
//! [`Surface::farfield`] triangulates a far field (a box or a sphere, [`FarfieldShape`]) facing
//! into the domain: the outer boundary the volume fill meshes up to.
//!
//! [`wing::build_wing`] makes a finite wing from a 2D section (its boundary nodes extruded
//! over the span, caps at the tips) with its true surface ([`wing::WingShape`]).
//!
//! [`SmoothSurface`] rebuilds a smooth surface from the facets (PN triangles, feature edges
//! over 30° kept sharp): the true shape of a wall known only by its triangles.
//!
//! No IO here: files are read by `mesh-io`.
//!
//! ```
//! use geom_surface::Surface;
//!
//! let s = Surface::sphere(1.0, 2);
//! s.check()?;
//! let exact = 4.0 / 3.0 * std::f64::consts::PI;
//! assert!((s.enclosed_volume() - exact).abs() < 0.1 * exact);
//! # Ok::<(), geom_surface::SurfaceError>(())
//! ```

mod build;
mod check;
mod farfield;
mod smooth;
pub mod wing;

pub use check::{SurfaceError, first_self_intersection, self_intersections};
pub use farfield::{FarfieldShape, MAX_FARFIELD_TRIANGLES};
use mesh_model::{Patch, Role};
pub use smooth::{DEFAULT_FEATURE_ANGLE_DEG, PnTriangle, SmoothSurface};

/// No fourth node: the facet is a triangle.
pub const NO_NODE: u32 = u32::MAX;

/// A triangle or a quad: its nodes counter-clockwise seen from the fluid side (for a triangle
/// the fourth is [`NO_NODE`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Facet(pub [u32; 4]);

impl Facet {
    /// A triangle.
    pub fn tri(a: u32, b: u32, c: u32) -> Self {
        Facet([a, b, c, NO_NODE])
    }

    /// A quad.
    pub fn quad(a: u32, b: u32, c: u32, d: u32) -> Self {
        Facet([a, b, c, d])
    }

    /// The facet's nodes in order (three or four).
    pub fn nodes(&self) -> &[u32] {
        if self.0[3] == NO_NODE {
            &self.0[..3]
        } else {
            &self.0
        }
    }

    /// The triangles a quad is split into for intersection tests (the quad itself need not
    /// be planar): `(0 1 2)` and `(0 2 3)`; a triangle is itself.
    pub fn triangles(&self) -> impl Iterator<Item = [u32; 3]> + '_ {
        let n = self.nodes();
        (1..n.len() - 1).map(move |k| [n[0], n[k], n[k + 1]])
    }
}

/// A closed surface of triangles and quads with a patch per facet.
#[derive(Debug, Clone, PartialEq)]
pub struct Surface {
    /// Node coordinates.
    pub nodes: Vec<[f64; 3]>,
    /// Facets, counter-clockwise seen from the fluid side.
    pub facets: Vec<Facet>,
    /// The patch of each facet (index into `patches`).
    pub facet_patch: Vec<u32>,
    /// Named patches with their roles.
    pub patches: Vec<Patch>,
}

impl Surface {
    /// A surface of one wall patch named `name`.
    pub fn single_patch(nodes: Vec<[f64; 3]>, facets: Vec<Facet>, name: &str) -> Self {
        let facet_patch = vec![0; facets.len()];
        Surface {
            nodes,
            facets,
            facet_patch,
            patches: vec![Patch {
                name: name.to_string(),
                role: Role::Wall,
            }],
        }
    }

    /// A wall surface from plain triangles (e.g. read from STL), counter-clockwise seen from
    /// the fluid side. Not checked: call [`Surface::check`].
    pub fn from_triangles(nodes: Vec<[f64; 3]>, tris: &[[u32; 3]]) -> Self {
        let facets = tris.iter().map(|t| Facet::tri(t[0], t[1], t[2])).collect();
        Surface::single_patch(nodes, facets, "wall")
    }

    /// The role of facet `f`.
    pub fn role(&self, f: usize) -> Role {
        self.patches[self.facet_patch[f] as usize].role
    }

    /// The volume the surface encloses by the divergence theorem (positive when the facets
    /// face out of the body), each facet fanned from its centroid (see [`facet_volume6`]).
    pub fn enclosed_volume(&self) -> f64 {
        let o = self.nodes.first().copied().unwrap_or([0.0; 3]);
        self.facets
            .iter()
            .map(|f| facet_volume6(&self.nodes, f.nodes(), o))
            .sum::<f64>()
            / 6.0
    }

    /// The total area of the facets (quads fanned from their centroid).
    pub fn area(&self) -> f64 {
        self.facets
            .iter()
            .map(|f| norm(fan_normal(&self.nodes, f.nodes())) / 2.0)
            .sum()
    }

    /// The angle-weighted unit normal of every node (pointing into the fluid): the sum of the
    /// normals of the facets around it, each weighted by the facet's angle at the node.
    /// A node in no facet gets a zero vector.
    pub fn node_normals(&self) -> Vec<[f64; 3]> {
        node_normals(&self.nodes, &self.facets)
    }
}

/// The angle-weighted unit normals of `facets` over `nodes` (see [`Surface::node_normals`]),
/// for facets that index a node array they do not own (a layer's front over a volume mesh's
/// nodes), without copying the nodes into a [`Surface`].
pub fn node_normals(nodes: &[[f64; 3]], facets: &[Facet]) -> Vec<[f64; 3]> {
    let mut acc = vec![[0.0; 3]; nodes.len()];
    for f in facets {
        let k = f.nodes();
        let n = unit(fan_normal(nodes, k));
        for i in 0..k.len() {
            let p = nodes[k[i] as usize];
            let a = sub(nodes[k[(i + k.len() - 1) % k.len()] as usize], p);
            let b = sub(nodes[k[(i + 1) % k.len()] as usize], p);
            let angle = angle_between(a, b);
            for d in 0..3 {
                acc[k[i] as usize][d] += angle * n[d];
            }
        }
    }
    acc.into_iter().map(unit).collect()
}

/// Six times the signed volume of the cone from `o` over the facet `k` (fanned from its
/// centroid): summed over a closed, outward surface it is six times the enclosed volume.
pub fn facet_volume6(nodes: &[[f64; 3]], k: &[u32], o: [f64; 3]) -> f64 {
    let rel = |v: u32| sub(nodes[v as usize], o);
    let mut c = [0.0; 3];
    for &v in k {
        let p = rel(v);
        (0..3).for_each(|d| c[d] += p[d] / k.len() as f64);
    }
    (0..k.len())
        .map(|i| dot(c, cross(rel(k[i]), rel(k[(i + 1) % k.len()]))))
        .sum()
}

/// Twice the vector area of the polygon `k` fanned from its centroid (its normal times twice
/// its area).
pub fn fan_normal(nodes: &[[f64; 3]], k: &[u32]) -> [f64; 3] {
    let mut c = [0.0; 3];
    for &v in k {
        (0..3).for_each(|d| c[d] += nodes[v as usize][d] / k.len() as f64);
    }
    let mut n = [0.0; 3];
    for i in 0..k.len() {
        let a = sub(nodes[k[i] as usize], c);
        let b = sub(nodes[k[(i + 1) % k.len()] as usize], c);
        let x = cross(a, b);
        (0..3).for_each(|d| n[d] += x[d]);
    }
    n
}

pub(crate) fn sub(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    geom_predicates::vector::sub(a, b)
}
pub(crate) fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    geom_predicates::vector::dot(a, b)
}
pub(crate) fn cross(a: [f64; 3], b: [f64; 3]) -> [f64; 3] {
    geom_predicates::vector::cross3(a, b)
}
pub(crate) fn norm(a: [f64; 3]) -> f64 {
    dot(a, a).sqrt()
}

/// `a` scaled to unit length (zero stays zero).
pub fn unit(a: [f64; 3]) -> [f64; 3] {
    let l = norm(a);
    if l > 0.0 { a.map(|x| x / l) } else { a }
}

/// The angle between two vectors in [0, π] (0 when one is zero).
pub fn angle_between(a: [f64; 3], b: [f64; 3]) -> f64 {
    norm(cross(a, b)).atan2(dot(a, b))
}
