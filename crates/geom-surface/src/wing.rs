//! A finite wing made from a 2D section (dissertation §5.1): the section's closed boundary
//! nodes extruded along z over the span at given stations, closed at both tips by a planar
//! cap mesh of the section's inside. Pure geometry: the section's nodes, their curve
//! parameters and the cap come from the caller (in the pipeline: `boundary1d` on the C2
//! curve and the 2D mesher run inside the section).
//!
//! The surface ([`build_wing`]) has quads on the side (section edge × span interval), and the
//! cap's cells at both tips: at the far tip (z = span) as given (counter-clockwise in the
//! xy-plane, so facing +z), at the root (z = 0) reversed, so every facet faces out of the
//! wing. Patches, all walls: `wall` (the side), `tip-root` and `tip-far` (the caps). Nodes:
//! side node `k·n + i` is section node `i` at station `k`; then the root cap's inner nodes,
//! then the far cap's.
//!
//! The true surface is the section's curve times a straight line ([`WingShape`]): a point
//! between two side nodes lies on the curve between their parameters at the z between their
//! stations, so the mid-edge nodes of a P2 surface lie on the true wing (spanwise edges are
//! straight, chordwise edges follow the curve, the caps are flat).
//!
//! [`span_stations`] spaces the stations: graded from each tip by the first height and the
//! growth ratio, capped at a largest step.

use mesh_model::{Patch, Role};

use crate::{Facet, NO_NODE, Surface};

/// The closed section curve a wing is made from, as the curving needs it.
pub trait SectionCurve {
    /// The point at fraction `s` ∈ [0, 1] of the arc length going forward along the curve
    /// from parameter `t0` to parameter `t1` (through the curve's seam when `t1 ≤ t0`).
    fn between(&self, t0: f64, t1: f64, s: f64) -> [f64; 2];
}

/// The planar mesh of the section's inside that closes the tips: its nodes (the section's
/// boundary nodes first, the same points in the same order, then the inner nodes) and its
/// cells (triangles and quads), counter-clockwise in the xy-plane.
#[derive(Debug, Clone, Copy)]
pub struct Cap<'a> {
    /// The cap's nodes: the section's boundary nodes, then the inner nodes.
    pub nodes: &'a [[f64; 2]],
    /// The cap's cells, counter-clockwise seen from +z.
    pub facets: &'a [Facet],
}

/// Why a wing could not be built.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum WingError {
    /// Fewer than three section nodes, or not one curve parameter per node.
    #[error(
        "the section has {nodes} nodes and {params} curve parameters: need at least 3, one each"
    )]
    Section {
        /// Section nodes.
        nodes: usize,
        /// Curve parameters.
        params: usize,
    },
    /// The section's nodes run clockwise (or enclose no area).
    #[error("the section's nodes must run counter-clockwise (signed area {area:e})")]
    Clockwise {
        /// The polygon's signed area.
        area: f64,
    },
    /// Fewer than two stations, or stations not increasing.
    #[error("the span stations must be at least two increasing values (station {station})")]
    Stations {
        /// The first bad station.
        station: usize,
    },
    /// The cap does not start with the section's nodes.
    #[error(
        "cap node {node} is not section node {node}: the cap must start with the section's nodes"
    )]
    CapNodes {
        /// The first differing node.
        node: usize,
    },
    /// A cap cell names a missing node.
    #[error("cap cell {cell} names a node the cap does not have")]
    CapCell {
        /// The cell.
        cell: usize,
    },
}

/// The true surface of a wing built by [`build_wing`]: the section curve times a straight
/// line, for placing high-order surface nodes.
#[derive(Debug, Clone)]
pub struct WingShape<C> {
    /// The section's curve.
    pub curve: C,
    /// The curve parameter of each section node.
    pub t: Vec<f64>,
    /// The section's nodes.
    pub section: Vec<[f64; 2]>,
    /// The span stations (z), increasing.
    pub stations: Vec<f64>,
}

impl<C: SectionCurve> WingShape<C> {
    /// Section node and station of a side node of the surface, `None` for a cap's inner node.
    pub fn side_node(&self, v: u32) -> Option<(usize, usize)> {
        let n = self.section.len();
        let v = v as usize;
        (v < n * self.stations.len()).then(|| (v % n, v / n))
    }

    /// The point on the side over section edge `i` (from node `i` to node `i + 1`) at
    /// fraction `u` of its arc length, at height `z`.
    pub fn side_point(&self, i: usize, u: f64, z: f64) -> [f64; 3] {
        let n = self.section.len();
        let p = self.curve.between(self.t[i], self.t[(i + 1) % n], u);
        [p[0], p[1], z]
    }

