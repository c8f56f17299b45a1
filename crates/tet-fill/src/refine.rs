//! Delaunay refinement of the region: a tet too large for the size field, or whose
//! circumradius over shortest edge exceeds the bound, gets its circumcentre inserted
//! (constrained Bowyer–Watson: the facets bound every cavity) — unless the circumcentre lies in
//! an input facet's diametral sphere or outside the region, for the facets are never split.
//! The size field: each input point's mean input edge length, growing by `grading - 1` per
//! unit distance from the nearest input point, capped by `max_size`.

use crate::error::FillError;
use crate::insert::{FaceSet, Located, Scratch};
use crate::mesh::{GHOST, Mesh};
use crate::quality::{circumcentre, dist, edge_range};
use crate::region::Side;
use crate::{FillInput, FillOptions};
use geom_predicates::PointTree;

/// The size field from the input surfaces.
struct SizeField {
    tree: PointTree<3>,
    size: Vec<f64>,
    slope: f64,
    cap: f64,
    /// The field at each mesh point, NaN until looked up.
    at_vertex: Vec<f64>,
}

impl SizeField {
    fn new(input: &FillInput, options: &FillOptions) -> Self {
        let n = input.points.len();
        let (mut sum, mut count) = (vec![0.0; n], vec![0u32; n]);
        for f in input.facets {
            for k in 0..3 {
                let (a, b) = (f[k] as usize, f[(k + 1) % 3] as usize);
                let l = dist(input.points[a], input.points[b]);
                // each edge is seen from its two facets: both ends counted twice alike
                for v in [a, b] {
                    sum[v] += l;
                    count[v] += 1;
                }
            }
        }
        let size = (0..n)
            .map(|v| {
                if count[v] > 0 {
                    sum[v] / f64::from(count[v])
                } else {
                    f64::INFINITY
                }
            })
            .collect();
        Self {
            tree: PointTree::new(input.points),
            size,
            // an infinite grading: no size refinement at all
            slope: (options.grading - 1.0).max(0.0),
            cap: if options.max_size > 0.0 {
                options.max_size
            } else {
                f64::INFINITY
            },
            at_vertex: Vec::new(),
        }
    }

    /// The size wanted at `p` inside the tet with corners `v`: the field at the corners (each
    /// looked up once) grown to `p` by the grading, which the field itself never exceeds.
    fn near(&mut self, mesh: &Mesh, v: [u32; 4], p: [f64; 3]) -> f64 {
        let mut h = f64::INFINITY;
        for w in v {
            if self.at_vertex.len() <= w as usize {
                self.at_vertex.resize(mesh.points.len(), f64::NAN);
            }
            let q = mesh.p(w);
            if self.at_vertex[w as usize].is_nan() {
                self.at_vertex[w as usize] = self.at(q);
            }
            h = h.min(self.at_vertex[w as usize] + self.slope * dist(p, q));
        }
        h.min(self.cap)
    }

    /// The size wanted at `p`.
    fn at(&self, p: [f64; 3]) -> f64 {
        let h = match self.tree.nearest(p) {
            Some((v, d)) if self.slope.is_finite() => self.size[v] + self.slope * d,
            Some(_) => f64::INFINITY,
            None => f64::INFINITY,
        };
        h.min(self.cap)
    }
}

/// The input facets' diametral spheres, searched by centre: grouped by radius (within a
/// factor of two), so that each group's search radius fits its spheres and a far field's large
/// facets do not make every search return the small ones.
pub(crate) struct Facets {
    groups: Vec<Group>,
}

/// Spheres of similar radii.
struct Group {
    tree: PointTree<3>,
    centre: Vec<[f64; 3]>,
    radius: Vec<f64>,
    largest: f64,
}

