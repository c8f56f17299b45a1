//! What the integration tests share beyond `testkit` (fixtures, generators): the turning
//! angle of a loop.

#![allow(dead_code)]

use geom_curve::Point2;

/// Change of direction at each point of a loop, degrees in [0, 180].
pub fn turning_deg(points: &[Point2<f64>]) -> Vec<f64> {
    let n = points.len();
    (0..n)
        .map(|i| {
            let before = points[i] - points[(i + n - 1) % n];
            let after = points[(i + 1) % n] - points[i];
            before
                .perp(&after)
                .abs()
                .atan2(before.dot(&after))
                .to_degrees()
        })
        .collect()
}
