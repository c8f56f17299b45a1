//! Property test of the mesher on random multi-body domains: one to three bodies (circles,
//! ellipses, star polygons) apart from each other inside a far-field circle, with a random
//! first height and growth. Every mesh must be valid, cover the domain exactly, keep the
//! boundary nodes where they were, and put every layered cell above (on the domain side of)
//! the boundary facet of its pipe. In debug builds the mesher also checks its whole front
//! state after every layer (`sanity_check`), so these cases exercise that too.

use crate::common;

use afsf2d::{AfsfParams, FrontLoop, grow_mesh};
use mesh_model::{NONE, Role, validate};
use proptest::prelude::*;

/// One body: shape kind (0 circle, 1 ellipse, 2 star), size, aspect or arm depth, arms,
/// rotation, centre jitter, number of points.
type Body = (u8, f64, f64, usize, f64, [f64; 2], usize);

fn body() -> impl Strategy<Value = Body> {
    (
        0u8..3,
        0.6f64..1.2,
        0.4f64..0.9,
        3usize..7,
        0.0f64..std::f64::consts::TAU,
        [-0.5f64..0.5, -0.5f64..0.5],
        24usize..48,
    )
}

/// The body's loop around `centre`.
fn body_loop(b: &Body, centre: [f64; 2], k: usize) -> FrontLoop {
    let (kind, size, shape, arms, rot, jitter, n) = *b;
    let c = [centre[0] + jitter[0], centre[1] + jitter[1]];
    let points = (0..n)
        .map(|i| {
            let t = std::f64::consts::TAU * i as f64 / n as f64;
            let (rx, ry) = match kind {
                0 => (size, size),
                1 => (size, size * shape),
                _ => {
                    // a smooth star: the radius swings between size·shape and size
                    let r = size * (1.0 - 0.5 * (1.0 - shape) * (1.0 - (arms as f64 * t).cos()));
                    (r, r)
                }
            };
            let (x, y) = (rx * t.cos(), ry * t.sin());
            let (s, co) = rot.sin_cos();
            [c[0] + co * x - s * y, c[1] + s * x + co * y]
        })
        .collect();
    FrontLoop::new(points, Role::Wall, format!("body{k}"))
}

/// One to three bodies at three places on a circle of radius 4 (so that bodies of radius at
/// most 1.2, moved by at most 0.5, stay apart), inside a far field of radius 10.
fn domain(bodies: &[Body]) -> Vec<FrontLoop> {
    let mut loops: Vec<FrontLoop> = bodies
        .iter()
        .enumerate()
        .map(|(k, b)| {
            let a = std::f64::consts::TAU * k as f64 / 3.0;
            body_loop(b, [4.0 * a.cos(), 4.0 * a.sin()], k)
        })
        .collect();
    loops.push(common::circle(
        [0.0, 0.0],
        10.0,
        64,
        Role::Farfield,
        "farfield",
    ));
    loops
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 64, ..ProptestConfig::default() })]

    #[test]
    fn random_multi_body_domains_mesh_exactly(
        bodies in proptest::collection::vec(body(), 1..=3),
        first_height in 0.002f64..0.02,
        growth in 1.1f64..1.4,
    ) {
        let loops = domain(&bodies);
        let params = AfsfParams { first_height, growth, max_layers: 20, ..AfsfParams::default() };
        let out = grow_mesh(&loops, &params).map_err(|e| TestCaseError::fail(e.to_string()))?;
        let (m, layering) = (&out.layered.mesh, &out.layered.layering);
        prop_assert!(out.stats.layers >= 3 && layering.layered_cells > 0, "{:?}", out.stats);
        prop_assert_eq!(layering.check(m), None);
        let problems = validate(m);
        prop_assert!(problems.is_empty(), "{} problems, first: {}", problems.len(), problems[0]);
        let area = common::domain_area(&loops);
        prop_assert!((m.linear_area() - area).abs() <= 1e-9 * area, "area {} vs {area}", m.linear_area());
        let mut k = 0;
        for l in &loops {
            for p in &l.points {
                prop_assert_eq!(m.nodes[k], [p[0], p[1], 0.0], "boundary node {} moved", k);
                k += 1;
            }
        }
        prop_assert_eq!(layering.node_parents.len(), m.nodes.len());
        for (i, pp) in layering.node_parents.iter().enumerate() {
            prop_assert!(pp[1] == NONE || (pp[1] != pp[0] && (pp[1] as usize) < m.nodes.len()), "node {}: {:?}", i, pp);
        }
        // every layered cell lies on the domain side of its pipe's facet
        let facets: Vec<[u32; 2]> = m.boundary.iter().map(|f| [f.nodes[0], f.nodes[1]]).collect();
        for (c, cell) in m.cells.iter().enumerate().take(layering.layered_cells) {
            let [a, b] = facets[m.cell_pipe[c] as usize].map(|g| m.xy(g));
            let n = cell.nodes.len() as f64;
            let centroid = cell.nodes.iter().fold([0.0, 0.0], |s, &g| {
                let p = m.xy(g);
                [s[0] + p[0] / n, s[1] + p[1] / n]
            });
            let side = (b[0] - a[0]) * (centroid[1] - a[1]) - (b[1] - a[1]) * (centroid[0] - a[0]);
            prop_assert!(side > 0.0, "layered cell {} (layer {}) is not above its facet {}", c, m.cell_layer[c], m.cell_pipe[c]);
        }
    }
}
