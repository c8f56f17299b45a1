//! The finite wing of a 2D case (dissertation §5.1, issue 13): the case's wall section,
//! meshed on its C2 curve as the 2D pipeline does, extruded over the span with stations
//! graded from each tip, and closed at both tips by caps meshed by the 2D mesher inside the
//! section: by default its fill alone (isotropic triangles, [`CapMesh::Fill`]), or its whole
//! mesh with layers (`inside = true`, [`CapMesh::Layers`]). The surface and its true shape come from
//! [`geom_surface::wing::build_wing`].

use crate::error::{Result, bail, input_error};
use geom_curve::ClosedCurve;
use geom_surface::wing::{Cap, SectionCurve, WingShape, build_wing, span_stations};
use geom_surface::{Facet, Surface};
use mesh_model::Role;

use crate::case::Case;
use crate::pipeline;

/// A section's C2 curve as the wing's true shape sees it.
#[derive(Debug, Clone)]
pub struct Section(pub ClosedCurve);

impl SectionCurve for Section {
    fn between(&self, t0: f64, t1: f64, s: f64) -> [f64; 2] {
        let c = &self.0;
        let t1 = if t1 <= t0 {
            t1 + c.segment_count() as f64
        } else {
            t1
        };
        let at = c.arc_length(0.0, t0) + s * c.arc_length(t0, t1);
        let p = c.point(c.t_at_arc_length(at));
        [p.x, p.y]
    }
}

/// The wing's true surface as the 3D curving sees it: the points of the curved side over its
/// facets ([`WingShape::edge_point`] along an edge, [`WingShape::side_point`] inside a side
/// facet), the caps flat.
#[derive(Debug, Clone)]
pub struct WingProjector {
    /// The wing's surface (the layers grew from it).
    pub surface: Surface,
    /// Its true shape.
    pub shape: WingShape<Section>,
}

impl vector_adding::SurfaceProjector for WingProjector {
    /// `p` is a point of wall facet `facet`: the straight midpoint of one of its edges goes to
    /// that edge's point at half its arc length (the P2 wall nodes); any other point of a side
    /// facet to the side's point at its height whose chordwise place over the section edge is
    /// `p`'s (the P3 wall faces' nodes); a cap's points stay (the caps are flat).
    fn project(&self, p: [f64; 3], facet: usize) -> [f64; 3] {
        let Some(f) = self.surface.facets.get(facet) else {
            return p;
        };
        let k = f.nodes();
        let x = |v: u32| self.surface.nodes[v as usize];
        let off = |i: usize| {
            let (a, b) = (x(k[i]), x(k[(i + 1) % k.len()]));
            (0..3)
                .map(|d| (0.5 * (a[d] + b[d]) - p[d]).abs())
                .fold(0.0, f64::max)
        };
        let i = (0..k.len())
            .min_by(|&i, &j| off(i).total_cmp(&off(j)))
            .expect("a facet has corners");
        if off(i) == 0.0 {
            return self
                .shape
                .edge_point(k[i], k[(i + 1) % k.len()], 0.5)
                .unwrap_or(p);
        }
        self.side_point_under(k, p).unwrap_or(p)
    }

    /// Along the section's curve at fraction `s` of the arc length where the edge follows it
    /// ([`WingShape::edge_point`]), else (the span, a cap's inside) along the chord.
    fn edge_point(&self, a: [f64; 3], b: [f64; 3], s: f64, facet: usize) -> [f64; 3] {
        let chord = [0, 1, 2].map(|d| a[d] + s * (b[d] - a[d]));
        let Some(f) = self.surface.facets.get(facet) else {
            return chord;
        };
        let node = |p: [f64; 3]| {
            f.nodes()
                .iter()
                .copied()
                .find(|&v| self.surface.nodes[v as usize] == p)
        };
        match (node(a), node(b)) {
            (Some(u), Some(v)) => self.shape.edge_point(u, v, s).unwrap_or(chord),
            _ => chord,
        }
    }
}

