//! Test kit: builds the boundary loops the tests mesh (graded resampling of the Selig
//! polygons in `fixtures/geometry`, circles, polygons with corners), and the property checks
//! every case must pass.
#![allow(dead_code)]

pub mod gaps;
pub mod real;

use afsf2d::{AfsfOutput, AfsfParams, AngleStats, FrontLoop, max_angle_histogram};
use mesh_model::{NONE, Role};
use testkit::checks;

/// The points of a Selig `.dat` file of the workspace fixtures.
pub use testkit::fixtures::selig_xy as selig;

fn turn_deg(a: [f64; 2], b: [f64; 2], c: [f64; 2]) -> f64 {
    let u = [b[0] - a[0], b[1] - a[1]];
    let v = [c[0] - b[0], c[1] - b[1]];
    (u[0] * v[1] - u[1] * v[0])
        .atan2(u[0] * v[0] + u[1] * v[1])
        .to_degrees()
        .abs()
}

/// Resamples a closed polygon: its vertices turning by more than `corner_deg` (and the extra
/// `features`, vertex indices) are kept; between them nodes are spaced from `h_feature` at the
/// features growing by `growth` up to `h_max`. Returns the points and their corner flags.
pub fn resample(
    poly: &[[f64; 2]],
    corner_deg: f64,
    features: &[usize],
    h_feature: f64,
    growth: f64,
    h_max: f64,
) -> (Vec<[f64; 2]>, Vec<bool>) {
    let n = poly.len();
    let mut breaks: Vec<usize> = (0..n)
        .filter(|&i| turn_deg(poly[(i + n - 1) % n], poly[i], poly[(i + 1) % n]) > corner_deg)
        .chain(features.iter().copied())
        .collect();
    breaks.sort_unstable();
    breaks.dedup();
    if breaks.is_empty() {
        breaks.push(0);
    }
    let mut out = Vec::new();
    let mut corner = Vec::new();
    for (bi, &start) in breaks.iter().enumerate() {
        let end = breaks[(bi + 1) % breaks.len()];
        // the piece's polyline from start to end
        let mut piece = vec![poly[start]];
        let mut i = start;
        loop {
            i = (i + 1) % n;
            piece.push(poly[i]);
            if i == end {
                break;
            }
        }
        let mut arc = vec![0.0];
        for w in piece.windows(2) {
            let d = ((w[1][0] - w[0][0]).powi(2) + (w[1][1] - w[0][1]).powi(2)).sqrt();
            arc.push(arc.last().unwrap() + d);
        }
        let len = *arc.last().unwrap();
        let h = |t: f64| (h_feature + (growth - 1.0) * t.min(len - t)).min(h_max);
        // density integral on a fine grid
        let m = 2000;
        let mut dens = vec![0.0; m + 1];
        for k in 0..m {
            let t = len * (k as f64 + 0.5) / m as f64;
            dens[k + 1] = dens[k] + len / m as f64 / h(t);
        }
        let count = (dens[m].round() as usize).max(1);
        let is_corner = turn_deg(
            poly[(start + n - 1) % n],
            poly[start],
            poly[(start + 1) % n],
        ) > corner_deg;
        out.push(poly[start]);
        corner.push(is_corner);
        for j in 1..count {
            let target = dens[m] * j as f64 / count as f64;
            let k = dens.partition_point(|&d| d < target).clamp(1, m);
            let frac = (target - dens[k - 1]) / (dens[k] - dens[k - 1]);
            let t = len * (k as f64 - 1.0 + frac) / m as f64;
            let s = arc.partition_point(|&a| a < t).clamp(1, piece.len() - 1);
            let u = (t - arc[s - 1]) / (arc[s] - arc[s - 1]);
            let (a, b) = (piece[s - 1], piece[s]);
            out.push([a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1])]);
            corner.push(false);
        }
    }
    (out, corner)
}

/// Index of the leading edge (least x) of an airfoil polygon.
pub fn leading_edge(poly: &[[f64; 2]]) -> usize {
    (0..poly.len())
        .min_by(|&a, &b| poly[a][0].total_cmp(&poly[b][0]))
        .unwrap()
}

/// A graded airfoil wall loop from a fixture file.
pub fn airfoil(rel: &str, name: &str, h_te: f64, h_max: f64) -> FrontLoop {
    let poly = selig(rel);
    let le = leading_edge(&poly);
    let (points, is_corner) = resample(&poly, 30.0, &[le], h_te, 1.12, h_max);
    FrontLoop {
        points,
        is_corner,
        role: Role::Wall,
        name: name.into(),
    }
}

/// A circle of `n` points.
pub fn circle(center: [f64; 2], radius: f64, n: usize, role: Role, name: &str) -> FrontLoop {
    FrontLoop::new(testkit::shapes::circle(center, radius, n), role, name)
}

/// NACA0012 (sharp trailing edge) in a far field of radius 20 chords.
pub fn naca0012(h_max: f64) -> Vec<FrontLoop> {
    vec![
        airfoil(
            "naca0012-sharp-te-generated.dat",
            "naca0012",
            0.1 * h_max,
            h_max,
        ),
        circle([0.5, 0.0], 20.0, 64, Role::Farfield, "farfield"),
    ]
}

/// The 30P30N three elements in a far field of radius 20 chords.
pub fn three_element(h_max: f64) -> Vec<FrontLoop> {
    vec![
        airfoil("30p30n/slat.dat", "slat", 0.15 * h_max, h_max),
        airfoil("30p30n/main.dat", "main", 0.15 * h_max, h_max),
        airfoil("30p30n/flap.dat", "flap", 0.15 * h_max, h_max),
        circle([0.5, 0.0], 20.0, 64, Role::Farfield, "farfield"),
    ]
}

