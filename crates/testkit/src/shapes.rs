//! Loop generators (circles, wavy stars, squares) and proptest strategies over them.

use geom_curve::Point2;
use proptest::prelude::*;

/// `n` points of the circle of centre `c` and radius `r`, counter-clockwise from angle 0
/// (`geom_curve::circle_points`, as the case files make circles).
///
/// # Panics
/// When the radius is not positive or `n` < 3.
pub fn circle(c: [f64; 2], r: f64, n: usize) -> Vec<[f64; 2]> {
    geom_curve::circle_points(Point2::new(c[0], c[1]), r, n)
        .expect("a circle")
        .iter()
        .map(|p| [p.x, p.y])
        .collect()
}

/// A smooth star-shaped loop r(θ) = radius·(1 + amplitude·sin(lobes·θ + phase)) about
/// `center`, `n` points at uniformly spaced angles, counter-clockwise.
pub fn wavy_loop(
    n: usize,
    center: Point2<f64>,
    radius: f64,
    amplitude: f64,
    lobes: u32,
    phase: f64,
) -> Vec<Point2<f64>> {
    (0..n)
        .map(|i| {
            let theta = std::f64::consts::TAU * i as f64 / n as f64;
            let r = radius * (1.0 + amplitude * (f64::from(lobes) * theta + phase).sin());
            Point2::new(center.x + r * theta.cos(), center.y + r * theta.sin())
        })
        .collect()
}

/// A star polygon of `tips` sharp tips, alternating radii `outer` and `inner` about `center`,
/// counter-clockwise.
pub fn star(center: [f64; 2], tips: usize, outer: f64, inner: f64) -> Vec<[f64; 2]> {
    (0..2 * tips)
        .map(|i| {
            let theta = std::f64::consts::PI * i as f64 / tips as f64;
            let r = if i % 2 == 0 { outer } else { inner };
            [center[0] + r * theta.cos(), center[1] + r * theta.sin()]
        })
        .collect()
}

/// An axis-aligned square from its lower-left corner and side, counter-clockwise.
pub fn square(lo: [f64; 2], side: f64) -> Vec<[f64; 2]> {
    vec![
        lo,
        [lo[0] + side, lo[1]],
        [lo[0] + side, lo[1] + side],
        [lo[0], lo[1] + side],
    ]
}

/// The shape of a [`wavy_loop`], as [`wavy`] draws it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Wavy {
    /// Points.
    pub n: usize,
    /// Relative amplitude of the waves, below 0.3 (the loop stays simple and star-shaped).
    pub amplitude: f64,
    /// Waves around, 1 to 3.
    pub lobes: u32,
    /// Phase of the waves, radians.
    pub phase: f64,
}

impl Wavy {
    /// The loop about `center` at `radius`.
    pub fn points(&self, center: Point2<f64>, radius: f64) -> Vec<Point2<f64>> {
        wavy_loop(
            self.n,
            center,
            radius,
            self.amplitude,
            self.lobes,
            self.phase,
        )
    }
}

/// Random smooth wavy loops of `n` points, at least 12 per wave (so the polygon resolves its
/// waves): amplitude in [0, 0.3), 1 to 3 lobes, any phase.
pub fn wavy(n: std::ops::Range<usize>) -> impl Strategy<Value = Wavy> {
    (1u32..4).prop_flat_map(move |lobes| {
        let lo = n.start.max(12 * lobes as usize);
        (
            lo..n.end.max(lo + 1),
            0.0..0.3f64,
            0.0..std::f64::consts::TAU,
        )
            .prop_map(move |(n, amplitude, phase)| Wavy {
                n,
                amplitude,
                lobes,
                phase,
            })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generators_run_counter_clockwise() {
        let area = |p: &[[f64; 2]]| mesh_model::polygon_area(p.iter().copied());
        assert!(area(&circle([0.0, 0.0], 1.0, 64)) > 0.0);
        assert!(area(&star([1.0, 2.0], 5, 1.0, 0.4)) > 0.0);
        assert_eq!(area(&square([0.0, 0.0], 2.0)), 4.0);
        let wavy: Vec<[f64; 2]> = wavy_loop(100, Point2::origin(), 1.0, 0.2, 3, 0.5)
            .iter()
            .map(|p| [p.x, p.y])
            .collect();
        assert!(area(&wavy) > 0.0);
    }
}