    /// The point at fraction `s` of the surface edge from node `a` to node `b`, when the
    /// edge lies on the curved side (both nodes on the side, over the same or neighbouring
    /// section nodes); `None` when the edge is straight on the true surface (in a flat cap).
    pub fn edge_point(&self, a: u32, b: u32, s: f64) -> Option<[f64; 3]> {
        let ((i, k), (j, l)) = (self.side_node(a)?, self.side_node(b)?);
        let n = self.section.len();
        let z = self.stations[k] + s * (self.stations[l] - self.stations[k]);
        if i == j {
            let p = self.section[i];
            Some([p[0], p[1], z])
        } else if j == (i + 1) % n {
            Some(self.side_point(i, s, z))
        } else if i == (j + 1) % n {
            Some(self.side_point(j, 1.0 - s, z))
        } else {
            None
        }
    }
}

/// Builds the closed wing surface: the section extruded over the `stations` (z values), the
/// `cap` at both tips (see the module's doc for the numbering and the patches). With
/// `triangles`, every quad is split into two triangles (side quads along their diagonal from
/// the lower node of the section edge, cap quads along the shorter diagonal).
pub fn build_wing<C: SectionCurve>(
    curve: C,
    t: &[f64],
    section: &[[f64; 2]],
    stations: &[f64],
    cap: Cap<'_>,
    triangles: bool,
) -> Result<(Surface, WingShape<C>), WingError> {
    check_input(t, section, stations, cap)?;
    let n = section.len();
    let ns = stations.len();
    let inner = cap.nodes.len() - n;
    let mut nodes = Vec::with_capacity(n * ns + 2 * inner);
    for &z in stations {
        nodes.extend(section.iter().map(|p| [p[0], p[1], z]));
    }
    let (z0, z1) = (stations[0], stations[ns - 1]);
    for z in [z0, z1] {
        nodes.extend(cap.nodes[n..].iter().map(|p| [p[0], p[1], z]));
    }
    let mut facets = Vec::new();
    let mut facet_patch = Vec::new();
    let mut push = |f: Facet, patch: u32, facets: &mut Vec<Facet>| {
        if triangles && f.0[3] != NO_NODE {
            split_quad(&nodes, f, facets);
        } else {
            facets.push(f);
        }
        facet_patch.resize(facets.len(), patch);
    };
    for k in 0..ns - 1 {
        for i in 0..n {
            let j = (i + 1) % n;
            let v = |i: usize, k: usize| (k * n + i) as u32;
            push(
                Facet::quad(v(i, k), v(j, k), v(j, k + 1), v(i, k + 1)),
                0,
                &mut facets,
            );
        }
    }
    // cap node j: a section node at the tip's station, else the tip's own inner node
    let tip = |j: u32, root: bool| {
        let j = j as usize;
        let id = match (j < n, root) {
            (true, true) => j,
            (true, false) => (ns - 1) * n + j,
            (false, true) => ns * n + j - n,
            (false, false) => ns * n + inner + j - n,
        };
        id as u32
    };
    for (patch, root) in [(1, true), (2, false)] {
        for f in cap.facets {
            // the root's cap faces -z: its cells reversed
            let mut k: Vec<u32> = f.nodes().iter().map(|&j| tip(j, root)).collect();
            if root {
                k.reverse();
            }
            push(facet_of(&k), patch, &mut facets);
        }
    }
    let wall = |name: &str| Patch {
        name: name.to_string(),
        role: Role::Wall,
    };
    let surface = Surface {
        nodes,
        facets,
        facet_patch,
        patches: vec![wall("wall"), wall("tip-root"), wall("tip-far")],
    };
    let shape = WingShape {
        curve,
        t: t.to_vec(),
        section: section.to_vec(),
        stations: stations.to_vec(),
    };
    Ok((surface, shape))
}