impl WingProjector {
    /// The side's point under `p` for a side facet with corners `k` (spanning two stations
    /// over section edge i → i + 1): at `p`'s height, at the arc fraction along the section
    /// edge whose point falls where `p` does along the edge's chord (by bisection: the
    /// fraction along the chord grows with the arc's on a section edge). `None` on a cap.
    fn side_point_under(&self, k: &[u32], p: [f64; 3]) -> Option<[f64; 3]> {
        let sides: Vec<(usize, usize)> = k
            .iter()
            .map(|&v| self.shape.side_node(v))
            .collect::<Option<_>>()?;
        if sides.iter().all(|&(_, station)| station == sides[0].1) {
            return None;
        }
        let n = self.shape.section.len();
        let first = sides[0].0;
        let other = sides.iter().map(|s| s.0).find(|&j| j != first)?;
        let i = if other == (first + 1) % n {
            first
        } else {
            other
        };
        let (a, b) = (self.shape.section[i], self.shape.section[(i + 1) % n]);
        let d = [b[0] - a[0], b[1] - a[1]];
        let along = |q: [f64; 3]| (q[0] - a[0]) * d[0] + (q[1] - a[1]) * d[1];
        let target = along(p);
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if along(self.shape.side_point(i, mid, p[2])) < target {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        Some(self.shape.side_point(i, 0.5 * (lo + hi), p[2]))
    }
}

/// The wing made from `case`'s one wall loop: chord and position as in the case, span `span`
/// along z from 0. The section's boundary nodes are the 2D pipeline's; the span stations are
/// graded from each tip by the case's first layer height (`[layers] first_height`) and the
/// boundary's growth ratio (`[boundary] growth`), capped at the section's largest boundary
/// segment; the caps are the 2D mesher's isotropic fill of the section ([`CapMesh::Fill`]).
/// With `triangles` every quad of the side is split along its shorter diagonal.
pub fn wing_surface(
    case: &Case,
    span: f64,
    triangles: bool,
) -> Result<(Surface, WingShape<Section>)> {
    wing_surface_with(case, span, triangles, CapMesh::default(), None)
}

/// How the tip caps are meshed (`[surface] cap`).
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, serde::Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CapMesh {
    /// `"fill"` (default): isotropic triangles graded by the section's own spacing
    /// (`afsf2d::fill_loop`: the 2D mesher's fill of the section, no layers), so that every
    /// cap triangle makes a well-shaped prism base; what a Gmsh or Pointwise user gets on a
    /// flat tip face meshed from its boundary.
    #[default]
    Fill,
    /// `"layers"`: the 2D mesher's whole mesh of the section's inside (`inside = true`): its
    /// own layers from the rim at the surface's first height, then the fill; the layers' thin
    /// cells make thin prism and hexahedron bases.
    Layers,
}

/// [`wing_surface`] with the tip caps meshed as `cap` says, and the span stations at most
/// `span_step` apart where given (`[surface] span_step`; else the section's longest
/// segment): an extruded element facing another across a narrow gap wants span steps near
/// the gap's width, so that the fronts across it are not long thin triangles.
pub fn wing_surface_with(
    case: &Case,
    span: f64,
    triangles: bool,
    cap: CapMesh,
    span_step: Option<f64>,
) -> Result<(Surface, WingShape<Section>)> {
    let walls: Vec<usize> = (0..case.loops.len())
        .filter(|&i| case.loops[i].role == Role::Wall)
        .collect();
    let [w] = walls[..] else {
        bail!(
            "a wing is made from a case with one wall loop; '{}' has {}",
            case.name,
            walls.len()
        );
    };
    if !(span.is_finite() && span > 0.0) {
        bail!("the wing's span must be a positive number, got {span}");
    }
    let mut curves = pipeline::curves(case)?;
    let mut nodes = pipeline::boundary_nodes(case, &curves)?;
    let (curve, section) = (curves.swap_remove(w), nodes.swap_remove(w));
    let points: Vec<[f64; 2]> = section.points.iter().map(|p| [p.x, p.y]).collect();
    let (cap_nodes, cap_facets) = match cap {
        CapMesh::Fill if triangles => cap_fill(&points)?,
        CapMesh::Fill => {
            let (nodes, facets) = cap_fill(&points)?;
            let facets = pair_rim_triangles(&nodes, &facets, points.len());
            (nodes, facets)
        }
        CapMesh::Layers => cap_mesh(case, w, &section)?,
    };
    let longest = (0..points.len())
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % points.len()]);
            (a[0] - b[0]).hypot(a[1] - b[1])
        })
        .fold(0.0, f64::max);
    let stations = span_stations(
        span,
        case.layers.first_height,
        case.boundary.growth,
        span_step.unwrap_or(longest),
    );
    let cap = Cap {
        nodes: &cap_nodes,
        facets: &cap_facets,
    };
    build_wing(
        Section(curve),
        &section.t,
        &points,
        &stations,
        cap,
        triangles,
    )
    .map_err(|e| input_error!("wing of '{}': {e}", case.name))
}

