//! Test kit of the curving: the checks every curved mesh must pass (the grown cases and
//! their curving come from `test-cases`, through the tool's own stages) — certified valid, conforming, boundary nodes on their curves, the
//! area of the cells equal to the area the curved boundary encloses, the first layers above
//! walls curved.
#![allow(dead_code)]

use std::collections::HashMap;

use afsf2d::AfsfOutput;
use geom_curve::{ClosedCurve, Point2};
use jacobian_check::MeshValidity;
use mesh_model::{Mesh, NONE, Role, Shape};
use testkit::checks;
use vector_adding::Curved;

/// The area a closed curve encloses (positive counter-clockwise): Green's theorem on each
/// quintic segment, by Gauss quadrature exact for its degree-9 integrand.
pub fn curve_area(curve: &ClosedCurve) -> f64 {
    // 5-point Gauss–Legendre on [0, 1]: exact to degree 9
    const G5: [(f64, f64); 5] = [
        (0.046_910_077_030_668, 0.118_463_442_528_094_5),
        (0.230_765_344_947_158_5, 0.239_314_335_249_683_2),
        (0.5, 0.284_444_444_444_444_4),
        (0.769_234_655_052_841_5, 0.239_314_335_249_683_2),
        (0.953_089_922_969_332, 0.118_463_442_528_094_5),
    ];
    let mut total = 0.0;
    for i in 0..curve.segment_count() {
        for (s, w) in G5 {
            let t = i as f64 + s;
            let (x, d) = (curve.point(t), curve.d1(t));
            total += 0.5 * w * (x.x * d.y - x.y * d.x);
        }
    }
    total
}

/// The distance of `x` from `curve`, relative to the curve's length.
fn off_curve(curve: &ClosedCurve, x: [f64; 2]) -> f64 {
    let (_, _, d) = curve.closest_point(Point2::new(x[0], x[1]));
    d / curve.total_length()
}

/// Whether the inner nodes of edge a → b (listed from a) lie off its chord (beyond 1e-9 of
/// its length).
fn off_chord(mesh: &Mesh, a: u32, b: u32, inner: &[u32]) -> bool {
    let (xa, xb) = (mesh.xy(a), mesh.xy(b));
    let length = (xb[0] - xa[0]).hypot(xb[1] - xa[1]);
    let n = inner.len() + 1;
    inner.iter().enumerate().any(|(i, &v)| {
        let s = (i + 1) as f64 / n as f64;
        let x = mesh.xy(v);
        let l = [xa[0] + s * (xb[0] - xa[0]), xa[1] + s * (xb[1] - xa[1])];
        (x[0] - l[0]).hypot(x[1] - l[1]) > 1e-9 * length
    })
}

/// Every edge of a high-order mesh by its (lower, higher) corner nodes: whether it is curved.
pub fn edge_curvature(mesh: &Mesh) -> HashMap<(u32, u32), bool> {
    let mut out = HashMap::new();
    for cell in mesh.cells.iter() {
        let p = cell.ty.order as usize;
        let corners = cell.ty.shape.corners();
        for (j, e) in cell.ty.shape.edges().iter().enumerate() {
            let (a, b) = (cell.nodes[e[0]], cell.nodes[e[1]]);
            let inner = &cell.nodes[corners + j * (p - 1)..corners + (j + 1) * (p - 1)];
            let curved = off_chord(mesh, a, b, inner);
            *out.entry((a.min(b), a.max(b))).or_insert(false) |= curved;
        }
    }
    out
}

/// A place where a pipe above a curved wall edge has a straight bottom edge below
/// `min_curved_layers`.
#[derive(Debug, Clone, Copy)]
pub struct EarlyStop {
    /// The wall facet the pipe grows from.
    pub facet: usize,
    /// The layer (0 = on the wall) of the linear cell whose bottom edge is straight.
    pub layer: u32,
    /// That cell of the linear mesh.
    pub cell: usize,
}

/// What [`curved_layers_above_walls`] found.
#[derive(Debug, Clone, Default)]
pub struct LayerReport {
    /// Curved wall edges.
    pub curved_walls: usize,
    /// Of their pipes, those that reach `min_curved_layers` layers (no collapse, no end).
    pub full_pipes: usize,
    /// Cells of those pipes below `min_curved_layers` with a straight bottom edge.
    pub early: Vec<EarlyStop>,
    /// Pipes that end below `min_curved_layers`, by cause: no layered cell of the next layer
    /// on the top edge, a triangle without a top edge.
    pub ended: [usize; 2],
}

