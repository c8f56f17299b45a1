//! Motions of boundary loops on the real loops of the built-in cases: Hicks–Henne bumps
//! (amplitude 0, peak, fixed edges, surfaces), the section rule on a turned and reversed
//! loop, the one-line errors of bad motions, and rigid motions undone by their inverse.

use mesh_model::Role;
use mesh_move::{
    BoundaryLoop, HicksHenne, LoopMotion, Motion, MoveError, RigidMotion, Section, Surface,
    move_loops,
};
use proptest::prelude::*;

fn loops(case: &str) -> Vec<BoundaryLoop> {
    test_cases::real_case(case)
        .loops
        .into_iter()
        .map(|l| BoundaryLoop {
            name: l.name,
            role: l.role,
            points: l.points,
        })
        .collect()
}

fn naca_points() -> Vec<[f64; 2]> {
    loops("naca0012").remove(0).points
}

fn on(name: &str, motion: Motion) -> LoopMotion {
    LoopMotion {
        loop_name: name.into(),
        motion,
    }
}

#[test]
fn a_bump_of_amplitude_zero_changes_nothing() {
    let p = naca_points();
    for surface in [Surface::Upper, Surface::Lower] {
        let m = Motion::bumps(vec![HicksHenne::new(0.3, 0.0, surface)]);
        assert_eq!(m.apply(&p), p);
    }
}

#[test]
fn a_bump_peaks_at_its_position_moves_one_surface_outward_and_keeps_both_edges() {
    let p = naca_points();
    let s = Section::of_loop(&p).unwrap();
    // Selig order from the upper trailing edge: the blunt base is the first and last points
    assert_eq!(s.trailing_edge, [p.len() - 1, 0]);
    assert!(
        p[s.leading_edge][0].abs() < 1e-12,
        "{:?}",
        p[s.leading_edge]
    );
    for surface in [Surface::Upper, Surface::Lower] {
        for position in [0.1, 0.3, 0.5, 0.8] {
            let bump = HicksHenne::new(position, 0.01, surface);
            assert_eq!(bump.shape(position), 1.0);
            assert!((1..1000).all(|i| bump.shape(i as f64 / 1000.0) <= 1.0));
            let q = Motion::bumps(vec![bump]).apply(&p);
            assert_eq!(q[s.leading_edge], p[s.leading_edge]);
            assert_eq!(q[s.trailing_edge[0]], p[s.trailing_edge[0]]);
            assert_eq!(q[s.trailing_edge[1]], p[s.trailing_edge[1]]);
            let dy: Vec<f64> = p.iter().zip(&q).map(|(a, b)| b[1] - a[1]).collect();
            // the chord is (almost) the x axis: the bump moves y only, up on the upper
            // surface (y > 0) and down on the lower one, and nothing on the other surface
            let sign = if surface == Surface::Upper { 1.0 } else { -1.0 };
            for (i, d) in dy.iter().enumerate() {
                if *d != 0.0 {
                    assert_eq!(d.signum(), sign, "point {i}");
                    assert_eq!(p[i][1].signum(), sign, "point {i}");
                }
            }
            let peak = (0..p.len())
                .max_by(|&a, &b| dy[a].abs().total_cmp(&dy[b].abs()))
                .unwrap();
            assert!(dy[peak].abs() <= 0.01 * s.chord() + 1e-15);
            assert!(
                dy[peak].abs() > 0.0097,
                "{position} {surface:?}: {}",
                dy[peak]
            );
            // the neighbours of the peak bracket the position
            let x = |i: usize| s.chord_coordinate(p[i]);
            let (lo, hi) = (x(peak - 1).min(x(peak + 1)), x(peak - 1).max(x(peak + 1)));
            assert!(lo <= position && position <= hi, "{position}: {lo}..{hi}");
        }
    }
}

#[test]
fn the_section_rule_ignores_the_loops_attitude_and_orientation() {
    let p = naca_points();
    let s = Section::of_loop(&p).unwrap();
    let turn = RigidMotion::rotation(140.0, [0.3, -2.0]);
    let mut q: Vec<[f64; 2]> = p.iter().map(|x| turn.apply(*x)).collect();
    q.reverse();
    let n = p.len();
    let t = Section::of_loop(&q).unwrap();
    assert_eq!(t.leading_edge, n - 1 - s.leading_edge);
    let [t0, t1] = s.trailing_edge;
    assert_eq!(t.trailing_edge, [n - 1 - t0, n - 1 - t1]);
    for i in 0..n {
        assert_eq!(t.surface(n - 1 - i), s.surface(i), "point {i}");
    }
    // the same bump moves the same points by the turned displacement
    let bump = Motion::bumps(vec![HicksHenne::new(0.4, 0.02, Surface::Lower)]);
    let (a, b) = (bump.apply(&p), bump.apply(&q));
    for i in 0..n {
        let want = turn.apply(a[i]);
        let got = b[n - 1 - i];
        assert!(
            (want[0] - got[0]).hypot(want[1] - got[1]) < 1e-12,
            "point {i}"
        );
    }
}

fn error(case: &str, motions: Vec<LoopMotion>) -> String {
    let err = move_loops(&loops(case), &motions).expect_err("a bad motion");
    let text = err.to_string();
    assert!(!text.contains('\n'), "{text}");
    text
}