fn check_input(
    t: &[f64],
    section: &[[f64; 2]],
    stations: &[f64],
    cap: Cap<'_>,
) -> Result<(), WingError> {
    let n = section.len();
    if n < 3 || t.len() != n {
        return Err(WingError::Section {
            nodes: n,
            params: t.len(),
        });
    }
    let area = geom_predicates::polygon_area(section.iter().copied());
    if area.is_nan() || area <= 0.0 {
        return Err(WingError::Clockwise { area });
    }
    if stations.len() < 2 {
        return Err(WingError::Stations {
            station: stations.len(),
        });
    }
    if let Some(k) = (0..stations.len())
        .find(|&k| !stations[k].is_finite() || (k > 0 && stations[k] <= stations[k - 1]))
    {
        return Err(WingError::Stations { station: k });
    }
    if let Some(node) = (0..n).find(|&i| cap.nodes.get(i) != Some(&section[i])) {
        return Err(WingError::CapNodes { node });
    }
    if let Some(cell) = cap
        .facets
        .iter()
        .position(|f| f.nodes().iter().any(|&j| j as usize >= cap.nodes.len()))
    {
        return Err(WingError::CapCell { cell });
    }
    Ok(())
}

fn facet_of(k: &[u32]) -> Facet {
    match *k {
        [a, b, c] => Facet::tri(a, b, c),
        [a, b, c, d] => Facet::quad(a, b, c, d),
        _ => unreachable!("a cap cell is a triangle or a quad"),
    }
}

/// A quad as two triangles along its shorter diagonal (the first on a tie).
fn split_quad(nodes: &[[f64; 3]], f: Facet, out: &mut Vec<Facet>) {
    let [a, b, c, d] = f.0;
    let len = |p: u32, q: u32| {
        let v = crate::sub(nodes[p as usize], nodes[q as usize]);
        crate::dot(v, v)
    };
    if len(a, c) <= len(b, d) {
        out.extend([Facet::tri(a, b, c), Facet::tri(a, c, d)]);
    } else {
        out.extend([Facet::tri(a, b, d), Facet::tri(b, c, d)]);
    }
}

/// Stations (z values) from 0 to `span`, graded from each tip: steps `first`,
/// `first·growth`, … up to at most `max_step`, then equal steps over the middle (between the
/// last graded step and `growth` times it, and at most `max_step`). Symmetric about the
/// middle; the first step is `first` whenever the span has room for it and a middle step
/// within the growth ratio of it; graded steps are dropped from the middle outwards until the
/// middle's steps are within the ratio (with none left, the span is cut into equal steps of at
/// most `max_step`). Every ratio of neighbouring steps is at most `growth`. Non-positive or
/// non-finite inputs give the two tips alone.
pub fn span_stations(span: f64, first: f64, growth: f64, max_step: f64) -> Vec<f64> {
    let ok = |x: f64| x.is_finite() && x > 0.0;
    if !(ok(span) && ok(first) && ok(max_step) && growth.is_finite() && growth >= 1.0) {
        return vec![0.0, span.max(0.0)];
    }
    let first = first.min(max_step);
    // the graded steps that fit under max_step and in the span
    let mut graded = vec![];
    let (mut s, mut sum) = (first, 0.0);
    while s <= max_step && 2.0 * (sum + s) <= span && graded.len() < 10_000 {
        graded.push(s);
        sum += s;
        if growth == 1.0 {
            break;
        }
        s *= growth;
    }
    loop {
        let m = graded.len();
        let middle = span - 2.0 * graded.iter().sum::<f64>();
        let last = graded.last().copied();
        let cap = last.map_or(max_step, |l| max_step.min(growth * l));
        let j = (middle / cap).ceil().max(1.0);
        let step = middle / j;
        let fits = last.is_none_or(|l| step * growth >= l && step <= growth * l);
        if fits && (m == 0 || middle > 0.0) {
            return stations_of(span, &graded, j as usize, step);
        }
        graded.pop();
    }
}

