//! The approximate curvature of the dissertation (§3.1.1, Eq. 2): κ = 1/R with R the radius
//! of the circle through a point and its two neighbours.
//!
//! Owns this discrete estimate only; the curvature of the fitted curve is
//! [`crate::ClosedCurve::curvature`].

use crate::Point2;

/// Signed curvature 1/R of the circle through `a`, `b`, `c` (in that order): positive when
/// `a → b → c` turns left (counter-clockwise), negative for a right turn, 0 for collinear
/// points and when two of the points coincide.
///
/// Computed as κ = 2·((b − a) × (c − a)) / (|ab|·|bc|·|ca|), the cross product taken from the
/// exact orientation predicate so that collinear points give exactly 0.
pub fn circumcircle_curvature(a: Point2<f64>, b: Point2<f64>, c: Point2<f64>) -> f64 {
    let twice_area = geom_predicates::orient2d(a.into(), b.into(), c.into());
    if twice_area == 0.0 {
        return 0.0;
    }
    let product = (b - a).norm() * (c - b).norm() * (c - a).norm();
    if product == 0.0 {
        return 0.0;
    }
    2.0 * twice_area / product
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn collinear_and_coincident_points_give_zero() {
        let a = Point2::new(0.0, 0.0);
        let b = Point2::new(0.25, 0.75);
        let c = Point2::new(0.5, 1.5);
        assert_eq!(circumcircle_curvature(a, b, c), 0.0);
        assert_eq!(circumcircle_curvature(a, a, c), 0.0);
    }

    proptest! {
        #[test]
        fn three_points_on_a_circle_give_one_over_r(
            cx in -10.0..10.0f64, cy in -10.0..10.0f64, radius in 1e-3..1e3f64,
            t0 in 0.0..std::f64::consts::TAU, d1 in 0.01..2.0f64, d2 in 0.01..2.0f64,
        ) {
            let on_circle = |t: f64| Point2::new(cx + radius * t.cos(), cy + radius * t.sin());
            let (a, b, c) = (on_circle(t0), on_circle(t0 + d1), on_circle(t0 + d1 + d2));
            let left = circumcircle_curvature(a, b, c);
            prop_assert!((left * radius - 1.0).abs() < 1e-8, "left turn {left}");
            let right = circumcircle_curvature(c, b, a);
            prop_assert!((right * radius + 1.0).abs() < 1e-8, "right turn {right}");
        }
    }
}
