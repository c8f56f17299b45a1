//! What the movers' integration tests share: one rigid motion applied to every loop, how far a
//! moved mesh is from that rigid motion of the original, and a morph by eight bumps.

use std::sync::OnceLock;

use mesh_model::{LayeredMesh, Mesh};
use mesh_move::{HicksHenne, LoopMotion, Motion, RigidMotion, Section, Surface};

/// Scaled by `scale`, turned by 37° about (0.25, 0.1), moved by (−5, 2).
pub fn turn_and_shift(scale: f64) -> RigidMotion {
    RigidMotion {
        scale,
        rotate_deg: 37.0,
        about: [0.25, 0.1],
        translate: [-5.0, 2.0],
    }
}

/// `rigid` for each of the loops `names`.
pub fn every_loop(names: &[&str], rigid: RigidMotion) -> Vec<LoopMotion> {
    names
        .iter()
        .map(|n| LoopMotion {
            loop_name: n.to_string(),
            motion: Motion::rigid(rigid),
        })
        .collect()
}

/// The largest distance of a node of `after` from `rigid` applied to its place in `before`.
pub fn rigid_error(before: &Mesh, after: &Mesh, rigid: &RigidMotion) -> f64 {
    (0..before.nodes.len() as u32)
        .map(|k| {
            let (want, got) = (rigid.apply(before.xy(k)), after.xy(k));
            (want[0] - got[0]).hypot(want[1] - got[1])
        })
        .fold(0.0, f64::max)
}

/// Eight Hicks–Henne bumps of 1 % chord on loop `name`: at 0.1, 0.3, 0.5 and 0.7 of the chord,
/// outward on the upper surface and inward on the lower.
#[allow(dead_code)] // not every test file uses it
pub fn eight_bumps(name: &str) -> Vec<LoopMotion> {
    let bumps: Vec<HicksHenne> = [0.1, 0.3, 0.5, 0.7]
        .iter()
        .flat_map(|&x| {
            [
                HicksHenne::new(x, 0.01, Surface::Upper),
                HicksHenne::new(x, -0.01, Surface::Lower),
            ]
        })
        .collect();
    vec![LoopMotion {
        loop_name: name.into(),
        motion: Motion::bumps(bumps),
    }]
}

/// The leading edge of loop `name` of `case` (a hinge for a flap).
#[allow(dead_code)] // not every test file uses it
pub fn leading_edge(case: &test_cases::Case, name: &str) -> [f64; 2] {
    let points = &case
        .loops
        .iter()
        .find(|l| l.name == name)
        .expect("the loop")
        .points;
    points[Section::of_loop(points).expect("a chord").leading_edge]
}

/// The layered mesh of the built-in NACA0012 case (far field of radius 20), grown once.
#[allow(dead_code)] // not every test file uses it
pub fn naca_layered() -> &'static LayeredMesh {
    static MESH: OnceLock<LayeredMesh> = OnceLock::new();
    MESH.get_or_init(|| {
        test_cases::grow(&test_cases::real_case("naca0012"))
            .output
            .layered
    })
}