impl Facets {
    pub(crate) fn new(input: &FillInput) -> Self {
        let mut spheres: Vec<(i32, [f64; 3], f64)> = input
            .facets
            .iter()
            .map(|f| {
                let (o, r) = diametral(f.map(|v| input.points[v as usize]));
                (r.log2().floor() as i32, o, r)
            })
            .collect();
        spheres.sort_unstable_by_key(|s| s.0);
        let groups = spheres
            .chunk_by(|a, b| a.0 == b.0)
            .map(|g| {
                let centre: Vec<[f64; 3]> = g.iter().map(|s| s.1).collect();
                let radius: Vec<f64> = g.iter().map(|s| s.2).collect();
                Group {
                    tree: PointTree::new(&centre),
                    largest: radius.iter().copied().fold(0.0, f64::max),
                    centre,
                    radius,
                }
            })
            .collect();
        Self { groups }
    }

    /// Whether `p` lies strictly inside some facet's diametral sphere.
    pub(crate) fn encroached(&self, p: [f64; 3]) -> bool {
        self.groups.iter().any(|g| {
            g.tree
                .within(p, g.largest)
                .iter()
                .any(|&(k, d)| d < g.radius[k] && dist(p, g.centre[k]) < g.radius[k])
        })
    }
}

/// A triangle's diametral sphere: its circumcircle's centre and radius.
fn diametral([a, b, c]: [[f64; 3]; 3]) -> ([f64; 3], f64) {
    // the circumcircle's centre: the circumcentre of the tet with a far apex on the normal
    let u = crate::quality::sub(a, b);
    let w = crate::quality::sub(a, c);
    let n = crate::quality::cross(u, w);
    let apex = [0, 1, 2].map(|k| a[k] + n[k]);
    let o = circumcentre([a, b, c, apex]).unwrap_or(a);
    // the tet's circumcentre lies on the circle's axis: project onto the plane
    let len2 = crate::quality::dot(n, n);
    let t = crate::quality::dot(crate::quality::sub(a, o), n) / len2;
    let o = [0, 1, 2].map(|k| o[k] - t * n[k]);
    (o, dist(o, a))
}

/// A tet is refined for its shape only when its circumradius is at least this fraction of
/// the size wanted there: below, radius–edge refinement between constrained faces can cascade
/// to ever smaller tets far from any input (millions of points at 1e-5 in a region sized 0.05,
/// beside the fronts of an extruded 30P30N); the sliver removal that follows takes the shape.
const SHAPE_FLOOR: f64 = 0.25;

/// Whether a tet of circumradius `r` and shortest edge `short`, where the size field wants
/// `h`, is refined: too large for `h`, or too skinny for the radius–edge bound `shape_bound`
/// — but for its shape only above [`SHAPE_FLOOR`] × `h` and above `floor` (half the input's
/// shortest edge).
fn wants_refining(r: f64, short: f64, h: f64, floor: f64, shape_bound: Option<f64>) -> bool {
    let skinny = |bound: f64| r > floor && r > SHAPE_FLOOR * h && r > bound * short;
    r > h || shape_bound.is_some_and(skinny)
}

/// The shortest edge of the input's facets.
fn shortest_input_edge(input: &FillInput) -> f64 {
    let p = |v: u32| input.points[v as usize];
    (input.facets.iter())
        .flat_map(|f| (0..3).map(move |k| dist(p(f[k]), p(f[(k + 1) % 3]))))
        .fold(f64::INFINITY, f64::min)
}