#[test]
fn bad_motion_values_are_named_in_one_line() {
    let rigid = |r: RigidMotion| on("naca0012", Motion::rigid(r));
    let bump = |b: HicksHenne| on("naca0012", Motion::bumps(vec![b]));
    let up = |position, amplitude| HicksHenne::new(position, amplitude, Surface::Upper);
    let cases = [
        (
            rigid(RigidMotion::rotation(f64::NAN, [0.0, 0.0])),
            "loop naca0012: rotate_deg must be a finite number, got NaN",
        ),
        (
            rigid(RigidMotion {
                translate: [f64::INFINITY, 0.0],
                ..RigidMotion::IDENTITY
            }),
            "loop naca0012: translate.x must be a finite number, got inf",
        ),
        (
            rigid(RigidMotion {
                scale: 0.0,
                ..RigidMotion::IDENTITY
            }),
            "loop naca0012: scale must be positive, got 0",
        ),
        (
            bump(up(1.0, 0.01)),
            "loop naca0012: bump position must be strictly between 0 and 1 (a fraction of the chord), got 1",
        ),
        (bump(up(0.0, 0.01)), "got 0"),
        (
            bump(HicksHenne {
                width: 0.0,
                ..up(0.5, 0.01)
            }),
            "loop naca0012: bump width exponent must be positive, got 0",
        ),
        (
            bump(up(0.5, -0.2)),
            "loop naca0012: bump amplitude -0.2 is too large: at most ±0.1 chords",
        ),
        (
            bump(up(0.5, f64::NAN)),
            "loop naca0012: bump amplitude must be a finite number, got NaN",
        ),
        (
            on("wing", Motion::default()),
            "no loop named \"wing\" (loops: naca0012, farfield)",
        ),
        (
            on("farfield", Motion::bumps(vec![up(0.5, 0.01)])),
            "loop farfield: Hicks-Henne bumps apply to wall loops only",
        ),
    ];
    for (motion, want) in cases {
        let got = error("naca0012", vec![motion]);
        assert!(got.ends_with(want), "{got}\nwant {want}");
    }
    let twice = error(
        "naca0012",
        vec![
            on("naca0012", Motion::default()),
            on("naca0012", Motion::default()),
        ],
    );
    assert_eq!(
        twice,
        "loop naca0012 is given two motions; combine them into one"
    );
}

#[test]
fn moved_loops_that_cross_or_leave_the_domain_are_named() {
    let shift = |name: &str, t: [f64; 2]| {
        on(
            name,
            Motion::rigid(RigidMotion {
                translate: t,
                ..RigidMotion::IDENTITY
            }),
        )
    };
    let through = error("naca0012", vec![shift("naca0012", [19.8, 0.0])]);
    assert!(
        through.starts_with("moved loops naca0012 and farfield cross near ("),
        "{through}"
    );
    let out = error("naca0012", vec![shift("naca0012", [100.0, 0.0])]);
    assert_eq!(
        out,
        "moved wall naca0012 lies outside the far field farfield"
    );
    let into = error("30p30n", vec![shift("flap", [-0.3, 0.0])]);
    assert!(
        into.starts_with("moved loops main and flap cross near ("),
        "{into}"
    );
    let swallowed = error(
        "30p30n",
        vec![on(
            "slat",
            Motion::rigid(RigidMotion {
                scale: 0.01,
                translate: [0.4, 0.0],
                ..RigidMotion::IDENTITY
            }),
        )],
    );
    assert_eq!(swallowed, "moved wall slat lies inside wall main");
    // dents on both surfaces deeper together than the section is thick fold it
    let dent = on(
        "naca0012",
        Motion::bumps(vec![
            HicksHenne::new(0.3, -0.1, Surface::Upper),
            HicksHenne::new(0.3, -0.1, Surface::Lower),
        ]),
    );
    let folded = error("naca0012", vec![dent]);
    assert!(
        folded.starts_with("moved loop naca0012 crosses itself near ("),
        "{folded}"
    );
    // and a valid motion of several loops passes
    let ok = move_loops(
        &loops("30p30n"),
        &[
            on(
                "flap",
                Motion::rigid(RigidMotion::rotation(-10.0, [0.87, 0.01])),
            ),
            on(
                "slat",
                Motion::rigid(RigidMotion::rotation(5.0, [0.0, 0.0])),
            ),
        ],
    );
    assert!(ok.is_ok(), "{ok:?}");
    assert_eq!(ok.unwrap()[3].role, Role::Farfield);
}

#[test]
fn errors_are_typed() {
    let e = move_loops(&loops("naca0012"), &[on("nope", Motion::default())]).unwrap_err();
    assert!(matches!(e, MoveError::UnknownLoop { .. }));
}

proptest! {
    #[test]
    fn a_rigid_motion_then_its_inverse_gives_the_points_back(
        scale in 0.1f64..10.0,
        deg in -720.0f64..720.0,
        about in prop::array::uniform2(-100.0f64..100.0),
        translate in prop::array::uniform2(-100.0f64..100.0),
        p in prop::array::uniform2(-100.0f64..100.0),
    ) {
        let m = RigidMotion { scale, rotate_deg: deg, about, translate };
        prop_assert!(m.validate().is_ok());
        let back = m.inverse().apply(m.apply(p));
        let size = 100.0 * (1.0 + scale + 1.0 / scale);
        prop_assert!((back[0] - p[0]).abs() <= 1e-13 * size, "{back:?} {p:?}");
        prop_assert!((back[1] - p[1]).abs() <= 1e-13 * size, "{back:?} {p:?}");
        // the motion is the stated one: scale and rotate about `about`, then translate
        let (s, c) = deg.to_radians().sin_cos();
        let r = [p[0] - about[0], p[1] - about[1]];
        let want = [
            about[0] + scale * (c * r[0] - s * r[1]) + translate[0],
            about[1] + scale * (s * r[0] + c * r[1]) + translate[1],
        ];
        let got = m.apply(p);
        prop_assert!((got[0] - want[0]).hypot(got[1] - want[1]) <= 1e-12 * size);
    }
}
