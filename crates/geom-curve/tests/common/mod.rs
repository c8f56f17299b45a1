//! Test kit shared by the integration tests: fixture loading and a few loop generators.

#![allow(dead_code)]

use geom_curve::{Point2, selig};

/// The repository's `fixtures/geometry` folder.
pub fn geometry_dir() -> std::path::PathBuf {
    std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/geometry")
}

/// Reads and parses a Selig file from `fixtures/geometry`.
pub fn load(name: &str) -> Vec<Point2<f64>> {
    let path = geometry_dir().join(name);
    let text = std::fs::read_to_string(&path)
        .unwrap_or_else(|e| panic!("cannot read fixture {}: {e}", path.display()));
    selig::parse(&text).unwrap_or_else(|e| panic!("{name}: {e}"))
}

/// Every airfoil fixture, by file name.
pub const AIRFOILS: [&str; 6] = [
    "naca0012.dat",
    "naca0012-sharp-te-generated.dat",
    "rae2822.dat",
    "30p30n/slat.dat",
    "30p30n/main.dat",
    "30p30n/flap.dat",
];

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

/// A smooth star-shaped loop r(θ) = 1 + amplitude·sin(lobes·θ + phase), `n` points at
/// uniformly spaced angles, counter-clockwise.
pub fn wavy_loop(n: usize, amplitude: f64, lobes: u32, phase: f64) -> Vec<Point2<f64>> {
    (0..n)
        .map(|i| {
            let theta = std::f64::consts::TAU * i as f64 / n as f64;
            let r = 1.0 + amplitude * (f64::from(lobes) * theta + phase).sin();
            Point2::new(r * theta.cos(), r * theta.sin())
        })
        .collect()
}