/// The stations of `graded` steps from each tip and `j` equal steps of `step` between them,
/// the right half mirrored from the left.
fn stations_of(span: f64, graded: &[f64], j: usize, step: f64) -> Vec<f64> {
    let total = 2 * graded.len() + j;
    let mut z = Vec::with_capacity(total + 1);
    z.push(0.0);
    for &s in graded {
        z.push(z.last().copied().unwrap_or(0.0) + s);
    }
    let base = z[graded.len()];
    for q in 1..=j {
        z.push(base + q as f64 * step);
    }
    z.resize(total + 1, 0.0);
    for k in 0..=total / 2 {
        z[total - k] = span - z[k];
    }
    let mid = total / 2;
    if total - mid == mid {
        z[mid] = span / 2.0;
    }
    z
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A circle of radius 1 as the section curve (parameter = angle / (2π / n)).
    #[derive(Debug)]
    struct Circle(usize);
    impl SectionCurve for Circle {
        fn between(&self, t0: f64, t1: f64, s: f64) -> [f64; 2] {
            let n = self.0 as f64;
            let t1 = if t1 <= t0 { t1 + n } else { t1 };
            let a = (t0 + s * (t1 - t0)) * std::f64::consts::TAU / n;
            [a.cos(), a.sin()]
        }
    }

    fn circle_wing(n: usize, triangles: bool) -> (Surface, WingShape<Circle>) {
        let t: Vec<f64> = (0..n).map(|i| i as f64).collect();
        let section: Vec<[f64; 2]> = t.iter().map(|&t| Circle(n).between(t, t, 0.0)).collect();
        // cap: a fan from the centre
        let mut cap_nodes = section.clone();
        cap_nodes.push([0.0, 0.0]);
        let facets: Vec<Facet> = (0..n)
            .map(|i| Facet::tri(i as u32, ((i + 1) % n) as u32, n as u32))
            .collect();
        let cap = Cap {
            nodes: &cap_nodes,
            facets: &facets,
        };
        let stations = span_stations(2.0, 0.05, 1.3, 0.2);
        build_wing(Circle(n), &t, &section, &stations, cap, triangles).unwrap()
    }

    #[test]
    fn a_circular_wing_is_closed_and_has_the_prism_volume() {
        for triangles in [false, true] {
            let (s, shape) = circle_wing(24, triangles);
            s.check().unwrap();
            let exact = geom_predicates::polygon_area(shape.section.iter().copied()) * 2.0;
            assert!((s.enclosed_volume() - exact).abs() < 1e-12 * exact);
            let tips = s.facet_patch.iter().filter(|&&p| p > 0).count();
            assert_eq!(tips, 48);
        }
    }

    #[test]
    fn edge_points_lie_on_the_true_surface() {
        let (s, shape) = circle_wing(12, false);
        for f in &s.facets {
            let k = f.nodes();
            for i in 0..k.len() {
                let (a, b) = (k[i], k[(i + 1) % k.len()]);
                match shape.edge_point(a, b, 0.5) {
                    Some(p) => {
                        let r = (p[0] * p[0] + p[1] * p[1]).sqrt();
                        assert!((r - 1.0).abs() < 1e-12);
                        let (za, zb) = (s.nodes[a as usize][2], s.nodes[b as usize][2]);
                        assert!((p[2] - (za + zb) / 2.0).abs() < 1e-15);
                    }
                    None => assert_eq!(s.nodes[a as usize][2], s.nodes[b as usize][2]),
                }
            }
        }
    }

    #[test]
    fn bad_input_is_refused() {
        let (_, shape) = circle_wing(6, false);
        let cap_nodes = shape.section.clone();
        let facets = [Facet::tri(0, 1, 9)];
        let cap = Cap {
            nodes: &cap_nodes,
            facets: &facets,
        };
        let err = build_wing(Circle(6), &shape.t, &shape.section, &[0.0, 1.0], cap, false);
        assert_eq!(err.unwrap_err(), WingError::CapCell { cell: 0 });
        let mut reversed = shape.section.clone();
        reversed.reverse();
        let err = build_wing(Circle(6), &shape.t, &reversed, &[0.0, 1.0], cap, false);
        assert!(matches!(err.unwrap_err(), WingError::Clockwise { .. }));
        let err = build_wing(Circle(6), &shape.t, &shape.section, &[0.0, 0.0], cap, false);
        assert_eq!(err.unwrap_err(), WingError::Stations { station: 1 });
        let moved = [[0.5, 0.0]; 6];
        let cap = Cap {
            nodes: &moved,
            facets: &facets,
        };
        let err = build_wing(Circle(6), &shape.t, &shape.section, &[0.0, 1.0], cap, false);
        assert_eq!(err.unwrap_err(), WingError::CapNodes { node: 0 });
    }

    #[test]
    fn stations_are_graded_from_both_tips() {
        let z = span_stations(2.0, 1e-3, 1.3, 0.05);
        assert_eq!(z[0], 0.0);
        assert_eq!(*z.last().unwrap(), 2.0);
        assert!((z[1] - 1e-3).abs() < 1e-18);
        assert!((z[2] - z[1] - 1.3e-3).abs() < 1e-15);
        assert_eq!(span_stations(-1.0, 1e-3, 1.3, 0.1), vec![0.0, 0.0]);
        assert_eq!(span_stations(1.0, 1.0, 1.3, 2.0), vec![0.0, 1.0]);
    }
}
