//! Simple generated loops (circles) for far fields and tests.

use crate::{CurveError, Point2};

/// `n` points evenly spaced on the circle of the given centre and radius, counter-clockwise,
/// the first at angle 0 (on the +x side of the centre), the first point not repeated.
///
/// Use at least 10 points if the loop is to be fitted by [`crate::ClosedCurve`] with the
/// default corner angle (fewer make every point a corner, i.e. a polygon), and some 64 or more
/// for a far field whose fitted curve should be round to 1e-8 of its radius.
///
/// # Errors
/// [`CurveError::InvalidParameter`] when the radius is not finite and positive, the centre is
/// not finite, `n < 3` or `n` above [`crate::MAX_GENERATED_POINTS`].
pub fn circle_points(
    center: Point2<f64>,
    radius: f64,
    n: usize,
) -> Result<Vec<Point2<f64>>, CurveError> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(CurveError::InvalidParameter {
            name: "radius",
            value: radius,
            reason: "must be finite and positive",
        });
    }
    if !(center.x.is_finite() && center.y.is_finite()) {
        return Err(CurveError::InvalidParameter {
            name: "center",
            value: if center.x.is_finite() {
                center.y
            } else {
                center.x
            },
            reason: "must be finite",
        });
    }
    if n < 3 {
        return Err(CurveError::InvalidParameter {
            name: "n",
            value: n as f64,
            reason: "a circle needs at least 3 points",
        });
    }
    if n > crate::MAX_GENERATED_POINTS {
        return Err(CurveError::InvalidParameter {
            name: "circle points",
            value: n as f64,
            reason: "at most 1000000 points define a circle (the mesh spacing is set separately)",
        });
    }
    Ok((0..n)
        .map(|i| {
            let angle = std::f64::consts::TAU * i as f64 / n as f64;
            Point2::new(
                center.x + radius * angle.cos(),
                center.y + radius * angle.sin(),
            )
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_lie_on_the_circle_counter_clockwise() {
        let center = Point2::new(0.5, -2.0);
        let points = circle_points(center, 3.0, 17).unwrap();
        assert_eq!(points.len(), 17);
        for p in &points {
            assert!(((p - center).norm() - 3.0).abs() < 1e-14);
        }
        assert!(crate::loops::signed_area(&points) > 0.0);
    }

    #[test]
    fn bad_inputs_are_errors() {
        let o = Point2::origin();
        assert!(circle_points(o, 0.0, 10).is_err());
        assert!(circle_points(o, f64::NAN, 10).is_err());
        assert!(circle_points(o, 1.0, 2).is_err());
        // D5 (issue 15): 1e12 points aborted on allocation failure
        let huge = circle_points(o, 20.0, 1_000_000_000_000).unwrap_err();
        assert!(huge.to_string().contains("at most 1000000"), "{huge}");
        assert!(circle_points(Point2::new(f64::INFINITY, 0.0), 1.0, 10).is_err());
    }
}