/// The smallest angle (degrees) the isotropic cap's fill refines toward. A prism's corner
/// scaled Jacobian is at most the sine of its base's angle there: 20° allows 0.34, above the
/// issue's 0.2. 30° (the 2D fill's default) adds more small triangles at the trailing edge's
/// finest spacing, and with it the tets of table 5–7's case 2 fail in layer 18 at the tip's
/// trailing edge (docs/3d.md).
const CAP_MIN_ANGLE_DEG: f64 = 20.0;

/// The section's inside filled with isotropic triangles from its boundary nodes `points`
/// (counter-clockwise; they come first, at their coordinates).
fn cap_fill(points: &[[f64; 2]]) -> Result<(Vec<[f64; 2]>, Vec<Facet>)> {
    let (nodes, tris) = afsf2d::fill_loop(points, CAP_MIN_ANGLE_DEG)
        .map_err(|e| input_error!("the wing's tip cap: {e}"))?;
    let facets = tris.iter().map(|&[a, b, c]| Facet::tri(a, b, c)).collect();
    Ok((nodes, facets))
}

/// The smallest corner angle (degrees) of a quad [`pair_rim_triangles`] makes.
const RIM_QUAD_MIN_ANGLE_DEG: f64 = 50.0;

/// The cap's triangles `facets` (nodes `nodes`, the first `rim` of them the section's, in
/// order around it) with the two triangles of each chord of the section — an edge between
/// two rim nodes that are not neighbours on the rim, across the section — joined into a quad
/// where every corner of the quad is at least [`RIM_QUAD_MIN_ANGLE_DEG`] (the squarest
/// first, each triangle in one pair). Chords are edges of the cap where the section is as
/// thin as its rim's spacing (no inner node between the rims): on the `naca0012` wing a
/// ladder of 24 quads per cap from x ≈ 0.14 to the trailing edge's strip, each bridging the
/// upper and lower rims. There the rims' columns lean apart as the layers grow, the strip's front
/// widens many times over while its cells keep their length along the chord, and a
/// triangle's corner shrinks to a sliver (corner scaled Jacobian 0.18 in layers 3–5,
/// `docs/3d.md`), where a near-rectangle across the strip stays one. For the quad side only:
/// hexahedra grow over these quads.
fn pair_rim_triangles(nodes: &[[f64; 2]], facets: &[Facet], rim: usize) -> Vec<Facet> {
    let chord = |a: u32, b: u32| {
        let (a, b) = (a as usize, b as usize);
        a < rim && b < rim && (a + 1) % rim != b && (b + 1) % rim != a
    };
    // each chord with the triangle on each side
    let mut edges: Vec<([u32; 2], usize)> = Vec::new();
    for (t, f) in facets.iter().enumerate() {
        let k = f.nodes();
        for i in 0..k.len() {
            let (a, b) = (k[i], k[(i + 1) % k.len()]);
            if k.len() == 3 && chord(a, b) {
                edges.push(([a.min(b), a.max(b)], t));
            }
        }
    }
    edges.sort_unstable();
    let third = |t: usize, a: u32, b: u32| {
        *facets[t]
            .nodes()
            .iter()
            .find(|&&v| v != a && v != b)
            .expect("a triangle has a third node")
    };
    let mut pairs: Vec<(f64, usize, usize, Facet)> = Vec::new();
    for w in edges.windows(2).filter(|w| w[0].0 == w[1].0) {
        let ([a, b], t, u) = (w[0].0, w[0].1, w[1].1);
        // t runs u0 → v0 → third: the quad is v0, third(t), u0, third(u)
        let k = facets[t].nodes();
        let i = k.iter().position(|&v| v == a).expect("shared");
        let (u0, v0) = if k[(i + 1) % 3] == b { (a, b) } else { (b, a) };
        let q = [v0, third(t, a, b), u0, third(u, a, b)];
        let angle = convex_min_angle(q.map(|v| nodes[v as usize]));
        if let Some(angle) = angle.filter(|&a| a >= RIM_QUAD_MIN_ANGLE_DEG) {
            pairs.push((angle, t, u, Facet::quad(q[0], q[1], q[2], q[3])));
        }
    }
    pairs.sort_by(|x, y| y.0.total_cmp(&x.0).then((x.1, x.2).cmp(&(y.1, y.2))));
    let mut used = vec![false; facets.len()];
    let mut quads = Vec::new();
    for (_, t, u, q) in pairs {
        if !used[t] && !used[u] {
            used[t] = true;
            used[u] = true;
            quads.push(q);
        }
    }
    let mut out: Vec<Facet> = (0..facets.len())
        .filter(|&t| !used[t])
        .map(|t| facets[t])
        .collect();
    out.extend(quads);
    out
}

