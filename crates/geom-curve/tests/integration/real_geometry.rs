//! The real airfoils of `fixtures/geometry`: they load, are simple counter-clockwise loops, the
//! 30P30N elements are disjoint, the fitted curves interpolate them and have corners exactly at
//! the trailing edges, blunt-base corners, the slat cusp and the cove, and nowhere else.

use crate::common;

use common::turning_deg;
use geom_curve::loops::{
    check_loops_disjoint, is_counter_clockwise, loop_inside_loop, validate_loop,
};
use geom_curve::{ClosedCurve, CurveParams, LoopCheckParams, Point2, circle_points, naca};
use testkit::fixtures::{AIRFOILS, selig as load};

#[test]
fn every_airfoil_is_a_valid_counter_clockwise_loop() {
    for name in AIRFOILS.iter().chain(&["bat.dat"]) {
        let points = load(name);
        assert_eq!(
            validate_loop(&points, &LoopCheckParams::default()),
            Ok(()),
            "{name}"
        );
        assert!(is_counter_clockwise(&points), "{name}");
    }
}

#[test]
fn the_30p30n_elements_are_disjoint_and_inside_the_far_field() {
    let elements = [
        load("30p30n/slat.dat"),
        load("30p30n/main.dat"),
        load("30p30n/flap.dat"),
    ];
    assert_eq!(check_loops_disjoint(&elements), Ok(()));
    let far_field = circle_points(Point2::new(0.5, 0.0), 20.0, 200).unwrap();
    for (i, a) in elements.iter().enumerate() {
        assert!(loop_inside_loop(a, &far_field));
        for (j, b) in elements.iter().enumerate() {
            if i != j {
                assert!(!loop_inside_loop(a, b), "element {i} inside element {j}");
            }
        }
    }
    // moving the slat onto the main element is caught, naming both loops
    let shifted: Vec<_> = elements[0]
        .iter()
        .map(|p| Point2::new(p.x + 0.05, p.y))
        .collect();
    let err = check_loops_disjoint(&[shifted, elements[1].clone()]).unwrap_err();
    assert!(err.to_string().starts_with("loop 0 (edge"), "{err}");
    assert!(err.to_string().contains("crosses loop 1"), "{err}");
}

/// The expected corners of each fixture, found by reading the geometry (see SOURCES.md):
/// trailing edges, the end points of blunt bases, the slat cusp and the two cove corners.
fn expected_corners(name: &str) -> Vec<usize> {
    match name {
        // blunt base: the upper and lower trailing-edge points (x = 1)
        "naca0012.dat" => vec![0, 130],
        // sharp trailing edges at point 0
        "naca0012-sharp-te-generated.dat" | "rae2822.dat" => vec![0],
        // base end points 0 and 200 (the base runs 200..207 and back to 0), cusp at 100
        "30p30n/slat.dat" => vec![0, 100, 200],
        // base end points 0 and 640, cove corners at the vertical wall x = 0.7 (600, 608)
        "30p30n/main.dat" => vec![0, 600, 608, 640],
        // base end points 0 and 200
        "30p30n/flap.dat" => vec![0, 200],
        _ => unreachable!("no expectation for {name}"),
    }
}

#[test]
fn corners_are_exactly_the_sharp_features() {
    for name in AIRFOILS {
        let points = load(name);
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        assert_eq!(curve.corners(), expected_corners(name).as_slice(), "{name}");
        // the leading edge (smallest x) and its neighbours are smooth
        let n = points.len();
        let le = (0..n)
            .min_by(|&a, &b| points[a].x.total_cmp(&points[b].x))
            .unwrap();
        for i in [le + n - 1, le, le + 1] {
            assert!(
                !curve.is_corner(i % n),
                "{name}: leading-edge point {}",
                i % n
            );
        }
    }
}

#[test]
fn corner_expectations_agree_with_the_turning_angles() {
    // independent of the curve code: every expected corner turns by more than 60 degrees,
    // every other point by less than 25 degrees
    for name in AIRFOILS {
        let turning = turning_deg(&load(name));
        let corners = expected_corners(name);
        for (i, &turn) in turning.iter().enumerate() {
            if corners.contains(&i) {
                assert!(turn > 60.0, "{name} {i}: {turn}");
            } else {
                assert!(turn < 25.0, "{name} {i}: {turn}");
            }
        }
    }
}

#[test]
fn bat_tips_and_ears_are_corners() {
    let points = load("bat.dat");
    let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
    let tips_and_ears = [
        (30.0, 4.0),
        (22.0, -6.0),
        (13.0, -8.0),
        (5.0, -5.0),
        (0.0, -9.0),
        (-5.0, -5.0),
        (-13.0, -8.0),
        (-22.0, -6.0),
        (-30.0, 4.0),
        (-4.0, 7.0),
        (-2.5, 11.0),
        (-1.0, 7.5),
        (1.0, 7.5),
        (2.5, 11.0),
        (4.0, 7.0),
    ];
    let mut expected: Vec<usize> = tips_and_ears
        .iter()
        .map(|&(x, y)| {
            points
                .iter()
                .position(|p| (p.x - x).abs() < 1e-9 && (p.y - y).abs() < 1e-9)
                .unwrap()
        })
        .collect();
    expected.sort_unstable();
    assert_eq!(curve.corners(), expected.as_slice());
}

#[test]
fn curves_through_real_airfoils_interpolate_and_stay_close_to_the_polygon() {
    for name in AIRFOILS {
        let points = load(name);
        let curve = ClosedCurve::new(&points, &CurveParams::default()).unwrap();
        let perimeter = geom_curve::loops::perimeter(&points);
        for (i, p) in points.iter().enumerate() {
            assert!((curve.point(i as f64) - p).norm() < 1e-14, "{name} {i}");
        }
        // the curve is a little longer than the polygon, by far less than a percent
        let excess = curve.total_length() / perimeter - 1.0;
        assert!(excess > 0.0 && excess < 1e-3, "{name}: {excess}");
        // each segment stays near its chord: the curve neither loops nor wiggles
        for (i, segment) in curve.segments().iter().enumerate() {
            let a = points[i];
            let b = points[(i + 1) % points.len()];
            let chord = b - a;
            for j in 1..8 {
                let q = segment.point(f64::from(j) / 8.0);
                let off = chord.perp(&(q - a)).abs() / chord.norm();
                assert!(off < 0.1 * chord.norm(), "{name} segment {i}: {off}");
            }
        }
        // closest point of the midpoint of every segment is that midpoint
        for i in 0..points.len() {
            let t = i as f64 + 0.5;
            let (t_found, _, distance) = curve.closest_point(curve.point(t));
            assert!(distance < 1e-12, "{name} {i}: {distance}");
            assert!((t_found - t).abs() < 1e-6, "{name} {i}: {t_found}");
        }
    }
}

#[test]
fn naca_generator_matches_the_reference_files() {
    let sharp = load("naca0012-sharp-te-generated.dat");
    let generated = naca::naca4("0012", 101, true).unwrap();
    assert_eq!(generated.len(), sharp.len());
    for (g, f) in generated.iter().zip(&sharp) {
        assert!((g - f).norm() < 1e-9, "{g} vs {f}");
    }
    let blunt = load("naca0012.dat");
    let generated = naca::naca4("0012", 66, false).unwrap();
    assert_eq!(generated.len(), blunt.len());
    for (g, f) in generated.iter().zip(&blunt) {
        assert!((g - f).norm() < 1e-7, "{g} vs {f}");
    }
}
