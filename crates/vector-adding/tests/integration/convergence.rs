//! Geometric accuracy of the curved boundary: a circle of radius 1 (4096 points, so that its
//! C2 curve is round to far below the errors measured) meshed inside, and the same circle as
//! a wall inside a far-field circle of radius 3 (an annulus, the far field at twice the
//! spacing: at equal spacings the two polygons' O(h²) area defects, π h²/6 each whatever the
//! radius, would cancel), at boundary spacings halved three times, at P1 (the linear mesh), P2 and P3. The area integrated over the cells is
//! compared with the area the curves themselves enclose (Green's theorem on the quintic
//! segments), and the observed order fitted from successive errors.
//!
//! The high-order boundary nodes are equally spaced in arc length between the ends of each
//! facet. A P1 chord cuts off O(h³) per facet, O(h²) in all. A P2 arc deviates by O(h³), but
//! the leading error term is odd about the facet's midpoint and cancels in the area, so the
//! area error is O(h⁴); a P3 arc deviates by O(h⁴) and the area error is O(h⁴) too. Hence the
//! bounds: at least 1.8 for P1, at least 3.5 for P2 and P3.

use crate::common;

use common::{check_curved, curve_area};
use geom_curve::{ClosedCurve, CurveParams, Point2, circle_points};
use mesh_model::Role;
use vector_adding::CurvingParams;

/// Spacings of the boundary mesh, each half the one before.
const SPACINGS: [f64; 4] = [0.4, 0.2, 0.1, 0.05];

/// A circle through 4096 points.
fn circle(c: [f64; 2], r: f64) -> Vec<[f64; 2]> {
    let pts = circle_points(Point2::new(c[0], c[1]), r, 4096).unwrap();
    pts.iter().map(|p| [p.x, p.y]).collect()
}

/// A loop of the domain: its points, its role, its spacing as a multiple of the wall's.
type Loop = (Vec<[f64; 2]>, Role, f64);

/// The relative area errors at P1, P2 and P3 of the domain bounded by `loops` at boundary
/// spacing `h`, and the number of boundary segments.
fn area_errors(loops: &[Loop], inside: bool, h: f64) -> ([f64; 3], usize) {
    let named = loops
        .iter()
        .map(|(points, role, _)| (format!("{role:?}"), *role, points.clone()))
        .collect();
    let mut case = test_cases::case_of("convergence", named, inside);
    // a small refinement angle, so that the spacing is set by `max_spacing` alone
    case.boundary.refine_angle_deg = 100.0;
    case.boundary.max_spacing = caps_max(loops) * h;
    for (input, l) in case.loops.iter_mut().zip(loops) {
        input.max_spacing = Some(l.2 * h);
    }
    case.layers.max_layers = 20;
    let g = test_cases::grow(&test_cases::with_layers(&case, 0.01, 1.3));
    let (out, curves, nodes) = (&g.output, &g.curves, &g.nodes);
    // the exact area of the domain the curves bound: walls are holes unless meshed inside
    let exact: f64 = loops
        .iter()
        .zip(curves)
        .map(|((_, role, _), c)| match role {
            Role::Wall if !inside => -curve_area(c),
            _ => curve_area(c),
        })
        .sum();
    let mut errors = [0.0; 3];
    errors[0] = (jacobian_check::integrate_area(&out.layered.mesh).unwrap() - exact).abs() / exact;
    for order in [2, 3] {
        let params = CurvingParams {
            order,
            ..CurvingParams::default()
        };
        let curved = g.curve(&params).unwrap();
        let c = check_curved(&format!("h {h} P{order}"), &curved, curves, order);
        errors[order as usize - 1] = (c.area - exact).abs() / exact;
    }
    (errors, nodes.iter().map(|n| n.len()).sum())
}

/// The largest spacing factor of the loops.
fn caps_max(loops: &[Loop]) -> f64 {
    loops.iter().map(|l| l.2).fold(1.0, f64::max)
}

/// Meshes the domain at every spacing, prints the errors and the observed orders, and
/// asserts the orders from each spacing to the next.
fn converges(what: &str, loops: &[Loop], inside: bool) {
    let levels: Vec<([f64; 3], usize)> = SPACINGS
        .iter()
        .map(|&h| area_errors(loops, inside, h))
        .collect();
    let mut table = vec![format!(
        "{what}: relative area error (observed order from the row above)"
    )];
    table.push(format!(
        "{:>9} {:>22} {:>22} {:>22}",
        "segments", "P1", "P2", "P3"
    ));
    let mut worst = [f64::INFINITY; 3];
    for (k, (errors, n)) in levels.iter().enumerate() {
        let mut line = format!("{n:>9}");
        for p in 0..3 {
            if k == 0 {
                line += &format!(" {:>12.3e} {:>9}", errors[p], "");
            } else {
                let (prev, m) = &levels[k - 1];
                // h is proportional to 1 / segments on these loops of fixed length
                let rate = (prev[p] / errors[p]).ln() / (*n as f64 / *m as f64).ln();
                worst[p] = worst[p].min(rate);
                line += &format!(" {:>12.3e} ({rate:>6.2})", errors[p]);
            }
        }
        table.push(line);
    }
    eprintln!("{}", table.join("\n"));
    assert!(worst[0] >= 1.8, "{what}: P1 order {}", worst[0]);
    assert!(worst[1] >= 3.5, "{what}: P2 order {}", worst[1]);
    assert!(worst[2] >= 3.5, "{what}: P3 order {}", worst[2]);
}

#[test]
fn circle_meshed_inside() {
    converges(
        "unit circle, inside",
        &[(circle([0.0, 0.0], 1.0), Role::Wall, 1.0)],
        true,
    );
}

#[test]
fn annulus() {
    converges(
        "annulus 1 < r < 3",
        &[
            (circle([0.0, 0.0], 1.0), Role::Wall, 1.0),
            (circle([0.0, 0.0], 3.0), Role::Farfield, 2.0),
        ],
        false,
    );
}

#[test]
fn the_circles_are_round() {
    // the reference areas are the curves' own; they must be those of the circles too
    for r in [1.0, 3.0] {
        let pts: Vec<Point2<f64>> = circle([0.0, 0.0], r)
            .iter()
            .map(|p| Point2::new(p[0], p[1]))
            .collect();
        let a = curve_area(&ClosedCurve::new(&pts, &CurveParams::default()).unwrap());
        let exact = std::f64::consts::PI * r * r;
        testkit::assert_near!(a, exact, 1e-12 * exact, "r {r}");
    }
}