/// The smallest corner angle (degrees) of the quad `p` (counter-clockwise), if it is strictly
/// convex.
fn convex_min_angle(p: [[f64; 2]; 4]) -> Option<f64> {
    let mut smallest = 180.0f64;
    for i in 0..4 {
        let (o, a, b) = (p[i], p[(i + 1) % 4], p[(i + 3) % 4]);
        let (u, v) = ([a[0] - o[0], a[1] - o[1]], [b[0] - o[0], b[1] - o[1]]);
        let cross = u[0] * v[1] - u[1] * v[0];
        if cross <= 0.0 {
            return None;
        }
        let dot = u[0] * v[0] + u[1] * v[1];
        smallest = smallest.min(cross.atan2(dot).to_degrees());
    }
    Some(smallest)
}

/// The 2D mesh of the inside of wall loop `w` from its boundary nodes: the nodes (the
/// boundary nodes first) and the cells, counter-clockwise.
fn cap_mesh(
    case: &Case,
    w: usize,
    section: &boundary1d::BoundaryNodes,
) -> Result<(Vec<[f64; 2]>, Vec<Facet>)> {
    let mut inside = case.clone();
    inside.loops = vec![case.loops[w].clone()];
    inside.layers.inside = true;
    let cap = pipeline::linear_mesh(&inside, std::slice::from_ref(section))
        .map_err(|e| input_error!("the wing's tip cap: {e}"))?;
    let mesh = &cap.layered.mesh;
    let nodes = mesh.nodes.iter().map(|p| [p[0], p[1]]).collect();
    let facets = mesh
        .cells
        .shapes_and_corners()
        .map(|(_, k)| match *k {
            [a, b, c] => Ok(Facet::tri(a, b, c)),
            [a, b, c, d] => Ok(Facet::quad(a, b, c, d)),
            _ => Err(input_error!(
                "the tip cap has a cell of {} corners",
                k.len()
            )),
        })
        .collect::<Result<_>>()?;
    Ok((nodes, facets))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The smallest corner angle (degrees) of the facets of `patch`.
    fn smallest_angle(s: &Surface, patch: &str) -> f64 {
        let p = s.patches.iter().position(|p| p.name == patch).unwrap() as u32;
        let mut smallest = 180.0_f64;
        for (f, _) in s
            .facets
            .iter()
            .zip(&s.facet_patch)
            .filter(|(_, q)| **q == p)
        {
            let k = f.nodes();
            for i in 0..k.len() {
                let x = |j: usize| s.nodes[k[(i + j) % k.len()] as usize];
                let (o, a, b) = (x(0), x(1), x(k.len() - 1));
                let u: [f64; 3] = std::array::from_fn(|d| a[d] - o[d]);
                let v: [f64; 3] = std::array::from_fn(|d| b[d] - o[d]);
                let dot = |a: [f64; 3], b: [f64; 3]| (0..3).map(|d| a[d] * b[d]).sum::<f64>();
                let c = dot(u, v) / (dot(u, u) * dot(v, v)).sqrt();
                smallest = smallest.min(c.clamp(-1.0, 1.0).acos().to_degrees());
            }
        }
        smallest
    }

    #[test]
    fn the_projector_puts_p3_points_on_the_section_curve() {
        use vector_adding::SurfaceProjector;
        let case = crate::load::load_2d("naca0012").unwrap();
        let (surface, shape) = wing_surface(&case, 2.0, false).unwrap();
        let w = WingProjector { surface, shape };
        let n = w.shape.section.len();
        // a side facet: section edge 10 → 11 between the first two stations
        let side = |v: usize| w.surface.nodes[v];
        let f = (0..w.surface.facets.len())
            .find(|&f| {
                let k = w.surface.facets[f].nodes();
                k.len() == 4 && k.contains(&10) && k.contains(&11) && k.contains(&(n as u32 + 10))
            })
            .unwrap();
        let (a, b) = (side(10), side(11));
        // along the edge: the curve at a third of its arc length
        let third = w.edge_point(a, b, 1.0 / 3.0, f);
        assert_eq!(third, w.shape.side_point(10, 1.0 / 3.0, a[2]));
        // inside the facet: the curve's point at that height whose place along the chord is
        // the point's
        let z = 0.5 * (a[2] + side(n + 10)[2]);
        let inside = [0, 1, 2].map(|d| a[d] + 0.4 * (b[d] - a[d]));
        let on = w.project([inside[0], inside[1], z], f);
        assert_eq!(on[2], z);
        let chord = [b[0] - a[0], b[1] - a[1]];
        let along = |q: [f64; 3]| (q[0] - a[0]) * chord[0] + (q[1] - a[1]) * chord[1];
        let length = chord[0] * chord[0] + chord[1] * chord[1];
        assert!((along(on) / length - 0.4).abs() < 1e-12, "{on:?}");
        // the P2 midpoint as before: the curve at half the arc length
        let mid = [0, 1, 2].map(|d| 0.5 * (a[d] + b[d]));
        assert_eq!(w.project(mid, f), w.shape.edge_point(10, 11, 0.5).unwrap());
    }

    #[test]
    fn the_tip_caps_are_isotropic_enough_for_a_corner_sj_of_0_2() {
        // a prism's corner scaled Jacobian is at most the sine of its base's angle: 0.2
        // needs 11.5°; the caps with the 2D layers had slivers of 0.5°
        let mut case = crate::load::load_2d("naca0012").unwrap();
        for h in [1e-3, 1e-4] {
            case.layers.first_height = h;
            let (s, _) = wing_surface(&case, 2.0, false).unwrap();
            s.check().unwrap();
            for patch in ["tip-root", "tip-far"] {
                let a = smallest_angle(&s, patch);
                assert!(a >= 20.0, "h {h}: {patch}'s smallest angle {a:.2}°");
            }
            assert!((smallest_angle(&s, "wall") - 90.0).abs() < 1e-6);
            let (s, _) = wing_surface_with(&case, 2.0, false, CapMesh::Layers, None).unwrap();
            assert!(smallest_angle(&s, "tip-root") < 11.5);
        }
    }

    /// `span_step` caps the span stations' spacing (the default is the section's longest
    /// segment), still graded from the tips.
    #[test]
    fn span_step_caps_the_stations_spacing() {
        let mut case = crate::load::load_2d("naca0012").unwrap();
        case.layers.first_height = 1e-3;
        let step = |s: &WingShape<Section>| {
            (s.stations.windows(2))
                .map(|w| w[1] - w[0])
                .fold(0.0, f64::max)
        };
        let (_, default) = wing_surface(&case, 2.0, true).unwrap();
        let (surface, fine) =
            wing_surface_with(&case, 2.0, true, CapMesh::Fill, Some(0.01)).unwrap();
        surface.check().unwrap();
        assert!(step(&default) > 0.05, "{}", step(&default));
        assert!(step(&fine) <= 0.01 * (1.0 + 1e-12), "{}", step(&fine));
        assert!((fine.stations[1] - 1e-3).abs() < 1e-15);
        assert_eq!(*fine.stations.last().unwrap(), 2.0);
    }

    #[test]
    fn the_naca0012_wing_is_closed_exact_in_volume_and_on_the_section() {
        let mut case = crate::load::load_2d("naca0012").unwrap();
        case.layers.first_height = 1e-3;
        for triangles in [false, true] {
            let (s, shape) = wing_surface(&case, 2.0, triangles).unwrap();
            s.check().unwrap();
            let exact = mesh_model::polygon_area(shape.section.iter().copied()) * 2.0;
            let volume = s.enclosed_volume();
            assert!((volume - exact).abs() < 1e-9 * exact, "{volume} vs {exact}");
            let n = shape.section.len();
            for (v, p) in s.nodes.iter().enumerate().take(n * shape.stations.len()) {
                let (i, k) = shape.side_node(v as u32).unwrap();
                let c = shape.curve.0.point(shape.t[i]);
                assert!((p[0] - c.x).abs() < 1e-12 && (p[1] - c.y).abs() < 1e-12);
                assert_eq!(p[2], shape.stations[k]);
                // the mid-edge point of the chordwise edge lies on the curve
                let m = shape.side_point(i, 0.5, p[2]);
                let (_, _, d) = shape.curve.0.closest_point(nalgebra_point(m));
                assert!(d < 1e-9, "mid-edge point off the curve by {d}");
            }
        }
    }

    fn nalgebra_point(p: [f64; 3]) -> geom_curve::Point2<f64> {
        geom_curve::Point2::new(p[0], p[1])
    }

    #[test]
    fn the_triangles_of_a_chord_pair_into_squares_not_into_slanted_quads() {
        // a 2 × 1 strip, its six nodes all on the rim: two squares, each cut by a chord
        // (0–4, 1–3), and the chord 1–4 between them, whose quad has 45° corners
        let nodes = [
            [0.0, 0.0],
            [1.0, 0.0],
            [2.0, 0.0],
            [2.0, 1.0],
            [1.0, 1.0],
            [0.0, 1.0],
        ];
        let tris = [
            Facet::tri(0, 1, 4),
            Facet::tri(0, 4, 5),
            Facet::tri(1, 2, 3),
            Facet::tri(1, 3, 4),
        ];
        let out = pair_rim_triangles(&nodes, &tris, 6);
        assert_eq!(out.len(), 2, "{out:?}");
        for f in &out {
            let k = f.nodes();
            assert_eq!(k.len(), 4);
            let p = [0, 1, 2, 3].map(|i| nodes[k[i] as usize]);
            assert!((convex_min_angle(p).unwrap() - 90.0).abs() < 1e-9, "{f:?}");
        }
        // an inner node makes no chord: nothing paired
        let inner = [[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.4, 0.4]];
        let fan = [
            Facet::tri(0, 1, 3),
            Facet::tri(1, 2, 3),
            Facet::tri(2, 0, 3),
        ];
        assert_eq!(pair_rim_triangles(&inner, &fan, 3), fan.to_vec());
    }

    #[test]
    fn the_quad_sides_caps_pair_the_triangles_across_the_trailing_edges_strip() {
        let mut case = crate::load::load_2d("naca0012").unwrap();
        case.layers.first_height = 1e-3;
        let (s, _) = wing_surface(&case, 2.0, false).unwrap();
        s.check().unwrap();
        let cap = s.patches.iter().position(|p| p.name == "tip-root").unwrap() as u32;
        let quads: Vec<&Facet> = s
            .facets
            .iter()
            .zip(&s.facet_patch)
            .filter(|(f, p)| **p == cap && f.nodes().len() == 4)
            .map(|(f, _)| f)
            .collect();
        // the ladder across the section, down to the trailing edge's strip, every quad's
        // corners at 50° or more
        assert!(quads.len() >= 6, "{} quads", quads.len());
        let x = |v: u32| s.nodes[v as usize][0];
        assert!(quads.iter().any(|f| f.nodes().iter().all(|&v| x(v) > 0.99)));
        for f in &quads {
            let p = [0, 1, 2, 3].map(|i| {
                let q = s.nodes[f.nodes()[i] as usize];
                [q[0], -q[1]] // the root cap faces −z: its quads run clockwise in (x, y)
            });
            let angle = convex_min_angle(p).expect("convex");
            assert!(angle >= RIM_QUAD_MIN_ANGLE_DEG, "{f:?}: {angle}");
        }
        assert!(smallest_angle(&s, "tip-root") >= 20.0);
        // a triangulated wing keeps its triangles
        let (t, _) = wing_surface(&case, 2.0, true).unwrap();
        assert!(t.facets.iter().all(|f| f.nodes().len() == 3));
    }

    #[test]
    fn a_case_with_two_walls_is_refused() {
        let case = crate::load::load_2d("two-element").unwrap();
        let err = wing_surface(&case, 2.0, false).unwrap_err().to_string();
        assert!(err.contains("one wall loop"), "{err}");
        let case = crate::load::load_2d("naca0012").unwrap();
        let err = wing_surface(&case, -1.0, false).unwrap_err().to_string();
        assert!(err.contains("span"), "{err}");
    }
}