/// Walks up the pipe of every curved wall edge of the linear mesh `out`, for
/// `min_curved_layers` layers, and looks up in the curved mesh whether each bottom edge met
/// is curved. A pipe ends where the next cell is missing (the top edge is not the bottom of a
/// layered cell of the next layer) or the cell has no top (a triangle whose two children
/// merged).
pub fn curved_layers_above_walls(
    out: &AfsfOutput,
    curved: &Mesh,
    min_curved_layers: u32,
) -> LayerReport {
    let lin = &out.layered.mesh;
    let node_layer = &out.layered.layering.node_layer;
    let edges = edge_curvature(curved);
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    // the layered cells by their bottom edge
    let mut by_bottom: HashMap<(u32, u32), usize> = HashMap::new();
    let mut tops: Vec<Option<(u32, u32)>> = vec![None; lin.cells.len()];
    for (i, cell) in lin
        .cells
        .iter()
        .enumerate()
        .take(out.layered.layering.layered_cells)
    {
        let layer = lin.cell_layer[i];
        if layer == NONE {
            continue;
        }
        let k = cell.corners();
        let mut bottom = None;
        let mut top = None;
        for (j, e) in cell.ty.shape.edges().iter().enumerate() {
            let (a, b) = (k[e[0]], k[e[1]]);
            let (la, lb) = (node_layer[a as usize], node_layer[b as usize]);
            if la == layer && lb == layer {
                bottom = Some((j, key(a, b)));
            } else if la == layer + 1 && lb == layer + 1 {
                top = Some((j, key(a, b)));
            }
        }
        if let Some((jb, b)) = bottom {
            by_bottom.insert(b, i);
            // a quadrilateral's top faces its bottom
            tops[i] = top
                .filter(|&(jt, _)| cell.ty.shape != Shape::Quad || (jb + 2) % 4 == jt)
                .map(|t| t.1);
        }
    }
    let mut report = LayerReport::default();
    for (f, facet) in lin.boundary.iter().enumerate() {
        let patch = lin.boundary_patch[f] as usize;
        if lin.patches[patch].role != Role::Wall {
            continue;
        }
        let mut edge = key(facet.nodes[0], facet.nodes[1]);
        if !edges.get(&edge).copied().unwrap_or(false) {
            continue;
        }
        report.curved_walls += 1;
        let mut full = true;
        for layer in 0..min_curved_layers {
            let cell = by_bottom.get(&edge).copied();
            let Some(cell) = cell.filter(|&c| lin.cell_layer[c] == layer) else {
                report.ended[0] += 1;
                full = false;
                break;
            };
            if !edges.get(&edge).copied().unwrap_or(false) {
                report.early.push(EarlyStop {
                    facet: f,
                    layer,
                    cell,
                });
            }
            match tops[cell] {
                Some(t) => edge = t,
                None => {
                    full = layer + 1 >= min_curved_layers;
                    report.ended[1] += !full as usize;
                    break;
                }
            }
        }
        report.full_pipes += full as usize;
    }
    report
}

/// The figures of one checked run, for the tables.
#[derive(Debug, Clone)]
pub struct Checked {
    /// The certified verdicts.
    pub validity: MeshValidity,
    /// Curved-edge fraction of the mesh.
    pub fraction: f64,
    /// Area integrated over the cells.
    pub area: f64,
    /// Relative difference to the area the curved boundary encloses.
    pub area_error: f64,
    /// Worst boundary node distance from its curve, relative to the curve's length.
    pub off_curve: f64,
}

/// Asserts what every curved mesh must satisfy: of order `order`, every cell certified
/// valid, no structural problem, boundary nodes on the curves (1e-9 of their length), the
/// integrated area equal to the enclosed area (1e-9 relative), the figures of the stats
/// matching the mesh.
pub fn check_curved(what: &str, curved: &Curved, curves: &[ClosedCurve], order: u8) -> Checked {
    let mesh = &curved.mesh;
    assert_eq!(mesh.order, order, "{what}: order");
    assert!(
        mesh.cells.types().iter().all(|t| t.order == order),
        "{what}: cell types {:?}",
        mesh.cells.types()
    );
    checks::assert_valid(what, mesh);
    let validity = checks::assert_certified(&format!("{what} ({:?})", curved.stats), mesh);
    assert!(validity.min_scaled_jacobian > 0.0, "{what}");
    // boundary nodes on their patch's curve, relative to the curve's length
    let off_curve =
        checks::assert_boundary_on(what, mesh, |patch, x| off_curve(&curves[patch], x), 1e-9);
    let area = jacobian_check::integrate_area(mesh).unwrap_or_else(|e| panic!("{what}: {e}"));
    let enclosed = jacobian_check::enclosed_area(mesh).unwrap_or_else(|e| panic!("{what}: {e}"));
    let area_error = checks::assert_area(what, area, enclosed, 1e-9);
    // the area `check_mesh` takes from the certificates' coefficients: the same integral
    for (of, other) in [("the cells", area), ("the boundary", enclosed)] {
        assert!(
            (validity.measure - other).abs() <= 1e-12 * other.abs(),
            "{what}: certified area {} vs {of}' {other}",
            validity.measure
        );
    }
    let fraction = jacobian_check::curved_edge_fraction(mesh);
    let s = &curved.stats;
    assert_eq!(
        s.curved_edges as f64 / s.edges as f64,
        s.curved_edge_fraction,
        "{what}"
    );
    assert!(
        (fraction - s.curved_edge_fraction).abs() <= 1.0 / s.edges as f64,
        "{what}: the mesh has a curved-edge fraction {fraction}, the stats say {}",
        s.curved_edge_fraction
    );
    assert!(
        s.curved_boundary_edges > 0,
        "{what}: no curved boundary edge"
    );
    Checked {
        validity,
        fraction,
        area,
        area_error,
        off_curve,
    }
}