/// A smooth concave star (five arms), to mesh inside.
pub fn star(n: usize) -> Vec<FrontLoop> {
    let points = (0..n)
        .map(|i| {
            let a = std::f64::consts::TAU * i as f64 / n as f64;
            let r = 1.0 + 0.45 * (5.0 * a).cos();
            [r * a.cos(), r * a.sin()]
        })
        .collect();
    vec![FrontLoop::new(points, Role::Wall, "star")]
}

/// A polygon body with sharp convex and concave corners (a cross when `cross`, else an L) in
/// a far field.
pub fn cornered(cross: bool, h_corner: f64, h_max: f64) -> Vec<FrontLoop> {
    let poly: Vec<[f64; 2]> = if cross {
        let (a, b) = (0.15, 0.5);
        vec![
            [a, -a],
            [b, -a],
            [b, a],
            [a, a],
            [a, b],
            [-a, b],
            [-a, a],
            [-b, a],
            [-b, -a],
            [-a, -a],
            [-a, -b],
            [a, -b],
        ]
    } else {
        vec![
            [0.0, 0.0],
            [1.0, 0.0],
            [1.0, 0.3],
            [0.3, 0.3],
            [0.3, 1.0],
            [0.0, 1.0],
        ]
    };
    let (points, is_corner) = resample(&poly, 30.0, &[], h_corner, 1.15, h_max);
    vec![
        FrontLoop {
            points,
            is_corner,
            role: Role::Wall,
            name: "body".into(),
        },
        circle([0.3, 0.3], 15.0, 64, Role::Farfield, "farfield"),
    ]
}

/// Area of the domain: far field minus walls, or the single loop.
pub fn domain_area(loops: &[FrontLoop]) -> f64 {
    let a = |l: &FrontLoop| mesh_model::polygon_area(l.points.iter().copied()).abs();
    if loops.len() == 1 {
        return a(&loops[0]);
    }
    loops
        .iter()
        .map(|l| {
            if l.role == Role::Farfield {
                a(l)
            } else {
                -a(l)
            }
        })
        .sum()
}

/// The properties every mesh must have; returns the angle figures.
pub fn check_mesh(loops: &[FrontLoop], params: &AfsfParams, out: &AfsfOutput) -> AngleStats {
    let m = &out.layered.mesh;
    checks::assert_valid("afsf2d", m);
    checks::assert_area("afsf2d", m.linear_area(), domain_area(loops), 1e-9);
    // boundary nodes untouched, in input order
    let mut k = 0;
    for l in loops {
        for p in &l.points {
            assert_eq!(m.nodes[k], [p[0], p[1], 0.0], "boundary node {k} moved");
            assert_eq!(out.layered.layering.node_parents[k], [NONE, NONE]);
            assert_eq!(out.layered.layering.node_layer[k], 0);
            k += 1;
        }
    }
    assert_eq!(m.boundary.len(), k);
    // layers, pipes, parents: the record's own invariants, and every layer node has a parent
    assert!(m.cell_layer.iter().all(|&l| l != NONE));
    assert!(m.cell_pipe.iter().all(|&p| (p as usize) < m.boundary.len()));
    let layering = &out.layered.layering;
    assert_eq!(layering.check(m), None);
    for i in k..m.nodes.len() {
        let p = layering.node_parents[i][0];
        assert_eq!(
            p == NONE,
            layering.node_layer[i] == NONE,
            "node {i}: a layer node has a parent, a fill node none"
        );
    }
    // first layer height, away from the corners (a corner and its two neighbours)
    let mut near_corner = Vec::new();
    for l in loops {
        let n = l.is_corner.len();
        near_corner.extend(
            (0..n).map(|i| {
                l.is_corner[i] || l.is_corner[(i + 1) % n] || l.is_corner[(i + n - 1) % n]
            }),
        );
    }
    for i in k..m.nodes.len() {
        let layering = &out.layered.layering;
        if layering.node_layer[i] != 1 || layering.node_parents[i][0] == NONE {
            continue;
        }
        let p = layering.node_parents[i][0] as usize;
        let wall = m.patches[m.boundary_patch[p] as usize].role == Role::Wall;
        if !wall || near_corner[p] {
            // at a sharp corner the first cells are legitimately compressed or fanned
            continue;
        }
        let (a, b) = (m.xy(i as u32), m.xy(p as u32));
        let h = ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2)).sqrt();
        assert!(
            (h - params.first_height).abs() <= 0.05 * params.first_height,
            "first-layer node {i}: extrusion length {h:e}, first height {:e}",
            params.first_height
        );
    }
    max_angle_histogram(m)
}

/// One line of figures for the report.
pub fn summary(name: &str, out: &AfsfOutput, q: &AngleStats) -> String {
    let s = &out.stats;
    format!(
        "{name}: nodes {} quads {} tris {} (fill {}) layers {} iters {} converged {} | tris-cut {} max angle {:.1} hist {:?} | time {:.3}s (plan {:.3} build {:.3} solve {:.3} verify {:.3} fill {:.3}) retries {}",
        out.layered.mesh.nodes.len(),
        out.layered.mesh.count(mesh_model::Shape::Quad),
        out.layered.mesh.count(mesh_model::Shape::Tri),
        s.fill_triangles,
        s.layers,
        s.iterations,
        s.all_converged,
        q.triangles,
        q.max_angle_deg,
        q.histogram,
        s.timings.total,
        s.timings.plan_and_closing,
        s.timings.build,
        s.timings.solve,
        s.timings.verify,
        s.timings.fill,
        s.layer_stats.iter().map(|l| l.retries).sum::<u32>(),
    )
}