/// Refines the inside tets; the number of points added.
pub(crate) fn refine(
    mesh: &mut Mesh,
    side: &mut Vec<Side>,
    faces: &FaceSet,
    input: &FillInput,
    facets: &Facets,
    options: &FillOptions,
) -> Result<usize, FillError> {
    let bound = options.max_radius_edge;
    let by_shape = bound > 0.0 && bound.is_finite();
    let mut sizes = SizeField::new(input, options);
    // no tet is refined for its shape below the input's own resolution, and no point goes
    // nearer an existing one than a tenth of it: a circumcentre rounded onto a vertex (of a
    // nearly flat tet, or across a constrained face) starts a cascade of ever smaller tets at
    // one place (on an extruded 30P30N, millions of points within 1e-15 of each other)
    let floor = 0.5 * shortest_input_edge(input);
    let mut bad = |mesh: &Mesh, t: u32| {
        let v = mesh.tets[t as usize];
        let p = v.map(|w| mesh.p(w));
        let c = circumcentre(p)?;
        let r = dist(c, p[0]);
        let (short, _) = edge_range(p);
        let centroid = [0, 1, 2].map(|k| (p[0][k] + p[1][k] + p[2][k] + p[3][k]) / 4.0);
        let h = sizes.near(mesh, v, centroid);
        let shape_bound = by_shape.then_some(bound);
        wants_refining(r, short, h, floor, shape_bound).then_some(c)
    };
    let mut queue: Vec<u32> = (0..mesh.tets.len() as u32)
        .filter(|&t| side[t as usize] == Side::Inside)
        .collect();
    let (mut scratch, mut new) = (Scratch::default(), Vec::new());
    // per slot, the corners of the tet last found good there: a slot reused while its old
    // entry waits in the queue is queued twice, and most entries are such repeats
    let mut good = vec![[GHOST; 4]; mesh.tets.len()];
    let mut added = 0;
    while let Some(t) = queue.pop() {
        let corners = mesh.tets[t as usize];
        if mesh.is_dead(t) || side[t as usize] != Side::Inside || good[t as usize] == corners {
            continue;
        }
        let Some(c) = bad(mesh, t) else {
            good[t as usize] = corners;
            continue;
        };
        if facets.encroached(c) {
            continue;
        }
        // the circumcentre must be in the region: start the walk at the tet itself
        mesh.hint = t;
        let Located::Tet(at) = mesh.locate(c) else {
            continue;
        };
        if side.get(at as usize) != Some(&Side::Inside) || mesh.near_vertex(at, c) {
            continue;
        }
        if mesh.tets[at as usize]
            .iter()
            .any(|&w| dist(mesh.p(w), c) < 0.1 * floor)
        {
            continue;
        }
        if mesh.points.len() >= options.max_points {
            return Err(FillError::TooManyPoints {
                limit: options.max_points,
            });
        }
        mesh.points.push(c);
        let v = (mesh.points.len() - 1) as u32;
        if !mesh.insert(v, at, Some(faces), &mut scratch, &mut new) {
            mesh.points.pop();
            continue;
        }
        added += 1;
        side.resize(mesh.tets.len(), Side::Unknown);
        good.resize(mesh.tets.len(), [GHOST; 4]);
        for &n in &new {
            side[n as usize] = Side::Inside;
            queue.push(n);
        }
    }
    Ok(added)
}

#[cfg(test)]
mod tests {
    use super::wants_refining;

    /// Large tets are refined whatever their shape; skinny ones only while they are at least a
    /// quarter of the size wanted and above the input's resolution.
    #[test]
    fn small_skinny_tets_are_left_to_the_sliver_removal() {
        let (h, floor, bound) = (0.05, 1e-5, Some(2.0));
        // larger than the size wanted: refined, skinny or not, shape bound or not
        assert!(wants_refining(0.06, 0.05, h, floor, None));
        // a skinny tet (radius 10 × its shortest edge) at a third of the size: refined
        assert!(wants_refining(0.02, 0.002, h, floor, bound));
        // a well-shaped one of the same size: not
        assert!(!wants_refining(0.02, 0.015, h, floor, bound));
        // the same skinny shape at a tenth of the size: left alone (the cascade's tets)
        assert!(!wants_refining(0.005, 0.0005, h, floor, bound));
        // below the input's resolution: left alone even where the size wanted is tiny
        assert!(!wants_refining(4e-6, 1e-7, 1e-5, floor, bound));
        // no shape bound: only size
        assert!(!wants_refining(0.02, 0.002, h, floor, None));
    }
}
